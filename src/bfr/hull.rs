//! The control hull of a face whose limit surface is not one regular patch
//! (`Bfr::IrregularPatchBuilder`): the mesh vertices it depends on in Bfr's
//! order — the face's own, then those each corner's faces add, corner by
//! corner — and a small mesh of those vertices (the face first, then the
//! faces around each corner) carrying the sharpness that matters, from
//! which Bfr builds the face's patches.

use super::corner::{Corner, CornerTag, Subset};
use crate::mesh::{Mesh, SHARPNESS_INFINITE};
use crate::rules::crease::is_sharp;
use std::collections::HashMap;

/// What each corner adds to the hull.
#[derive(Debug, Clone, Copy, Default)]
struct CornerHull {
    verts: i64,
    faces: usize,
    /// The hull's first vertex this corner adds.
    next_vert: i64,
    /// Interior, valence 3, every corner so: one vertex shared by all.
    single_shared_vert: bool,
    /// Interior, valence 2, every corner so: one face shared by all.
    single_shared_face: bool,
}

/// A face's control hull.
#[derive(Debug, Clone)]
pub(crate) struct Hull {
    /// The mesh vertex of each hull vertex, in Bfr's order.
    pub control_points: Vec<u32>,
    /// The hull as a mesh of its vertices (positions unset), the face
    /// first.
    pub mesh: Mesh,
}

struct Builder<'a> {
    corners: &'a [Corner],
    subsets: &'a [Subset],
    hulls: Vec<CornerHull>,
    num_verts: i64,
    num_faces: usize,
    /// Incident faces overlap (interior corners of valence 2): vertices are
    /// found through a map.
    overlap: bool,
    map: HashMap<u32, u32>,
    verts: Vec<u32>,
}

impl<'a> Builder<'a> {
    fn new(corners: &'a [Corner], subsets: &'a [Subset]) -> Self {
        let n = corners.len();
        let mut b = Builder {
            corners,
            subsets,
            hulls: Vec::with_capacity(n),
            num_verts: n as i64,
            num_faces: 1,
            overlap: false,
            map: HashMap::new(),
            verts: Vec::new(),
        };
        let (mut val2, mut val3_tris) = (0, 0);
        for (c, s) in corners.iter().zip(subsets) {
            let mut h = CornerHull::default();
            if s.after > 0 {
                let mut next = c.after(1);
                if s.is_boundary() {
                    for _ in 1..s.after {
                        next = c.after_face(next);
                        h.verts += c.face_size(next) as i64 - 2;
                    }
                    h.faces = s.after - 1;
                    h.verts += 1;
                } else if s.total == 3 && c.face_size(c.after(2)) == 3 {
                    val3_tris += 1;
                    if val3_tris == n {
                        h.single_shared_vert = true;
                        h.verts = 1;
                    }
                    h.faces = 1;
                } else if s.total > 2 {
                    for _ in 2..s.total {
                        next = c.after_face(next);
                        h.verts += c.face_size(next) as i64 - 2;
                    }
                    h.faces = s.total - 2;
                    h.verts -= 1;
                } else {
                    val2 += 1;
                    if val2 == n {
                        h.single_shared_face = true;
                        h.faces = 1;
                    }
                }
            }
            if s.before > 0 {
                let mut next = c.first(s);
                for _ in 0..s.before {
                    h.verts += c.face_size(next) as i64 - 2;
                    next = c.after_face(next);
                }
                h.faces += s.before;
                h.verts -= 1;
            }
            h.next_vert = b.num_verts;
            b.num_faces += h.faces;
            b.num_verts += h.verts;
            b.hulls.push(h);
        }
        b.overlap = val2 > 0;
        if b.overlap {
            b.build_map();
        }
        b
    }

    fn base_face(&self) -> &[u32] {
        let c = &self.corners[0];
        c.face(c.face_in_ring)
    }

    fn add(&mut self, v: u32) {
        if let std::collections::hash_map::Entry::Vacant(e) = self.map.entry(v) {
            e.insert(self.verts.len() as u32);
            self.verts.push(v);
        }
    }

    fn add_face(&mut self, corner: usize, f: usize) {
        let face = self.corners[corner].face(f).to_vec();
        for &v in &face[1..] {
            self.add(v);
        }
    }

    /// `initializeControlVertexMap`.
    fn build_map(&mut self) {
        let base = self.base_face().to_vec();
        for (i, &v) in base.iter().enumerate() {
            self.add(v);
            if self.verts.len() == i {
                self.verts.push(v);
            }
        }
        for k in 0..self.corners.len() {
            let (c, s, h) = (&self.corners[k], self.subsets[k], self.hulls[k]);
            if h.faces == 0 {
                continue;
            }
            if h.single_shared_face {
                let f = c.after(1);
                self.add_face(k, f);
                continue;
            }
            let mut faces = Vec::new();
            if s.after > 1 {
                let mut next = c.after(1);
                for _ in 1..s.after {
                    next = c.after_face(next);
                    faces.push(next);
                }
            }
            if s.before > 0 {
                let mut next = c.first(&s);
                for _ in 0..s.before {
                    faces.push(next);
                    next = c.after_face(next);
                }
            }
            for f in faces {
                self.add_face(k, f);
            }
        }
        self.num_verts = self.verts.len() as i64;
    }

    /// `GatherControlVertexIndices`.
    fn control_points(&self) -> Vec<u32> {
        if self.overlap {
            return self.verts.clone();
        }
        let mut out = self.base_face().to_vec();
        for ((c, s), h) in self.corners.iter().zip(self.subsets).zip(&self.hulls) {
            if h.verts == 0 {
                continue;
            }
            if h.single_shared_vert {
                out.push(c.face(c.after(2))[1]);
                continue;
            }
            if s.after > 1 {
                let mut next = c.after(1);
                let n = s.after - 1;
                for j in 0..n {
                    next = c.after_face(next);
                    let fv = c.face(next);
                    let last = usize::from(j + 1 == n && !s.is_boundary());
                    out.extend_from_slice(&fv[1..=fv.len() - 2 - last]);
                }
            }
            if s.after > 0 && s.is_boundary() {
                out.push(c.trailing(c.after(s.after)));
            }
            if s.before > 0 {
                let mut next = c.first(s);
                for j in 0..s.before {
                    let fv = c.face(next);
                    let last = usize::from(j + 1 == s.before);
                    out.extend_from_slice(&fv[1..=fv.len() - 2 - last]);
                    next = c.after_face(next);
                }
            }
        }
        out
    }

    fn local(&self, v: u32) -> u32 {
        self.map.get(&v).copied().unwrap_or(0)
    }

    /// A face around `corner` whose other vertices run along the hull's
    /// perimeter from `next`, wrapping to the face (`getControlFaceVertices`).
    fn perimeter_face(&self, size: usize, corner: usize, next: i64, last_face: bool) -> Vec<u32> {
        let n = self.corners.len() as i64;
        let wrap = |x: i64| if x == self.num_verts { n } else { x };
        let mut f = Vec::with_capacity(size);
        f.push(corner as u32);
        for i in 1..size as i64 - 2 {
            f.push((next + i - 1) as u32);
        }
        f.push(wrap(next + size as i64 - 3) as u32);
        let last = if last_face {
            (corner as i64 + 1) % n
        } else {
            wrap(next + size as i64 - 2)
        };
        f.push(last as u32);
        f
    }

    fn mapped_face(&self, corner: usize, f: usize) -> Vec<u32> {
        let fv = self.corners[corner].face(f);
        std::iter::once(corner as u32)
            .chain(fv[1..].iter().map(|&v| self.local(v)))
            .collect()
    }

    /// `gatherControlFaces`.
    fn faces(&self) -> Vec<Vec<u32>> {
        let n = self.corners.len();
        let mut faces = vec![(0..n as u32).collect::<Vec<_>>()];
        for (k, ((c, s), h)) in self
            .corners
            .iter()
            .zip(self.subsets)
            .zip(&self.hulls)
            .enumerate()
        {
            if h.faces == 0 {
                continue;
            }
            if h.single_shared_face {
                faces.push(self.mapped_face(k, c.after(1)));
                continue;
            }
            let mut next_vert = h.next_vert;
            if s.after > 1 {
                let mut next = c.after(2);
                let m = s.after - 1;
                for j in 0..m {
                    let size = c.face_size(next);
                    faces.push(if self.overlap {
                        self.mapped_face(k, next)
                    } else if s.is_boundary() {
                        (0..size)
                            .map(|i| if i == 0 { k as i64 } else { next_vert + i as i64 - 1 } as u32)
                            .collect()
                    } else {
                        self.perimeter_face(size, k, next_vert, j + 1 == m)
                    });
                    next_vert += size as i64 - 2;
                    next = c.after_face(next);
                }
            }
            if s.after > 0 && s.is_boundary() {
                next_vert += 1;
            }
            if s.before > 0 {
                let mut next = c.first(s);
                for j in 0..s.before {
                    let size = c.face_size(next);
                    faces.push(if self.overlap {
                        self.mapped_face(k, next)
                    } else {
                        self.perimeter_face(size, k, next_vert, j + 1 == s.before)
                    });
                    next_vert += size as i64 - 2;
                    next = c.after_face(next);
                }
            }
        }
        faces
    }

    /// `gatherControlVertexSharpness`.
    fn corner_sharpness(&self) -> Vec<(u32, f32)> {
        let mut out = Vec::new();
        for (i, (c, s)) in self.corners.iter().zip(self.subsets).enumerate() {
            if s.tag.inf_sharp {
                out.push((i as u32, SHARPNESS_INFINITE));
            } else if s.tag.semi_sharp {
                let sharpness = if s.local_sharpness > 0.0 {
                    s.local_sharpness
                } else {
                    c.vertex_sharpness
                };
                out.push((i as u32, sharpness));
            }
        }
        out
    }

    /// `gatherControlEdgeSharpness`.
    fn edge_sharpness(&self) -> Vec<(u32, u32, f32)> {
        let n = self.corners.len();
        let mut out = Vec::new();
        for (k, (c, s)) in self.corners.iter().zip(self.subsets).enumerate() {
            if !s.tag.sharp_edges() {
                continue;
            }
            if !s.is_boundary() || s.before > 0 {
                let sharp = c.edge_sharpness(c.face_in_ring, false);
                if is_sharp(sharp) {
                    out.push((k as u32, ((k + 1) % n) as u32, sharp));
                }
            }
        }
        for (k, ((c, s), h)) in self
            .corners
            .iter()
            .zip(self.subsets)
            .zip(&self.hulls)
            .enumerate()
        {
            if !s.tag.sharp_edges() || h.faces == 0 {
                continue;
            }
            let mut next_vert = h.next_vert;
            let end = |next_vert: i64, f: usize| -> u32 {
                if self.overlap {
                    self.local(c.trailing(f))
                } else if next_vert < self.num_verts {
                    next_vert as u32
                } else {
                    n as u32
                }
            };
            if s.after > 1 {
                let mut next = c.after(1);
                for _ in 1..s.after {
                    let sharp = c.edge_sharpness(next, true);
                    if is_sharp(sharp) {
                        out.push((k as u32, end(next_vert, next), sharp));
                    }
                    next = c.after_face(next);
                    next_vert += c.face_size(next) as i64 - 2;
                }
            }
            if s.after > 0 && s.is_boundary() {
                next_vert += 1;
            }
            if s.before > 0 {
                let mut next = c.first(s);
                for _ in 1..s.before {
                    next_vert += c.face_size(next) as i64 - 2;
                    let sharp = c.edge_sharpness(next, true);
                    if is_sharp(sharp) {
                        out.push((k as u32, end(next_vert, next), sharp));
                    }
                    next = c.after_face(next);
                }
            }
        }
        out
    }
}

/// Whether faces `a` and `b` have the same vertices in the same cyclic
/// order.
fn same_face(a: &[u32], b: &[u32]) -> bool {
    a.len() == b.len()
        && b.iter().position(|&x| x == a[0]).is_some_and(|start| {
            a.iter()
                .enumerate()
                .all(|(i, &x)| b[(start + i) % b.len()] == x)
        })
}

/// The control hull of a face from its corners and their subsets; `tag`
/// is the subsets' tags combined.
pub(crate) fn hull(corners: &[Corner], subsets: &[Subset], tag: CornerTag) -> Hull {
    let b = Builder::new(corners, subsets);
    let control_points = b.control_points();
    let mut faces = b.faces();
    let corner_sharpness = if tag.sharp_vertices() {
        b.corner_sharpness()
    } else {
        Vec::new()
    };
    let mut creases = if tag.sharp_edges() {
        b.edge_sharpness()
    } else {
        Vec::new()
    };
    if b.overlap {
        // Later duplicates of earlier faces (the face itself excepted).
        if faces.len() > 2 {
            let mut keep = vec![true; faces.len()];
            for i in (2..faces.len()).rev() {
                keep[i] = !(1..i).any(|j| same_face(&faces[i], &faces[j]));
            }
            let mut k = keep.iter();
            faces.retain(|_| *k.next().unwrap_or(&true));
        }
        if tag.boundary {
            let n = corners.len();
            for (k, s) in subsets.iter().enumerate() {
                if s.is_boundary() && s.before == 0 {
                    creases.push((k as u32, ((k + 1) % n) as u32, SHARPNESS_INFINITE));
                }
            }
        }
    }
    let mut mesh = Mesh {
        positions: vec![glam::DVec3::ZERO; control_points.len()],
        ..Mesh::default()
    };
    for f in &faces {
        mesh.add_face(f);
    }
    for (v0, v1, s) in creases {
        mesh.add_crease(v0, v1, s);
    }
    for (v, s) in corner_sharpness {
        mesh.add_corner(v, s);
    }
    Hull {
        control_points,
        mesh,
    }
}
