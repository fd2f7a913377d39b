//! Native face-varying refinement against OpenSubdiv: value counts, the value
//! of every face corner and the interpolated values, level by level, over
//! meshes with UV seams and every face-varying option — plus a few results
//! derived by hand.
#![cfg(feature = "osd")]

use std::collections::HashMap;

use glam::DVec3;
use subdiv::compare::compare;
use subdiv::{
    BoundaryInterpolation, CreasingMethod, FVarChannel, FVarLinearInterpolation, Mesh, Options,
    Precision, Scheme, UniformOptions, osd, refiner, shapes,
};

/// Values must agree to this fraction of the channel's range…
const TOLERANCE: f64 = 1e-12;

/// …and in fact bit for bit: the native engine accumulates every value in
/// OpenSubdiv's order (`f64`).
const BIT_EXACT: bool = true;

// ---------------------------------------------------------------------------
// Channels with seams.

/// Union-find over face corners.
struct Corners(Vec<usize>);

impl Corners {
    fn find(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.0[a.max(b)] = a.min(b);
        }
    }
}

/// A UV-like channel of width 2 that is continuous across every edge shared
/// by faces except the `seams` (pairs of vertices, in either order). Values
/// are numbered by first use, or backwards with `reversed` (the numbering at
/// level 0 is the caller's), and differ on the two sides of a seam.
fn seamed(mesh: &Mesh, seams: &[[u32; 2]], reversed: bool) -> FVarChannel {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let seams: std::collections::HashSet<(u32, u32)> =
        seams.iter().map(|s| key(s[0], s[1])).collect();
    let corners = mesh.face_vertices.len();
    let mut sets = Corners((0..corners).collect());
    // The corners of each face at each end of each edge.
    let mut at_edge: HashMap<(u32, u32), Vec<(usize, usize)>> = HashMap::new();
    for f in 0..mesh.face_count() {
        let o = mesh.face_offsets[f] as usize;
        let verts = mesh.face(f);
        let n = verts.len();
        for j in 0..n {
            let (a, b) = (verts[j], verts[(j + 1) % n]);
            if a != b {
                let (ca, cb) = (o + j, o + (j + 1) % n);
                let pair = if a < b { (ca, cb) } else { (cb, ca) };
                at_edge.entry(key(a, b)).or_default().push(pair);
            }
        }
    }
    let mut edges: Vec<_> = at_edge.into_iter().collect();
    edges.sort();
    for (edge, list) in edges {
        if seams.contains(&edge) {
            continue;
        }
        for w in list.windows(2) {
            sets.union(w[0].0, w[1].0);
            sets.union(w[0].1, w[1].1);
        }
    }
    let mut class_of = HashMap::new();
    let mut indices = Vec::with_capacity(corners);
    for c in 0..corners {
        let root = sets.find(c);
        let next = class_of.len() as u32;
        indices.push(*class_of.entry(root).or_insert(next));
    }
    let count = class_of.len() as u32;
    if reversed {
        for i in &mut indices {
            *i = count - 1 - *i;
        }
    }
    let mut values = vec![0.0; 2 * count as usize];
    for (c, &i) in indices.iter().enumerate() {
        let p = mesh.positions[mesh.face_vertices[c] as usize];
        let k = i as f64;
        values[2 * i as usize] = 0.5 + 0.4 * p.x + 0.1 * p.z + 0.013 * k;
        values[2 * i as usize + 1] = 0.5 + 0.4 * p.y - 0.1 * p.z + 0.007 * k;
    }
    FVarChannel {
        width: 2,
        values,
        indices,
    }
}

/// Every face its own island.
fn islands(mesh: &Mesh) -> FVarChannel {
    let mut seams = Vec::new();
    for f in mesh.faces() {
        for j in 0..f.len() {
            seams.push([f[j], f[(j + 1) % f.len()]]);
        }
    }
    seamed(mesh, &seams, false)
}

/// The channel follows the vertices (one value per vertex).
fn per_vertex(mesh: &Mesh) -> FVarChannel {
    seamed(mesh, &[], false)
}

fn with(mut mesh: Mesh, channels: impl IntoIterator<Item = FVarChannel>) -> Mesh {
    mesh.fvar_channels.clear();
    mesh.fvar_channels.extend(channels);
    mesh
}

/// A chain of edges through consecutive vertices.
fn chain(vertices: &[u32]) -> Vec<[u32; 2]> {
    vertices.windows(2).map(|w| [w[0], w[1]]).collect()
}

// ---------------------------------------------------------------------------
// The generated shapes.

/// The cube unwrapped as a cross: bottom, front, top and back in a column,
/// left and right on the sides of front; the other 7 edges are seams.
fn cube_cross() -> Mesh {
    let cube = shapes::cube();
    let seams = [[1, 2], [2, 3], [3, 0], [5, 6], [7, 4], [2, 6], [3, 7]];
    let channel = seamed(&cube, &seams, true);
    with(cube, [channel])
}

/// A 4×4 grid cut into four UV regions along its middle row and column.
fn grid_quadrants() -> Mesh {
    let g = shapes::grid(4, 4);
    let at = |i: u32, j: u32| j * 5 + i;
    let mut seams = chain(&[at(2, 0), at(2, 1), at(2, 2), at(2, 3), at(2, 4)]);
    seams.extend(chain(&[at(0, 2), at(1, 2), at(2, 2), at(3, 2), at(4, 2)]));
    let channel = seamed(&g, &seams, false);
    let plain = per_vertex(&g);
    with(g, [channel, plain])
}

/// A torus with one seam loop around the tube.
fn torus_seam_loop() -> Mesh {
    let t = shapes::torus(8, 6);
    let ring: Vec<u32> = (0..=6).map(|j| (j % 6) * 8).collect();
    let channel = seamed(&t, &chain(&ring), false);
    with(t, [channel])
}

/// A torus unwrapped with both seam loops (one vertex has four values).
fn torus_unwrapped() -> Mesh {
    let t = shapes::torus(8, 6);
    let ring: Vec<u32> = (0..=6).map(|j| (j % 6) * 8).collect();
    let mut seams = chain(&ring);
    seams.extend(chain(&(0..=8).map(|i| i % 8).collect::<Vec<_>>()));
    let channel = seamed(&t, &seams, true);
    with(t, [channel])
}

/// A pole of valence `n` with a seam passing through the pole, or (with
/// `through = false`) ending there.
fn pole_seam(n: u32, through: bool) -> Mesh {
    let p = shapes::pole(n);
    // Pole 0, first ring 1..=n, second ring n+1..=2n.
    let mut seams = vec![[0, 1], [1, n + 1]];
    if through {
        let opposite = 1 + n / 2;
        seams.extend([[0, opposite], [opposite, opposite + n]]);
    }
    let channel = seamed(&p, &seams, false);
    with(p, [channel])
}

/// A pyramid whose base n-gon and each side triangle are islands.
fn pyramid_islands(n: u32) -> Mesh {
    let p = shapes::pyramid(n);
    let channel = islands(&p);
    with(p, [channel])
}

/// A prism whose caps are islands, the sides a band cut by one seam.
fn prism_caps(n: u32) -> Mesh {
    let p = shapes::prism(n);
    let mut seams: Vec<[u32; 2]> = (0..n).map(|i| [i, (i + 1) % n]).collect();
    seams.extend((0..n).map(|i| [n + i, n + (i + 1) % n]));
    seams.push([0, n]);
    let channel = seamed(&p, &seams, false);
    with(p, [channel])
}

/// A grid with holes and a seam through them.
fn grid_holes_seam() -> Mesh {
    let mut g = shapes::grid(4, 4);
    g.holes.extend([5, 6, 15]);
    let at = |i: u32, j: u32| j * 5 + i;
    let channel = seamed(
        &g,
        &chain(&[at(2, 0), at(2, 1), at(2, 2), at(2, 3), at(2, 4)]),
        false,
    );
    with(g, [channel])
}

/// The cube cross with a hole.
fn cube_cross_hole() -> Mesh {
    let mut m = cube_cross();
    m.holes.push(2);
    m
}

/// The non-manifold fin, with islands and with one seam.
fn fin_uv() -> Mesh {
    let f = shapes::fin();
    let a = islands(&f);
    let b = seamed(&f, &[[1, 5], [0, 2]], false);
    with(f, [a, b])
}

/// The bowtie (two quads sharing one vertex), continuous and with a seam.
fn bowtie_uv() -> Mesh {
    let b = shapes::bowtie();
    let plain = per_vertex(&b);
    let cut = seamed(&b, &[[1, 2]], true);
    with(b, [plain, cut])
}

/// The inconsistently wound grid with a degenerate face, with UVs.
fn inconsistent_uv() -> Mesh {
    let m = shapes::inconsistent();
    let plain = per_vertex(&m);
    let cut = seamed(&m, &[[1, 5], [5, 9]], false);
    with(m, [plain, cut])
}

/// A grid with a seam down the middle crossed by a semi-sharp crease, a
/// semi-sharp crease running along part of the seam, and a semi-sharp corner
/// on the seam.
fn grid_semi_sharp_seam() -> Mesh {
    let mut g = shapes::grid(4, 4);
    let at = |i: u32, j: u32| j * 5 + i;
    let channel = seamed(
        &g,
        &chain(&[at(2, 0), at(2, 1), at(2, 2), at(2, 3), at(2, 4)]),
        false,
    );
    for i in 0..4 {
        g.add_crease(at(i, 2), at(i + 1, 2), 1.5 + 0.5 * i as f32);
    }
    g.add_crease(at(2, 3), at(2, 4), 2.3);
    g.add_crease(at(1, 1), at(1, 2), 0.7);
    g.add_corner(at(2, 1), 1.2);
    with(g, [channel])
}

/// A torus with a seam loop crossed by a semi-sharp crease loop and a dart
/// ending on the seam.
fn torus_semi_sharp_seam() -> Mesh {
    let mut t = shapes::torus(8, 6);
    let ring: Vec<u32> = (0..=6).map(|j| (j % 6) * 8).collect();
    let channel = seamed(&t, &chain(&ring), false);
    for i in 0..8 {
        t.add_crease(16 + i, 16 + (i + 1) % 8, 2.5);
    }
    t.add_crease(33, 32, 1.25);
    t.add_crease(8, 16, 0.5);
    with(t, [channel])
}

/// Values alternating A B A B around an interior vertex (a bowtie in UV space).
fn alternating() -> Mesh {
    let mut g = shapes::grid(2, 2);
    let mut channel = islands(&g);
    // Give the centre corners of diagonally opposite faces the same value.
    let centre = 4;
    let corner = |f: usize| {
        g.face_offsets[f] as usize + g.face(f).iter().position(|&v| v == centre).unwrap()
    };
    let (a, b) = (channel.indices[corner(0)], channel.indices[corner(1)]);
    channel.indices[corner(3)] = a;
    channel.indices[corner(2)] = b;
    g.fvar_channels = vec![channel];
    g
}

/// A seam turning at a vertex (an L through the middle of a grid), so that
/// the larger span around the corner wraps past the vertex's first face, with
/// semi-sharp edges on both sides of the wrap.
fn grid_seam_turn() -> Mesh {
    let mut g = shapes::grid(4, 4);
    let at = |i: u32, j: u32| j * 5 + i;
    let seam = [at(2, 0), at(2, 1), at(2, 2), at(3, 2), at(4, 2)];
    let channel = seamed(&g, &chain(&seam), false);
    g.add_crease(at(2, 2), at(2, 3), 2.5);
    g.add_crease(at(1, 2), at(2, 2), 1.0);
    with(g, [channel])
}

/// A semi-sharp edge on a seam and a shorter-lived one on one side of it: the
/// other side's value depends on it under the "corners plus" options.
fn grid_seam_dependent() -> Mesh {
    let mut g = shapes::grid(4, 4);
    let at = |i: u32, j: u32| j * 5 + i;
    let seam = [at(2, 0), at(2, 1), at(2, 2), at(2, 3), at(2, 4)];
    let channel = seamed(&g, &chain(&seam), false);
    g.add_crease(at(2, 2), at(2, 3), 3.0);
    g.add_crease(at(1, 2), at(2, 2), 1.0);
    // The same with the sides swapped: the first value depends on the second.
    g.add_crease(at(2, 0), at(2, 1), 3.0);
    g.add_crease(at(2, 1), at(3, 1), 0.5);
    with(g, [channel])
}

/// Three seams through a pole of valence 6: three values of two faces each.
fn pole_three_seams() -> Mesh {
    let p = shapes::pole(6);
    let seams = [[0, 1], [1, 7], [0, 3], [3, 9], [0, 5], [5, 11]];
    let channel = seamed(&p, &seams, false);
    with(p, [channel])
}

/// Two seams ending at one interior vertex from different directions, each
/// split at its far end only: the vertex keeps a single value but has two
/// split edges.
fn grid_two_darts() -> Mesh {
    let mut g = shapes::grid(4, 4);
    let at = |i: u32, j: u32| j * 5 + i;
    let mut channel = per_vertex(&g);
    // Give `vertex` a new value in `faces`.
    let mut split = |vertex: u32, faces: &[usize]| {
        let value = (channel.values.len() / 2) as u32;
        let old =
            channel.indices[g.face_vertices.iter().position(|&v| v == vertex).unwrap()] as usize;
        channel.values.extend([
            channel.values[2 * old] + 0.25,
            channel.values[2 * old + 1] - 0.125,
        ]);
        for &f in faces {
            let k = g.face(f).iter().position(|&v| v == vertex).unwrap();
            channel.indices[g.face_offsets[f] as usize + k] = value;
        }
    };
    split(at(2, 1), &[2, 6]);
    split(at(3, 2), &[10, 11]);
    g.fvar_channels = vec![channel];
    g
}

/// A grid with an unused vertex and unused values at both ends of the
/// channel's value list.
fn grid_unused() -> Mesh {
    let mut g = shapes::grid(2, 2);
    g.positions.push(DVec3::new(5.0, 5.0, 1.0));
    let mut channel = seamed(&g, &[[1, 4], [4, 7]], false);
    for i in &mut channel.indices {
        *i += 1;
    }
    channel.values.splice(0..0, [9.0, -9.0]);
    channel.values.extend([7.0, 7.5]);
    g.fvar_channels = vec![channel];
    g
}

/// Two quads side by side with a seam between them.
fn two_quads_seam() -> Mesh {
    let g = shapes::grid(2, 1);
    let channel = seamed(&g, &[[1, 4]], false);
    with(g, [channel])
}

fn generated() -> Vec<(String, Mesh)> {
    let mut out = vec![
        ("cube-cross".to_string(), cube_cross()),
        ("grid-quadrants".into(), grid_quadrants()),
        ("torus-seam-loop".into(), torus_seam_loop()),
        ("torus-unwrapped".into(), torus_unwrapped()),
        ("pole-5-seam-through".into(), pole_seam(5, true)),
        ("pole-6-seam-through".into(), pole_seam(6, true)),
        ("pole-5-seam-ends".into(), pole_seam(5, false)),
        ("pyramid-5-islands".into(), pyramid_islands(5)),
        ("prism-6-caps".into(), prism_caps(6)),
        ("grid-holes-seam".into(), grid_holes_seam()),
        ("cube-cross-hole".into(), cube_cross_hole()),
        ("fin-uv".into(), fin_uv()),
        ("bowtie-uv".into(), bowtie_uv()),
        ("inconsistent-uv".into(), inconsistent_uv()),
        ("grid-semi-sharp-seam".into(), grid_semi_sharp_seam()),
        ("torus-semi-sharp-seam".into(), torus_semi_sharp_seam()),
        ("alternating".into(), alternating()),
        ("two-quads-seam".into(), two_quads_seam()),
        ("grid-seam-turn".into(), grid_seam_turn()),
        ("grid-seam-dependent".into(), grid_seam_dependent()),
        ("pole-6-three-seams".into(), pole_three_seams()),
        ("grid-two-darts".into(), grid_two_darts()),
        ("grid-unused".into(), grid_unused()),
        // The benchmark's tori with UVs (`shapes::with_torus_uvs`).
        (
            "torus-uv-quads".into(),
            shapes::with_torus_uvs(shapes::torus(8, 6), 8, 6),
        ),
        (
            "torus-uv-mixed".into(),
            shapes::with_torus_uvs(shapes::torus_mixed(8, 6), 8, 6),
        ),
        (
            "torus-uv-triangles".into(),
            shapes::with_torus_uvs(shapes::torus_triangles(8, 6), 8, 6),
        ),
        // Mostly clean faces (the vertex kernel's path on one thread) and
        // an unused last vertex, which has no value of the channel.
        ("torus-uv-unused".into(), {
            let mut t = shapes::with_torus_uvs(shapes::torus(8, 6), 8, 6);
            t.positions.push(DVec3::new(9.0, 9.0, 9.0));
            t
        }),
    ];
    for (name, m) in &out {
        m.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    out.shrink_to_fit();
    out
}

// ---------------------------------------------------------------------------
// Comparison with OpenSubdiv.

/// The spread of a channel's base values (at least 1).
fn range(channel: &FVarChannel) -> f64 {
    let lo = channel.values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = channel
        .values
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    (hi - lo).max(1.0)
}

/// A pool of one thread, where face-varying interpolation takes the vertex
/// kernel's path.
fn one_thread() -> &'static rayon::ThreadPool {
    static POOL: std::sync::OnceLock<rayon::ThreadPool> = std::sync::OnceLock::new();
    POOL.get_or_init(|| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a one-thread pool")
    })
}

/// Refines `mesh` with both engines and compares every channel at every level.
fn check(
    name: &str,
    mesh: &Mesh,
    options: &Options,
    uniform: UniformOptions,
) -> Result<(), String> {
    let what = || {
        format!(
            "{name} {options:?} level {} faces-first {}",
            uniform.level, uniform.order_vertices_from_faces_first
        )
    };
    let expected = osd::TopologyRefiner::new(mesh, options)
        .and_then(|mut r| r.refine_uniform(uniform).map(|()| r));
    let actual = refiner::Refiner::new(mesh, options)
        .and_then(|mut r| r.refine_uniform(uniform).map(|()| r));
    let (expected, actual) = match (expected, actual) {
        (Ok(e), Ok(a)) => (e, a),
        (Err(e), Err(a)) => {
            return Err(format!(
                "{}: both engines fail: osd {e} / native {a}",
                what()
            ));
        }
        (e, a) => {
            return Err(format!(
                "{}: osd {:?} vs native {:?}",
                what(),
                e.err(),
                a.err()
            ));
        }
    };
    let mut data: Vec<(Vec<f64>, Vec<f64>)> = mesh
        .fvar_channels
        .iter()
        .map(|c| (c.values.clone(), c.values.clone()))
        .collect();
    let mut native_levels: Vec<Vec<Vec<f64>>> = vec![Vec::new(); mesh.fvar_channels.len()];
    for level in 0..=uniform.level {
        let (te, ta) = (
            expected.level(level).map_err(|e| e.to_string())?,
            actual.level(level).map_err(|e| e.to_string())?,
        );
        if te.face_vertices != ta.face_vertices {
            return Err(format!("{}: level {level}: face-vertices differ", what()));
        }
        for (c, channel) in mesh.fvar_channels.iter().enumerate() {
            let (fe, fa) = (&te.fvar[c], &ta.fvar[c]);
            if fe.value_count != fa.value_count {
                return Err(format!(
                    "{}: level {level} channel {c}: {} values, OpenSubdiv has {}",
                    what(),
                    fa.value_count,
                    fe.value_count
                ));
            }
            if let Some(i) =
                (0..fe.face_values.len()).find(|&i| fe.face_values.get(i) != fa.face_values.get(i))
            {
                return Err(format!(
                    "{}: level {level} channel {c}: face corner {i} has value {:?}, OpenSubdiv {:?}",
                    what(),
                    fa.face_values.get(i),
                    fe.face_values[i]
                ));
            }
            if fe.face_values.len() != fa.face_values.len() {
                return Err(format!(
                    "{}: level {level} channel {c}: corner counts differ",
                    what()
                ));
            }
            if level > 0 {
                let (de, da) = &data[c];
                let de = expected
                    .interpolate_face_varying(c, level, channel.width, de)
                    .map_err(|e| e.to_string())?;
                // One thread and the pool (its work split differently):
                // both must give OpenSubdiv's. (Both take the vertex
                // kernel's path where it applies; the face-varying pass
                // alone is compared with it in
                // src/refiner/fvar_paths_tests.rs.)
                let on_pool = actual
                    .interpolate_face_varying(c, level, channel.width, da)
                    .map_err(|e| e.to_string())?;
                let da = one_thread()
                    .install(|| actual.interpolate_face_varying(c, level, channel.width, da))
                    .map_err(|e| e.to_string())?;
                if let Some(i) = (0..da.len()).find(|&i| da[i].to_bits() != on_pool[i].to_bits()) {
                    return Err(format!(
                        "{}: level {level} channel {c}: value {} differs between one thread ({}) and the pool ({})",
                        what(),
                        i / channel.width,
                        da[i],
                        on_pool[i]
                    ));
                }
                let tolerance = TOLERANCE * range(channel);
                let differs = |i: usize| {
                    if BIT_EXACT {
                        de[i] != da[i]
                    } else {
                        // NaN counts as a difference.
                        (de[i] - da[i]).abs().is_nan() || (de[i] - da[i]).abs() > tolerance
                    }
                };
                if let Some(i) = (0..de.len()).find(|&i| differs(i)) {
                    return Err(format!(
                        "{}: level {level} channel {c}: value {} component {}: native {} osd {} (Δ {:e})",
                        what(),
                        i / channel.width,
                        i % channel.width,
                        da[i],
                        de[i],
                        da[i] - de[i]
                    ));
                }
                native_levels[c].push(da.clone());
                data[c] = (de, da);
            }
        }
    }
    // The whole-refinement calls give the levels just checked, bit for bit,
    // on one thread and on the pool.
    for (c, channel) in mesh.fvar_channels.iter().enumerate() {
        let base = &channel.values;
        for pool in [false, true] {
            let (all, last) = if pool {
                (
                    actual.interpolate_face_varying_all(c, channel.width, base),
                    actual.interpolate_face_varying_last(c, channel.width, base),
                )
            } else {
                one_thread().install(|| {
                    (
                        actual.interpolate_face_varying_all(c, channel.width, base),
                        actual.interpolate_face_varying_last(c, channel.width, base),
                    )
                })
            };
            let (all, last) = (
                all.map_err(|e| e.to_string())?,
                last.map_err(|e| e.to_string())?,
            );
            let same = |a: &[f64], b: &[f64]| {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
            };
            let levels = &native_levels[c];
            if all.len() != levels.len() + 1
                || !same(&all[0], base)
                || all[1..].iter().zip(levels).any(|(a, b)| !same(a, b))
                || !same(&last, all.last().expect("level 0"))
            {
                return Err(format!(
                    "{}: channel {c}: interpolate_face_varying_all/_last (pool {pool}) differ from the level-by-level values",
                    what()
                ));
            }
        }
    }
    Ok(())
}

/// Every face-varying option with `schemes`, every vertex boundary
/// interpolation and both creasing methods.
fn all_options(schemes: &[Scheme]) -> Vec<Options> {
    let mut out = Vec::new();
    for &scheme in schemes {
        for &boundary in BoundaryInterpolation::ALL {
            for &fvar in FVarLinearInterpolation::ALL {
                for &creasing in CreasingMethod::ALL {
                    out.push(Options {
                        scheme,
                        boundary,
                        fvar,
                        creasing,
                        ..Options::default()
                    });
                }
            }
        }
    }
    out
}

const QUAD_SCHEMES: &[Scheme] = &[Scheme::Catmark, Scheme::Bilinear];

/// Levels 1..=3, or 1..=4 for tiny meshes.
fn max_level(mesh: &Mesh) -> u32 {
    if mesh.face_count() <= 6 { 4 } else { 3 }
}

/// Checks every shape under every option, to its deepest level and (every
/// option on small meshes, every other one on larger ones) to level 2 with
/// the faces-first vertex order.
fn run(shapes: &[(String, Mesh)], schemes: &[Scheme]) {
    let options = all_options(schemes);
    let mut failures = Vec::new();
    let mut checked = 0;
    for (name, mesh) in shapes {
        assert!(
            !mesh.fvar_channels.is_empty(),
            "{name} has no face-varying channel"
        );
        for (i, o) in options.iter().enumerate() {
            let mut uniforms = vec![UniformOptions::new(max_level(mesh))];
            if mesh.face_count() <= 12 || i % 2 == 0 {
                uniforms.push(UniformOptions::new(2).faces_first(true));
            }
            for u in uniforms {
                checked += 1;
                if let Err(e) = check(name, mesh, o, u) {
                    failures.push(e);
                }
            }
        }
    }
    eprintln!("checked {checked} refinements of {} shapes", shapes.len());
    if !failures.is_empty() {
        let n = failures.len();
        failures.truncate(10);
        panic!(
            "{n} of {checked} refinements differ from OpenSubdiv; first ones:\n{}",
            failures.join("\n")
        );
    }
}

/// Closed shapes among the generated ones.
fn is_closed(name: &str) -> bool {
    ["cube", "torus", "pole", "pyramid", "prism"]
        .iter()
        .any(|p| name.starts_with(p))
}

#[test]
fn corpus_shapes_with_channels() {
    let shapes: Vec<_> = shapes::corpus()
        .into_iter()
        .filter(|(_, m)| !m.fvar_channels.is_empty())
        .collect();
    assert!(shapes.len() >= 5);
    run(&shapes, QUAD_SCHEMES);
}

#[test]
fn seamed_closed_shapes() {
    let shapes: Vec<_> = generated()
        .into_iter()
        .filter(|(n, _)| is_closed(n))
        .collect();
    run(&shapes, QUAD_SCHEMES);
}

#[test]
fn seamed_open_and_non_manifold_shapes() {
    let shapes: Vec<_> = generated()
        .into_iter()
        .filter(|(n, _)| !is_closed(n))
        .collect();
    run(&shapes, QUAD_SCHEMES);
}

/// Channels of every width the native engine computes differently — one
/// column, two (UVs), three and four (whole in registers), and wider ones in
/// blocks of 16 columns (17 and 33 leave a short last block) — on the
/// production-like shape and on a seamed cube: each component a different
/// function of the UVs, so a column computed from the wrong one shows.
#[test]
fn channels_of_every_width() {
    let widen = |mut m: Mesh, widths: &[usize]| {
        let uv = m.fvar_channels[0].clone();
        m.fvar_channels = widths
            .iter()
            .map(|&width| FVarChannel {
                width,
                values: (0..uv.value_count())
                    .flat_map(|i| {
                        let (u, v) = (uv.values[2 * i], uv.values[2 * i + 1]);
                        (0..width).map(move |k| {
                            let k = k as f64;
                            u * (1.0 + 0.37 * k) - v * (0.5 - 0.11 * k) + k
                        })
                    })
                    .collect(),
                indices: uv.indices.clone(),
            })
            .collect();
        m
    };
    let shapes = vec![
        (
            "production".to_string(),
            widen(shapes::production(16, 9), &[1, 3, 4, 17]),
        ),
        (
            "cube-uv".to_string(),
            widen(shapes::cube_with_uvs(), &[5, 16, 33]),
        ),
    ];
    run(&shapes, &[Scheme::Catmark]);
}

/// The corpus shapes without channels (creases, corners, n-gons, poles,
/// non-manifold features), each given an island per face, a channel with a
/// seam along two edges of its first face, and a channel following the
/// vertices.
fn corpus_with_generated_channels() -> Vec<(String, Mesh)> {
    shapes::corpus()
        .into_iter()
        .filter(|(_, m)| m.fvar_channels.is_empty())
        .map(|(name, m)| {
            let f0 = m.face(0).to_vec();
            let cut = seamed(&m, &chain(&[f0[0], f0[1], f0[2]]), true);
            let channels = [islands(&m), cut, per_vertex(&m)];
            (name, with(m, channels))
        })
        .collect()
}

#[test]
fn corpus_shapes_with_generated_channels() {
    run(&corpus_with_generated_channels(), QUAD_SCHEMES);
}

/// Loop's triangle split: the same face-varying topology and rules, with
/// three child faces per face around an edge point and no face points.
#[test]
fn loop_scheme_channels() {
    let mut shapes: Vec<_> = corpus_with_generated_channels()
        .into_iter()
        .filter(|(_, m)| m.faces().all(|f| f.len() == 3))
        .collect();
    let ico = shapes::icosahedron();
    let loop_seam = seamed(&ico, &chain(&[0, 11, 10, 7, 1, 0]), false);
    shapes.push(("icosahedron-seam-loop".into(), with(ico, [loop_seam])));
    let fan = shapes::fan(5, 2.5);
    let fan_seam = seamed(&fan, &[[0, 3]], false);
    shapes.push(("fan-seam".into(), with(fan, [fan_seam])));
    assert!(shapes.len() >= 6);
    run(&shapes, &[Scheme::Loop]);
}

/// Whole refinements, positions and every channel, in `f64` and `f32`,
/// through the engines' `refine` and the crate's comparison.
#[test]
fn whole_refinements_in_both_precisions() {
    for (name, mesh) in [
        ("cube-cross", cube_cross()),
        ("grid-semi-sharp-seam", grid_semi_sharp_seam()),
        ("fin-uv", fin_uv()),
    ] {
        for &fvar in FVarLinearInterpolation::ALL {
            let options = Options {
                fvar,
                ..Options::shape_file_defaults()
            };
            for (precision, tolerance) in [(Precision::F64, 0.0), (Precision::F32, 1e-6)] {
                let uniform = UniformOptions::new(3);
                let e = osd::refine(
                    &mesh,
                    &options,
                    subdiv::Request::from(uniform).precision(precision),
                )
                .unwrap();
                let a = refiner::refine(
                    &mesh,
                    &options,
                    subdiv::Request::from(uniform).precision(precision),
                )
                .unwrap();
                for c in compare(&a, &e) {
                    assert!(c.agrees(tolerance), "{name} {fvar:?} {precision:?}: {c:?}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Results derived by hand.

fn native(mesh: &Mesh, options: &Options, levels: u32) -> refiner::Refiner {
    let mut r = refiner::Refiner::new(mesh, options).unwrap();
    r.refine_uniform(UniformOptions::new(levels)).unwrap();
    r
}

/// With linear interpolation, the point of an edge on a seam takes, on each
/// side, the midpoint of that side's two end values.
#[test]
fn linear_seam_edge_points_are_midpoints() {
    let mesh = two_quads_seam();
    let channel = &mesh.fvar_channels[0];
    for scheme in [Scheme::Catmark, Scheme::Bilinear] {
        let options = Options {
            scheme,
            fvar: FVarLinearInterpolation::All,
            ..Options::shape_file_defaults()
        };
        let r = native(&mesh, &options, 1);
        let level = r.level(1).unwrap();
        let values = r
            .interpolate_face_varying(0, 1, 2, &channel.values)
            .unwrap();
        // The edge 1-4 between the two faces; its child vertex is the one
        // both faces' children share apart from the face points.
        let e = r.find_edge(0, 1, 4).unwrap().unwrap() as usize;
        let child_of_edge =
            r.level_counts(1).unwrap().vertices - r.level_counts(0).unwrap().edges + e;
        let uv = |f: usize, v: u32| {
            let k = mesh.face(f).iter().position(|&x| x == v).unwrap();
            let i = channel.indices[mesh.face_offsets[f] as usize + k] as usize;
            DVec3::new(channel.values[2 * i], channel.values[2 * i + 1], 0.0)
        };
        let mut seen = 0;
        for cf in 0..level.face_count() {
            let parent_face = cf / 4;
            if let Some(k) = level
                .face(cf)
                .iter()
                .position(|&v| v as usize == child_of_edge)
            {
                let i = level.fvar[0].face_values[level.face_offsets[cf] as usize + k] as usize;
                let got = DVec3::new(values[2 * i], values[2 * i + 1], 0.0);
                let want = (uv(parent_face, 1) + uv(parent_face, 4)) * 0.5;
                assert_eq!(got, want, "{scheme:?} child face {cf}");
                seen += 1;
            }
        }
        assert_eq!(seen, 4);
        // Two values at the seam's edge point, one per side.
        let mut distinct: Vec<u32> = (0..level.face_count())
            .filter_map(|cf| {
                let k = level
                    .face(cf)
                    .iter()
                    .position(|&v| v as usize == child_of_edge)?;
                Some(level.fvar[0].face_values[level.face_offsets[cf] as usize + k])
            })
            .collect();
        distinct.sort();
        distinct.dedup();
        assert_eq!(distinct.len(), 2);
    }
}

/// Where the channel follows the vertices of a closed smooth surface, option
/// `None` refines it exactly as vertex data (same numbering, same bits).
#[test]
fn smooth_channel_matches_vertex_interpolation() {
    for mesh in [shapes::torus(6, 5), shapes::pole(5), shapes::prism(5)] {
        // One value per vertex, numbered like the vertices, holding data
        // derived from the positions; a semi-sharp crease for good measure.
        let data: Vec<f64> = mesh
            .positions
            .iter()
            .flat_map(|p| [p.x, p.y - 0.3 * p.z])
            .collect();
        let indices = mesh.face_vertices.clone();
        let mut mesh = with(
            mesh,
            [FVarChannel {
                width: 2,
                values: data.clone(),
                indices,
            }],
        );
        mesh.add_crease(mesh.face(0)[0], mesh.face(0)[1], 1.5);
        let options = Options {
            fvar: FVarLinearInterpolation::None,
            ..Options::shape_file_defaults()
        };
        let r = native(&mesh, &options, 3);
        let (mut fvar, mut vertex) = (data.clone(), data);
        for l in 1..=3 {
            fvar = r.interpolate_face_varying(0, l, 2, &fvar).unwrap();
            vertex = r.interpolate(l, 2, &vertex).unwrap();
            assert_eq!(fvar, vertex, "level {l}");
            let level = r.level(l).unwrap();
            assert_eq!(level.fvar[0].face_values, level.face_vertices);
        }
    }
}

/// Corners of an open grid: kept exactly by every option but `None`, which
/// smooths them like the vertex boundary (here: edge-only, a smooth corner).
#[test]
fn grid_corner_values() {
    let mesh = shapes::grid(3, 3);
    let channel = &mesh.fvar_channels[0];
    for &fvar in FVarLinearInterpolation::ALL {
        let options = Options {
            fvar,
            ..Options::shape_file_defaults()
        };
        let r = native(&mesh, &options, 2);
        let mut values = channel.values.clone();
        for l in 1..=2 {
            values = r.interpolate_face_varying(0, l, 2, &values).unwrap();
        }
        // The child of vertex 0 is the corner of the refined grid's face 0.
        let level = r.level(2).unwrap();
        let i = level.fvar[0].face_values[0] as usize;
        let corner = [values[2 * i], values[2 * i + 1]];
        if fvar == FVarLinearInterpolation::None {
            assert!(corner[0] > 0.0 && corner[1] > 0.0, "{fvar:?}: {corner:?}");
        } else {
            assert_eq!(corner, [0.0, 0.0], "{fvar:?}");
        }
    }
}

/// Alternating values around a vertex: OpenSubdiv counts the second
/// reappearance of the second value as a new value, so the vertex has three.
#[test]
fn alternating_values_give_three_siblings() {
    let mesh = alternating();
    let options = Options {
        fvar: FVarLinearInterpolation::CornersOnly,
        ..Options::shape_file_defaults()
    };
    let r = native(&mesh, &options, 1);
    let level = r.level(1).unwrap();
    // The centre's child is vertex 4 (vertex children come first).
    let mut values: Vec<u32> = (0..level.face_count())
        .filter_map(|f| {
            let k = level.face(f).iter().position(|&v| v == 4)?;
            Some(level.fvar[0].face_values[level.face_offsets[f] as usize + k])
        })
        .collect();
    values.sort();
    values.dedup();
    assert_eq!(values.len(), 3);
}

/// Argument errors.
#[test]
fn bad_arguments() {
    let mesh = shapes::cube_with_uvs();
    let r = native(&mesh, &Options::default(), 1);
    let values = &mesh.fvar_channels[0].values;
    assert!(r.interpolate_face_varying(1, 1, 2, values).is_err());
    assert!(r.interpolate_face_varying(0, 2, 2, values).is_err());
    assert!(r.interpolate_face_varying(0, 0, 2, values).is_err());
    assert!(r.interpolate_face_varying(0, 1, 0, values).is_err());
    assert!(r.interpolate_face_varying(0, 1, 2, &values[1..]).is_err());
    assert!(r.interpolate_face_varying(0, 1, 2, values).is_ok());
}

/// Channels of a mesh large enough that each kind of child vertex is
/// computed in several parallel chunks (more than 4,096 parent elements per
/// kind from level 1 on), on two threads: still OpenSubdiv's values bit for
/// bit, under USD's face-varying default and the two extremes.
#[test]
fn large_channels_in_parallel_chunks() {
    let mesh = shapes::production(64, 48);
    assert!(mesh.face_count() > 3000);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let mut failures = Vec::new();
    for fvar in [
        FVarLinearInterpolation::CornersPlus1,
        FVarLinearInterpolation::None,
        FVarLinearInterpolation::All,
    ] {
        let options = Options::default()
            .with_boundary(BoundaryInterpolation::EdgeAndCorner)
            .with_fvar(fvar);
        if let Err(e) =
            pool.install(|| check("production 64x48", &mesh, &options, UniformOptions::new(2)))
        {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Found by fuzzing (mesh_differential): degenerate faces (a vertex
/// repeated around a face, faces of one vertex) make OpenSubdiv list one
/// face twice among a vertex's faces at level 2 and miss another; the
/// siblings it adds corner by corner then sum at that corner. The minimal
/// last level, whose face values are read from the parent's faces, must
/// number them the same (it assigned instead of adding, and read several
/// values where the parent's first value passes one on).
#[test]
fn degenerate_faces_number_values_as_opensubdiv() {
    let faces: [&[u32]; 7] = [
        &[2, 3, 1],
        &[0, 3, 4],
        &[1, 3, 0, 4, 3, 2, 0, 0, 0],
        &[0, 0, 0, 0, 0, 0],
        &[0, 0, 0, 0, 0, 0],
        &[0, 0, 0, 0, 0, 0],
        &[0, 0, 0, 2, 2, 0],
    ];
    let positions = (0..5)
        .map(|i| DVec3::new(i as f64, (i * i % 3) as f64, 0.5 * i as f64))
        .collect();
    let mut mesh = Mesh::from_faces(positions, &faces);
    for (vertices, sharpness) in [
        ([0, 0], 3.25),
        ([2, 0], 4.75),
        ([0, 0], -1.0),
        ([0, 0], 4.75),
        ([0, 0], 4.75),
    ] {
        mesh.creases.push(subdiv::Crease {
            vertices,
            sharpness,
        });
    }
    for (vertex, sharpness) in [(3, 0.5), (0, 0.0)] {
        mesh.corners.push(subdiv::Corner { vertex, sharpness });
    }
    mesh.holes.extend([1, 6]);
    let indices: [&[u32]; 2] = [
        &[
            2, 3, 1, 0, 3, 3, 0, 4, 0, 0, 2, 2, 3, 5, 0, 1, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0,
            2, 0, 0, 1, 1, 0, 0, 4, 0, 0,
        ],
        &[
            2, 3, 1, 0, 3, 4, 1, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
            0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
        ],
    ];
    for (width, count, indices) in [(1, 6, indices[0]), (2, 9, indices[1])] {
        mesh.fvar_channels.push(subdiv::FVarChannel {
            width,
            values: (0..width * count).map(|i| i as f64 * 0.25).collect(),
            indices: indices.to_vec(),
        });
    }
    let options = Options {
        scheme: Scheme::Catmark,
        boundary: BoundaryInterpolation::None,
        fvar: FVarLinearInterpolation::None,
        creasing: CreasingMethod::Uniform,
        ..Options::default()
    };
    for full in [false, true] {
        check(
            "degenerate faces",
            &mesh,
            &options,
            UniformOptions::new(3).full_topology(full),
        )
        .unwrap();
    }
}

/// The caller's-buffer and whole-refinement calls: the level-by-level
/// values, every value written (over a buffer of NaNs), and typed refusals
/// of a wrong channel, level, source or destination length.
#[test]
fn face_varying_into_all_and_last() {
    use subdiv::{Buffer, Error};
    let mesh = shapes::with_torus_uvs(shapes::torus_mixed(8, 6), 8, 6);
    let channel = &mesh.fvar_channels[0];
    let r = native(&mesh, &Options::default(), 2);
    let one = r
        .interpolate_face_varying(0, 1, 2, &channel.values)
        .unwrap();
    let two = r.interpolate_face_varying(0, 2, 2, &one).unwrap();
    let mut dst = vec![f64::NAN; two.len()];
    r.interpolate_face_varying_into(0, 2, 2, &one, &mut dst)
        .unwrap();
    assert!(
        dst.iter()
            .zip(&two)
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
    let all = r
        .interpolate_face_varying_all(0, 2, &channel.values)
        .unwrap();
    assert_eq!(all.len(), 3);
    assert_eq!((&all[1][..], &all[2][..]), (&one[..], &two[..]));
    let last = r
        .interpolate_face_varying_last(0, 2, &channel.values)
        .unwrap();
    assert_eq!(&last[..], &two[..]);
    // Refusals.
    let mut short = vec![0.0; two.len() - 2];
    assert!(matches!(
        r.interpolate_face_varying_into(0, 2, 2, &one, &mut short),
        Err(Error::BufferLength { buffer: Buffer::Destination, got, .. }) if got == two.len() - 2
    ));
    assert!(matches!(
        r.interpolate_face_varying_into(0, 2, 2, &one[2..], &mut dst),
        Err(Error::BufferLength {
            buffer: Buffer::FaceVaryingSource,
            ..
        })
    ));
    assert!(matches!(
        r.interpolate_face_varying_into(1, 2, 2, &one, &mut dst),
        Err(Error::NoSuchChannel {
            channel: 1,
            count: 1
        })
    ));
    assert!(
        r.interpolate_face_varying_into(0, 3, 2, &two, &mut dst)
            .is_err()
    );
    assert!(matches!(
        r.interpolate_face_varying_all(0, 2, &channel.values[1..]),
        Err(Error::BufferLength {
            buffer: Buffer::FaceVaryingSource,
            ..
        })
    ));
    // Level 0 only: the base values back, checked all the same.
    let base = native(&mesh, &Options::default(), 0);
    let values = base
        .interpolate_face_varying_last(0, 2, &channel.values)
        .unwrap();
    assert_eq!(&values[..], &channel.values[..]);
    assert!(matches!(
        base.interpolate_face_varying_last(0, 2, &channel.values[1..]),
        Err(Error::BufferLength {
            buffer: Buffer::FaceVaryingSource,
            ..
        })
    ));
    assert!(matches!(
        base.interpolate_face_varying_last(3, 2, &channel.values),
        Err(Error::NoSuchChannel {
            channel: 3,
            count: 1
        })
    ));
}
