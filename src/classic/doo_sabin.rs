//! Doo-Sabin subdivision of arbitrary polygon meshes: the generalisation of
//! Chaikin's corner cutting to surfaces.
//!
//! One level makes a new point for every face corner (a *corner point*) and
//! three kinds of faces:
//!
//! - an **F-face** for every face: its corner points, in the face's order;
//! - an **E-face** for every edge shared by two faces: the quad of the two
//!   corner points at each end of the edge;
//! - a **V-face** for every vertex surrounded by faces: its corner points in
//!   the faces around it (a vertex of valence `k` gives a `k`-gon).
//!
//! The corner point of corner `i` of an `n`-sided face with vertices `v_j` is
//! `Σ_j α_ij v_j`:
//!
//! - [`Weights::Original`] (Doo and Sabin, 1978): `α_ii = (n + 5) / (4n)`,
//!   `α_ij = (3 + 2 cos(2π (i - j) / n)) / (4n)` for `j ≠ i`;
//! - [`Weights::Centroid`]: the average of the vertex, the midpoints of its two
//!   edges in the face and the face's centroid,
//!   `(v_i + (v_i + v_{i+1}) / 2 + (v_{i-1} + v_i) / 2 + c) / 4`.
//!
//! Both give `9/16, 3/16, 1/16, 3/16` on a quad, the tensor product of
//! Chaikin's `3/4, 1/4`: on a regular quad grid one level is one level of
//! biquadratic B-spline splitting ([`crate::patch`]); they differ on other
//! polygons (a triangle: `2/3, 1/6, 1/6` against `7/12, 5/24, 5/24`).
//!
//! # Output order
//!
//! The corner point of face corner `c` (the index into [`Mesh::face_vertices`])
//! is vertex `c` of the result; boundary points (see below) follow. Faces come
//! as all F-faces (in face order), then all E-faces (in the order of the face
//! corner that starts the edge, first seen), then all V-faces (in vertex order).
//! All faces keep the input's orientation.
//!
//! # Boundaries
//!
//! An edge with one face is a boundary edge; an edge with more than two faces,
//! or whose two faces run along it in the same direction, is non-manifold.
//!
//! - [`Boundary::Open`] (the default) makes E-faces only for manifold interior
//!   edges and V-faces only for vertices whose faces form one closed fan (at
//!   least 3 of them). The surface shrinks away from the boundary exactly as an
//!   open B-spline surface does from its control grid: on a regular quad grid
//!   the result is the biquadratic B-spline's refined grid, whose boundary is
//!   the quadratic B-spline through the midpoints of the boundary strip.
//!   Non-manifold edges and vertices are accepted and treated like boundaries.
//! - [`Boundary::Chaikin`] keeps the boundary where it is: every boundary edge
//!   `a → b` gets two *boundary points* `3/4 a + 1/4 b` and `1/4 a + 3/4 b`
//!   (vertices `C + 2k` and `C + 2k + 1` for the `k`-th boundary edge in corner
//!   order, `C` the number of corners) and an E-face joining them to the edge's
//!   corner points; every boundary vertex gets a V-face from the boundary
//!   point before it, through its corner points, to the boundary point after
//!   it. The new boundary polygon is Chaikin's refinement of the old one, so
//!   the limit boundary is the quadratic B-spline of the boundary polygon
//!   ([`crate::curve::chaikin`]). This mode needs a manifold mesh.
//!
//! Creases, corners, holes and face-varying channels are not used (the result
//! has none); vertices in no face are dropped.
//!
//! ```
//! use subdiv::doo_sabin::{refine, DooSabinOptions};
//! let cube = subdiv::shapes::cube();
//! let levels = refine(&cube, &DooSabinOptions::default(), 2)?;
//! // 24 corners; faces: 6 F-quads + 12 E-quads + 8 V-triangles.
//! assert_eq!((levels[1].vertex_count(), levels[1].face_count()), (24, 26));
//! // 6·4 + 12·4 + 8·3 = 96 corners; faces: 26 F + 48 E + 24 V.
//! assert_eq!((levels[2].vertex_count(), levels[2].face_count()), (96, 26 + 48 + 24));
//! # Ok::<(), subdiv::doo_sabin::DooSabinError>(())
//! ```

use crate::mesh::{Mesh, MeshError};
use glam::DVec3;
use std::collections::HashMap;
use std::f64::consts::TAU;

use crate::names::impl_named;
use thiserror::Error;

/// The corner-point weights.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Weights {
    /// Doo and Sabin's: `α_ii = (n + 5) / (4n)`, `α_ij = (3 + 2 cos(2π(i-j)/n)) / (4n)`.
    #[default]
    Original,
    /// The average of the vertex, its two edge midpoints and the face centroid.
    Centroid,
}

/// How boundaries are treated (see the [module documentation](self#boundaries)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Boundary {
    /// No faces along the boundary: the surface shrinks like an open B-spline surface.
    #[default]
    Open,
    /// Boundary polygons refined by Chaikin's rule: the boundary stays.
    Chaikin,
}

impl_named!(Weights, "Doo-Sabin weights", { Original => "original", Centroid => "centroid" });
impl_named!(Boundary, "Doo-Sabin boundary", { Open => "open", Chaikin => "chaikin" });

/// Doo-Sabin options.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct DooSabinOptions {
    /// The corner-point weights.
    pub weights: Weights,
    /// The boundary rule.
    pub boundary: Boundary,
}

/// The largest number of vertices or face corners a refined mesh may have.
pub const MAX_ELEMENTS: usize = i32::MAX as usize;

/// Why a Doo-Sabin refinement was refused.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DooSabinError {
    /// The input mesh is invalid.
    #[error("invalid mesh: {0}")]
    Mesh(#[from] MeshError),
    /// An edge with more than two faces, or two faces along it in the same direction
    /// (refused by [`Boundary::Chaikin`]).
    #[error(
        "edge {a}-{b} is non-manifold ({faces} faces, or two faces in the same direction); the chaikin boundary needs a manifold mesh"
    )]
    NonManifoldEdge {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
        /// How many faces use the edge.
        faces: usize,
    },
    /// A vertex whose faces do not form one fan (refused by [`Boundary::Chaikin`]).
    #[error(
        "vertex {0} is non-manifold (its faces do not form one fan); the chaikin boundary needs a manifold mesh"
    )]
    NonManifoldVertex(u32),
    /// The refined mesh would be too large.
    #[error("level {level} would have more than {MAX_ELEMENTS} vertices or face corners")]
    TooLarge {
        /// The level refused.
        level: u32,
    },
}

/// The weights `α_i0 … α_i(n-1)` of the corner point of corner `i` of an
/// `n`-sided face (they sum to 1). Weights that are simple fractions (cosines
/// of multiples of π/3 and π/2) are computed exactly.
///
/// ```
/// use subdiv::doo_sabin::{corner_weights, Weights};
/// assert_eq!(corner_weights(4, 0, Weights::Original), [9.0 / 16.0, 3.0 / 16.0, 1.0 / 16.0, 3.0 / 16.0]);
/// assert_eq!(corner_weights(3, 1, Weights::Original), [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0]);
/// assert_eq!(corner_weights(3, 0, Weights::Centroid), [7.0 / 12.0, 5.0 / 24.0, 5.0 / 24.0]);
/// ```
pub fn corner_weights(n: usize, i: usize, weights: Weights) -> Vec<f64> {
    if n == 0 {
        return Vec::new();
    }
    let nf = n as f64;
    (0..n)
        .map(|j| {
            let k = (j + n - i % n) % n; // j - i mod n
            match weights {
                Weights::Original => {
                    // 3 + 2 cos(2πk/n), exact where the cosine is 0 or ±1/2 or -1.
                    let numerator = if k == 0 {
                        return (nf + 5.0) / (4.0 * nf);
                    } else if 2 * k == n {
                        1.0
                    } else if 4 * k == n || 4 * k == 3 * n {
                        3.0
                    } else if 3 * k == n || 3 * k == 2 * n {
                        2.0
                    } else if 6 * k == n || 6 * k == 5 * n {
                        4.0
                    } else {
                        3.0 + 2.0 * (TAU * k as f64 / nf).cos()
                    };
                    numerator / (4.0 * nf)
                }
                Weights::Centroid => {
                    if k == 0 {
                        (2.0 * nf + 1.0) / (4.0 * nf)
                    } else if k == 1 || k + 1 == n {
                        (nf + 2.0) / (8.0 * nf)
                    } else {
                        1.0 / (4.0 * nf)
                    }
                }
            }
        })
        .collect()
}

/// Levels 0 (the input's positions and faces) to `levels` of Doo-Sabin
/// subdivision: `levels + 1` meshes.
pub fn refine(
    mesh: &Mesh,
    options: &DooSabinOptions,
    levels: u32,
) -> Result<Vec<Mesh>, DooSabinError> {
    mesh.validate()?;
    let mesh = &*mesh.right_handed();
    let base = Mesh {
        positions: mesh.positions.clone(),
        face_offsets: mesh.face_offsets.clone(),
        face_vertices: mesh.face_vertices.clone(),
        ..Mesh::default()
    };
    let mut all = vec![base];
    for level in 1..=levels {
        let next = refine_level(&all[all.len() - 1], options, level)?;
        all.push(next);
    }
    Ok(all)
}

/// One level of Doo-Sabin subdivision.
pub fn refine_once(mesh: &Mesh, options: &DooSabinOptions) -> Result<Mesh, DooSabinError> {
    mesh.validate()?;
    refine_level(&mesh.right_handed(), options, 1)
}

/// The half-edge structure of a face-vertex mesh: for every face corner, the
/// previous and next corner in its face and the twin corner (the corner of the
/// other face that starts the same edge the other way).
struct Corners {
    next: Vec<usize>,
    prev: Vec<usize>,
    /// The corner across the edge `c → next(c)`, when the edge is manifold interior.
    twin: Vec<Option<usize>>,
    /// How many corners start the undirected edge `c → next(c)` (either way).
    edge_uses: Vec<usize>,
}

impl Corners {
    fn new(mesh: &Mesh) -> Corners {
        let nc = mesh.face_vertices.len();
        let mut next = vec![0; nc];
        let mut prev = vec![0; nc];
        for w in mesh.face_offsets.windows(2) {
            let (a, b) = (w[0] as usize, w[1] as usize);
            let n = b - a;
            for k in 0..n {
                next[a + k] = a + (k + 1) % n;
                prev[a + k] = a + (k + n - 1) % n;
            }
        }
        let fv = &mesh.face_vertices;
        let mut edges: HashMap<(u32, u32), Vec<usize>> = HashMap::with_capacity(nc);
        for c in 0..nc {
            let (a, b) = (fv[c], fv[next[c]]);
            edges.entry((a.min(b), a.max(b))).or_default().push(c);
        }
        let mut twin = vec![None; nc];
        let mut edge_uses = vec![0; nc];
        for uses in edges.values() {
            for &c in uses {
                edge_uses[c] = uses.len();
            }
            if let &[c, d] = uses.as_slice() {
                // Manifold interior: the two faces run along it in opposite directions.
                if fv[c] == fv[next[d]] && fv[next[c]] == fv[d] && fv[c] != fv[d] {
                    twin[c] = Some(d);
                    twin[d] = Some(c);
                }
            }
        }
        Corners {
            next,
            prev,
            twin,
            edge_uses,
        }
    }

    /// The next corner around the same vertex, in the order of the V-face (so
    /// that it runs against the E-faces): the twin of the corner entering `c`.
    fn turn(&self, c: usize) -> Option<usize> {
        self.twin[self.prev[c]]
    }
}

fn refine_level(mesh: &Mesh, options: &DooSabinOptions, level: u32) -> Result<Mesh, DooSabinError> {
    let nc = mesh.face_vertices.len();
    // At most 3 points per corner and 7 face corners per corner (F: 1, E: 4, V: 1 + 2).
    if nc.checked_mul(7).is_none_or(|n| n > MAX_ELEMENTS) {
        return Err(DooSabinError::TooLarge { level });
    }
    let fv = &mesh.face_vertices;
    let pos = &mesh.positions;
    let corners = Corners::new(mesh);
    let chaikin = options.boundary == Boundary::Chaikin;

    // Corner points, face by face: vertex c is the corner point of corner c.
    let mut positions = Vec::with_capacity(nc);
    let mut weight_cache: HashMap<usize, Vec<Vec<f64>>> = HashMap::new();
    for verts in mesh.faces() {
        let n = verts.len();
        let table = weight_cache.entry(n).or_insert_with(|| {
            (0..n)
                .map(|i| corner_weights(n, i, options.weights))
                .collect()
        });
        for row in table.iter() {
            let p = verts
                .iter()
                .zip(row)
                .fold(DVec3::ZERO, |acc, (&v, &w)| acc + pos[v as usize] * w);
            positions.push(p);
        }
    }

    // Chaikin mode: the two boundary points of every boundary edge, in corner order.
    let mut boundary_point: Vec<Option<u32>> = vec![None; nc];
    if chaikin {
        for c in 0..nc {
            if corners.edge_uses[c] == 1 {
                let (a, b) = (pos[fv[c] as usize], pos[fv[corners.next[c]] as usize]);
                boundary_point[c] = Some(positions.len() as u32);
                positions.push(a * 0.75 + b * 0.25);
                positions.push(a * 0.25 + b * 0.75);
            } else if corners.twin[c].is_none() {
                let (a, b) = (fv[c], fv[corners.next[c]]);
                return Err(DooSabinError::NonManifoldEdge {
                    a: a.min(b),
                    b: a.max(b),
                    faces: corners.edge_uses[c],
                });
            }
        }
    }

    let mut out = Mesh {
        positions,
        ..Mesh::default()
    };
    let id = |c: usize| c as u32;

    // F-faces.
    for w in mesh.face_offsets.windows(2) {
        let face: Vec<u32> = (w[0]..w[1]).collect();
        out.add_face(&face);
    }
    // E-faces: [f_b, f_a, g_a, g_b] for the edge a → b of f and b → a of g;
    // [f_b, f_a, Q, R] for a boundary edge a → b of f (chaikin mode).
    for (c, &boundary) in boundary_point.iter().enumerate() {
        if let Some(d) = corners.twin[c] {
            if c < d {
                out.add_face(&[id(corners.next[c]), id(c), id(corners.next[d]), id(d)]);
            }
        } else if let Some(q) = boundary {
            out.add_face(&[id(corners.next[c]), id(c), q, q + 1]);
        }
    }

    // V-faces, vertex by vertex.
    let mut at_vertex: Vec<Vec<usize>> = vec![Vec::new(); pos.len()];
    for (c, &v) in fv.iter().enumerate() {
        at_vertex[v as usize].push(c);
    }
    let mut ring = Vec::new();
    for (v, cs) in at_vertex.iter().enumerate() {
        let Some(&start) = cs.first() else { continue };
        // A closed fan: turning from any corner comes back to it after all the others.
        ring.clear();
        let mut c = start;
        let mut closed = false;
        for _ in 0..cs.len() {
            ring.push(id(c));
            match corners.turn(c) {
                Some(n) if n == start => {
                    closed = true;
                    break;
                }
                Some(n) => c = n,
                None => break,
            }
        }
        if closed && ring.len() == cs.len() {
            if ring.len() >= 3 {
                out.add_face(&ring);
            }
            continue;
        }
        if !chaikin {
            continue;
        }
        // Chaikin mode: one open fan, from the corner whose edge leaving v is
        // a boundary edge to the corner whose edge entering v is one. The V-face
        // runs from the boundary point after v, through the fan, to the one before.
        let non_manifold = DooSabinError::NonManifoldVertex(v as u32);
        let Some(first) = cs.iter().copied().find(|&c| corners.edge_uses[c] == 1) else {
            return Err(non_manifold);
        };
        ring.clear();
        let mut c = first;
        let mut last = None;
        for _ in 0..cs.len() {
            ring.push(id(c));
            match corners.turn(c) {
                Some(n) if n != first => c = n,
                Some(_) => break,
                None => {
                    last = Some(c);
                    break;
                }
            }
        }
        let (Some(last), true) = (last, ring.len() == cs.len()) else {
            return Err(non_manifold);
        };
        let (Some(after), Some(before)) =
            (boundary_point[first], boundary_point[corners.prev[last]])
        else {
            return Err(non_manifold);
        };
        let mut face = Vec::with_capacity(ring.len() + 2);
        face.push(after);
        face.extend_from_slice(&ring);
        face.push(before + 1);
        out.add_face(&face);
    }
    Ok(out)
}
