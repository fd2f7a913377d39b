//! What the ports of OpenSubdiv's bfr tutorials share: the input (an OBJ
//! file with OpenSubdiv's tags, or a built-in shape), the native surfaces —
//! evaluated as the tutorials do, face by face: the factory's `Surface`
//! of a face, its patch points prepared from the mesh's points, then
//! evaluated — and, with the `osd` feature, OpenSubdiv's own
//! `Bfr::Surface`s to check every evaluated point against, and an OBJ of
//! separately tessellated faces.

#![allow(dead_code)]

use glam::DVec3;
use subdiv::bfr::{MeshSurfaces, Surface, SurfaceOptions};
use subdiv::io::{ObjOutput, UvOutput};
use subdiv::patches::{Derivatives, SurfaceSamples};
use subdiv::{Mesh, Options, Precision};

/// The command line the tutorials share: `[INPUT.obj] [-o OUT.obj]` and
/// their own flags (`-res N`, `-quads`, ...), returned for each to read.
pub struct Args {
    pub input: Option<String>,
    pub output: Option<String>,
    pub flags: Vec<String>,
}

impl Args {
    pub fn parse() -> Args {
        let mut args = Args {
            input: None,
            output: None,
            flags: Vec::new(),
        };
        let mut it = std::env::args().skip(1);
        while let Some(a) = it.next() {
            if a == "-o" {
                args.output = it.next();
            } else if a.ends_with(".obj") && args.input.is_none() {
                args.input = Some(a);
            } else {
                args.flags.push(a);
            }
        }
        args
    }

    /// Whether `flag` was given.
    pub fn has(&self, flag: &str) -> bool {
        self.flags.iter().any(|f| f == flag)
    }

    /// The number after `flag`, or `default`.
    pub fn number(&self, flag: &str, default: f64) -> f64 {
        self.flags
            .iter()
            .position(|f| f == flag)
            .and_then(|i| self.flags.get(i + 1))
            .map_or(default, |v| {
                v.parse()
                    .unwrap_or_else(|_| panic!("{flag} {v}: not a number"))
            })
    }

    /// The mesh (the file's, or a cube with UVs) and its options.
    pub fn mesh(&self) -> (Mesh, Options) {
        match &self.input {
            Some(path) => {
                let shape = subdiv::io::read_obj(std::path::Path::new(path))
                    .unwrap_or_else(|e| panic!("{path}: {e}"));
                let options = shape.options();
                (shape.mesh, options)
            }
            None => (
                subdiv::shapes::cube_with_uvs(),
                Options::shape_file_defaults(),
            ),
        }
    }
}

/// The native surfaces of `mesh`, and OpenSubdiv's to check them against.
pub struct Surfaces {
    /// The native surfaces (`Bfr::RefinerSurfaceFactory` with the mesh's
    /// points): `native.factory()` builds each face's `Surface`.
    pub native: MeshSurfaces,
    /// The mesh's positions, and its first face-varying channel (values
    /// and width), flat.
    points: Vec<f64>,
    uvs: Option<(Vec<f64>, usize)>,
    #[cfg(feature = "osd")]
    pub osd: subdiv::osd::bfr::Surfaces,
    scale: f64,
    pub checked: usize,
}

impl Surfaces {
    pub fn new(mesh: &Mesh, options: &Options) -> Surfaces {
        let so = SurfaceOptions::default();
        let (mut lo, mut hi) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
        for p in &mesh.positions {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        Surfaces {
            native: MeshSurfaces::new(mesh, options, &so).expect("native surfaces"),
            points: mesh.flat_positions(),
            uvs: mesh
                .fvar_channels
                .first()
                .map(|c| (c.values.clone(), c.width)),
            #[cfg(feature = "osd")]
            osd: subdiv::osd::bfr::Surfaces::new(mesh, options, &so)
                .expect("OpenSubdiv's surfaces"),
            scale: (hi - lo).length().max(1e-300),
            checked: 0,
        }
    }

    /// `surface` at `coords` as the tutorials evaluate it: its patch points
    /// prepared from `points` (`width` values each), then evaluated.
    fn at(
        surface: &Surface,
        points: &[f64],
        width: usize,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> SurfaceSamples {
        let patch = surface.patch_points(points, width).expect("patch points");
        surface
            .evaluate_patch_points(&patch, width, coords, derivatives)
            .expect("evaluate")
    }

    /// Positions and first derivatives of `face` at `coords` — natively,
    /// checked against OpenSubdiv's `Surface::Evaluate` with `osd`.
    pub fn evaluate(&mut self, face: usize, coords: &[[f64; 2]]) -> SurfaceSamples {
        let surface = self
            .native
            .factory()
            .vertex_surface(face)
            .expect("vertex surface");
        let s = Self::at(&surface, &self.points, 3, coords, Derivatives::First);
        #[cfg(feature = "osd")]
        {
            let o = self
                .osd
                .evaluate(face, coords, Derivatives::First)
                .expect("osd evaluate");
            self.compare(face, &s, &o);
        }
        s
    }

    /// Face-varying channel 0 of `face` at `coords` (checked likewise).
    pub fn evaluate_uv(&mut self, face: usize, coords: &[[f64; 2]]) -> SurfaceSamples {
        let (values, width) = self.uvs.as_ref().expect("a face-varying channel");
        let surface = self
            .native
            .factory()
            .fvar_surface(face, 0)
            .expect("face-varying surface");
        let s = Self::at(&surface, values, *width, coords, Derivatives::None);
        #[cfg(feature = "osd")]
        {
            use subdiv::bfr::FaceSurfaces;
            let o = FaceSurfaces::evaluate_fvar(&self.osd, face, 0, coords).expect("osd fvar");
            self.compare(face, &s, &o);
        }
        s
    }

    #[cfg(feature = "osd")]
    fn compare(&mut self, face: usize, a: &SurfaceSamples, b: &SurfaceSamples) {
        for (x, y) in [
            (&a.values.point, &b.values.point),
            (&a.values.du, &b.values.du),
            (&a.values.dv, &b.values.dv),
        ] {
            for (p, q) in x.iter().zip(y) {
                assert!(
                    (p - q).abs() <= 1e-9 * self.scale,
                    "face {face}: {p} against OpenSubdiv's {q}"
                );
            }
        }
        self.checked += a.values.point.len() / a.width;
    }

    /// What was checked, for the summary line.
    pub fn summary(&self) -> String {
        if cfg!(feature = "osd") {
            format!("{} points equal OpenSubdiv's Bfr within 1e-9", self.checked)
        } else {
            "not checked against OpenSubdiv (built without the osd feature)".into()
        }
    }
}

/// An OBJ of faces tessellated one by one (points not shared).
#[derive(Default)]
pub struct Obj {
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub uvs: Vec<f64>,
    pub offsets: Vec<u32>,
    pub corners: Vec<u32>,
}

impl Obj {
    /// Appends the points (and normals from the derivatives) of `s`,
    /// returning the index of the first.
    pub fn points(&mut self, s: &SurfaceSamples) -> u32 {
        let first = self.positions.len() as u32;
        let v = &s.values;
        for i in 0..v.point.len() / 3 {
            let at = |c: &[f64]| DVec3::from_slice(&c[3 * i..3 * i + 3]);
            self.positions.push(at(&v.point));
            self.normals
                .push(at(&v.du).cross(at(&v.dv)).normalize_or_zero());
        }
        first
    }

    /// Appends facets (`size` indices each, -1 padding dropped), offset by `first`.
    pub fn facets(&mut self, facets: &[i32], size: usize, first: u32) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        for f in facets.chunks(size) {
            self.corners
                .extend(f.iter().filter(|&&i| i >= 0).map(|&i| first + i as u32));
            self.offsets.push(self.corners.len() as u32);
        }
    }

    /// Writes the OBJ to `path`, or prints its counts.
    pub fn write(&self, path: Option<&str>) {
        let uv = (!self.uvs.is_empty()).then_some(UvOutput {
            width: 2,
            values: &self.uvs,
            face_values: &self.corners,
        });
        let data = ObjOutput {
            positions: &self.positions,
            face_offsets: &self.offsets,
            face_vertices: &self.corners,
            holes: None,
            uv,
            normals: Some(&self.normals),
            precision: Precision::F32,
        };
        match path {
            Some(p) => subdiv::io::write_obj(std::path::Path::new(p), &data).expect("write"),
            None => println!(
                "{} points, {} faces (-o OUT.obj writes them)",
                self.positions.len(),
                self.offsets.len().saturating_sub(1)
            ),
        }
    }
}
