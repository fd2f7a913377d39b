//! Subdivision options shared by the native and the OpenSubdiv engines.
//!
//! Each enum mirrors one of OpenSubdiv's `Sdc::Options` (or `Sdc::SchemeType`)
//! values one to one, so a refinement set up here means the same thing in both
//! engines. [`Options::default`] equals `Sdc::Options()`; OpenSubdiv's own shape
//! files assume [`Options::shape_file_defaults`] instead.

use crate::error::{Error, LevelRefusal, Result};
use crate::mesh::Mesh;
use crate::names::impl_named;

/// An enum of `Sdc::Options` values with their OpenSubdiv codes and names.
macro_rules! option_enum {
    (
        $(#[$meta:meta])*
        $name:ident {
            $( $(#[$vmeta:meta])* $variant:ident = $code:expr, $text:literal; )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $( $(#[$vmeta])* $variant, )+
        }

        impl_named!($name, stringify!($name), { $($variant => $text),+ });

        impl $name {
            /// OpenSubdiv's numeric value of this option.
            pub fn code(self) -> i32 {
                match self { $($name::$variant => $code,)+ }
            }

            /// The option with OpenSubdiv's numeric value `code`, if there is one.
            pub fn from_code(code: i64) -> Option<Self> {
                match code { $(c if c == $code => Some($name::$variant),)+ _ => None }
            }
        }
    };
}

option_enum! {
    /// The subdivision scheme (`Sdc::SchemeType`).
    Scheme {
        /// Bilinear: faces split linearly, positions are never smoothed.
        Bilinear = 0, "bilinear";
        /// Catmull-Clark, for quads and arbitrary polygons.
        Catmark = 1, "catmark";
        /// Loop, for triangle meshes only.
        Loop = 2, "loop";
    }
}

option_enum! {
    /// How boundary edges and corners of the vertex data are interpolated
    /// (`Sdc::Options::VtxBoundaryInterpolation`).
    BoundaryInterpolation {
        /// No boundary interpolation: faces on the boundary become holes unless
        /// their boundary edges are made sharp explicitly.
        None = 0, "none";
        /// Boundary edges are infinitely sharp creases; corners stay smooth.
        EdgeOnly = 1, "edge-only";
        /// Boundary edges are sharp and vertices with one face are sharp corners.
        EdgeAndCorner = 2, "edge-and-corner";
    }
}

option_enum! {
    /// How face-varying data is linearly interpolated
    /// (`Sdc::Options::FVarLinearInterpolation`).
    FVarLinearInterpolation {
        /// Smooth everywhere, boundaries included ("edge only").
        None = 0, "none";
        /// Sharpen corners only.
        CornersOnly = 1, "corners-only";
        /// Sharpen corners and junctions of three or more regions.
        CornersPlus1 = 2, "corners-plus1";
        /// As `CornersPlus1`, also sharpening darts and concave corners.
        CornersPlus2 = 3, "corners-plus2";
        /// Linear along all boundaries.
        Boundaries = 4, "boundaries";
        /// Linear everywhere (bilinear face-varying data).
        All = 5, "all";
    }
}

option_enum! {
    /// How semi-sharp creases lose sharpness from level to level
    /// (`Sdc::Options::CreasingMethod`).
    CreasingMethod {
        /// Sharpness decreases by one per level.
        Uniform = 0, "uniform";
        /// Chaikin's rule: sharpness of a child edge averages its neighbours'.
        Chaikin = 1, "chaikin";
    }
}

option_enum! {
    /// Which weights Catmull-Clark uses on triangles
    /// (`Sdc::Options::TriangleSubdivision`).
    TriangleSubdivision {
        /// The plain Catmull-Clark weights.
        Catmark = 0, "catmark";
        /// Modified weights for smoother results on triangles.
        Smooth = 1, "smooth";
    }
}

/// All the options of one refinement: the scheme and the four `Sdc::Options`.
///
/// ```
/// use subdiv::{Options, Scheme, BoundaryInterpolation};
/// let opts = Options::default()
///     .with_scheme(Scheme::Loop)
///     .with_boundary(BoundaryInterpolation::EdgeAndCorner);
/// assert_eq!(opts.scheme, Scheme::Loop);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Options {
    /// The subdivision scheme.
    pub scheme: Scheme,
    /// Vertex boundary interpolation.
    pub boundary: BoundaryInterpolation,
    /// Face-varying linear interpolation.
    pub fvar: FVarLinearInterpolation,
    /// Creasing method for semi-sharp creases.
    pub creasing: CreasingMethod,
    /// Catmull-Clark triangle weights.
    pub triangles: TriangleSubdivision,
}

impl Options {
    /// `Sdc::Options()` with the Catmull-Clark scheme: boundary `None`,
    /// face-varying `All`, uniform creasing, Catmull-Clark triangles.
    pub const DEFAULT: Options = Options {
        scheme: Scheme::Catmark,
        boundary: BoundaryInterpolation::None,
        fvar: FVarLinearInterpolation::All,
        creasing: CreasingMethod::Uniform,
        triangles: TriangleSubdivision::Catmark,
    };

    /// The conventions of OpenSubdiv's shape files (OBJ with `t` tags) when a
    /// tag is absent: like [`Options::DEFAULT`] but with `EdgeOnly` boundaries.
    pub fn shape_file_defaults() -> Options {
        Options {
            boundary: BoundaryInterpolation::EdgeOnly,
            ..Options::DEFAULT
        }
    }

    /// Returns these options with another scheme.
    pub fn with_scheme(mut self, scheme: Scheme) -> Self {
        self.scheme = scheme;
        self
    }

    /// Returns these options with another vertex boundary interpolation.
    pub fn with_boundary(mut self, boundary: BoundaryInterpolation) -> Self {
        self.boundary = boundary;
        self
    }

    /// Returns these options with another face-varying interpolation.
    pub fn with_fvar(mut self, fvar: FVarLinearInterpolation) -> Self {
        self.fvar = fvar;
        self
    }

    /// Returns these options with another creasing method.
    pub fn with_creasing(mut self, creasing: CreasingMethod) -> Self {
        self.creasing = creasing;
        self
    }

    /// Returns these options with another triangle subdivision rule.
    pub fn with_triangles(mut self, triangles: TriangleSubdivision) -> Self {
        self.triangles = triangles;
        self
    }
}

impl Default for Options {
    fn default() -> Self {
        Options::DEFAULT
    }
}

/// Options of uniform refinement (`Far::TopologyRefiner::UniformOptions`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct UniformOptions {
    /// The number of levels to refine, `0..=MAX_LEVEL`.
    pub level: u32,
    /// Order child vertices from faces first (faces, edges, vertices) instead of
    /// OpenSubdiv's default (vertices, faces, edges).
    pub order_vertices_from_faces_first: bool,
    /// Keep the full topology of the last level; needed for limit evaluation.
    pub full_topology_in_last_level: bool,
}

impl UniformOptions {
    /// Refine `level` levels with OpenSubdiv's default orders.
    pub fn new(level: u32) -> Self {
        UniformOptions {
            level,
            order_vertices_from_faces_first: false,
            full_topology_in_last_level: false,
        }
    }

    /// Returns these options with `orderVerticesFromFacesFirst` set.
    pub fn faces_first(mut self, yes: bool) -> Self {
        self.order_vertices_from_faces_first = yes;
        self
    }

    /// Returns these options with `fullTopologyInLastLevel` set.
    pub fn full_topology(mut self, yes: bool) -> Self {
        self.full_topology_in_last_level = yes;
        self
    }
}

/// The deepest uniform refinement level either engine accepts.
///
/// OpenSubdiv keeps the level in a 4-bit field (16 silently becomes 0); ten
/// levels already multiply the face count by about a million.
pub const MAX_LEVEL: u32 = 10;

/// Refuses a level before anything is allocated: above [`MAX_LEVEL`], one whose
/// face-vertex count would not fit OpenSubdiv's 32-bit indices, or one whose
/// estimated memory exceeds what this machine has available.
pub fn check_level(mesh: &Mesh, options: &Options, level: u32) -> Result<()> {
    check_level_counts(
        mesh.face_count(),
        mesh.face_vertices.len(),
        options.scheme,
        level,
    )
}

/// Bytes per refined face corner and per refined vertex that a refinement
/// needs, roughly (topology tables of every level plus f64 positions).
const BYTES_PER_CORNER: f64 = 40.0;
const BYTES_PER_VERTEX: f64 = 64.0;

/// [`check_level`] from the base counts alone.
pub fn check_level_counts(faces: usize, corners: usize, scheme: Scheme, level: u32) -> Result<()> {
    if level > MAX_LEVEL {
        return Err(Error::Level {
            level,
            reason: LevelRefusal::TooDeep { max: MAX_LEVEL },
        });
    }
    if level == 0 {
        return Ok(());
    }
    // After one level every face has become quads (one per corner) or, under
    // Loop, four triangles; each later level multiplies the faces by four.
    let first = match scheme {
        Scheme::Loop => 4.0 * faces as f64 * 3.0,
        _ => corners as f64 * 4.0,
    };
    let face_vertices = first * 4f64.powi(level as i32 - 1);
    if face_vertices > i32::MAX as f64 {
        return Err(Error::Level {
            level,
            reason: LevelRefusal::TooManyCorners {
                corners: face_vertices,
            },
        });
    }
    // All levels together hold about 4/3 of the last one; a quad mesh has
    // about as many vertices as faces.
    let all_corners = face_vertices * 4.0 / 3.0;
    let bytes = all_corners * BYTES_PER_CORNER + all_corners / 4.0 * BYTES_PER_VERTEX;
    if let Some(available) = available_memory() {
        if bytes > available as f64 {
            return Err(Error::Level {
                level,
                reason: LevelRefusal::OutOfMemory {
                    needed: bytes,
                    available,
                },
            });
        }
    }
    Ok(())
}

/// Memory available to a new allocation, from `/proc/meminfo` where there is one.
fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn names_and_codes_round_trip() {
        for &b in BoundaryInterpolation::ALL {
            assert_eq!(b.name().parse::<BoundaryInterpolation>().unwrap(), b);
            assert_eq!(BoundaryInterpolation::from_code(b.code() as i64), Some(b));
        }
        for &f in FVarLinearInterpolation::ALL {
            assert_eq!(f.name().parse::<FVarLinearInterpolation>().unwrap(), f);
        }
        assert_eq!(
            FVarLinearInterpolation::from_code(3),
            Some(FVarLinearInterpolation::CornersPlus2)
        );
        assert_eq!(FVarLinearInterpolation::from_code(6), None);
        assert!(
            "wobbly"
                .parse::<Scheme>()
                .unwrap_err()
                .to_string()
                .contains("catmark")
        );
    }

    #[test]
    fn defaults_match_sdc() {
        let d = Options::default();
        assert_eq!(d.boundary, BoundaryInterpolation::None);
        assert_eq!(d.fvar, FVarLinearInterpolation::All);
        assert_eq!(
            Options::shape_file_defaults().boundary,
            BoundaryInterpolation::EdgeOnly
        );
    }

    #[test]
    fn absurd_levels_are_refused() {
        let cube = shapes::cube();
        let opts = Options::default();
        assert!(check_level(&cube, &opts, 10).is_ok());
        assert!(matches!(
            check_level(&cube, &opts, 11),
            Err(Error::Level { level: 11, .. })
        ));
        let grid = shapes::grid(200, 200);
        assert!(check_level(&grid, &opts, 4).is_ok());
        let err = check_level(&grid, &opts, 9).unwrap_err();
        assert!(matches!(err, Error::Level { level: 9, .. }));
        assert!(err.to_string().contains("4.194e10 face corners"), "{err}");
        // About 2e9 corners at level 5: fits 32 bits, but needs over 100 GiB.
        if let Some(avail) = available_memory() {
            let err = check_level_counts(500_000, 2_000_000, Scheme::Catmark, 5);
            if (avail as f64) < 1e11 {
                let err = err.unwrap_err().to_string();
                assert!(err.contains("GiB"), "{err}");
            }
        }
    }
}
