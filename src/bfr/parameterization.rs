//! The (u, v) parameterization of one base face (`Bfr::Parameterization`).
//!
//! A face whose size is the scheme's regular one (a quad under Catmull-Clark
//! and bilinear, a triangle under Loop) is parameterized over the unit square
//! or the unit triangle. Any other face of a quad scheme is split at its
//! centre into quadrilateral sub-faces, one per corner, laid out as tiles of a
//! grid `u_dim` wide: sub-face `i` covers `[i % u_dim, i % u_dim + 0.5] ×
//! [i / u_dim, i / u_dim + 0.5]`, and its normalized coordinates (doubled) are
//! the ptex coordinates of that corner's ptex face. Loop has no
//! parameterization for non-triangles.
//!
//! Every coordinate is computed in the caller's precision exactly as
//! OpenSubdiv computes it, so a coordinate from here equals OpenSubdiv's bit
//! for bit in `f32` and in `f64` (the triangle's centre, for one, is
//! `1.0f / 3.0f` widened, in both).

use crate::error::{Error, Result};
use crate::options::Scheme;
use crate::real::Real;

/// The largest face OpenSubdiv parameterizes (`Bfr::Limits::MaxFaceSize`,
/// `Far::VALENCE_LIMIT`).
pub const MAX_FACE_SIZE: usize = (1 << 16) - 1;

/// The three kinds of parameterization (`Bfr::Parameterization::Type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParameterizationType {
    /// The unit square (a quad of a quad scheme).
    Quad,
    /// The unit triangle `u, v ≥ 0, u + v ≤ 1` (a triangle of Loop).
    Triangle,
    /// Quadrilateral sub-faces, one per corner (any other face of a quad
    /// scheme, triangles of Catmull-Clark included).
    QuadSubfaces,
}

/// The parameterization of a face of a given size under a given scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Parameterization {
    kind: ParameterizationType,
    face_size: usize,
    u_dim: usize,
}

impl Parameterization {
    /// The parameterization of a `face_size`-sided face under `scheme`.
    ///
    /// Refused, as OpenSubdiv leaves them invalid: faces of fewer than 3 or
    /// more than [`MAX_FACE_SIZE`] vertices, and non-triangles under Loop.
    ///
    /// ```
    /// use subdiv::Scheme;
    /// use subdiv::bfr::{Parameterization, ParameterizationType};
    ///
    /// let pentagon = Parameterization::new(Scheme::Catmark, 5).unwrap();
    /// assert_eq!(pentagon.kind(), ParameterizationType::QuadSubfaces);
    /// assert_eq!(pentagon.vertex_coord::<f64>(4), [1.0, 1.0]);
    /// assert!(Parameterization::new(Scheme::Loop, 4).is_err());
    /// ```
    pub fn new(scheme: Scheme, face_size: usize) -> Result<Self> {
        let regular = if scheme == Scheme::Loop { 3 } else { 4 };
        let refuse = |reason: String| {
            Err(Error::Parameterization {
                face_size,
                reason: format!("{reason} (scheme {scheme})"),
            })
        };
        if face_size == regular {
            let kind = if regular == 4 {
                ParameterizationType::Quad
            } else {
                ParameterizationType::Triangle
            };
            return Ok(Self {
                kind,
                face_size,
                u_dim: 0,
            });
        }
        if !(3..=MAX_FACE_SIZE).contains(&face_size) {
            return refuse(format!("a face needs 3 to {MAX_FACE_SIZE} vertices"));
        }
        if regular == 3 {
            return refuse("the Loop scheme parameterizes triangles only".into());
        }
        // OpenSubdiv: 2 or 3 tiles wide below ten sides, else one more than
        // the square root (taken in f32) of the size less one.
        let u_dim = if face_size < 10 {
            2 + usize::from(face_size > 4)
        } else {
            1 + ((face_size - 1) as f32).sqrt() as usize
        };
        Ok(Self {
            kind: ParameterizationType::QuadSubfaces,
            face_size,
            u_dim,
        })
    }

    /// The kind of parameterization.
    pub fn kind(&self) -> ParameterizationType {
        self.kind
    }

    /// The number of vertices of the face.
    pub fn face_size(&self) -> usize {
        self.face_size
    }

    /// Whether the face is split into sub-faces (`HasSubFaces`).
    pub fn has_subfaces(&self) -> bool {
        self.kind == ParameterizationType::QuadSubfaces
    }

    /// The width, in tiles, of the sub-face layout (0 without sub-faces).
    pub fn u_dim(&self) -> usize {
        self.u_dim
    }

    /// The (u, v) of the face's vertex `vertex` (`GetVertexCoord`); for
    /// sub-faces, the corner of that vertex's tile.
    ///
    /// # Panics
    /// When `vertex` is not below the face size.
    pub fn vertex_coord<R: Real>(&self, vertex: usize) -> [R; 2] {
        assert!(
            vertex < self.face_size,
            "vertex {vertex} of a {}-sided face",
            self.face_size
        );
        let flag = |b: bool| if b { R::ONE } else { R::ZERO };
        match self.kind {
            ParameterizationType::Quad => [flag(vertex == 1 || vertex == 2), flag(vertex > 1)],
            ParameterizationType::Triangle => [flag(vertex == 1), flag(vertex == 2)],
            ParameterizationType::QuadSubfaces => [
                small::<R>(vertex % self.u_dim),
                small::<R>(vertex / self.u_dim),
            ],
        }
    }

    /// The (u, v) at parameter `t` in `[0, 1]` along edge `edge` (from
    /// vertex `edge` to the next, `GetEdgeCoord`). On sub-faces the edge runs
    /// along the first tile's lower side up to `t = 0.5`, then down the next
    /// tile's left side.
    ///
    /// # Panics
    /// When `edge` is not below the face size.
    pub fn edge_coord<R: Real>(&self, edge: usize, t: R) -> [R; 2] {
        assert!(
            edge < self.face_size,
            "edge {edge} of a {}-sided face",
            self.face_size
        );
        let one = R::ONE;
        match self.kind {
            ParameterizationType::Quad => match edge {
                0 => [t, R::ZERO],
                1 => [one, t],
                2 => [one - t, one],
                _ => [R::ZERO, one - t],
            },
            ParameterizationType::Triangle => match edge {
                0 => [t, R::ZERO],
                1 => [one - t, t],
                _ => [R::ZERO, one - t],
            },
            ParameterizationType::QuadSubfaces => {
                if t < half::<R>() {
                    let [u, v] = self.vertex_coord::<R>(edge);
                    [u + t, v]
                } else {
                    let [u, v] = self.vertex_coord::<R>((edge + 1) % self.face_size);
                    [u, v + (one - t)]
                }
            }
        }
    }

    /// The (u, v) of the face's centre (`GetCenterCoord`): (0.5, 0.5), or
    /// (1/3, 1/3) in `f32` for a triangle.
    pub fn center_coord<R: Real>(&self) -> [R; 2] {
        center::<R>(self.kind)
    }

    /// The sub-face holding (u, v) (`GetSubFace`; 0 without sub-faces).
    /// Coordinates up to a quarter tile beyond a tile's far side belong to the
    /// next tile, as in OpenSubdiv.
    pub fn subface<R: Real>(&self, uv: [R; 2]) -> usize {
        if !self.has_subfaces() {
            return 0;
        }
        self.split_subface(uv, false).0
    }

    /// The sub-face holding (u, v) and the coordinates within it
    /// (`ConvertCoordToSubFace`: in `[0, 0.5]`, or `[0, 1]` when `normalized`,
    /// `ConvertCoordToNormalizedSubFace`, which are ptex coordinates).
    /// Coordinates far outside the face give a meaningless sub-face, as in
    /// OpenSubdiv.
    pub fn coord_to_subface<R: Real>(
        &self,
        uv: [R; 2],
        normalized: bool,
    ) -> Result<(usize, [R; 2])> {
        self.require_subfaces()?;
        Ok(self.split_subface(uv, normalized))
    }

    /// The (u, v) of coordinates `sub` within sub-face `subface`
    /// (`ConvertSubFaceToCoord`, or `ConvertNormalizedSubFaceToCoord` when
    /// `normalized`).
    pub fn subface_to_coord<R: Real>(
        &self,
        subface: usize,
        sub: [R; 2],
        normalized: bool,
    ) -> Result<[R; 2]> {
        self.require_subfaces()?;
        if subface >= self.face_size {
            return Err(Error::Parameterization {
                face_size: self.face_size,
                reason: format!("sub-face {subface} does not exist"),
            });
        }
        let scale = if normalized { half::<R>() } else { R::ONE };
        Ok([
            small::<R>(subface % self.u_dim) + sub[0] * scale,
            small::<R>(subface / self.u_dim) + sub[1] * scale,
        ])
    }

    /// Whether `uv` lies in the face's domain, up to `slack` beyond its
    /// sides: the unit square, the unit triangle, or one of the sub-face
    /// tiles (a tile's `[0, 0.5]²` corner).
    pub fn contains(&self, [u, v]: [f64; 2], slack: f64) -> bool {
        let within = |x: f64, hi: f64| x >= -slack && x <= hi + slack;
        match self.kind {
            ParameterizationType::Quad => within(u, 1.0) && within(v, 1.0),
            ParameterizationType::Triangle => {
                within(u, 1.0) && within(v, 1.0) && u + v <= 1.0 + slack
            }
            ParameterizationType::QuadSubfaces => {
                if !(u.is_finite() && v.is_finite()) || u < -slack || v < -slack {
                    return false;
                }
                let (sub, [s, t]) = self.split_subface([u, v], false);
                sub < self.face_size && within(s, 0.5) && within(t, 0.5)
            }
        }
    }

    /// The domain, in words (for errors).
    pub fn domain(&self) -> &'static str {
        match self.kind {
            ParameterizationType::Quad => "the unit square",
            ParameterizationType::Triangle => "the unit triangle",
            ParameterizationType::QuadSubfaces => "a sub-face tile [i, i + 0.5] x [j, j + 0.5]",
        }
    }

    fn require_subfaces(&self) -> Result<()> {
        if self.has_subfaces() {
            Ok(())
        } else {
            Err(Error::Parameterization {
                face_size: self.face_size,
                reason: "the face has no sub-faces".into(),
            })
        }
    }

    /// Tile and fraction of (u, v), a fraction above 0.75 moved to the next
    /// tile (as a negative fraction), as OpenSubdiv does.
    fn split_subface<R: Real>(&self, uv: [R; 2], normalized: bool) -> (usize, [R; 2]) {
        let three_quarters = R::from_f64(0.75);
        let split = |x: R| {
            // `(int) x` truncates toward zero, as the cast does here.
            let tile = x.to_f64() as i64;
            let frac = x - R::from_f64(tile as f64);
            if frac > three_quarters {
                (tile + 1, frac - R::ONE)
            } else {
                (tile, frac)
            }
        };
        let (ut, uf) = split(uv[0]);
        let (vt, vf) = split(uv[1]);
        let scale = if normalized { R::from_f64(2.0) } else { R::ONE };
        let index = (self.u_dim as i64) * vt + ut;
        (index.max(0) as usize, [uf * scale, vf * scale])
    }
}

/// The centre of a parameterization of kind `kind`.
pub(crate) fn center<R: Real>(kind: ParameterizationType) -> [R; 2] {
    if kind == ParameterizationType::Triangle {
        let third = R::from_f32(1.0f32 / 3.0f32);
        [third, third]
    } else {
        [half::<R>(), half::<R>()]
    }
}

/// 0.5 in `R`.
pub(crate) fn half<R: Real>() -> R {
    R::from_f64(0.5)
}

/// A small non-negative integer, exactly, in `R`.
pub(crate) fn small<R: Real>(n: usize) -> R {
    R::from_f64(n as f64)
}
