//! The 18 points of a quartic Gregory triangle over a triangular source
//! patch (`GregoryTriConverter` in `far/loopPatchBuilder.cpp`): for each
//! corner its limit point `P`, the edge points `Ep`, `Em` along its two
//! edges and the face points `Fp`, `Fm` beside them (rows `5 * corner +
//! 0..5`), then the mid-edge point `M` of each edge (rows `15..18`).
//!
//! The patch is first built as a cubic-quartic hybrid — cubic edge points
//! from the Loop limit weights of each corner's ring (fixed box-spline
//! weights at regular corners), face points from them and the ring across
//! the edge — and its edge points are then raised to quartic ones.

use super::loop_limits;
use super::matrix::{Matrix, Scratch, accumulate, combine, copy_row, set_all, write_row};
use super::source::SourcePatch;
use crate::real::Real;
use std::f64::consts::PI;

/// What the converter keeps of each corner.
#[derive(Debug, Clone, Default)]
struct Corner<R> {
    boundary: bool,
    sharp: bool,
    regular: bool,
    val2_interior: bool,
    /// A boundary corner of one face.
    single_face: bool,
    ep_on_boundary: bool,
    em_on_boundary: bool,
    fp_regular: bool,
    fm_regular: bool,
    fp_copied: bool,
    fm_copied: bool,
    valence: usize,
    faces: usize,
    face_in_ring: usize,
    cos_angle: R,
    ring: Vec<usize>,
}

/// A triangular source patch seen as a Gregory triangle.
pub(super) struct GregoryTriangle<R> {
    corners: [Corner<R>; 3],
    points: usize,
    /// One irregular interior corner of valence above 2, nothing sharp:
    /// the matrix then has OpenSubdiv's compact row sizes.
    isolated: Option<(usize, usize)>,
    has_val2_interior: bool,
}

impl<R: Real> GregoryTriangle<R> {
    /// Reads the corners of `patch` (`GregoryTriConverter::Initialize`).
    pub fn new(patch: &SourcePatch) -> GregoryTriangle<R> {
        let mut corners: [Corner<R>; 3] = std::array::from_fn(|c| {
            let s = &patch.corners[c];
            let regular = (s.faces << s.boundary as usize) == 6 && !s.sharp;
            // A regular corner's face angle is π/3: cosine 1/2 exactly.
            let cos_angle = if regular {
                R::from_f64(0.5)
            } else {
                let turn = if s.boundary { PI } else { 2.0 * PI };
                (R::from_f64(turn) / R::from_f64(s.faces as f64)).cos()
            };
            Corner {
                boundary: s.boundary,
                sharp: s.sharp,
                regular,
                val2_interior: s.val2_interior,
                single_face: s.faces == 1,
                valence: s.faces + s.boundary as usize,
                faces: s.faces,
                face_in_ring: s.patch_face,
                cos_angle,
                ring: patch.ring(c),
                ..Corner::default()
            }
        });
        let irregular: Vec<usize> = (0..3).filter(|&c| !corners[c].regular).collect();
        let boundaries = corners.iter().filter(|c| c.boundary).count();
        let sharps = corners.iter().filter(|c| c.sharp).count();
        let has_val2_interior = corners.iter().any(|c| c.val2_interior);
        for c in 0..3 {
            let (next, prev) = ((c + 1) % 3, (c + 2) % 3);
            let (next_regular, prev_regular) = (corners[next].regular, corners[prev].regular);
            let corner = &mut corners[c];
            corner.fp_regular = corner.regular && next_regular;
            corner.fm_regular = corner.regular && prev_regular;
            if corner.boundary {
                corner.ep_on_boundary = corner.face_in_ring == 0;
                corner.em_on_boundary = corner.face_in_ring + 1 == corner.faces;
                if corner.faces > 1 {
                    if corner.ep_on_boundary {
                        corner.fp_regular = corner.fm_regular;
                        corner.fp_copied = !corner.fp_regular;
                    }
                    if corner.em_on_boundary {
                        corner.fm_regular = corner.fp_regular;
                        corner.fm_copied = !corner.fm_regular;
                    }
                } else {
                    corner.fp_regular = true;
                    corner.fm_regular = true;
                }
            }
        }
        let isolated = match irregular.as_slice() {
            [c] if boundaries == 0 && sharps == 0 && corners[*c].valence > 2 => {
                Some((*c, corners[*c].valence))
            }
            _ => None,
        };
        GregoryTriangle {
            corners,
            points: patch.points,
            isolated,
            has_val2_interior,
        }
    }

    /// The change-of-basis matrix (`GregoryTriConverter::Convert`), into
    /// `m`.
    pub fn convert_into(&self, m: &mut Matrix<R>) {
        let sizes = match self.isolated {
            Some((c, valence)) => isolated_sizes(c, valence),
            None => self.unisolated_sizes(),
        };
        m.reset(&sizes, self.points);
        for c in 0..3 {
            if self.corners[c].regular {
                self.regular_edge_points(c, m);
            } else {
                self.irregular_edge_points(c, m);
            }
        }
        let mut scratch = (vec![R::ZERO; self.points], vec![false; self.points]);
        for c in 0..3 {
            let corner = &self.corners[c];
            if corner.fp_regular || corner.fm_regular {
                self.regular_face_points(c, m);
            }
            if !corner.fp_regular || !corner.fm_regular {
                self.irregular_face_points(c, m, &mut scratch);
            }
        }
        for e in 0..3 {
            let (c0, c1) = (&self.corners[e], &self.corners[(e + 1) % 3]);
            let boundary_edge = c0.ep_on_boundary && c1.em_on_boundary;
            let dart_edge = c0.ep_on_boundary != c1.em_on_boundary;
            if boundary_edge || (c0.regular && c1.regular && !dart_edge) {
                self.regular_mid_edge_point(e, m);
            } else {
                let half = R::from_f64(0.5);
                let terms = [(5 * e + 1, half), (5 * ((e + 1) % 3) + 2, half)];
                combine(m, 15 + e, &terms, &mut scratch, Some(0));
            }
        }
        self.raise_edge_points(m, &mut scratch);
        if self.has_val2_interior {
            m.merge_repeated_corners();
        }
    }

    /// Row sizes when no corner is isolated (`resizeMatrixUnisolated`).
    fn unisolated_sizes(&self) -> Vec<usize> {
        let mut sizes = vec![0; 18];
        for (c, corner) in self.corners.iter().enumerate() {
            let edge = |on_boundary: bool, interior: usize| {
                if on_boundary { 3 } else { interior }
            };
            let (p, ep, em) = if corner.regular {
                if !corner.boundary {
                    (7, 7, 7)
                } else {
                    (
                        3,
                        edge(corner.ep_on_boundary, 5),
                        edge(corner.em_on_boundary, 5),
                    )
                }
            } else if corner.sharp {
                (1, 2, 2)
            } else if !corner.boundary {
                let ring = 1 + corner.valence;
                (ring, ring, ring)
            } else if corner.faces > 1 {
                let ring = 1 + corner.valence;
                (
                    3,
                    edge(corner.ep_on_boundary, ring),
                    edge(corner.em_on_boundary, ring),
                )
            } else {
                (3, 3, 3)
            };
            let (next, prev) = ((c + 1) % 3, (c + 2) % 3);
            let regular_face = 5 - corner.ep_on_boundary as usize - corner.em_on_boundary as usize;
            let fp = if corner.fp_regular {
                regular_face
            } else {
                self.face_point_size(c, if corner.fp_copied { prev } else { next })
            };
            let fm = if corner.fm_regular {
                regular_face
            } else {
                self.face_point_size(c, if corner.fm_copied { next } else { prev })
            };
            sizes[5 * c..5 * c + 5].copy_from_slice(&[p, ep, em, fp, fm]);
            let n = &self.corners[next];
            sizes[15 + c] = if corner.ep_on_boundary && n.em_on_boundary {
                2
            } else if corner.regular && n.regular && corner.ep_on_boundary == n.em_on_boundary {
                4
            } else {
                self.face_point_size(c, next)
            };
        }
        sizes
    }

    /// Entries of an irregular face point, or of a mid-edge point between
    /// two corners (`getIrregularFacePointSize`).
    fn face_point_size(&self, near: usize, far: usize) -> usize {
        let (n, f) = (&self.corners[near], &self.corners[far]);
        if n.sharp && f.sharp {
            return 2;
        }
        let beyond = |c: &Corner<R>| {
            if c.sharp {
                0
            } else {
                c.ring.len().saturating_sub(3)
            }
        };
        4 + beyond(n) + beyond(f)
    }

    /// `P`, `Ep`, `Em` of a regular corner (`assignRegularEdgePoints`).
    fn regular_edge_points(&self, c: usize, m: &mut Matrix<R>) {
        let corner = &self.corners[c];
        let r = |i: usize| corner.ring.get(i).copied().unwrap_or(c);
        let w = R::from_f64;
        let [p, ep, em] = &mut m.rows[5 * c..5 * c + 3] else {
            return;
        };
        let half = w(0.5);
        if !corner.boundary {
            let twelfth = w(1.0 / 12.0);
            p.set(0, c, half);
            for i in 0..6 {
                p.set(1 + i, r(i), twelfth);
            }
            // Along the edge, its two neighbours, ... around the ring.
            const E: [f32; 6] = [7.0, 5.0, 1.0, -1.0, 1.0, 5.0];
            let scale = w(1.0 / 36.0);
            for (row, first) in [
                (ep, corner.face_in_ring),
                (em, (corner.face_in_ring + 1) % 6),
            ] {
                row.set(0, c, half);
                for (k, &x) in E.iter().enumerate() {
                    row.set(1 + k, r((first + k) % 6), scale * R::from_f32(x));
                }
            }
        } else {
            let (third, two_thirds, sixth) = (w(1.0 / 3.0), w(2.0 / 3.0), w(1.0 / 6.0));
            set_all(p, &[(c, two_thirds), (r(0), sixth), (r(3), sixth)]);
            // Interior edges take phantom points into account.
            let (ep_on, em_on) = (corner.ep_on_boundary, corner.em_on_boundary);
            for (row, on, other_on, end, far) in
                [(ep, ep_on, em_on, 0, 3), (em, em_on, ep_on, 3, 0)]
            {
                if on {
                    set_all(row, &[(c, two_thirds), (r(end), third), (r(far), R::ZERO)]);
                } else {
                    let (a, b) = if other_on { (far, end) } else { (end, far) };
                    set_all(
                        row,
                        &[
                            (c, half),
                            (r(1), sixth),
                            (r(2), sixth),
                            (r(a), sixth),
                            (r(b), R::ZERO),
                        ],
                    );
                }
            }
        }
    }

    /// `P`, `Ep`, `Em` of an irregular corner (`computeIrregularEdgePoints`).
    fn irregular_edge_points(&self, c: usize, m: &mut Matrix<R>) {
        let corner = &self.corners[c];
        let w = R::from_f64;
        let (next, prev) = ((c + 1) % 3, (c + 2) % 3);
        let [p, ep, em] = &mut m.rows[5 * c..5 * c + 3] else {
            return;
        };
        let ring = |i: usize| corner.ring.get(i).copied().unwrap_or(c);
        let at = |v: &[R], i: usize| v.get(i).copied().unwrap_or(R::ZERO);
        if corner.sharp {
            set_all(p, &[(c, R::ONE)]);
            set_all(ep, &[(c, w(2.0 / 3.0)), (next, w(1.0 / 3.0))]);
            set_all(em, &[(c, w(2.0 / 3.0)), (prev, w(1.0 / 3.0))]);
        } else if !corner.boundary {
            let [wp, wep, wem] =
                loop_limits::interior::<R>(corner.valence, corner.face_in_ring, true);
            for i in 0..=corner.valence {
                let column = if i == 0 { c } else { ring(i - 1) };
                p.set(i, column, at(&wp, i));
                ep.set(i, column, at(&wep, i));
                em.set(i, column, at(&wem, i));
            }
        } else if corner.faces > 1 {
            let valence = corner.valence;
            let [wp, wep, wem] = loop_limits::boundary::<R>(valence, corner.face_in_ring, true);
            let (p1, pn) = (ring(0), ring(valence - 1));
            set_all(
                p,
                &[(c, at(&wp, 0)), (p1, at(&wp, 1)), (pn, at(&wp, valence))],
            );
            // Along a boundary edge only the edge's two ends weigh.
            for (row, weights, on, end, end_at, far) in [
                (ep, &wep, corner.ep_on_boundary, p1, 1, pn),
                (em, &wem, corner.em_on_boundary, pn, valence, p1),
            ] {
                row.set(0, c, at(weights, 0));
                if on {
                    row.set(1, end, at(weights, end_at));
                    row.set(2, far, R::ZERO);
                } else {
                    for i in 1..=valence {
                        row.set(i, ring(i - 1), at(weights, i));
                    }
                }
            }
        } else {
            set_all(
                p,
                &[
                    (c, w(4.0 / 6.0)),
                    (next, w(1.0 / 6.0)),
                    (prev, w(1.0 / 6.0)),
                ],
            );
            set_all(
                ep,
                &[(c, w(2.0 / 3.0)), (next, w(1.0 / 3.0)), (prev, R::ZERO)],
            );
            set_all(
                em,
                &[(c, w(2.0 / 3.0)), (prev, w(1.0 / 3.0)), (next, R::ZERO)],
            );
        }
    }

    /// Regular `Fp` and/or `Fm` (`assignRegularFacePoints`).
    fn regular_face_points(&self, c: usize, m: &mut Matrix<R>) {
        let corner = &self.corners[c];
        let r = |i: usize| corner.ring.get(i).copied().unwrap_or(c);
        let w = R::from_f64;
        let (next, prev) = ((c + 1) % 3, (c + 2) % 3);
        let quarter = w(0.25);
        let entries: Vec<(usize, R)> = if corner.single_face {
            vec![(c, w(0.5)), (next, quarter), (prev, quarter)]
        } else if corner.ep_on_boundary {
            // The first face of the boundary ring.
            vec![
                (c, w(11.0 / 24.0)),
                (r(0), w(7.0 / 24.0)),
                (r(1), w(5.0 / 24.0)),
                (r(2), w(1.0 / 24.0)),
            ]
        } else if corner.em_on_boundary {
            // The last face of the boundary ring.
            vec![
                (c, w(11.0 / 24.0)),
                (r(3), w(7.0 / 24.0)),
                (r(2), w(5.0 / 24.0)),
                (r(1), w(1.0 / 24.0)),
            ]
        } else {
            // An interior face, or the middle one of a boundary.
            let (e_next, e_prev) = if corner.boundary {
                (0, 3)
            } else {
                ((corner.face_in_ring + 5) % 6, (corner.face_in_ring + 2) % 6)
            };
            vec![
                (c, w(10.0 / 24.0)),
                (prev, quarter),
                (next, quarter),
                (r(e_prev), w(1.0 / 24.0)),
                (r(e_next), w(1.0 / 24.0)),
            ]
        };
        if corner.fp_regular {
            set_all(&mut m.rows[5 * c + 3], &entries);
        }
        if corner.fm_regular {
            set_all(&mut m.rows[5 * c + 4], &entries);
        }
    }

    /// Irregular `Fp` and/or `Fm`, then the copies
    /// (`computeIrregularFacePoints`).
    fn irregular_face_points(&self, c: usize, m: &mut Matrix<R>, scratch: &mut Scratch<R>) {
        let corner = &self.corners[c];
        let (next, prev) = ((c + 1) % 3, (c + 2) % 3);
        if !corner.fp_regular && !corner.fp_copied {
            self.irregular_face_point(
                c,
                corner.face_in_ring,
                next,
                [5 * c, 5 * c + 1, 5 * next + 2, 5 * c + 3],
                R::ONE,
                m,
                scratch,
            );
        }
        if !corner.fm_regular && !corner.fm_copied {
            self.irregular_face_point(
                c,
                (corner.face_in_ring + 1) % corner.valence.max(1),
                prev,
                [5 * c, 5 * c + 2, 5 * prev + 1, 5 * c + 4],
                -R::ONE,
                m,
                scratch,
            );
        }
        if corner.fp_copied {
            let from = m.rows[5 * c + 4].clone();
            copy_row(&mut m.rows[5 * c + 3], &from);
        }
        if corner.fm_copied {
            let from = m.rows[5 * c + 3].clone();
            copy_row(&mut m.rows[5 * c + 4], &from);
        }
    }

    /// A face point next to an irregular corner from the corner's `P`, its
    /// edge point towards the far corner and the far corner's edge point
    /// back (rows `p`, `e_near`, `e_far`), adjusted by the two ring points
    /// on either side of the edge (only where those already weigh), into
    /// row `out` (`computeIrregularFacePoint`).
    #[allow(clippy::too_many_arguments)]
    fn irregular_face_point(
        &self,
        near: usize,
        edge_in_ring: usize,
        far: usize,
        [p, e_near, e_far, out]: [usize; 4],
        sign: R,
        m: &mut Matrix<R>,
        (weights, used): &mut Scratch<R>,
    ) {
        let (cn, cf) = (&self.corners[near], &self.corners[far]);
        let (two, four) = (R::from_f64(2.0), R::from_f64(4.0));
        let p_coeff = cf.cos_angle / four;
        let e_near_coeff = (four - two * cn.cos_angle - cf.cos_angle) / four;
        let e_far_coeff = two * cn.cos_angle / four;
        accumulate(
            m,
            &[(p, p_coeff), (e_near, e_near_coeff), (e_far, e_far_coeff)],
            weights,
            used,
        );
        let valence = cn.valence.max(1);
        let prev_edge = (edge_in_ring + valence - 1) % valence;
        let next_edge = (edge_in_ring + 1) % valence;
        let r_scale = R::from_f64(0.25 * (7.0 / 18.0));
        for (at, w) in [
            (cn.ring.get(prev_edge), -sign * r_scale),
            (cn.ring.get(next_edge), sign * r_scale),
        ] {
            if let Some(x) = at.and_then(|&i| weights.get_mut(i)) {
                *x += w;
            }
        }
        let pad = self.has_val2_interior.then_some(near);
        write_row(&mut m.rows[out], weights, used, pad);
    }

    /// The mid-edge point of a boundary edge or of an edge between two
    /// regular corners (`assignRegularMidEdgePoint`).
    fn regular_mid_edge_point(&self, e: usize, m: &mut Matrix<R>) {
        let corner = &self.corners[e];
        let row = &mut m.rows[15 + e];
        let (next, opposite) = ((e + 1) % 3, (e + 2) % 3);
        let w = R::from_f64;
        if corner.ep_on_boundary {
            set_all(row, &[(e, w(0.5)), (next, w(0.5))]);
        } else {
            // The two corners and the two vertices facing the edge.
            let in_ring = if corner.boundary {
                corner.face_in_ring.wrapping_sub(1)
            } else {
                (corner.face_in_ring + 5) % 6
            };
            let across = corner.ring.get(in_ring).copied().unwrap_or(e);
            set_all(
                row,
                &[
                    (e, w(1.0 / 3.0)),
                    (next, w(1.0 / 3.0)),
                    (opposite, w(1.0 / 6.0)),
                    (across, w(1.0 / 6.0)),
                ],
            );
        }
    }

    /// The cubic edge points made quartic (`promoteCubicEdgePointsToQuartic`):
    /// fixed weights along boundary edges and at regular corners, elsewhere
    /// a quarter of `P` and three quarters of the cubic point.
    fn raise_edge_points(&self, m: &mut Matrix<R>, scratch: &mut Scratch<R>) {
        const ON_BOUNDARY: [f32; 3] = [16.0, 7.0, 1.0];
        const REGULAR_BOUNDARY: [f32; 5] = [13.0, 3.0, 3.0, 4.0, 1.0];
        const REGULAR_INTERIOR: [f32; 7] = [12.0, 4.0, 3.0, 1.0, 0.0, 1.0, 3.0];
        let over24 = R::from_f64(1.0 / 24.0);
        for (c, corner) in self.corners.iter().enumerate() {
            for (e, on_boundary) in [(1, corner.ep_on_boundary), (2, corner.em_on_boundary)] {
                let row = 5 * c + e;
                let fixed: Option<&[f32]> = if on_boundary && !corner.sharp {
                    Some(&ON_BOUNDARY)
                } else if corner.regular && corner.boundary {
                    Some(&REGULAR_BOUNDARY)
                } else if corner.regular {
                    Some(&REGULAR_INTERIOR)
                } else {
                    None
                };
                match fixed {
                    Some(weights) => {
                        let row = &mut m.rows[row];
                        for (x, &k) in row.weights.iter_mut().zip(weights) {
                            *x = R::from_f32(k) * over24;
                        }
                    }
                    None => {
                        let terms = [(5 * c, R::from_f64(0.25)), (row, R::from_f64(0.75))];
                        combine(m, row, &terms, scratch, Some(0));
                    }
                }
            }
        }
    }
}

/// Row sizes with one isolated irregular interior corner `c` of `valence`
/// (`resizeMatrixIsolatedIrregular`).
fn isolated_sizes(c: usize, valence: usize) -> Vec<usize> {
    let ring = 1 + valence;
    let (plus, minus) = ((c + 1) % 3, (c + 2) % 3);
    let mut sizes = vec![0; 18];
    sizes[5 * c..][..5].copy_from_slice(&[ring, ring, ring, 3 + ring, 3 + ring]);
    sizes[5 * plus..][..5].copy_from_slice(&[7, 7, 7, 5, 3 + ring]);
    sizes[5 * minus..][..5].copy_from_slice(&[7, 7, 7, 3 + ring, 5]);
    sizes[15 + c] = 3 + ring;
    sizes[15 + plus] = 4;
    sizes[15 + minus] = 3 + ring;
    sizes
}
