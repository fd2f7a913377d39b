//! The report's tessellated limit surface: each input's base faces
//! tessellated the Bfr way (`subdiv tessellate`) over the native surfaces
//! and over OpenSubdiv's `Bfr::Surface`s, the two meshes compared point by
//! point, and the native one drawn coloured by the distance.

use super::format::slug;
use super::inputs::Input;
use super::picture::{Shaded, render};
use subdiv::bfr::{MeshSurfaces, SurfaceOptions, TessellateOptions, tessellate};
use subdiv::compare::bbox_diagonal;
use subdiv::{CreasingMethod, osd};

/// The tessellation rate for an input of `faces` base faces: fewer points
/// per face on larger meshes, to keep the report to about a minute.
pub fn rate_for(faces: usize) -> u32 {
    match faces {
        0..=20_000 => 4,
        _ => 2,
    }
}

/// The largest input whose limit surface the report compares (patch
/// tables and the Bfr tessellation): on a 291,200-face production mesh the
/// two comparisons took most of 3 minutes and 21 GB; above this, `subdiv
/// compare --patches` and `subdiv tessellate` do them on request.
pub const MAX_FACES: usize = 50_000;

/// The tessellated limit surface of an input, by both engines.
#[derive(Debug, Clone, PartialEq)]
pub enum Tessellated {
    /// Both engines tessellated it.
    Compared {
        /// The rate of every edge.
        rate: u32,
        /// Points of the mesh.
        points: usize,
        /// Facets of the mesh.
        facets: usize,
        /// Whether both meshes have the same facets.
        same_facets: bool,
        /// Largest distance between corresponding points, relative to the
        /// diagonal.
        deviation: f64,
        /// A departure OpenSubdiv's Bfr is known for (CONFORMANCE.md), which
        /// the comparison does not hold against the native engine.
        known_departure: Option<&'static str>,
        /// Whether it agrees within the report's tolerance (or departs as
        /// known).
        agrees: bool,
        /// The native mesh coloured by deviation (SVG).
        picture: String,
    },
    /// Not compared, and why.
    NotCompared(String),
}

impl Tessellated {
    /// One sentence for the report.
    pub fn sentence(&self) -> String {
        match self {
            Tessellated::Compared {
                rate,
                points,
                facets,
                same_facets,
                deviation,
                known_departure,
                agrees,
                ..
            } => format!(
                "Tessellated limit surface (Bfr, rate {rate}, `subdiv tessellate`): {points} points, {facets} facets, {}; native and OpenSubdiv's Bfr surfaces deviate by at most {deviation:.2e} of the diagonal: {}{}.",
                if *same_facets {
                    "the same facets"
                } else {
                    "DIFFERENT facets"
                },
                if *agrees { "agrees" } else { "DIFFERS" },
                known_departure.map_or(String::new(), |k| format!(" ({k})")),
            ),
            Tessellated::NotCompared(why) => {
                format!("Tessellated limit surface: not compared ({why}).")
            }
        }
    }

    /// Whether it does not fail the input.
    pub fn conforms(&self) -> bool {
        !matches!(self, Tessellated::Compared { agrees: false, .. })
    }
}

/// Tessellates `input` with both engines and compares the meshes.
pub fn tessellated(input: &Input, tolerance: f64) -> Tessellated {
    let faces = input.mesh.face_count();
    if faces > MAX_FACES {
        return Tessellated::NotCompared(format!(
            "{faces} faces, above the report's {MAX_FACES} for this comparison; `subdiv tessellate --engine native|osd` tessellates it"
        ));
    }
    let so = SurfaceOptions::default();
    let tess = TessellateOptions {
        rate: rate_for(input.mesh.face_count()),
        uvs: false,
        ..TessellateOptions::default()
    };
    let both = || -> subdiv::Result<_> {
        let native = MeshSurfaces::new(&input.mesh, &input.options, &so)?;
        let ours = tessellate(&input.mesh, &native, &tess)?;
        let surfaces = osd::bfr::Surfaces::new(&input.mesh, &input.options, &so)?;
        let theirs = tessellate(&input.mesh, &surfaces, &tess)?;
        Ok((ours, theirs))
    };
    let (ours, theirs) = match both() {
        Ok(pair) => pair,
        Err(e) => return Tessellated::NotCompared(e.to_string()),
    };
    let diagonal = bbox_diagonal(&input.mesh.positions).max(1e-300);
    let same_facets =
        ours.face_vertices == theirs.face_vertices && ours.face_offsets == theirs.face_offsets;
    let deviations: Vec<f64> = ours
        .positions
        .iter()
        .zip(&theirs.positions)
        .map(|(a, b)| a.distance(*b) / diagonal)
        .collect();
    let deviation = if same_facets {
        deviations.iter().copied().fold(0.0, f64::max)
    } else {
        f64::INFINITY
    };
    let known_departure = (input.options.creasing == CreasingMethod::Chaikin && !input.mesh.creases.is_empty())
        .then_some("Chaikin creasing: Bfr's per-face neighbourhoods depart from the mesh's refinement, docs/CONFORMANCE.md");
    let agrees = same_facets && (deviation <= tolerance || known_departure.is_some());
    let faces: Vec<&[u32]> = ours
        .face_offsets
        .windows(2)
        .map(|w| &ours.face_vertices[w[0] as usize..w[1] as usize])
        .collect();
    let note = format!("largest deviation {deviation:.2e} of the diagonal");
    let picture = render(&Shaded {
        title: "tessellated limit surface (Bfr), coloured by deviation".into(),
        subtitle: format!(
            "{} facets at rate {}; {}",
            faces.len(),
            tess.rate,
            input.name
        ),
        faces: &faces,
        closed: false,
        positions: &ours.positions,
        deviations: &deviations,
        max_deviation: deviation,
        note,
        gradient: format!("tesscale-{}", slug(0, &input.name)),
        tolerance,
    });
    Tessellated::Compared {
        rate: tess.rate,
        points: ours.positions.len(),
        facets: faces.len(),
        same_facets,
        deviation,
        known_departure,
        agrees,
        picture,
    }
}
