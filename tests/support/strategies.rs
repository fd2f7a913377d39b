//! Random meshes and options for the property tests
//! (`tests/native_proptest.rs`, `tests/bfr_face_surfaces.rs`).

use glam::DVec3;
use proptest::prelude::*;
use subdiv::{BoundaryInterpolation, CreasingMethod, Mesh, Options, Scheme, TriangleSubdivision};

/// Random options: every scheme, boundary rule, creasing method and
/// triangle rule.
pub fn options() -> impl Strategy<Value = Options> {
    (
        prop_oneof![
            Just(Scheme::Catmark),
            Just(Scheme::Bilinear),
            Just(Scheme::Loop)
        ],
        prop::sample::select(BoundaryInterpolation::ALL),
        prop::sample::select(CreasingMethod::ALL),
        prop::sample::select(TriangleSubdivision::ALL),
    )
        .prop_map(|(scheme, boundary, creasing, triangles)| Options {
            scheme,
            boundary,
            creasing,
            triangles,
            ..Options::default()
        })
}

pub fn sharpness() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(10.0),
        Just(1.0),
        0.0f32..4.0,
        -1.0f32..12.0
    ]
}

/// A perturbed grid with random faces removed, quads split into triangles or
/// merged into hexagons, and random creases, corners and holes.
pub fn structured() -> impl Strategy<Value = Mesh> {
    (2u32..6, 2u32..5)
        .prop_flat_map(|(nx, ny)| {
            let cells = (nx * ny) as usize;
            let verts = ((nx + 1) * (ny + 1)) as usize;
            (
                Just((nx, ny)),
                prop::collection::vec(0u8..10, cells),
                prop::collection::vec((-0.3f64..0.3, -0.3f64..0.3, -0.5f64..0.5), verts),
                prop::collection::vec((0usize..1000, sharpness()), 0..6),
                prop::collection::vec((0usize..1000, sharpness()), 0..3),
                prop::collection::vec(0usize..1000, 0..2),
            )
        })
        .prop_map(|((nx, ny), kinds, jitter, creases, corners, holes)| {
            // One mesh in four is all triangles, so that Loop applies.
            let all_triangles = kinds[0] == 9;
            let mut m = Mesh::default();
            for j in 0..=ny {
                for i in 0..=nx {
                    let (dx, dy, dz) = jitter[(j * (nx + 1) + i) as usize];
                    m.positions
                        .push(DVec3::new(i as f64 + dx, j as f64 + dy, dz));
                }
            }
            let at = |i: u32, j: u32| j * (nx + 1) + i;
            let mut skip_next = false;
            for j in 0..ny {
                for i in 0..nx {
                    let kind = if all_triangles {
                        1
                    } else {
                        kinds[(j * nx + i) as usize]
                    };
                    if std::mem::take(&mut skip_next) {
                        continue;
                    }
                    let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                    match kind {
                        0 => {} // removed: a hole in the surface
                        1 => {
                            m.add_face(&[q[0], q[1], q[2]]);
                            m.add_face(&[q[0], q[2], q[3]]);
                        }
                        2 if i + 1 < nx => {
                            // A hexagon over two cells.
                            m.add_face(&[q[0], q[1], at(i + 2, j), at(i + 2, j + 1), q[2], q[3]]);
                            skip_next = true;
                        }
                        _ => m.add_face(&q),
                    }
                }
            }
            if m.face_count() == 0 {
                m.add_face(&[0, 1, at(1, 1), at(0, 1)]);
            }
            let edges: Vec<[u32; 2]> = m
                .faces()
                .flat_map(|f| (0..f.len()).map(move |k| [f[k], f[(k + 1) % f.len()]]))
                .collect();
            for (e, s) in creases {
                let [a, b] = edges[e % edges.len()];
                m.add_crease(a, b, s);
            }
            let nv = m.positions.len();
            for (v, s) in corners {
                m.add_corner((v % nv) as u32, s);
            }
            let nf = m.face_count();
            m.holes.extend(holes.into_iter().map(|f| (f % nf) as u32));
            m
        })
}

/// Random polygons over a handful of vertices: non-manifold edges, bowties,
/// inconsistent winding, repeated vertices — whatever comes.
pub fn soup() -> impl Strategy<Value = Mesh> {
    (4usize..10)
        .prop_flat_map(|nv| {
            (
                prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), nv),
                prop::collection::vec(prop::collection::vec(0..nv as u32, 3..6), 1..7),
                any::<bool>(),
                prop::collection::vec((0usize..100, sharpness()), 0..4),
            )
        })
        .prop_map(|(points, mut faces, triangles, creases)| {
            if triangles {
                for f in &mut faces {
                    f.truncate(3);
                }
            }
            let mut m = Mesh {
                positions: points
                    .into_iter()
                    .map(|(x, y, z)| DVec3::new(x, y, z))
                    .collect(),
                ..Mesh::default()
            };
            for f in &faces {
                m.add_face(f);
            }
            let edges: Vec<[u32; 2]> = faces
                .iter()
                .flat_map(|f| (0..f.len()).map(move |k| [f[k], f[(k + 1) % f.len()]]))
                .collect();
            for (e, s) in creases {
                let [a, b] = edges[e % edges.len()];
                m.add_crease(a, b, s);
            }
            m
        })
}

/// `m` with every face of more than three corners split into a fan of
/// triangles (creases and corners kept, a hole's first triangle a hole): for
/// Loop.
pub fn triangulated(m: Mesh) -> Mesh {
    let mut out = Mesh {
        positions: m.positions.clone(),
        creases: m.creases.clone(),
        corners: m.corners.clone(),
        ..Mesh::default()
    };
    for (i, f) in m.faces().enumerate() {
        if m.holes.contains(&(i as u32)) {
            out.holes.push(out.face_count() as u32);
        }
        for k in 1..f.len().saturating_sub(1) {
            out.add_face(&[f[0], f[k], f[k + 1]]);
        }
    }
    out
}
