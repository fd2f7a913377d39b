//! `subdiv tessellate`: every base face's limit surface tessellated (Bfr's
//! patterns) into one watertight OBJ, by the native engine (the default) or
//! OpenSubdiv's Bfr (`--engine osd`).

use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use subdiv::bfr::{FaceSurfaces, LimitSurfaces, MeshSurfaces, SurfaceOptions, TessellateOptions};
use subdiv::io::{ObjOutput, UvOutput};
use subdiv::{Engine, Precision};

use crate::Failure;
use crate::args::{MeshArgs, parse};
use crate::output::write_output;

/// `subdiv tessellate`: the arguments.
#[derive(Args)]
pub(crate) struct TessellateArgs {
    #[command(flatten)]
    pub(crate) mesh: MeshArgs,
    /// Tessellation rate of every edge (points per edge = rate + 1).
    #[arg(long, value_name = "N", default_value = "4")]
    pub(crate) rate: u32,
    /// Instead of --rate: a rate per base edge, 1 + its control edge's length over L
    /// rounded down (bfr tutorial 2_1's rule on the control hull).
    #[arg(long, value_name = "L")]
    pub(crate) edge_length: Option<f64>,
    /// Keep quads where the patterns have them (else triangles).
    #[arg(long)]
    pub(crate) quads: bool,
    /// Write unit normals (vn) from the surface's derivatives.
    #[arg(long)]
    pub(crate) normals: bool,
    #[command(flatten)]
    pub(crate) surface: SurfaceArgs,
    /// The engine evaluating the surfaces: native or osd (OpenSubdiv's Bfr).
    #[arg(long, default_value = "native", value_parser = parse::<Engine>)]
    pub(crate) engine: Engine,
    /// Output OBJ file (`-` for standard output).
    #[arg(short, long, value_name = "OUT.obj")]
    pub(crate) output: PathBuf,
}

/// How the per-face limit surfaces are built (`tessellate`, `eval --surface bfr`).
#[derive(Args)]
pub(crate) struct SurfaceArgs {
    /// Bfr's approximation level for smooth features (approxLevelSmooth).
    #[arg(long, value_name = "N", default_value = "2")]
    pub(crate) level_smooth: u32,
    /// Bfr's approximation level for sharp features (approxLevelSharp).
    #[arg(long, value_name = "N", default_value = "6")]
    pub(crate) level_sharp: u32,
    /// Native engine: evaluate every face on one adaptive refinement of
    /// the whole mesh with Bfr's options, instead of each face's own
    /// surface built as Bfr builds it (the default: index-exact with
    /// OpenSubdiv's Bfr, and faster). Not for `eval --surface bfr`.
    #[arg(long)]
    pub(crate) global: bool,
    /// Each face's own surface, as Bfr builds it (the default; kept for
    /// scripts written when it was not).
    #[arg(long, hide = true, conflicts_with = "global")]
    pub(crate) per_face: bool,
}

impl SurfaceArgs {
    /// The surfaces of `mesh` by `engine`; errors name `name`.
    pub(crate) fn build(
        &self,
        engine: Engine,
        name: &str,
        mesh: &subdiv::Mesh,
        options: &subdiv::Options,
    ) -> Result<Box<dyn FaceSurfaces>, Failure> {
        if self.level_smooth > 10 || self.level_sharp > 10 {
            return Err(Failure::Usage(
                "--level-smooth/--level-sharp: 10 levels at most".into(),
            ));
        }
        let surface = SurfaceOptions {
            approx_level_smooth: self.level_smooth,
            approx_level_sharp: self.level_sharp,
            ..SurfaceOptions::default()
        };
        let in_input = |e: subdiv::Error| Failure::from(e).in_input(name);
        Ok(match engine {
            Engine::Native if self.global => {
                Box::new(LimitSurfaces::new(mesh, options, &surface).map_err(in_input)?)
            }
            Engine::Native => {
                Box::new(MeshSurfaces::new(mesh, options, &surface).map_err(in_input)?)
            }
            #[cfg(feature = "osd")]
            Engine::Osd => Box::new(
                subdiv::osd::bfr::Surfaces::new(mesh, options, &surface).map_err(in_input)?,
            ),
            #[cfg(not(feature = "osd"))]
            Engine::Osd => return Err(Failure::from(subdiv::Error::OsdUnavailable)),
        })
    }
}

/// Runs `subdiv tessellate`.
pub(crate) fn tessellate(args: &TessellateArgs) -> Result<(), Failure> {
    if args.rate == 0 {
        return Err(Failure::Usage("--rate: rates start at 1".into()));
    }
    let (name, mesh, options) = crate::args::load(&args.mesh)?;
    let in_input = |e: subdiv::Error| Failure::from(e).in_input(&name);
    let start = Instant::now();
    let surfaces = args.surface.build(args.engine, &name, &mesh, &options)?;
    let tess_options = TessellateOptions {
        rate: args.rate,
        edge_length: args.edge_length,
        quads: args.quads,
        normals: args.normals,
        uvs: !mesh.fvar_channels.is_empty(),
    };
    let t = subdiv::bfr::tessellate(&mesh, surfaces.as_ref(), &tess_options).map_err(in_input)?;
    let elapsed = start.elapsed();
    let uv = (!t.uvs.is_empty()).then_some(UvOutput {
        width: 2,
        values: &t.uvs,
        face_values: &t.uv_indices,
    });
    let data = ObjOutput {
        positions: &t.positions,
        face_offsets: &t.face_offsets,
        face_vertices: &t.face_vertices,
        holes: None,
        uv,
        normals: args.normals.then_some(&t.normals[..]),
        precision: Precision::F64,
    };
    write_output(&args.output, args.mesh.input.as_deref(), |w| {
        subdiv::io::write_obj_to(w, &data)
    })?;
    eprintln!(
        "subdiv: {name}: {} points, {} facets ({} engine, {:.1} ms)",
        t.positions.len(),
        t.face_offsets.len() - 1,
        args.engine,
        elapsed.as_secs_f64() * 1e3
    );
    Ok(())
}
