//! Names of option values: one mechanism for every enum the command line,
//! reports and files spell out (`catmark`, `edge-only`, `f32`, `osd`, ...).
//!
//! Each such enum implements [`Named`] (through a crate-internal macro), which
//! gives it `ALL`, `name()`, [`Display`](std::fmt::Display) and
//! [`FromStr`](std::str::FromStr) with one error type, [`ParseNameError`].
//!
//! ```
//! use subdiv::{BoundaryInterpolation, Named, ParseNameError};
//! let b: BoundaryInterpolation = "edge-only".parse()?;
//! assert_eq!(b, BoundaryInterpolation::EdgeOnly);
//! assert_eq!(b.to_string(), "edge-only");
//! let err = "wobbly".parse::<BoundaryInterpolation>().unwrap_err();
//! assert_eq!(err.expected, ["none", "edge-only", "edge-and-corner"]);
//! assert_eq!(BoundaryInterpolation::KIND, "BoundaryInterpolation");
//! # Ok::<(), ParseNameError>(())
//! ```

use thiserror::Error;

/// An enum whose values have fixed names.
pub trait Named: Copy + PartialEq + 'static {
    /// What the values are, as error messages name it.
    const KIND: &'static str;
    /// Every value, in declaration order.
    const ALL: &'static [Self];

    /// The value's name.
    fn name(self) -> &'static str;

    /// The value named `text`, or an error listing the names.
    fn from_name(text: &str) -> Result<Self, ParseNameError> {
        Self::ALL
            .iter()
            .copied()
            .find(|v| v.name() == text)
            .ok_or_else(|| ParseNameError {
                kind: Self::KIND,
                given: text.to_string(),
                expected: Self::ALL.iter().map(|v| v.name()).collect(),
            })
    }
}

/// A name that is not one of an enum's values.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown {kind} '{given}' (expected one of: {})", expected.join(", "))]
pub struct ParseNameError {
    /// What was being parsed ([`Named::KIND`]).
    pub kind: &'static str,
    /// The text given.
    pub given: String,
    /// The names accepted.
    pub expected: Vec<&'static str>,
}

/// Implements [`Named`] for an enum, with inherent `ALL` and `name()` (no
/// import needed), `Display` and `FromStr`.
macro_rules! impl_named {
    ($ty:ident, $kind:expr, { $($variant:ident => $text:literal),+ $(,)? }) => {
        impl $ty {
            /// Every value, in declaration order.
            pub const ALL: &'static [$ty] = &[$($ty::$variant),+];

            /// The name used on the command line, in reports and in files.
            pub fn name(self) -> &'static str {
                match self { $($ty::$variant => $text,)+ }
            }
        }

        impl $crate::names::Named for $ty {
            const KIND: &'static str = $kind;
            const ALL: &'static [$ty] = $ty::ALL;
            fn name(self) -> &'static str {
                $ty::name(self)
            }
        }

        impl ::std::fmt::Display for $ty {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl ::std::str::FromStr for $ty {
            type Err = $crate::names::ParseNameError;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                <$ty as $crate::names::Named>::from_name(s)
            }
        }
    };
}
pub(crate) use impl_named;
