//! Subdivision options shared by the native and the OpenSubdiv engines.
//!
//! Each enum mirrors one of OpenSubdiv's `Sdc::Options` (or `Sdc::SchemeType`)
//! values one to one, so a refinement set up here means the same thing in both
//! engines. [`Options::default`] equals `Sdc::Options()`; OpenSubdiv's own shape
//! files assume [`Options::shape_file_defaults`] instead.

use crate::names::impl_named;
use crate::real::Precision;

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

/// Options of feature-adaptive refinement
/// (`Far::TopologyRefiner::AdaptiveOptions` of OpenSubdiv 3.5): only the
/// faces around features that a regular patch cannot represent
/// (extraordinary vertices, irregular faces, sharp features, and with
/// [`Self::consider_fvar_channels`] face-varying boundaries) are refined, down
/// to [`Self::isolation_level`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct AdaptiveOptions {
    /// How deep features are isolated, `0..=MAX_LEVEL` (OpenSubdiv stores it
    /// in 4 bits; validate it with [`crate::check_level`]).
    pub isolation_level: u32,
    /// The level below which fewer features (semi-sharp and infinitely sharp
    /// features that patches represent) are isolated; 15 by default, i.e.
    /// never.
    pub secondary_level: u32,
    /// Leave faces with a single semi-sharp crease unrefined (a single-crease
    /// patch represents them).
    pub use_single_crease_patch: bool,
    /// Leave infinitely sharp features that patches represent unrefined.
    pub use_inf_sharp_patch: bool,
    /// Also isolate the features of non-linear face-varying channels.
    pub consider_fvar_channels: bool,
    /// Order child vertices from faces first (faces, edges, vertices).
    pub order_vertices_from_faces_first: bool,
}

impl AdaptiveOptions {
    /// OpenSubdiv's defaults for isolation `level`: secondary level 15, every
    /// flag off.
    pub fn new(level: u32) -> Self {
        AdaptiveOptions {
            isolation_level: level,
            secondary_level: 15,
            use_single_crease_patch: false,
            use_inf_sharp_patch: false,
            consider_fvar_channels: false,
            order_vertices_from_faces_first: false,
        }
    }

    /// Returns these options with another secondary level.
    pub fn secondary(mut self, level: u32) -> Self {
        self.secondary_level = level;
        self
    }

    /// Returns these options with `useSingleCreasePatch` set.
    pub fn single_crease_patch(mut self, yes: bool) -> Self {
        self.use_single_crease_patch = yes;
        self
    }

    /// Returns these options with `useInfSharpPatch` set.
    pub fn inf_sharp_patch(mut self, yes: bool) -> Self {
        self.use_inf_sharp_patch = yes;
        self
    }

    /// Returns these options with `considerFVarChannels` set.
    pub fn consider_fvar(mut self, yes: bool) -> Self {
        self.consider_fvar_channels = yes;
        self
    }

    /// Returns these options with `orderVerticesFromFacesFirst` set.
    pub fn faces_first(mut self, yes: bool) -> Self {
        self.order_vertices_from_faces_first = yes;
        self
    }
}

/// What to compute in one uniform refinement: the uniform options (level,
/// vertex order, full topology), the precision of the interpolation, and
/// whether limit values are evaluated at the last level.
///
/// `Request::new(level)` is OpenSubdiv's default uniform refinement in `f64`
/// without limits; a [`UniformOptions`] converts into a request of its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct Request {
    /// Level, vertex order and last-level topology.
    pub uniform: UniformOptions,
    /// The precision primvars are interpolated in.
    pub precision: Precision,
    /// Evaluate limit positions, tangents and face-varying values at the last
    /// level (the last level then keeps its full topology, as OpenSubdiv
    /// requires).
    pub limit: bool,
}

impl Request {
    /// Refine `level` levels with OpenSubdiv's defaults, in `f64`, no limit.
    pub fn new(level: u32) -> Request {
        UniformOptions::new(level).into()
    }

    /// This request with other uniform options.
    pub fn uniform(mut self, uniform: UniformOptions) -> Request {
        self.uniform = uniform;
        self
    }

    /// This request in another precision.
    pub fn precision(mut self, precision: Precision) -> Request {
        self.precision = precision;
        self
    }

    /// This request with (or without) limit evaluation.
    pub fn limit(mut self, limit: bool) -> Request {
        self.limit = limit;
        self
    }

    /// This request with child vertices ordered from faces first.
    pub fn faces_first(mut self, yes: bool) -> Request {
        self.uniform = self.uniform.faces_first(yes);
        self
    }

    /// The uniform options the engines refine with: those asked for, with
    /// full topology in the last level when limits are evaluated.
    pub fn effective_uniform(&self) -> UniformOptions {
        if self.limit {
            self.uniform.full_topology(true)
        } else {
            self.uniform
        }
    }
}

impl From<UniformOptions> for Request {
    fn from(uniform: UniformOptions) -> Request {
        Request {
            uniform,
            precision: Precision::F64,
            limit: false,
        }
    }
}

/// Which refiner does the work.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Engine {
    /// The pure-Rust engine ([`crate::refiner`]).
    #[default]
    Native,
    /// OpenSubdiv through the C++ bridge (`subdiv::osd`, feature `osd`).
    Osd,
}

impl_named!(Engine, "engine", { Native => "native", Osd => "osd" });

/// The deepest uniform refinement level either engine accepts.
///
/// OpenSubdiv keeps the level in a 4-bit field (16 silently becomes 0); ten
/// levels already multiply the face count by about a million.
pub const MAX_LEVEL: u32 = 10;

#[cfg(test)]
mod tests {
    use super::*;

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
}
