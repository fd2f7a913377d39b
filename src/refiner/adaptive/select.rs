//! Which faces of a level feature-adaptive refinement selects — what
//! OpenSubdiv's `Far::TopologyRefiner::selectFeatureAdaptiveComponents`
//! decides (`far/topologyRefiner.cpp`): the faces around features a regular
//! patch cannot represent, from the tags of their corners combined.

use super::features::Features;
use super::vtag::{CORNER, CREASE, DART, SMOOTH, Tag};
use crate::options::AdaptiveOptions;
use crate::topology::fvar::ChannelLevel;
use crate::topology::refine::sparse::SparseSplit;
use crate::topology::{Level, VertexTag};

/// The features to isolate at one level (`Far::internal::FeatureMask`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FeatureMask {
    pub xordinary_interior: bool,
    pub xordinary_boundary: bool,
    pub semi_sharp_single: bool,
    pub semi_sharp_non_single: bool,
    pub inf_sharp_regular_crease: bool,
    pub inf_sharp_regular_corner: bool,
    pub inf_sharp_irregular_dart: bool,
    pub inf_sharp_irregular_crease: bool,
    pub inf_sharp_irregular_corner: bool,
    pub unisolated_interior_edge: bool,
    pub non_manifold: bool,
    /// Also isolate the features of the face-varying channels.
    pub fvar_features: bool,
}

impl FeatureMask {
    /// Every feature the options ask to isolate. Single-crease patches exist
    /// for quads only.
    pub fn new(options: &AdaptiveOptions, regular_face_size: usize) -> Self {
        let single = options.use_single_crease_patch && regular_face_size == 4;
        let inf_patch = options.use_inf_sharp_patch;
        FeatureMask {
            xordinary_interior: true,
            xordinary_boundary: true,
            semi_sharp_single: !single,
            semi_sharp_non_single: true,
            inf_sharp_regular_crease: !(inf_patch || single),
            inf_sharp_regular_corner: !inf_patch,
            inf_sharp_irregular_dart: true,
            inf_sharp_irregular_crease: true,
            inf_sharp_irregular_corner: true,
            unisolated_interior_edge: single && !inf_patch,
            non_manifold: true,
            fvar_features: options.consider_fvar_channels,
        }
    }

    /// The smaller set isolated past the secondary level: no extraordinary
    /// vertices, and with infinitely sharp patches only irregular corners.
    pub fn reduced(mut self, options: &AdaptiveOptions) -> Self {
        self.xordinary_interior = false;
        self.xordinary_boundary = false;
        if options.use_inf_sharp_patch {
            self.inf_sharp_regular_crease = false;
            self.inf_sharp_regular_corner = false;
            self.inf_sharp_irregular_dart = false;
            self.inf_sharp_irregular_crease = false;
        }
        self
    }
}

/// Whether the infinitely sharp features of a tag (one corner's, or a
/// face's combined: the tests are bitwise, so both read the same) are ones
/// the mask isolates.
fn inf_sharp_tag_has_features(t: Tag, mask: &FeatureMask) -> bool {
    if t.features.inf_irregular {
        if t.rule & CORNER != 0 {
            mask.inf_sharp_irregular_corner
        } else if t.rule & CREASE != 0 {
            if t.boundary {
                mask.xordinary_boundary
            } else {
                mask.inf_sharp_irregular_crease
            }
        } else if t.rule & DART != 0 {
            mask.inf_sharp_irregular_dart
        } else {
            false
        }
    } else if t.boundary {
        // Regular boundaries are never isolated, except a boundary crease
        // made a corner by an interior sharp edge.
        t.rule & CORNER != 0 && !t.corner && mask.inf_sharp_regular_corner
    } else if t.rule & CORNER != 0 {
        mask.inf_sharp_regular_corner
    } else {
        mask.inf_sharp_regular_crease
    }
}

/// Whether a face with infinitely sharp features needs isolating.
fn inf_sharp_face_has_features(composite: Tag, corners: &[Tag], mask: &FeatureMask) -> bool {
    let one_smooth_corner = composite.rule & SMOOTH != 0;
    if corners.len() == 4 {
        if one_smooth_corner {
            return inf_sharp_tag_has_features(composite, mask);
        }
        if mask.unisolated_interior_edge && corners.iter().any(|t| t.inf_sharp_edges && !t.boundary)
        {
            return true;
        }
    } else if one_smooth_corner && !composite.boundary {
        return inf_sharp_tag_has_features(composite, mask);
    }
    corners
        .iter()
        .any(|&t| t.rule & SMOOTH == 0 && inf_sharp_tag_has_features(t, mask))
}

/// Whether face `f` of a quad level is a regular interior face with a
/// single semi-sharp crease along one edge (`Vtr::Level::isSingleCreasePatch`):
/// two adjacent crease corners, the other two smooth, and the crease
/// regular at both crease corners (opposite edges equally sharp).
fn is_single_crease_patch(level: &Level, composite: Tag, corners: &[Tag], verts: &[u32]) -> bool {
    if composite.rule & CREASE == 0
        || composite.rule & (CORNER | DART) != 0
        || composite.boundary
        || composite.features.xordinary
        || composite.non_manifold
    {
        return false;
    }
    let mask = corners
        .iter()
        .enumerate()
        .map(|(i, t)| ((t.rule == CREASE) as usize) << i)
        .sum::<usize>();
    let edge = match mask {
        3 => 0,
        6 => 1,
        12 => 2,
        9 => 3,
        _ => return false,
    };
    let regular = |v: u32| {
        let edges = level.vertex_edges_of(v as usize);
        let s = |k: usize| level.edge_sharpness_at(edges[k] as usize);
        s(0) == s(2) && s(1) == s(3)
    };
    regular(verts[edge]) && regular(verts[(edge + 1) % 4])
}

/// Whether face `f` has features to isolate, or, when the mask says so, its
/// face-varying channels do where their topology differs from the
/// vertices' (`selectFeatureAdaptiveComponents`).
pub(crate) fn face_is_selected(
    level: &Level,
    features: &[Features],
    channels: &[&ChannelLevel],
    f: usize,
    mask: &FeatureMask,
    regular_face_size: usize,
) -> bool {
    face_has_features(level, features, f, mask, regular_face_size)
        || (mask.fvar_features
            && channels.iter().any(|&channel| {
                let verts = level.face_verts(f);
                let matches = verts
                    .iter()
                    .all(|&v| !channel.vertex_value_tags(v as usize)[0].is_mismatch());
                !matches && face_varying_features(level, features, channel, f, mask)
            }))
}

/// Whether the face-varying boundary features of face `f`'s corners in one
/// channel need isolating (`doesFaceHaveDistinctFaceVaryingFeatures`): the
/// tags of each corner combined over all of its values in the channel, so
/// that faces across the channel's boundaries stay within one level.
fn face_varying_features(
    level: &Level,
    features: &[Features],
    channel: &ChannelLevel,
    f: usize,
    mask: &FeatureMask,
) -> bool {
    let verts = level.face_verts(f);
    let mut corners = [Tag::default(); 4];
    for (slot, &v) in corners.iter_mut().zip(verts) {
        let base = Tag::of(level, features, v as usize);
        let values = channel.vertex_value_tags(v as usize);
        *slot = if values[0].is_mismatch() {
            values
                .iter()
                .map(|&value| base.with_value(value))
                .fold(Tag::default(), Tag::or)
        } else {
            base
        };
    }
    let corners = &corners[..verts.len().min(4)];
    let composite = corners.iter().fold(Tag::default(), |a, &b| a.or(b));
    if composite.features.incomplete {
        return false;
    }
    if composite.non_manifold && mask.non_manifold {
        return true;
    }
    if composite.features.xordinary && mask.xordinary_interior {
        return true;
    }
    inf_sharp_face_has_features(composite, corners, mask)
}

/// Whether face `f` has features to isolate (`doesFaceHaveFeatures`).
pub(crate) fn face_has_features(
    level: &Level,
    features: &[Features],
    f: usize,
    mask: &FeatureMask,
    regular_face_size: usize,
) -> bool {
    let verts = level.face_verts(f);
    // Irregular faces are always isolated.
    if verts.len() != regular_face_size {
        return true;
    }
    // Corners with refinement's default tags (smooth, nothing sharp, not on
    // a boundary, manifold), the most common face: the steps below reduce to
    // the adaptive features alone.
    if verts
        .iter()
        .all(|&v| level.vertex_tag(v as usize) == VertexTag::default())
    {
        let (mut xordinary, mut incomplete, mut irregular) = (false, false, false);
        for &v in verts {
            let f = features[v as usize];
            xordinary |= f.xordinary;
            incomplete |= f.incomplete;
            irregular |= f.incid_irreg_face;
        }
        return irregular || (!incomplete && xordinary && mask.xordinary_interior);
    }
    let mut corners = [Tag::default(); 4];
    for (slot, &v) in corners.iter_mut().zip(verts) {
        *slot = Tag::of(level, features, v as usize);
    }
    let corners = &corners[..verts.len()];
    let composite = corners.iter().fold(Tag::default(), |a, &b| a.or(b));

    if composite.features.incid_irreg_face {
        return true;
    }
    if composite.features.incomplete {
        return false;
    }
    if composite.non_manifold && mask.non_manifold {
        return true;
    }
    if composite.features.xordinary && mask.xordinary_interior {
        if composite.rule == SMOOTH {
            return true;
        }
        if level.depth < 2
            && corners
                .iter()
                .any(|t| t.features.xordinary && t.rule == SMOOTH)
        {
            return true;
        }
    }
    if composite.rule == SMOOTH {
        return false;
    }
    if composite.semi_sharp || composite.semi_sharp_edges {
        return if mask.semi_sharp_single && mask.semi_sharp_non_single {
            true
        } else if is_single_crease_patch(level, composite, corners, verts) {
            mask.semi_sharp_single
        } else {
            mask.semi_sharp_non_single
        };
    }
    if composite.inf_sharp || composite.inf_sharp_edges {
        return inf_sharp_face_has_features(composite, corners, mask);
    }
    false
}

/// The faces of a quad split's child level that may have features to
/// isolate: the children of the faces `split` selected, in index order. A
/// child of a face that was not selected holds that face's point, which is
/// incomplete, and a face with an incomplete corner is never selected
/// (`doesFaceHaveFeatures`; its face-varying features likewise): every
/// child face is a quad, so no irregular face selects itself either. Not
/// for Loop's split, whose middle children have no face point.
pub(crate) fn children_of_selected(split: &SparseSplit) -> impl Iterator<Item = usize> + '_ {
    debug_assert!(!split.triangles);
    split
        .child_face_parent
        .iter()
        .enumerate()
        .filter(|&(_, &p)| split.selection.face(p as usize))
        .map(|(c, _)| c)
}
