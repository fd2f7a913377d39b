//! `subdiv curve --knots` against an independent NURBS implementation
//! written here from the definitions, sharing no code with the library:
//!
//! - points of the curve from the Cox–de Boor recursion of the basis
//!   functions, `C(t) = Σ N_i,d(t) w_i P_i / Σ N_i,d(t) w_i`, not from de
//!   Boor's algorithm;
//! - control points after insertion from the blossom (polar form): on any
//!   span of the new knot vector, the new control point `Q_i` is the blossom
//!   of the old curve's polynomial piece on that span at the new knots
//!   `t̂_{i+1} .. t̂_{i+d}`, in homogeneous coordinates `(w P, w)` — which
//!   holds for one insertion or many, so it checks Boehm's rule without
//!   repeating it.
//!
//! Random curves of degrees 1-5, clamped and unclamped, rational and not,
//! 2-D and 3-D, with repeated interior knots, and 1-4 insertions (some at
//! existing knots); the CLI's output must agree to 1e-9 relative.
//!
//! `scripts/check-nurbs.py` (run by `make test`) makes the same comparison
//! against geomdl, a third-party library; this one needs no Python or
//! package index, so `cargo test` alone runs it.

use crate::curve_knots::list;
use crate::support::{Rng, scratch, subdiv, write};
use std::path::Path;

/// A curve as the test holds it: homogeneous control points `(w x, w y[, w z], w)`.
struct Reference {
    degree: usize,
    knots: Vec<f64>,
    /// Euclidean control points.
    points: Vec<Vec<f64>>,
    weights: Option<Vec<f64>>,
}

impl Reference {
    fn weight(&self, i: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i])
    }

    fn homogeneous(&self, i: usize) -> Vec<f64> {
        let w = self.weight(i);
        let mut h: Vec<f64> = self.points[i].iter().map(|x| x * w).collect();
        h.push(w);
        h
    }

    fn domain(&self) -> (f64, f64) {
        let m = self.knots.len() - 1;
        (self.knots[self.degree], self.knots[m - self.degree])
    }

    /// The span `k` of the domain holding `t`: `u_k <= t < u_{k+1}`, or the
    /// last non-empty span for the domain's end.
    fn span(&self, t: f64) -> usize {
        let (d, u) = (self.degree, &self.knots);
        let last = u.len() - 1 - d - 1;
        let (_, end) = self.domain();
        if t >= end {
            return (d..=last).rev().find(|&k| u[k] < u[k + 1]).unwrap();
        }
        (d..=last).find(|&k| u[k] <= t && t < u[k + 1]).unwrap()
    }

    /// Every `N_i,d(t)` by the Cox–de Boor recursion (0/0 = 0).
    fn basis(&self, t: f64) -> Vec<f64> {
        let u = &self.knots;
        let k = self.span(t);
        let mut n: Vec<f64> = (0..u.len() - 1).map(|i| (i == k) as u8 as f64).collect();
        for p in 1..=self.degree {
            let ratio = |num: f64, den: f64| if den == 0.0 { 0.0 } else { num / den };
            n = (0..u.len() - 1 - p)
                .map(|i| {
                    ratio(t - u[i], u[i + p] - u[i]) * n[i]
                        + ratio(u[i + p + 1] - t, u[i + p + 1] - u[i + 1]) * n[i + 1]
                })
                .collect();
        }
        n
    }

    /// The curve point at `t`, from the basis.
    fn point(&self, t: f64) -> Vec<f64> {
        let n = self.basis(t);
        let dim = self.points[0].len();
        let mut h = vec![0.0; dim + 1];
        for (i, ni) in n.iter().enumerate() {
            for (a, b) in h.iter_mut().zip(self.homogeneous(i)) {
                *a += ni * b;
            }
        }
        h[..dim].iter().map(|x| x / h[dim]).collect()
    }

    /// The blossom of the polynomial piece on span `k` at `args` (d values),
    /// homogeneous.
    fn blossom(&self, k: usize, args: &[f64]) -> Vec<f64> {
        let (d, u) = (self.degree, &self.knots);
        let mut p: Vec<Vec<f64>> = (k - d..=k).map(|j| self.homogeneous(j)).collect();
        for (r, &a) in (1..=d).zip(args) {
            // p[s] stands for the control point j = k - d + s.
            for s in (r..=d).rev() {
                let j = k - d + s;
                let alpha = (a - u[j]) / (u[j + d - r + 1] - u[j]);
                let blended: Vec<f64> = p[s - 1]
                    .iter()
                    .zip(&p[s])
                    .map(|(x, y)| (1.0 - alpha) * x + alpha * y)
                    .collect();
                p[s] = blended;
            }
        }
        p.pop().unwrap()
    }

    /// The curve after inserting `ts`: new knots sorted in, each new control
    /// point the blossom of the old piece under one of its non-empty spans.
    fn inserted(&self, ts: &[f64]) -> Reference {
        let d = self.degree;
        let mut knots = self.knots.clone();
        knots.extend_from_slice(ts);
        knots.sort_by(f64::total_cmp);
        let m = knots.len() - 1;
        let count = m - d;
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for i in 0..count {
            let j = (i.max(d)..=(i + d).min(m - d - 1))
                .find(|&j| knots[j] < knots[j + 1])
                .expect("every control point acts on a non-empty span");
            let k = self.span(0.5 * (knots[j] + knots[j + 1]));
            let h = self.blossom(k, &knots[i + 1..=i + d]);
            let w = h[h.len() - 1];
            points.push(h[..h.len() - 1].iter().map(|x| x / w).collect());
            weights.push(w);
        }
        Reference {
            degree: d,
            knots,
            points,
            weights: self.weights.as_ref().map(|_| weights),
        }
    }
}

/// A random curve: degree 1-5, `degree + 1` to `degree + 6` points, clamped
/// or not, interior knots repeated up to the degree, the first and last spans
/// of the domain non-empty (else an end control point would not act on the
/// curve and nothing could check it).
fn random_curve(rng: &mut Rng, case: usize) -> Reference {
    let degree = 1 + case % 5;
    let clamped = case.is_multiple_of(2);
    let count = degree + 1 + ((rng.next() + 1.0) * 3.0) as usize;
    let m = count + degree;
    let mut knots = vec![rng.next() * 4.0];
    let mut run = 1;
    for k in 1..=m {
        let end_repeat = clamped && (k <= degree || k > m - degree);
        let gap = k == degree + 1 || k == m - degree;
        let repeat = end_repeat || (!gap && run < degree && rng.next() > 0.5);
        let last = knots[k - 1];
        knots.push(if repeat {
            last
        } else {
            last + 0.25 + (rng.next() + 1.0)
        });
        run = if repeat { run + 1 } else { 1 };
    }
    let dim = 2 + case % 3 / 2;
    let points = (0..count)
        .map(|_| (0..dim).map(|_| rng.next() * 50.0).collect())
        .collect();
    let rational = case % 4 >= 2;
    let weights = rational.then(|| (0..count).map(|_| 0.2 + (rng.next() + 1.0) * 2.0).collect());
    Reference {
        degree,
        knots,
        points,
        weights,
    }
}

/// 1-4 values strictly inside the domain, some of them existing interior
/// knots whose multiplicity stays at most the degree.
fn random_insertions(rng: &mut Rng, c: &Reference) -> Vec<f64> {
    let (start, end) = c.domain();
    let many = 1 + ((rng.next() + 1.0) * 2.0) as usize;
    let mut ts: Vec<f64> = Vec::new();
    for _ in 0..many {
        let interior: Vec<f64> = c.knots[c.degree + 1..c.knots.len() - 1 - c.degree]
            .iter()
            .copied()
            .filter(|&k| {
                let times = c.knots.iter().chain(&ts).filter(|&&x| x == k).count();
                k > start && k < end && times < c.degree
            })
            .collect();
        let t = if !interior.is_empty() && rng.next() > 0.3 {
            interior[((rng.next() + 1.0) * 0.5 * interior.len() as f64) as usize]
        } else {
            start + (end - start) * (0.02 + 0.96 * (rng.next() + 1.0) * 0.5)
        };
        ts.push(t);
    }
    ts
}

fn numbers(line: &str) -> Vec<f64> {
    line.split(' ').map(|x| x.parse().unwrap()).collect()
}

/// Runs `subdiv curve INPUT --degree D --knots=K [--weights=W] EXTRA...`.
fn run(input: &Path, c: &Reference, extra: &[String]) -> String {
    let degree = c.degree.to_string();
    let knots = format!("--knots={}", list(&c.knots));
    let mut args = vec![
        "curve",
        input.to_str().unwrap(),
        "--degree",
        &degree,
        &knots,
    ];
    let weights = c.weights.as_ref().map(|w| format!("--weights={}", list(w)));
    if let Some(w) = &weights {
        args.push(w);
    }
    args.extend(extra.iter().map(String::as_str));
    let o = subdiv(&args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{args:?}: {err}");
    String::from_utf8(o.stdout).unwrap()
}

fn assert_near(got: &[f64], want: &[f64], scale: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= 1e-9 * scale,
            "{what}: got {got:?}, the reference {want:?}"
        );
    }
}

#[test]
fn insertion_and_samples_match_an_independent_implementation() {
    let dir = scratch("curve-reference");
    let mut rng = Rng(0x5eed_c0de_2026_1125);
    for case in 0..40 {
        let c = random_curve(&mut rng, case);
        let text: String = c
            .points
            .iter()
            .map(|p| list(p).replace(',', " ") + "\n")
            .collect();
        let input = write(&dir, &format!("c{case}.txt"), &text);
        let scale = c
            .points
            .iter()
            .flatten()
            .fold(1.0f64, |a, x| a.max(x.abs()));
        let what = format!(
            "case {case}: degree {} knots {:?} weights {:?}",
            c.degree, c.knots, c.weights
        );

        // Insertion: knots, weights and control points.
        let ts = random_insertions(&mut rng, &c);
        let out = run(&input, &c, &[format!("--insert={}", list(&ts))]);
        let want = c.inserted(&ts);
        let mut lines = out.lines();
        let knots = lines.next().and_then(|l| l.strip_prefix("# knots "));
        assert_eq!(
            knots.map(numbers),
            Some(want.knots.clone()),
            "{what} {ts:?}"
        );
        if let Some(w) = &want.weights {
            let got = lines.next().and_then(|l| l.strip_prefix("# weights "));
            let got = got.map(numbers).unwrap_or_default();
            let wscale = w.iter().fold(1.0f64, |a, x| a.max(*x));
            assert_near(&got, w, wscale, &format!("{what} {ts:?} weights"));
        }
        let got: Vec<Vec<f64>> = lines.map(numbers).collect();
        assert_eq!(got.len(), want.points.len(), "{what} {ts:?}");
        for (i, (g, w)) in got.iter().zip(&want.points).enumerate() {
            assert_near(g, w, scale, &format!("{what} {ts:?} Q{i}"));
        }

        // Samples, both ends of the domain included.
        let n = 2 + case % 9;
        let out = run(&input, &c, &["--samples".into(), n.to_string()]);
        let got: Vec<Vec<f64>> = out
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(numbers)
            .collect();
        assert_eq!(got.len(), n, "{what}");
        let (start, end) = c.domain();
        for (i, g) in got.iter().enumerate() {
            let t = if i + 1 == n {
                end
            } else {
                start + (end - start) * i as f64 / (n - 1) as f64
            };
            assert_near(
                g,
                &c.point(t),
                scale,
                &format!("{what} sample {i}, t = {t}"),
            );
        }
    }
}
