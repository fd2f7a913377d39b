//! The tags of a vertex as feature-adaptive refinement and patch tables
//! read them — OpenSubdiv's `Vtr::Level::VTag`: refinement's tags
//! ([`crate::topology::VertexTag`]) with the adaptive [`Features`], or-ed
//! over a face's corners, and as a face-varying value sees them.

use super::features::Features;
use crate::rules::Rule;
use crate::topology::Level;
use crate::topology::fvar::ValueTag;

/// OpenSubdiv's rule bits, which combine by `|` over a face's corners.
pub(crate) const SMOOTH: u8 = 1;
pub(crate) const DART: u8 = 2;
pub(crate) const CREASE: u8 = 4;
pub(crate) const CORNER: u8 = 8;

pub(crate) fn rule_bits(rule: Rule) -> u8 {
    match rule {
        Rule::Smooth => SMOOTH,
        Rule::Dart => DART,
        Rule::Crease => CREASE,
        Rule::Corner => CORNER,
    }
}

/// The tags of a vertex as the selection reads them, or of several combined
/// (`Vtr::Level::VTag` and `VTag::BitwiseOr`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Tag {
    pub non_manifold: bool,
    pub boundary: bool,
    pub corner: bool,
    pub inf_sharp: bool,
    pub semi_sharp: bool,
    pub semi_sharp_edges: bool,
    pub inf_sharp_edges: bool,
    /// One bit per rule present (see [`rule_bits`]).
    pub rule: u8,
    pub features: Features,
}

impl Tag {
    /// The tags of vertex `v` of `level` (`features`: the level's).
    #[inline(always)]
    pub fn of(level: &Level, features: &[Features], v: usize) -> Tag {
        let t = level.vertex_tag(v);
        Tag {
            non_manifold: t.non_manifold(),
            boundary: t.boundary(),
            corner: t.corner(),
            inf_sharp: t.inf_sharp(),
            semi_sharp: t.semi_sharp(),
            semi_sharp_edges: t.semi_sharp_edges(),
            inf_sharp_edges: t.inf_sharp_edges(),
            rule: rule_bits(t.rule()),
            features: features[v],
        }
    }

    /// The tags of a vertex as one of its values in a face-varying channel
    /// sees it (`FVarLevel::ValueTag::combineWithLevelVTag`): a value where
    /// the channel's topology differs lies on an infinitely sharp boundary
    /// of the channel, a crease or a corner.
    #[inline(always)]
    pub fn with_value(mut self, value: ValueTag) -> Tag {
        if !value.is_mismatch() {
            return self;
        }
        self.rule = if value.is_corner() { CORNER } else { CREASE };
        if value.is_crease() || value.is_semi_sharp() {
            self.inf_sharp = false;
            self.features.inf_sharp_crease = true;
            self.corner = false;
        } else {
            self.inf_sharp = true;
            self.features.inf_sharp_crease = false;
            self.corner = !value.is_inf_irregular() && !value.has_inf_sharp_edges();
        }
        self.inf_sharp_edges = true;
        self.features.inf_irregular = value.is_inf_irregular();
        self.boundary = true;
        self.features.xordinary = value.is_xordinary();
        self.non_manifold |= value.is_non_manifold();
        self
    }

    /// The tags of two vertices combined (`VTag::BitwiseOr`).
    #[inline(always)]
    pub fn or(self, o: Tag) -> Tag {
        let (a, b) = (self.features, o.features);
        Tag {
            non_manifold: self.non_manifold | o.non_manifold,
            boundary: self.boundary | o.boundary,
            corner: self.corner | o.corner,
            inf_sharp: self.inf_sharp | o.inf_sharp,
            semi_sharp: self.semi_sharp | o.semi_sharp,
            semi_sharp_edges: self.semi_sharp_edges | o.semi_sharp_edges,
            inf_sharp_edges: self.inf_sharp_edges | o.inf_sharp_edges,
            rule: self.rule | o.rule,
            features: Features {
                xordinary: a.xordinary | b.xordinary,
                incomplete: a.incomplete | b.incomplete,
                incid_irreg_face: a.incid_irreg_face | b.incid_irreg_face,
                inf_sharp_crease: a.inf_sharp_crease | b.inf_sharp_crease,
                inf_irregular: a.inf_irregular | b.inf_irregular,
            },
        }
    }
}
