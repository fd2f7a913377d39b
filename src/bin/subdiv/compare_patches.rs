//! `subdiv compare --patches`: both engines' patch tables of a mesh,
//! compared patch by patch (types, control vertices, `PatchParam` words,
//! sharpness, local-point stencils), and the limit surface each evaluates
//! from its own refinement and table at a grid of locations on every ptex
//! face; the first differing patch and the largest deviation are reported.

use crate::Failure;
use crate::compare::{CompareArgs, describe_options};
use subdiv::patches::{self, Derivatives, PatchOptions, PatchTable};
use subdiv::refiner::Refiner;
use subdiv::{AdaptiveOptions, Error, Mesh, Options, osd};

/// The locations on each ptex face: u and v in {0, 1/4, 1/2, 3/4, 1}.
pub(crate) const STEPS: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// The report, as printed and as JSON.
#[derive(serde::Serialize)]
struct PatchReport<'a> {
    input: &'a str,
    options: String,
    isolation: u32,
    end_caps: &'static str,
    tolerance: f64,
    /// Per array: type name and patch count of each engine.
    arrays: Vec<(String, usize, String, usize)>,
    local_points: [usize; 2],
    tables_identical: bool,
    first_difference: Option<String>,
    locations: usize,
    /// Locations on patches without a basis (legacy Gregory), not evaluated.
    unevaluable_locations: usize,
    max_position_deviation: f64,
    relative_position_deviation: f64,
    worst_location: Option<(u32, f64, f64)>,
    relative_derivative_deviation: f64,
    agrees: bool,
}

/// Both engines' patch tables of one mesh and the limit surfaces they
/// evaluate (each from its own refinement and table).
pub(crate) struct LimitComparison {
    /// Per array: type name and patch count of each engine.
    pub arrays: Vec<(String, usize, String, usize)>,
    pub local_points: [usize; 2],
    pub patches: usize,
    pub first_difference: Option<String>,
    pub locations: usize,
    /// Locations on patches without a basis (legacy Gregory).
    pub unevaluable: usize,
    pub max_position_deviation: f64,
    pub relative_position_deviation: f64,
    pub worst_location: Option<(u32, f64, f64)>,
    pub relative_derivative_deviation: f64,
    /// The locations evaluated, the native limit positions there and their
    /// distances from OpenSubdiv's, relative to the diagonal (the report's
    /// limit-surface picture).
    pub samples: Vec<((u32, f64, f64), glam::DVec3, f64)>,
}

impl LimitComparison {
    /// Tables identical and the surfaces within `tolerance` (positions of
    /// the diagonal, derivatives of their largest).
    pub fn agrees(&self, tolerance: f64) -> bool {
        self.first_difference.is_none()
            && self.relative_position_deviation <= tolerance
            && self.relative_derivative_deviation <= tolerance
    }
}

/// Builds both engines' tables of `mesh` refined with `ao` and compares
/// them, then their limit surfaces at u, v ∈ {0, ¼, ½, ¾, 1} on every ptex
/// face (off the holes).
pub(crate) fn limit_comparison(
    mesh: &Mesh,
    options: &Options,
    po: &PatchOptions,
    ao: AdaptiveOptions,
    faces: &[u32],
) -> Result<LimitComparison, Error> {
    let base = mesh.flat_positions::<f64>();
    let native = Refiner::new(mesh, options)?.refine_adaptive(ao, faces)?;
    let mine = native.patch_table(po, faces)?;
    let mut theirs = osd::TopologyRefiner::new(mesh, options)?;
    theirs.refine_adaptive(ao, faces)?;
    let osds = theirs.patch_table(po, faces)?;
    let t = osds.table();
    let first_difference = first_difference(&mine, t);
    let map = patches::PatchMap::new(&mine);
    let on_patches: Vec<((u32, f64, f64), bool)> = (0..mine.ptex_faces as u32)
        .flat_map(|f| {
            STEPS
                .iter()
                .flat_map(move |&u| STEPS.iter().map(move |&v| (f, u, v)))
        })
        .filter_map(|(f, u, v)| {
            let h = map.find_patch(f, u, v)?;
            Some(((f, u, v), mine.arrays[h.array].patch_type.is_evaluable()))
        })
        .collect();
    // Legacy Gregory patches have no basis (in OpenSubdiv either).
    let locations: Vec<(u32, f64, f64)> = on_patches.iter().filter(|l| l.1).map(|l| l.0).collect();
    let points = native.patch_points(&mine, 3, &base)?;
    let a = patches::evaluate_with(&map, &mine, &points, 3, &locations, Derivatives::First)?;
    let b = osds.evaluate(&theirs, 3, &base, &locations, Derivatives::First)?;
    let diagonal = subdiv::compare::bbox_diagonal(&mesh.positions).max(f64::MIN_POSITIVE);
    let (max_dev, worst) = largest_deviation(&a.values.point, &b.values.point);
    let derivative_scale = b
        .values
        .du
        .iter()
        .chain(&b.values.dv)
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    let samples = locations
        .iter()
        .zip(
            a.values
                .point
                .chunks_exact(3)
                .zip(b.values.point.chunks_exact(3)),
        )
        .map(|(&l, (p, q))| {
            let (p, q) = (glam::DVec3::from_slice(p), glam::DVec3::from_slice(q));
            (l, p, (p - q).length() / diagonal)
        })
        .collect();
    let (du_dev, _) = largest_deviation(&a.values.du, &b.values.du);
    let (dv_dev, _) = largest_deviation(&a.values.dv, &b.values.dv);
    let arrays = (0..mine.arrays.len().max(t.arrays.len()))
        .map(|i| {
            let side = |table: &PatchTable| {
                table.arrays.get(i).map_or(("-".to_string(), 0), |a| {
                    (a.patch_type.name().to_string(), a.len())
                })
            };
            let ((ta, na), (tb, nb)) = (side(&mine), side(t));
            (ta, na, tb, nb)
        })
        .collect();
    Ok(LimitComparison {
        arrays,
        local_points: [mine.local_points, t.local_points],
        patches: mine.patch_count(),
        first_difference,
        locations: locations.len(),
        unevaluable: on_patches.len() - locations.len(),
        max_position_deviation: max_dev,
        relative_position_deviation: max_dev / diagonal,
        worst_location: worst.map(|k| locations[k]),
        relative_derivative_deviation: du_dev.max(dv_dev) / derivative_scale,
        samples,
    })
}

pub(crate) fn compare_patches(args: &CompareArgs) -> Result<(), Failure> {
    let (name, mesh, options) = crate::args::load(&args.mesh)?;
    let isolation = args.adaptive.adaptive.unwrap_or(4);
    let po = PatchOptions::new()
        .max_isolation(isolation)
        .end_caps(args.end_caps)
        .single_crease_patch(args.adaptive.single_crease)
        .inf_sharp_patch(args.adaptive.inf_sharp);
    let mut ao = po
        .refine_adaptive_options()
        .faces_first(args.mesh.faces_first)
        .consider_fvar(args.adaptive.consider_fvar);
    if let Some(s) = args.adaptive.secondary {
        ao = ao.secondary(s);
    }
    let c = limit_comparison(&mesh, &options, &po, ao, &args.adaptive.select_faces)
        .map_err(|e| Failure::from(e).in_input(&name))?;
    let agrees = c.agrees(args.tolerance);
    let report = PatchReport {
        input: &name,
        options: describe_options(&options, args.mesh.faces_first),
        isolation,
        end_caps: crate::patches::end_cap_name(args.end_caps),
        tolerance: args.tolerance,
        arrays: c.arrays,
        local_points: c.local_points,
        tables_identical: c.first_difference.is_none(),
        first_difference: c.first_difference,
        locations: c.locations,
        unevaluable_locations: c.unevaluable,
        max_position_deviation: c.max_position_deviation,
        relative_position_deviation: c.relative_position_deviation,
        worst_location: c.worst_location,
        relative_derivative_deviation: c.relative_derivative_deviation,
        agrees,
    };
    print_report(args.json, &report)?;
    if agrees { Ok(()) } else { Err(Failure::Differ) }
}

fn print_report(json: bool, r: &PatchReport) -> Result<(), Failure> {
    if json {
        let text = serde_json::to_string_pretty(r)
            .map_err(|e| Failure::Message(format!("cannot encode the report: {e}")))?;
        outln!("{text}");
        return Ok(());
    }
    outln!(
        "{}: {} patches (isolation {}, {} end caps), tolerance {:e} of the bounding-box diagonal",
        r.input,
        r.options,
        r.isolation,
        r.end_caps,
        r.tolerance
    );
    let arrays: Vec<String> = r
        .arrays
        .iter()
        .map(|(ta, na, tb, nb)| {
            if ta == tb && na == nb {
                format!("{ta} {na}")
            } else {
                format!("{ta} {na}/{tb} {nb}")
            }
        })
        .collect();
    outln!(
        "patch tables: {} ({}; local points {}/{})",
        match &r.first_difference {
            None => "identical".to_string(),
            Some(d) => format!("DIFFERENT, first at {d}"),
        },
        arrays.join(", "),
        r.local_points[0],
        r.local_points[1]
    );
    outln!(
        "limit surface at {} locations: max deviation {:.3e} ({:.3e} of the diagonal){}, derivatives {:.3e} of their largest: {}",
        r.locations,
        r.max_position_deviation,
        r.relative_position_deviation,
        r.worst_location.map_or(String::new(), |(f, u, v)| format!(
            " at ptex face {f} ({u}, {v})"
        )),
        r.relative_derivative_deviation,
        if r.relative_position_deviation <= r.tolerance
            && r.relative_derivative_deviation <= r.tolerance
        {
            "ok"
        } else {
            "DIFFERENT"
        }
    );
    if r.unevaluable_locations > 0 {
        outln!(
            "{} locations on legacy Gregory patches not evaluated (no basis, in OpenSubdiv either)",
            r.unevaluable_locations
        );
    }
    outln!(
        "{}",
        if r.agrees {
            "the engines agree"
        } else {
            "the engines DIFFER"
        }
    );
    Ok(())
}

/// The largest absolute difference of two equally long lists of xyz
/// values, and the location (index / 3) where it is.
fn largest_deviation(a: &[f64], b: &[f64]) -> (f64, Option<usize>) {
    let mut worst = (0.0f64, None);
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        let d = (x - y).abs();
        if d > worst.0 || (worst.1.is_none() && d.is_nan()) {
            worst = (d, Some(k / 3));
        }
    }
    worst
}

/// Where two tables first differ: the array and patch and what differs, or
/// the table-wide field.
fn first_difference(a: &PatchTable, b: &PatchTable) -> Option<String> {
    if a.arrays.len() != b.arrays.len() {
        return Some(format!(
            "the number of arrays ({} / {})",
            a.arrays.len(),
            b.arrays.len()
        ));
    }
    for (i, (x, y)) in a.arrays.iter().zip(&b.arrays).enumerate() {
        if x.patch_type != y.patch_type || x.len() != y.len() {
            return Some(format!(
                "array {i} ({} {} / {} {})",
                x.patch_type.name(),
                x.len(),
                y.patch_type.name(),
                y.len()
            ));
        }
        for p in 0..x.len() {
            let what = if x.patch_vertices(p) != y.patch_vertices(p) {
                format!(
                    "control vertices {:?} / {:?}",
                    x.patch_vertices(p),
                    y.patch_vertices(p)
                )
            } else if x.params[p] != y.params[p] {
                format!(
                    "PatchParam [{}, {}] / [{}, {}]",
                    x.params[p].field0, x.params[p].field1, y.params[p].field0, y.params[p].field1
                )
            } else if x.sharpness[p].to_bits() != y.sharpness[p].to_bits() {
                format!("sharpness {} / {}", x.sharpness[p], y.sharpness[p])
            } else {
                continue;
            };
            return Some(format!(
                "array {i} ({}) patch {p}: {what}",
                x.patch_type.name()
            ));
        }
    }
    for (name, x, y) in [
        (
            "local-point stencils",
            &a.local_point_stencils,
            &b.local_point_stencils,
        ),
        (
            "varying local-point stencils",
            &a.local_point_varying_stencils,
            &b.local_point_varying_stencils,
        ),
    ] {
        if x.sizes != y.sizes || x.indices != y.indices {
            let k = (0..x.sizes.len().min(y.sizes.len()))
                .find(|&k| x.sizes[k] != y.sizes[k])
                .unwrap_or(x.sizes.len().min(y.sizes.len()));
            return Some(format!("the {name} (stencil {k}: sizes or indices)"));
        }
        if let Some(k) =
            (0..x.weights.len()).find(|&k| x.weights[k].to_bits() != y.weights[k].to_bits())
        {
            return Some(format!(
                "the {name} (weight {k}: {} / {})",
                x.weights[k], y.weights[k]
            ));
        }
    }
    if a != b {
        return Some(
            "the table's other fields (valence, ptex faces, legacy Gregory tables)".into(),
        );
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use subdiv::patches::{PatchArray, PatchParam, PatchType};

    /// The first difference is named where it is: a control vertex, a
    /// parameter word, a local-point weight, the number of arrays.
    #[test]
    fn first_difference_names_the_patch() {
        let table = PatchTable {
            arrays: vec![PatchArray {
                patch_type: PatchType::Quads,
                control_vertices: (0..8).collect(),
                params: vec![PatchParam::default(); 2],
                sharpness: vec![0.0; 2],
                varying_vertices: Vec::new(),
            }],
            local_point_stencils: subdiv::StencilTable {
                sizes: vec![1].into(),
                offsets: vec![0].into(),
                indices: vec![3].into(),
                weights: vec![1.0].into(),
            },
            ..PatchTable::default()
        };
        assert_eq!(first_difference(&table, &table), None);
        let mut b = table.clone();
        b.arrays[0].control_vertices[5] = 9;
        assert_eq!(
            first_difference(&table, &b).unwrap(),
            "array 0 (QUADS) patch 1: control vertices [4, 5, 6, 7] / [4, 9, 6, 7]"
        );
        let mut b = table.clone();
        b.arrays[0].params[0].field1 = 3;
        assert_eq!(
            first_difference(&table, &b).unwrap(),
            "array 0 (QUADS) patch 0: PatchParam [0, 0] / [0, 3]"
        );
        let mut b = table.clone();
        b.local_point_stencils.weights[0] = 0.5;
        assert_eq!(
            first_difference(&table, &b).unwrap(),
            "the local-point stencils (weight 0: 1 / 0.5)"
        );
        let mut b = table.clone();
        b.arrays.clear();
        assert_eq!(
            first_difference(&table, &b).unwrap(),
            "the number of arrays (1 / 0)"
        );
        let mut b = table.clone();
        b.max_valence = 4;
        assert!(
            first_difference(&table, &b)
                .unwrap()
                .contains("other fields")
        );
    }
}
