//! The neighbourhood of one corner of a base face, as Bfr describes it
//! (`Bfr::FaceVertex` and `Bfr::FaceVertexSubset`): the faces around the
//! corner's vertex in order, each face's vertices starting at the corner,
//! the sharpness of the edges around it, the tags summarising them, and the
//! subset of those faces the face's limit surface depends on.
//!
//! Only manifold vertices (whose faces can be ordered around them) are
//! described natively; the callers refuse the others.

use crate::rules::crease::{is_infinite, is_semi_sharp, is_sharp};
use crate::topology::Level;

/// What a corner's neighbourhood holds (`Bfr::VertexTag`), or — or-ed over
/// a face's corners — what the whole neighbourhood holds
/// (`Bfr::MultiVertexTag`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct CornerTag {
    /// On a boundary.
    pub boundary: bool,
    /// Infinitely sharp, explicitly or by its edges.
    pub inf_sharp: bool,
    /// Has infinitely sharp interior edges.
    pub inf_sharp_edges: bool,
    /// An interior vertex with exactly one infinitely sharp edge.
    pub inf_sharp_dart: bool,
    /// Semi-sharp.
    pub semi_sharp: bool,
    /// Has semi-sharp interior edges.
    pub semi_sharp_edges: bool,
    /// Its faces are not all of one size.
    pub uncommon_sizes: bool,
    /// A face around it is not of the scheme's regular size.
    pub irregular_sizes: bool,
    /// A boundary whose boundary edges are not both infinitely sharp.
    pub boundary_non_sharp: bool,
}

impl CornerTag {
    /// Both tags combined (`MultiVertexTag::Combine`).
    pub fn or(self, o: CornerTag) -> CornerTag {
        CornerTag {
            boundary: self.boundary | o.boundary,
            inf_sharp: self.inf_sharp | o.inf_sharp,
            inf_sharp_edges: self.inf_sharp_edges | o.inf_sharp_edges,
            inf_sharp_dart: self.inf_sharp_dart | o.inf_sharp_dart,
            semi_sharp: self.semi_sharp | o.semi_sharp,
            semi_sharp_edges: self.semi_sharp_edges | o.semi_sharp_edges,
            uncommon_sizes: self.uncommon_sizes | o.uncommon_sizes,
            irregular_sizes: self.irregular_sizes | o.irregular_sizes,
            boundary_non_sharp: self.boundary_non_sharp | o.boundary_non_sharp,
        }
    }

    /// Any sharp interior edge.
    pub fn sharp_edges(self) -> bool {
        self.inf_sharp_edges || self.semi_sharp_edges
    }

    /// Any sharp vertex.
    pub fn sharp_vertices(self) -> bool {
        self.inf_sharp || self.semi_sharp
    }
}

/// The faces around a corner of a face that its limit surface depends on
/// (`Bfr::FaceVertexSubset`): for a manifold vertex all of them, counted
/// before and after the corner's face in the ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Subset {
    /// Faces before the corner's face (clockwise; boundary rings only).
    pub before: usize,
    /// Faces after the corner's face (counter-clockwise).
    pub after: usize,
    /// All faces, the corner's included.
    pub total: usize,
    /// The corner's tags within the subset (sharpened by the boundary
    /// interpolation rules where they apply).
    pub tag: CornerTag,
}

impl Subset {
    /// On a boundary.
    pub fn is_boundary(&self) -> bool {
        self.tag.boundary
    }

    /// Infinitely sharp.
    pub fn is_sharp(&self) -> bool {
        self.tag.inf_sharp
    }

    /// Made infinitely sharp (`FaceVertex::SharpenSubset`).
    pub fn sharpen(&mut self) {
        self.tag.inf_sharp = true;
        self.tag.semi_sharp = false;
    }
}

/// One corner of a face and the faces around its vertex.
#[derive(Debug, Clone)]
pub(crate) struct Corner {
    /// Face `i`'s vertices, starting at the corner's vertex, at
    /// `offsets[i]..offsets[i + 1]`.
    offsets: Vec<usize>,
    indices: Vec<u32>,
    /// The sharpness of each face's leading (`2i`) and trailing (`2i + 1`)
    /// edges at the vertex; empty when none is sharp.
    edge_sharpness: Vec<f32>,
    /// Where the base face is in the ring.
    pub face_in_ring: usize,
    /// The vertex's own sharpness.
    pub vertex_sharpness: f32,
    /// What the neighbourhood holds.
    pub tag: CornerTag,
}

impl Corner {
    /// Corner `corner` of base face `face` of `level`, under a scheme whose
    /// regular faces have `reg_size` vertices; `None` when the corner's
    /// vertex is non-manifold.
    pub fn new(level: &Level, face: usize, corner: usize, reg_size: usize) -> Option<Corner> {
        let fverts = level.face_verts(face);
        let v = fverts[corner] as usize;
        let vtag = level.vertex_tag(v);
        if vtag.non_manifold() {
            return None;
        }
        let faces = level.vertex_faces_of(v);
        let n = faces.len();
        let local = |i: usize| -> usize {
            let f = faces[i] as usize;
            if level.has_local_indices() {
                usize::from(level.vertex_face_locals(v)[i])
            } else {
                level
                    .face_verts(f)
                    .iter()
                    .position(|&x| x as usize == v)
                    .unwrap_or(0)
            }
        };
        let face_in_ring = faces.iter().position(|&f| f as usize == face)?;
        let mut offsets = Vec::with_capacity(n + 1);
        let mut indices = Vec::new();
        offsets.push(0);
        let mut uncommon = false;
        let mut irregular = false;
        let base_size = fverts.len();
        for (i, &f) in faces.iter().enumerate() {
            let fv = level.face_verts(f as usize);
            let start = local(i);
            indices.extend(fv[start..].iter().chain(&fv[..start]));
            offsets.push(indices.len());
            uncommon |= fv.len() != base_size;
            irregular |= fv.len() != reg_size;
        }
        let boundary = vtag.boundary();
        let mut edge_sharpness = Vec::new();
        if vtag.semi_sharp_edges() || vtag.inf_sharp_edges() {
            edge_sharpness.reserve(2 * n);
            for (i, &f) in faces.iter().enumerate() {
                let fe = level.face_edges_of(f as usize);
                let j = local(i);
                let lead = fe[j] as usize;
                let trail = fe[(j + fe.len() - 1) % fe.len()] as usize;
                edge_sharpness.push(level.edge_sharpness_at(lead));
                edge_sharpness.push(level.edge_sharpness_at(trail));
            }
        }
        let vertex_sharpness = if vtag.semi_sharp() || vtag.inf_sharp() {
            level.vertex_sharpness_at(v)
        } else {
            0.0
        };
        let mut tag = CornerTag {
            boundary,
            inf_sharp: is_infinite(vertex_sharpness),
            semi_sharp: is_semi_sharp(vertex_sharpness),
            uncommon_sizes: uncommon,
            irregular_sizes: irregular,
            boundary_non_sharp: boundary,
            ..CornerTag::default()
        };
        if !edge_sharpness.is_empty() {
            let s = &edge_sharpness;
            if boundary {
                tag.boundary_non_sharp = !is_infinite(s[0]) || !is_infinite(s[2 * n - 1]);
            }
            let (mut inf, mut semi) = (0, 0);
            for i in usize::from(boundary)..n {
                if is_infinite(s[2 * i]) {
                    inf += 1;
                } else if is_sharp(s[2 * i]) {
                    semi += 1;
                }
            }
            tag.inf_sharp_edges = inf > 0;
            tag.semi_sharp_edges = semi > 0;
            tag.inf_sharp_dart = inf == 1 && !boundary;
            let inf_total = inf + 2 * usize::from(boundary);
            if inf_total > 2 && !tag.inf_sharp {
                tag.inf_sharp = true;
                tag.semi_sharp = false;
            }
        }
        Some(Corner {
            offsets,
            indices,
            edge_sharpness,
            face_in_ring,
            vertex_sharpness,
            tag,
        })
    }

    /// The number of faces around the vertex.
    pub fn face_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Face `f`'s vertices, starting at the corner's vertex.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.indices[self.offsets[f]..self.offsets[f + 1]]
    }

    /// The number of vertices of face `f`.
    pub fn face_size(&self, f: usize) -> usize {
        self.offsets[f + 1] - self.offsets[f]
    }

    /// The face after `f` in the ring (`GetFaceNext`).
    pub fn next(&self, f: usize) -> Option<usize> {
        let n = self.face_count();
        if f + 1 < n {
            Some(f + 1)
        } else if self.tag.boundary {
            None
        } else {
            Some(0)
        }
    }

    /// The face after `f`, wrapping around the ring (`GetFaceNext` where
    /// the ring goes on).
    pub fn after_face(&self, f: usize) -> usize {
        (f + 1) % self.face_count()
    }

    /// The face `step` after the corner's face (`GetFaceAfter`).
    pub fn after(&self, step: usize) -> usize {
        (self.face_in_ring + step) % self.face_count()
    }

    /// The face `step` before the corner's face (`GetFaceBefore`).
    pub fn before(&self, step: usize) -> usize {
        let n = self.face_count();
        (self.face_in_ring + n - step % n) % n
    }

    /// The first face of `subset` (`GetFaceFirst`).
    pub fn first(&self, subset: &Subset) -> usize {
        self.before(subset.before)
    }

    /// The last vertex of face `f` (the far end of its trailing edge).
    pub fn trailing(&self, f: usize) -> u32 {
        self.indices[self.offsets[f + 1] - 1]
    }

    /// The sharpness of face `f`'s leading (`false`) or trailing edge.
    pub fn edge_sharpness(&self, f: usize, trailing: bool) -> f32 {
        self.edge_sharpness
            .get(2 * f + usize::from(trailing))
            .copied()
            .unwrap_or(0.0)
    }

    /// The subset of a manifold vertex: all its faces
    /// (`FaceVertex::GetVertexSubset`).
    pub fn subset(&self) -> Subset {
        let n = self.face_count();
        let (before, after) = if self.tag.boundary {
            (self.face_in_ring, n - 1 - self.face_in_ring)
        } else {
            (0, n - 1)
        };
        Subset {
            before,
            after,
            total: n,
            tag: self.tag,
        }
    }
}
