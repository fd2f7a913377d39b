//! The tables of legacy Gregory patches (`PatchTableBuilder::
//! LegacyGregoryHelper`): for each patch, interior patches first, the
//! positions of its face in the rings of its four corners (quad offsets);
//! for each vertex of the last level, its ring of neighbours (vertex
//! valences). OpenSubdiv reads them from the last level only, so a table
//! with an irregular patch above it, a face there that is not a quad or a
//! non-manifold vertex there is refused (OpenSubdiv would read and write
//! out of bounds; the `osd` engine refuses the same).

use super::{Builder, Patch};
use crate::error::{Error, Result};

/// The faces of the legacy Gregory patches, interior and boundary apart.
#[derive(Debug, Default)]
pub(super) struct Faces {
    interior: Vec<usize>,
    boundary: Vec<usize>,
}

impl Faces {
    pub(super) fn add(&mut self, face: usize, boundary: bool) {
        if boundary {
            self.boundary.push(face);
        } else {
            self.interior.push(face);
        }
    }
}

impl Builder<'_> {
    /// Refuses what OpenSubdiv's legacy Gregory tables cannot describe.
    pub(super) fn check_legacy(&self, patches: &[Patch], regular: &[bool]) -> Result<()> {
        let max = self.max_level();
        let last = &self.levels[max];
        if let Some(f) = (0..last.face_count()).find(|&f| last.face_vertices.count(f) != 4) {
            return Err(Error::PatchOptions {
                reason: format!(
                    "legacy Gregory end caps need quads in the last level; face {f} of level \
                     {max} has {} vertices",
                    last.face_vertices.count(f)
                ),
            });
        }
        if let Some(v) = (0..last.vertex_count).find(|&v| last.vertex_tag(v).non_manifold()) {
            return Err(Error::PatchOptions {
                reason: format!(
                    "legacy Gregory end caps need a manifold last level; vertex {v} of level \
                     {max} is non-manifold"
                ),
            });
        }
        if let Some(p) = patches
            .iter()
            .zip(regular)
            .find(|(p, r)| !**r && p.level != max)
        {
            return Err(Error::PatchOptions {
                reason: format!(
                    "legacy Gregory end caps need every irregular patch in the last level \
                     ({max}); one is at level {}",
                    p.0.level
                ),
            });
        }
        Ok(())
    }

    /// For each corner of each patch face, its position in the corner's
    /// faces and the next position modulo the corner's edges, in one word
    /// (`QuadOffsetsTable`).
    pub(super) fn quad_offsets(&self, faces: &Faces) -> Vec<u32> {
        let last = &self.levels[self.max_level()];
        let mut out = Vec::with_capacity(4 * (faces.interior.len() + faces.boundary.len()));
        for &f in faces.interior.iter().chain(&faces.boundary) {
            for &v in last.face_verts(f) {
                let at = last
                    .vertex_faces_of(v as usize)
                    .iter()
                    .position(|&x| x as usize == f)
                    .unwrap_or(0);
                let edges = last.vertex_edges_of(v as usize).len().max(1);
                out.push(at as u32 | ((((at + 1) % edges) as u32) << 8));
            }
        }
        out
    }

    /// The ring of every vertex of the last level, `2 * max_valence + 1`
    /// entries per vertex of every level (zero above the last): its
    /// valence (negative on a boundary, whose last ring point is repeated),
    /// then the two points each face contributes counter-clockwise
    /// (`VertexValenceTable`).
    pub(super) fn vertex_valences(&self, max_valence: usize, last_offset: u32) -> Vec<i32> {
        let width = 2 * max_valence + 1;
        let total: usize = self.levels.iter().map(|l| l.vertex_count).sum();
        let mut table = crate::alloc::vec_or_unwind(0i32, total * width);
        let max = self.max_level();
        for v in 0..self.levels[max].vertex_count {
            let ring = self.quad_ring(max, v as u32, None);
            let entry = &mut table[(last_offset as usize + v) * width..][..width];
            for (slot, &r) in entry[1..].iter_mut().zip(&ring) {
                *slot = (r + last_offset) as i32;
            }
            let mut size = ring.len();
            if size % 2 == 1 {
                size += 1;
                if size < width {
                    entry[size] = entry[size - 1];
                }
                entry[0] = -((size / 2) as i32);
            } else {
                entry[0] = (size / 2) as i32;
            }
        }
        table
    }
}
