//! A level's relations as plain slices ([`LevelView`]), read through the
//! tables' representations once per level instead of on every access, for
//! the patch builder's commonest case: a regular interior patch.

use super::Builder;
use super::points::{PER_CORNER, TRIANGLE_PER_CORNER};
use crate::topology::{Level, Offsets, RelationView};

/// A level's face-vertex and vertex-face relations as slices, and whether
/// each vertex is "plain": not extraordinary, without an infinitely sharp
/// tag or edge ([`LevelView::plain_face`]).
pub(super) struct LevelView<'a> {
    /// The face-vertex relation.
    faces: RelationView<'a>,
    /// Where each vertex's faces start; `None` where the level keeps no
    /// local indices (then no patch's points are read here).
    vertex_offsets: Option<&'a [u32]>,
    vertex_faces: &'a [u32],
    vertex_face_locals: &'a [u16],
    plain: Vec<bool>,
    /// The scheme's regular face size.
    size: usize,
}

impl<'a> LevelView<'a> {
    /// The view of level `level` of `builder`.
    pub(super) fn new(builder: &Builder<'a>, level: usize) -> Self {
        let l: &'a Level = &builder.levels[level];
        let features = &builder.features[level];
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
            faces: l.face_vertices.view(),
            vertex_offsets,
            vertex_faces: &l.vertex_faces.members,
            vertex_face_locals: &l.vertex_face_local,
            plain,
            size: builder.reg,
        }
    }

    /// The vertices of face `f`.
    #[inline(always)]
    fn face(&self, f: usize) -> Option<&[u32]> {
        self.faces.try_get(f)
    }

    /// The vertices of face `f` if it has `N` of them.
    #[inline(always)]
    fn sized<const N: usize>(&self, f: usize) -> Option<&[u32; N]> {
        let start = self.faces.start_if_sized(f, N)?;
        self.faces.members.get(start..start + N)?.try_into().ok()
    }

    /// The faces around vertex `v` and its position in each, if it has
    /// `N` faces (and the level keeps local indices).
    #[inline(always)]
    fn ring<const N: usize>(&self, v: usize) -> Option<(&[u32; N], &[u16; N])> {
        let offsets = self.vertex_offsets?;
        let first = *offsets.get(v)? as usize;
        if *offsets.get(v + 1)? as usize != first + N {
            return None;
        }
        let faces = self.vertex_faces.get(first..first + N)?.try_into().ok()?;
        let locals = self.vertex_face_locals.get(first..first + N)?;
        Some((faces, locals.try_into().ok()?))
    }

    /// Whether face `f` has the scheme's regular size and no corner of it
    /// is extraordinary or has an infinitely sharp vertex or edge: then
    /// its patch is regular with boundary mask 0 (what
    /// [`Builder::is_regular_with`] and [`Builder::boundary_mask_with`]
    /// conclude from the combined tags). The case of nearly every patch.
    #[inline]
    pub(super) fn plain_face(&self, f: usize) -> bool {
        self.face(f).is_some_and(|verts| {
            verts.len() == self.size && verts.iter().all(|&v| self.plain[v as usize])
        })
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
        let verts = self.sized::<4>(f)?;
        for (&v, slots) in verts.iter().zip(&PER_CORNER) {
            let (faces, locals) = self.ring::<4>(v as usize)?;
            let at = faces.iter().position(|&x| x as usize == f)?;
            let opposite = (at + 2) & 3;
            let p = self.sized::<4>(faces[opposite] as usize)?;
            let k = usize::from(locals[opposite]);
            out[slots[0]] = v + offset;
            out[slots[1]] = p[(k + 1) & 3] + offset;
            out[slots[2]] = p[(k + 2) & 3] + offset;
            out[slots[3]] = p[(k + 3) & 3] + offset;
        }
        Some(())
    }

    /// The points of the box-spline patch of interior triangle `f` whose
    /// corners all have six faces (nearly every patch of a Loop mesh),
    /// each plus `offset`, written into `out`: at each corner its vertex,
    /// the far vertex of the second face after `f` around it and the two
    /// far vertices of the third. `None` for any other face (`out` then
    /// partly written).
    #[inline]
    pub(super) fn triangle_points_into(
        &self,
        f: usize,
        offset: u32,
        out: &mut [u32; 12],
    ) -> Option<()> {
        let verts = self.sized::<3>(f)?;
        for (&v, slots) in verts.iter().zip(&TRIANGLE_PER_CORNER) {
            let (faces, locals) = self.ring::<6>(v as usize)?;
            let at = faces.iter().position(|&x| x as usize == f)?;
            let (i2, i3) = ((at + 2) % 6, (at + 3) % 6);
            let (p2, k2) = (self.sized::<3>(faces[i2] as usize)?, locals[i2]);
            let (p3, k3) = (self.sized::<3>(faces[i3] as usize)?, locals[i3]);
            let at = |p: &[u32; 3], k: u16| p[usize::from(k) % 3] + offset;
            out[slots[0]] = v + offset;
            out[slots[1]] = at(p2, k2 + 1);
            out[slots[2]] = at(p3, k3 + 1);
            out[slots[3]] = at(p3, k3 + 2);
        }
        Some(())
    }
}
