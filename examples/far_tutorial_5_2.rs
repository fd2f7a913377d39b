//! OpenSubdiv's far tutorial 5_2 ("patch tables for groups of faces") with
//! the native engine, run with the tutorial's defaults: a lattice of
//! 10 × 10 × 10 unit cubes (6,000 quads) divided into 10 groups of
//! consecutive faces; for each group a refinement of the base mesh
//! adapted to the group's faces only (level 2), a patch table of those
//! faces (Gregory basis end caps, end-cap points not shared, no varying
//! tables), its map and points, then every face of the group tessellated
//! as a fan of four triangles around its midpoint — the limit surface at
//! the middle and the four corners of its ptex face — printed as the same
//! OBJ text. The points are computed in `f32`, as the tutorial computes
//! them (the refined levels, the local points, the basis weights, the
//! weighted sums; `tests/far_tutorials.rs` holds the output to
//! OpenSubdiv's program, `cpp/far_tutorials.cpp`).
//!
//! ```sh
//! cargo run --example far_tutorial_5_2 > groups.obj
//! ```

use glam::DVec3;
use std::fmt::Write as _;
use subdiv::patches::{self, Derivatives, EndCapType, PatchMap, PatchOptions};
use subdiv::ptex::PtexIndices;
use subdiv::refiner::Refiner;
use subdiv::{BoundaryInterpolation, Mesh, Options};

/// The tutorial's cubes: `multiplier`³ unit cubes, 2 apart, each with its
/// own 8 vertices and 6 quads.
fn cubes(multiplier: u32) -> Mesh {
    const CORNERS: [[f64; 3]; 8] = [
        [-0.5, -0.5, -0.5],
        [-0.5, 0.5, -0.5],
        [-0.5, 0.5, 0.5],
        [-0.5, -0.5, 0.5],
        [0.5, -0.5, -0.5],
        [0.5, 0.5, -0.5],
        [0.5, 0.5, 0.5],
        [0.5, -0.5, 0.5],
    ];
    const FACES: [[u32; 4]; 6] = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 4, 7, 3],
        [1, 2, 6, 5],
        [0, 1, 5, 4],
        [3, 7, 6, 2],
    ];
    let mut mesh = Mesh::default();
    for x in 0..multiplier {
        for y in 0..multiplier {
            for z in 0..multiplier {
                let origin = 2.0 * DVec3::new(f64::from(x), f64::from(y), f64::from(z));
                let first = mesh.positions.len() as u32;
                mesh.positions
                    .extend(CORNERS.iter().map(|&c| origin + DVec3::from_array(c)));
                for face in FACES {
                    mesh.add_face(&face.map(|v| first + v));
                }
            }
        }
    }
    mesh
}

/// `Σ w p` over the points `indices` names, in f32 and in order, as the
/// tutorial's `AddWithWeight` sums them.
fn sum(indices: &[u32], weights: impl Iterator<Item = f32>, points: &[f32]) -> [f32; 3] {
    let mut p = [0.0f32; 3];
    for (&i, w) in indices.iter().zip(weights) {
        let q = &points[3 * i as usize..3 * i as usize + 3];
        for k in 0..3 {
            p[k] += w * q[k];
        }
    }
    p
}

fn main() -> Result<(), subdiv::Error> {
    print!("{}", run()?);
    Ok(())
}

/// The tutorial's output.
pub fn run() -> Result<String, subdiv::Error> {
    let (multiplier, groups, depth) = (10, 10, 2);
    let mesh = cubes(multiplier);
    let options = Options::default().with_boundary(BoundaryInterpolation::EdgeAndCorner);
    let ptex = PtexIndices::new(&Refiner::new(&mesh, &options)?)?;
    let base = mesh.flat_positions::<f32>();

    let patch_options = PatchOptions {
        varying_tables: false,
        share_end_cap_points: false,
        ..PatchOptions::new()
            .max_isolation(depth)
            .end_caps(EndCapType::GregoryBasis)
    };

    // Groups of consecutive faces, the first ones one face larger when the
    // faces do not divide evenly.
    let faces = mesh.face_count() as u32;
    let groups = groups.clamp(1, faces);
    let (smaller, larger) = (faces / groups, faces % groups);
    // The fan of a quad: the midpoint, then the corners.
    const FAN: [(f64, f64); 5] = [(0.5, 0.5), (0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

    let mut out = String::new();
    let mut obj_vertices = 0;
    for g in 0..groups {
        let first = g * smaller + g.min(larger);
        let group: Vec<u32> = (first..first + smaller + u32::from(g < larger)).collect();

        // A refinement of the base mesh adapted to the group's faces, and
        // the group's patches.
        let refiner = Refiner::new(&mesh, &options)?
            .refine_adaptive(patch_options.refine_adaptive_options(), &group)?;
        let table = refiner.patch_table(&patch_options, &group)?;
        // The group's points in f32, as the tutorial's: every level's
        // vertices, then the local points (`UpdateValues` in f32).
        let mut points = base.clone();
        let mut level = base.clone();
        for l in 1..=refiner.max_level() {
            level = refiner.interpolate(l, 3, &level)?;
            points.extend_from_slice(&level);
        }
        let stencils = &table.local_point_stencils;
        for i in 0..stencils.len() {
            let (indices, weights) = stencils.row(i);
            let p = sum(indices, weights.iter().map(|&w| w as f32), &points);
            points.extend_from_slice(&p);
        }
        let map = PatchMap::new(&table);

        // The fan of each face: `FindPatch`, `EvaluateBasis` in f32 and the
        // weighted sum of the patch's points.
        let mut fans = Vec::with_capacity(group.len() * FAN.len());
        for &face in &group {
            let ptex_face = ptex.face_id(face as usize)?;
            for (s, t) in FAN {
                let Some(h) = map.find_patch(ptex_face, s, t) else {
                    return Err(subdiv::Error::NoPatchAt {
                        face: ptex_face,
                        u: s,
                        v: t,
                    });
                };
                let array = &table.arrays[h.array];
                let w = patches::evaluate_basis_in::<f32>(
                    array.patch_type,
                    array.params[h.patch],
                    s as f32,
                    t as f32,
                    Derivatives::None,
                )?;
                let cvs = array.patch_vertices(h.patch);
                fans.push(sum(cvs, w.point.iter().copied(), &points));
            }
        }

        let _ = writeln!(out, "g patchGroup_{g}");
        for fan in fans.chunks_exact(FAN.len()) {
            for p in fan {
                let _ = writeln!(out, "v {:.6} {:.6} {:.6}", p[0], p[1], p[2]);
            }
            let centre = obj_vertices + 1;
            for k in 0..4 {
                let _ = writeln!(
                    out,
                    "f {centre} {} {}",
                    centre + 1 + k,
                    centre + 1 + (k + 1) % 4
                );
            }
            obj_vertices += FAN.len();
        }
    }
    Ok(out)
}
