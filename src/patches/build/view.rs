//! A level's relations as plain slices ([`LevelView`]), read through the
//! tables' representations once per level instead of on every access, for
//! the patch builder's commonest case: a regular interior patch.

use super::Builder;
use super::points::PER_CORNER;
use crate::topology::{Level, Offsets};

/// A level's face-vertex and vertex-face relations as slices, and whether
/// each vertex is "plain": not extraordinary, without an infinitely sharp
/// tag or edge ([`LevelView::plain_face`]).
pub(super) struct LevelView<'a> {
    face_vertices: &'a [u32],
    /// Where each face starts in `face_vertices` (one more entry than
    /// faces); `None` when every face has four vertices.
    face_offsets: Option<&'a [u32]>,
    /// Where each vertex's faces start; `None` where the level keeps no
    /// local indices (then no quad's points are read here).
    vertex_offsets: Option<&'a [u32]>,
    vertex_faces: &'a [u32],
    vertex_face_locals: &'a [u16],
    plain: Vec<bool>,
}

impl<'a> LevelView<'a> {
    /// The view of level `level` of `builder`.
    pub(super) fn new(builder: &Builder<'a>, level: usize) -> Self {
        let l: &'a Level = &builder.levels[level];
        let features = &builder.features[level];
        let face_offsets = match &l.face_vertices.offsets {
            Offsets::Uniform { size: 4, .. } => None,
            // (Faces of another uniform size: no face is a quad.)
            Offsets::Uniform { .. } => Some(&[][..]),
            Offsets::Table(t) => Some(&t[..]),
        };
        let vertex_offsets = match &l.vertex_faces.offsets {
            Offsets::Table(t) if l.has_local_indices() => Some(&t[..]),
            _ => None,
        };
        let plain = (0..l.vertex_count)
            .map(|v| {
                let t = l.vertex_tag(v);
                !t.inf_sharp() && !t.inf_sharp_edges() && !features[v].xordinary
            })
            .collect();
        LevelView {
            face_vertices: &l.face_vertices.members,
            face_offsets,
            vertex_offsets,
            vertex_faces: &l.vertex_faces.members,
            vertex_face_locals: &l.vertex_face_local,
            plain,
        }
    }

    /// The vertices of face `f`.
    #[inline(always)]
    fn face(&self, f: usize) -> Option<&[u32]> {
        match self.face_offsets {
            None => self.face_vertices.get(4 * f..4 * f + 4),
            Some(o) => self
                .face_vertices
                .get(*o.get(f)? as usize..*o.get(f + 1)? as usize),
        }
    }

    /// Where quad `f` starts in the face-vertex list; `None` if it is not
    /// a quad.
    #[inline(always)]
    fn quad_start(&self, f: usize) -> Option<usize> {
        match self.face_offsets {
            None => Some(4 * f),
            Some(o) => {
                let (s, e) = (*o.get(f)? as usize, *o.get(f + 1)? as usize);
                (e.checked_sub(s) == Some(4)).then_some(s)
            }
        }
    }

    /// Whether no corner of face `f` is extraordinary or has an infinitely
    /// sharp vertex or edge: then its patch is regular with boundary mask 0
    /// (what [`Builder::is_regular_with`] and [`Builder::boundary_mask_with`]
    /// conclude from the combined tags). The case of nearly every patch.
    #[inline]
    pub(super) fn plain_face(&self, f: usize) -> bool {
        self.face(f)
            .is_some_and(|verts| verts.iter().all(|&v| self.plain[v as usize]))
    }

    /// The points of the B-spline patch of interior quad `f` whose corners
    /// all have four faces (nearly every patch of a quad mesh), each plus
    /// `offset`, written into `out`: at each corner its vertex and the
    /// opposite face's other three. `None` for any other face (`out` then
    /// partly written).
    #[inline]
    pub(super) fn quad_points_into(
        &self,
        f: usize,
        offset: u32,
        out: &mut [u32; 16],
    ) -> Option<()> {
        let vertex_offsets = self.vertex_offsets?;
        let start = self.quad_start(f)?;
        let verts = self.face_vertices.get(start..start + 4)?;
        for (&v, slots) in verts.iter().zip(&PER_CORNER) {
            let v = v as usize;
            let first = *vertex_offsets.get(v)? as usize;
            if *vertex_offsets.get(v + 1)? as usize != first + 4 {
                return None;
            }
            let faces = self.vertex_faces.get(first..first + 4)?;
            let at = faces.iter().position(|&x| x as usize == f)?;
            let opposite = (at + 2) & 3;
            let there = self.quad_start(faces[opposite] as usize)?;
            let k = usize::from(*self.vertex_face_locals.get(first + opposite)?);
            let p = self.face_vertices.get(there..there + 4)?;
            out[slots[0]] = v as u32 + offset;
            out[slots[1]] = p[(k + 1) & 3] + offset;
            out[slots[2]] = p[(k + 2) & 3] + offset;
            out[slots[3]] = p[(k + 3) & 3] + offset;
        }
        Some(())
    }
}
