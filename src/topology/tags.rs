//! The tags of edges and vertices ([`EdgeTag`], [`VertexTag`]), packed in
//! bits — the parts of OpenSubdiv's `Vtr::Level::ETag` and `VTag` that
//! refinement uses.

use crate::rules::Rule;

/// Generates a getter and a setter for each bit of a packed tag.
macro_rules! tag_bits {
    ($ty:ty, $bits:ty; $($(#[$doc:meta])* $get:ident, $set:ident = $bit:expr;)*) => {
        impl $ty {
            $(
                $(#[$doc])*
                #[inline]
                pub fn $get(self) -> bool {
                    self.0 & $bit != 0
                }

                #[doc = concat!("Sets [`Self::", stringify!($get), "`].")]
                #[inline]
                pub fn $set(&mut self, on: bool) {
                    if on {
                        self.0 |= $bit;
                    } else {
                        self.0 &= !($bit as $bits);
                    }
                }
            )*
        }
    };
}

/// Tags of an edge (OpenSubdiv's `ETag`, the parts refinement uses), packed
/// in one byte; all clear by default.
#[derive(Clone, Copy, PartialEq, Eq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct EdgeTag(u8);

tag_bits! {
    EdgeTag, u8;
    /// More than two faces, a repeated or degenerate edge, or faces of opposite winding.
    non_manifold, set_non_manifold = 1;
    /// Fewer than two incident faces.
    boundary, set_boundary = 2;
    /// Infinitely sharp.
    inf_sharp, set_inf_sharp = 4;
    /// Sharp but finite.
    semi_sharp, set_semi_sharp = 8;
}

impl std::fmt::Debug for EdgeTag {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EdgeTag")
            .field("non_manifold", &self.non_manifold())
            .field("boundary", &self.boundary())
            .field("inf_sharp", &self.inf_sharp())
            .field("semi_sharp", &self.semi_sharp())
            .finish()
    }
}

/// Tags of a vertex (OpenSubdiv's `VTag`, the parts refinement uses), packed
/// in two bytes; all clear and the rule [`Rule::Smooth`] by default.
#[derive(Clone, Copy, PartialEq, Eq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct VertexTag(u16);

tag_bits! {
    VertexTag, u16;
    /// Its incident faces and edges cannot be ordered around it.
    non_manifold, set_non_manifold = 1;
    /// On a boundary edge.
    boundary, set_boundary = 2;
    /// A topological corner (one face, two edges) that is infinitely sharp.
    corner, set_corner = 4;
    /// Infinitely sharp.
    inf_sharp, set_inf_sharp = 8;
    /// Sharp but finite.
    semi_sharp, set_semi_sharp = 16;
    /// Has semi-sharp incident edges.
    semi_sharp_edges, set_semi_sharp_edges = 32;
    /// Has infinitely sharp incident edges.
    inf_sharp_edges, set_inf_sharp_edges = 64;
}

impl VertexTag {
    const RULE_SHIFT: u32 = 8;

    /// The subdivision rule of the vertex.
    #[inline]
    pub fn rule(self) -> Rule {
        match (self.0 >> Self::RULE_SHIFT) & 3 {
            0 => Rule::Smooth,
            1 => Rule::Dart,
            2 => Rule::Crease,
            _ => Rule::Corner,
        }
    }

    /// Sets [`Self::rule`].
    #[inline]
    pub fn set_rule(&mut self, rule: Rule) {
        let code = match rule {
            Rule::Smooth => 0,
            Rule::Dart => 1,
            Rule::Crease => 2,
            Rule::Corner => 3,
        };
        self.0 = (self.0 & !(3 << Self::RULE_SHIFT)) | (code << Self::RULE_SHIFT);
    }
}

impl std::fmt::Debug for VertexTag {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VertexTag")
            .field("non_manifold", &self.non_manifold())
            .field("boundary", &self.boundary())
            .field("corner", &self.corner())
            .field("inf_sharp", &self.inf_sharp())
            .field("semi_sharp", &self.semi_sharp())
            .field("semi_sharp_edges", &self.semi_sharp_edges())
            .field("inf_sharp_edges", &self.inf_sharp_edges())
            .field("rule", &self.rule())
            .finish()
    }
}
