//! The 20 points of a Gregory patch over a source patch (`GregoryConverter`
//! in `far/catmarkPatchBuilder.cpp`): for each corner its limit point `P`,
//! the edge points `Ep`, `Em` along its two edges and the face points
//! `Fp`, `Fm` beside them, rows `5 * corner + 0..5` of the matrix.
//! Regular corners take fixed B-spline weights, irregular ones the limit
//! weights of their ring; face points next to an irregular corner combine
//! the edge points and the ring across the edge.

use super::limits;
use super::matrix::{Matrix, copy_row, set_all};
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

/// A source patch seen as a Gregory patch.
pub(super) struct Gregory<R> {
    corners: Vec<Corner<R>>,
    points: usize,
    /// One irregular interior corner of valence above 2, nothing sharp:
    /// the matrix then has OpenSubdiv's compact row sizes.
    isolated: Option<(usize, usize)>,
    has_val2_interior: bool,
}

impl<R: Real> Gregory<R> {
    /// Reads the corners of `patch` (`GregoryConverter::Initialize`).
    pub fn new(patch: &SourcePatch) -> Gregory<R> {
        let mut corners: Vec<Corner<R>> = (0..4)
            .map(|c| {
                let s = &patch.corners[c];
                let valence = s.faces + s.boundary as usize;
                let regular = (s.faces << s.boundary as usize) == 4 && !s.sharp;
                // A regular corner's face angle is π/2: cosine 0.
                let cos_angle = if regular {
                    R::ZERO
                } else {
                    let half_turns = if s.boundary {
                        R::from_f64(PI)
                    } else {
                        R::from_f64(2.0) * R::from_f64(PI)
                    };
                    (half_turns / R::from_f64(s.faces as f64)).cos()
                };
                Corner {
                    boundary: s.boundary,
                    sharp: s.sharp,
                    regular,
                    val2_interior: s.val2_interior,
                    valence,
                    faces: s.faces,
                    face_in_ring: s.patch_face,
                    cos_angle,
                    ring: patch.ring(c),
                    ..Corner::default()
                }
            })
            .collect();
        let irregular: Vec<usize> = (0..4).filter(|&c| !corners[c].regular).collect();
        let boundaries = corners.iter().filter(|c| c.boundary).count();
        let sharps = corners.iter().filter(|c| c.sharp).count();
        let has_val2_interior = corners.iter().any(|c| c.val2_interior);
        for c in 0..4 {
            let (next, prev) = ((c + 1) % 4, (c + 3) % 4);
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
        Gregory {
            corners,
            points: patch.points,
            isolated,
            has_val2_interior,
        }
    }

    /// The corner of an isolated irregular interior patch, if it is one.
    pub fn isolated_corner(&self) -> Option<usize> {
        self.isolated.map(|(c, _)| c)
    }

    /// The change-of-basis matrix (`GregoryConverter::Convert`), into `m`.
    pub fn convert_into(&self, m: &mut Matrix<R>) {
        let sizes = match self.isolated {
            Some((c, valence)) => isolated_sizes(c, valence),
            None => self.unisolated_sizes(),
        };
        m.reset(&sizes, self.points);
        for c in 0..4 {
            if self.corners[c].regular {
                self.regular_edge_points(c, m);
            } else {
                self.irregular_edge_points(c, m);
            }
        }
        let mut scratch = (vec![R::ZERO; self.points], vec![false; self.points]);
        for c in 0..4 {
            let corner = &self.corners[c];
            if corner.fp_regular || corner.fm_regular {
                self.regular_face_points(c, m);
            }
            if !corner.fp_regular || !corner.fm_regular {
                self.irregular_face_points(c, m, &mut scratch);
            }
        }
        if self.has_val2_interior {
            m.merge_repeated_corners();
        }
    }

    /// Row sizes when no corner is isolated (`resizeMatrixUnisolated`).
    fn unisolated_sizes(&self) -> Vec<usize> {
        let mut sizes = vec![0; 20];
        for (c, corner) in self.corners.iter().enumerate() {
            let row = &mut sizes[5 * c..5 * c + 5];
            let (p, ep, em) = if corner.regular {
                if !corner.boundary {
                    (9, 6, 6)
                } else {
                    (
                        3,
                        edge_size(corner.ep_on_boundary, 6),
                        edge_size(corner.em_on_boundary, 6),
                    )
                }
            } else if corner.sharp {
                (1, 2, 2)
            } else if !corner.boundary {
                let ring = 1 + 2 * corner.valence;
                (ring, ring, ring)
            } else if corner.faces > 1 {
                let ring = 1 + corner.valence + corner.faces;
                (
                    3,
                    edge_size(corner.ep_on_boundary, ring),
                    edge_size(corner.em_on_boundary, ring),
                )
            } else {
                (3, 2, 2)
            };
            row[0] = p;
            row[1] = ep;
            row[2] = em;
            let (next, prev) = ((c + 1) % 4, (c + 3) % 4);
            row[3] = if corner.fp_regular {
                4
            } else {
                self.face_point_size(c, if corner.fp_copied { prev } else { next })
            };
            row[4] = if corner.fm_regular {
                4
            } else {
                self.face_point_size(c, if corner.fm_copied { next } else { prev })
            };
        }
        sizes
    }

    /// Entries of an irregular face point (`getIrregularFacePointSize`).
    fn face_point_size(&self, near: usize, far: usize) -> usize {
        let (n, f) = (&self.corners[near], &self.corners[far]);
        if n.sharp && f.sharp {
            return 2;
        }
        let this = if n.sharp { 6 } else { 1 + n.ring.len() };
        let adjacent = if f.regular || f.sharp {
            0
        } else {
            (1 + f.ring.len()).saturating_sub(6)
        };
        this + adjacent
    }

    /// `P`, `Ep`, `Em` of a regular corner (`assignRegularEdgePoints`).
    fn regular_edge_points(&self, c: usize, m: &mut Matrix<R>) {
        let corner = &self.corners[c];
        let r = |i: usize| corner.ring.get(i).copied().unwrap_or(c);
        let w = R::from_f64;
        let rows = &mut m.rows[5 * c..5 * c + 3];
        let [p, ep, em] = rows else { return };
        if !corner.boundary {
            set_all(
                p,
                &[
                    (c, w(4.0 / 9.0)),
                    (r(0), w(1.0 / 9.0)),
                    (r(2), w(1.0 / 9.0)),
                    (r(4), w(1.0 / 9.0)),
                    (r(6), w(1.0 / 9.0)),
                    (r(1), w(1.0 / 36.0)),
                    (r(3), w(1.0 / 36.0)),
                    (r(5), w(1.0 / 36.0)),
                    (r(7), w(1.0 / 36.0)),
                ],
            );
            let e_ep = 2 * corner.face_in_ring;
            let e_em = 2 * ((corner.face_in_ring + 1) % 4);
            let e_op = 2 * ((corner.face_in_ring + 2) % 4);
            let e_om = 2 * ((corner.face_in_ring + 3) % 4);
            set_all(
                ep,
                &[
                    (c, w(4.0 / 9.0)),
                    (r(e_ep), w(2.0 / 9.0)),
                    (r(e_em), w(1.0 / 9.0)),
                    (r(e_om), w(1.0 / 9.0)),
                    (r(e_ep + 1), w(1.0 / 18.0)),
                    (r(e_om + 1), w(1.0 / 18.0)),
                ],
            );
            set_all(
                em,
                &[
                    (c, w(4.0 / 9.0)),
                    (r(e_em), w(2.0 / 9.0)),
                    (r(e_ep), w(1.0 / 9.0)),
                    (r(e_op), w(1.0 / 9.0)),
                    (r(e_ep + 1), w(1.0 / 18.0)),
                    (r(e_em + 1), w(1.0 / 18.0)),
                ],
            );
        } else {
            set_all(
                p,
                &[
                    (c, w(2.0 / 3.0)),
                    (r(0), w(1.0 / 6.0)),
                    (r(4), w(1.0 / 6.0)),
                ],
            );
            let (on_boundary, interior, i_boundary) = if corner.ep_on_boundary {
                (ep, em, 0)
            } else {
                (em, ep, 4)
            };
            set_all(
                on_boundary,
                &[(c, w(2.0 / 3.0)), (r(i_boundary), w(1.0 / 3.0))],
            );
            set_all(
                interior,
                &[
                    (c, w(4.0 / 9.0)),
                    (r(2), w(2.0 / 9.0)),
                    (r(0), w(1.0 / 9.0)),
                    (r(4), w(1.0 / 9.0)),
                    (r(1), w(1.0 / 18.0)),
                    (r(3), w(1.0 / 18.0)),
                ],
            );
        }
    }

    /// `P`, `Ep`, `Em` of an irregular corner (`computeIrregularEdgePoints`).
    fn irregular_edge_points(&self, c: usize, m: &mut Matrix<R>) {
        let corner = &self.corners[c];
        let w = R::from_f64;
        let (next, prev) = ((c + 1) % 4, (c + 3) % 4);
        let rows = &mut m.rows[5 * c..5 * c + 3];
        let [p, ep, em] = rows else { return };
        let ring = |i: usize| corner.ring.get(i).copied().unwrap_or(c);
        if corner.sharp {
            set_all(p, &[(c, R::ONE)]);
            set_all(ep, &[(c, w(2.0 / 3.0)), (next, w(1.0 / 3.0))]);
            set_all(em, &[(c, w(2.0 / 3.0)), (prev, w(1.0 / 3.0))]);
        } else if !corner.boundary {
            let [wp, wep, wem] = limits::interior::<R>(corner.valence, corner.face_in_ring, true);
            for (i, ((&a, &b), &d)) in wp.iter().zip(&wep).zip(&wem).enumerate() {
                let column = if i == 0 { c } else { ring(i - 1) };
                p.set(i, column, a);
                ep.set(i, column, b);
                em.set(i, column, d);
            }
        } else if corner.faces > 1 {
            let [wp, wep, wem] = limits::boundary::<R>(corner.valence, corner.face_in_ring, true);
            let width = 1 + corner.valence + corner.faces;
            let n = width - 1;
            let (p1, pn) = (ring(0), ring(2 * (corner.valence - 1)));
            let at = |v: &[R], i: usize| v.get(i).copied().unwrap_or(R::ZERO);
            set_all(p, &[(c, at(&wp, 0)), (p1, at(&wp, 1)), (pn, at(&wp, n))]);
            ep.set(0, c, at(&wep, 0));
            if corner.ep_on_boundary {
                ep.set(1, p1, at(&wep, 1));
            } else {
                for i in 1..width {
                    ep.set(i, ring(i - 1), at(&wep, i));
                }
            }
            em.set(0, c, at(&wem, 0));
            if corner.em_on_boundary {
                em.set(1, pn, at(&wem, n));
            } else {
                for i in 1..width {
                    em.set(i, ring(i - 1), at(&wem, i));
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
            set_all(ep, &[(c, w(2.0 / 3.0)), (next, w(1.0 / 3.0))]);
            set_all(em, &[(c, w(2.0 / 3.0)), (prev, w(1.0 / 3.0))]);
        }
    }

    /// Regular `Fp` and/or `Fm` (`assignRegularFacePoints`).
    fn regular_face_points(&self, c: usize, m: &mut Matrix<R>) {
        let corner = &self.corners[c];
        let w = R::from_f64;
        let (next, opp, prev) = ((c + 1) % 4, (c + 2) % 4, (c + 3) % 4);
        let entries = [
            (c, w(4.0 / 9.0)),
            (prev, w(2.0 / 9.0)),
            (next, w(2.0 / 9.0)),
            (opp, w(1.0 / 9.0)),
        ];
        if corner.fp_regular {
            set_all(&mut m.rows[5 * c + 3], &entries);
        }
        if corner.fm_regular {
            set_all(&mut m.rows[5 * c + 4], &entries);
        }
    }

    /// Irregular `Fp` and/or `Fm`, then the copies
    /// (`computeIrregularFacePoints`).
    fn irregular_face_points(
        &self,
        c: usize,
        m: &mut Matrix<R>,
        scratch: &mut (Vec<R>, Vec<bool>),
    ) {
        let corner = &self.corners[c];
        let (next, prev) = ((c + 1) % 4, (c + 3) % 4);
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
    /// back (rows `p`, `e_near`, `e_far` of `m`), plus the ring across the
    /// edge, written into row `out` (`computeIrregularFacePoint`).
    #[allow(clippy::too_many_arguments)]
    fn irregular_face_point(
        &self,
        near: usize,
        edge_in_ring: usize,
        far: usize,
        [p, e_near, e_far, out]: [usize; 4],
        sign: R,
        m: &mut Matrix<R>,
        (weights, used): &mut (Vec<R>, Vec<bool>),
    ) {
        let (cn, cf) = (&self.corners[near], &self.corners[far]);
        let three = R::from_f64(3.0);
        let two = R::from_f64(2.0);
        let p_coeff = cf.cos_angle / three;
        let e_near_coeff = (three - two * cn.cos_angle - cf.cos_angle) / three;
        let e_far_coeff = two * cn.cos_angle / three;
        weights.iter_mut().for_each(|w| *w = R::ZERO);
        used.iter_mut().for_each(|u| *u = false);
        for (row, s) in [(p, p_coeff), (e_near, e_near_coeff), (e_far, e_far_coeff)] {
            let row = &m.rows[row];
            for (&i, &w) in row.columns.iter().zip(&row.weights) {
                if let Some(x) = weights.get_mut(i) {
                    *x += s * w;
                    used[i] = true;
                }
            }
        }
        let valence = cn.valence.max(1);
        let interior = edge_in_ring;
        let prev_edge = (interior + valence - 1) % valence;
        let next_edge = (interior + 1) % valence;
        let ring = |i: usize| cn.ring.get(i).copied();
        let nine = R::from_f64(9.0);
        let eighteen = R::from_f64(18.0);
        for (at, w) in [
            (ring(2 * prev_edge), -sign / nine),
            (ring(2 * prev_edge + 1), -sign / eighteen),
            (ring(2 * interior + 1), sign / eighteen),
            (ring(2 * next_edge), sign / nine),
        ] {
            if let Some(x) = at.and_then(|i| weights.get_mut(i)) {
                *x += w;
            }
        }
        let row = &mut m.rows[out];
        let size = row.len();
        row.columns.clear();
        row.weights.clear();
        for (i, (&u, &w)) in used.iter().zip(weights.iter()).enumerate() {
            if u && row.columns.len() < size {
                row.columns.push(i);
                row.weights.push(w);
            }
        }
        // Valence-2 corners repeat points: pad to the expected size.
        if self.has_val2_interior {
            while row.columns.len() < size {
                row.columns.push(near);
                row.weights.push(R::ZERO);
            }
        }
    }
}

/// An edge point's entries: 2 along a boundary edge, else `interior`.
fn edge_size(on_boundary: bool, interior: usize) -> usize {
    if on_boundary { 2 } else { interior }
}

/// Row sizes with one isolated irregular interior corner `c` of `valence`
/// (`resizeMatrixIsolatedIrregular`).
fn isolated_sizes(c: usize, valence: usize) -> Vec<usize> {
    let ring = 1 + 2 * valence;
    let mut sizes = vec![0; 20];
    sizes[5 * c..5 * c + 5].copy_from_slice(&[ring; 5]);
    sizes[5 * ((c + 1) % 4)..][..5].copy_from_slice(&[9, 6, 6, 4, 3 + ring]);
    sizes[5 * ((c + 2) % 4)..][..5].copy_from_slice(&[9, 6, 6, 4, 4]);
    sizes[5 * ((c + 3) % 4)..][..5].copy_from_slice(&[9, 6, 6, 3 + ring, 4]);
    sizes
}
