//! Tessellation patterns of a parameterized face (`Bfr::Tessellation`).
//!
//! A [`Tessellation`] is the pattern of points ("coords", in the face's
//! [`Parameterization`]) and facets (triangles, or quads kept where the
//! pattern allows) that covers one face at given rates: one uniform rate, or
//! a rate per edge (with inner rates given or inferred). Neighbouring faces
//! tessellated at the same rate on their shared edge have the same points
//! along it, which is what makes a mesh of tessellated faces watertight; the
//! coordinate-index transforms ([`CoordIndexMap`]) renumber a pattern's
//! facets into such a mesh.
//!
//! The pattern is OpenSubdiv's, index by index: the same coordinates in the
//! same order (boundary first, counter-clockwise from vertex 0, then the
//! interior rings inward), bit for bit in `f32` and `f64`, and the same
//! facets.
//!
//! ```
//! use subdiv::Scheme;
//! use subdiv::bfr::{FacetSize, Parameterization, Tessellation, TessellationOptions};
//!
//! let quad = Parameterization::new(Scheme::Catmark, 4).unwrap();
//! let t = Tessellation::uniform(quad, 2, TessellationOptions::default()).unwrap();
//! assert_eq!((t.num_boundary_coords(), t.num_interior_coords()), (8, 1));
//! let coords = t.coords::<f64>().unwrap();
//! assert_eq!(coords[1], [0.5, 0.0]);
//! assert_eq!(coords[8], [0.5, 0.5]);
//! assert_eq!(t.num_facets(), 8); // four quads, each as two triangles
//!
//! let quads = TessellationOptions { preserve_quads: true, facet_size: FacetSize::Four };
//! let t = Tessellation::uniform(quad, 2, quads).unwrap();
//! assert_eq!(t.facets().unwrap().len(), 4 * 4);
//! ```

mod coords;
mod facets;
mod strip;
#[cfg(test)]
mod tests;

use crate::alloc;
use crate::bfr::{Parameterization, ParameterizationType};
use crate::error::{Error, Result};
use crate::real::Real;
use strip::FacetSink;

/// The largest rate OpenSubdiv uses: greater rates are clamped to it.
pub const MAX_RATE: u32 = i16::MAX as u32;

/// The number of indices per facet (`Tessellation::Options::SetFacetSize`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum FacetSize {
    /// Triangles: 3 indices per facet.
    #[default]
    Three,
    /// 4 indices per facet: quads, and triangles padded with -1.
    Four,
}

impl FacetSize {
    /// 3 or 4.
    pub fn indices(self) -> usize {
        match self {
            FacetSize::Three => 3,
            FacetSize::Four => 4,
        }
    }
}

/// How a pattern is made (`Bfr::Tessellation::Options`, its strides aside).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct TessellationOptions {
    /// Keep quads where the pattern has them (needs [`FacetSize::Four`];
    /// OpenSubdiv's `PreserveQuads`, off by default).
    pub preserve_quads: bool,
    /// Indices per facet (3 by default).
    pub facet_size: FacetSize,
}

/// How a pattern's facets are renumbered into a larger mesh
/// ([`Tessellation::transform_facet_coord_indices`], OpenSubdiv's three
/// `TransformFacetCoordIndices`). Padding (-1) is left alone.
#[derive(Debug, Clone, Copy)]
pub enum CoordIndexMap<'a> {
    /// Every index moved by one offset.
    Offset(i32),
    /// Boundary coordinate `i` becomes `boundary[i]`; interior ones move by
    /// `interior_offset`.
    Boundary {
        /// New indices of the boundary coordinates.
        boundary: &'a [i32],
        /// The offset of the interior coordinates.
        interior_offset: i32,
    },
    /// Boundary coordinate `i` becomes `boundary[i]`, interior coordinate
    /// `j` (counted from the first interior one) `interior[j]`.
    Explicit {
        /// New indices of the boundary coordinates.
        boundary: &'a [i32],
        /// New indices of the interior coordinates.
        interior: &'a [i32],
    },
}

/// How the facets of a pattern are laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Form {
    /// The face itself (rate 1, a triangle or a kept quad).
    Single,
    /// A quad at rate 1 as two triangles.
    SplitQuad,
    /// Triangles around the centre.
    Fan,
    /// A 1 × M strip of a quad without interior points.
    Segmented,
    /// Rings (uniform or not).
    Rings,
}

/// A tessellation pattern of one face (`Bfr::Tessellation`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tessellation {
    param: Parameterization,
    given: usize,
    outer: Vec<i32>,
    inner: [i32; 2],
    uniform: bool,
    triangulate: bool,
    facet_size: FacetSize,
    form: Form,
    boundary: usize,
    interior: usize,
    facets: usize,
}

impl Tessellation {
    /// The pattern of `param` at one rate for every edge.
    pub fn uniform(
        param: Parameterization,
        rate: u32,
        options: TessellationOptions,
    ) -> Result<Self> {
        Self::new(param, &[rate], options)
    }

    /// The pattern of `param` at `rates`. For an N-sided face:
    ///
    /// | rates | meaning |
    /// | --- | --- |
    /// | 1 | one inner rate, every edge at it (uniform) |
    /// | 2 | (quads) the inner rates in u and v, opposite edges at them |
    /// | N | one rate per edge (edge i from vertex i to i+1), inner rates inferred |
    /// | N+1 | per edge, and one inner rate |
    /// | N+2 | (quads) per edge, and inner rates in u and v |
    ///
    /// As in OpenSubdiv, other counts below N are read as one uniform rate
    /// (the first), rates beyond those the table names are ignored, and
    /// rates above [`MAX_RATE`] are clamped to it. Inferred inner rates
    /// average the edges (opposite edges of a quad). Refused: no rates, a
    /// zero rate, and patterns whose coordinates do not fit 32-bit indices.
    pub fn new(
        param: Parameterization,
        rates: &[u32],
        options: TessellationOptions,
    ) -> Result<Self> {
        let refuse = |reason: String| Err(Error::Tessellation { reason });
        if rates.is_empty() {
            return refuse("no tessellation rate given".into());
        }
        if let Some(i) = rates.iter().position(|&r| r == 0) {
            return refuse(format!("rate {i} is 0; rates start at 1"));
        }
        let n = param.face_size();
        let is_quad = n == 4;
        let clamp = |r: u32| r.min(MAX_RATE) as i32;
        let mut outer = Vec::new();
        alloc::reserve(&mut outer, n)?;
        let (inner, uniform);
        if rates.len() < n {
            if rates.len() == 2 && is_quad {
                inner = [clamp(rates[0]), clamp(rates[1])];
                outer.extend_from_slice(&[inner[0], inner[1], inner[0], inner[1]]);
                uniform = inner[0] == inner[1];
            } else {
                inner = [clamp(rates[0]); 2];
                outer.resize(n, inner[0]);
                uniform = true;
            }
        } else {
            outer.extend(rates[..n].iter().map(|&r| clamp(r)));
            let all_equal = outer.iter().all(|&r| r == outer[0]);
            if rates.len() > n {
                let second = if rates.len() == 6 && is_quad {
                    rates[5]
                } else {
                    rates[n]
                };
                inner = [clamp(rates[n]), clamp(second)];
                uniform = all_equal && inner[0] == outer[0] && inner[1] == outer[0];
            } else {
                inner = if is_quad {
                    [(outer[0] + outer[2]) / 2, (outer[1] + outer[3]) / 2]
                } else {
                    let sum: i64 = outer.iter().map(|&r| i64::from(r)).sum();
                    [(sum / n as i64) as i32; 2]
                };
                uniform = all_equal;
            }
        }
        let triangulate = options.facet_size == FacetSize::Three || !options.preserve_quads;
        let mut t = Tessellation {
            param,
            given: rates.len(),
            outer,
            inner,
            uniform,
            triangulate,
            facet_size: options.facet_size,
            form: Form::Rings,
            boundary: 0,
            interior: 0,
            facets: 0,
        };
        t.take_inventory()?;
        Ok(t)
    }

    /// Counts the coordinates and facets and chooses the form.
    fn take_inventory(&mut self) -> Result<()> {
        let n = self.param.face_size() as i64;
        let outer: Vec<i64> = self.outer.iter().map(|&r| i64::from(r)).collect();
        let sum: i64 = outer.iter().sum();
        let [iu, iv] = self.inner.map(i64::from);
        let tri = self.triangulate;
        let (interior, facets, form) = match self.param.kind() {
            ParameterizationType::Quad => {
                if self.uniform {
                    if iu > 1 {
                        (
                            (iu - 1) * (iu - 1),
                            facets::quad::uniform_count(iu, tri),
                            Form::Rings,
                        )
                    } else if tri {
                        (0, 2, Form::SplitQuad)
                    } else {
                        (0, 1, Form::Single)
                    }
                } else if iu > 1 && iv > 1 {
                    (
                        (iu - 1) * (iv - 1),
                        facets::quad::non_uniform_count(&outer, [iu, iv], tri),
                        Form::Rings,
                    )
                } else if outer[0] == iu && outer[2] == iu && outer[1] == iv && outer[3] == iv {
                    (
                        0,
                        facets::quad::segmented_count([iu, iv], tri),
                        Form::Segmented,
                    )
                } else {
                    (1, sum, Form::Fan)
                }
            }
            ParameterizationType::Triangle => {
                let interior = |res: i64| (res - 2) * (res - 1) / 2;
                if self.uniform {
                    if iu > 1 {
                        (interior(iu), facets::tri::uniform_count(iu), Form::Rings)
                    } else {
                        (0, 1, Form::Single)
                    }
                } else if iu > 2 {
                    (
                        interior(iu),
                        facets::tri::non_uniform_count(&outer, iu),
                        Form::Rings,
                    )
                } else {
                    (1, sum, Form::Fan)
                }
            }
            ParameterizationType::QuadSubfaces => {
                let interior = |res: i64| {
                    let h = res / 2;
                    if res & 1 != 0 {
                        (h + 1) * (h + 1) * n + i64::from(n != 3)
                    } else {
                        h * (h + 1) * n + 1
                    }
                };
                if self.uniform {
                    if iu > 1 {
                        (
                            interior(iu - 2),
                            facets::qsub::uniform_count(n, iu, tri),
                            Form::Rings,
                        )
                    } else if n == 3 {
                        (0, 1, Form::Single)
                    } else {
                        (1, n, Form::Fan)
                    }
                } else if iu > 1 {
                    (
                        interior(iu - 2),
                        facets::qsub::non_uniform_count(&outer, iu, tri),
                        Form::Rings,
                    )
                } else {
                    (1, sum, Form::Fan)
                }
            }
        };
        let limit = i64::from(i32::MAX);
        if sum + interior > limit || facets > limit {
            return Err(Error::Tessellation {
                reason: format!(
                    "{} coordinates and {facets} facets do not fit 32-bit indices",
                    sum + interior
                ),
            });
        }
        (self.boundary, self.interior, self.facets, self.form) =
            (sum as usize, interior as usize, facets as usize, form);
        Ok(())
    }

    /// The face's parameterization.
    pub fn parameterization(&self) -> Parameterization {
        self.param
    }

    /// The face's number of vertices.
    pub fn face_size(&self) -> usize {
        self.param.face_size()
    }

    /// The rates as given, clamped, with inner rates inferred where they were
    /// not given (`GetRates`): the edge rates for as many edges as rates were
    /// given, then the inner rates for the rest.
    pub fn rates(&self) -> Vec<u32> {
        let n = self.face_size();
        let outer = self.given.min(n);
        let inner = self.given.saturating_sub(n);
        let mut rates: Vec<u32> = self.outer[..outer].iter().map(|&r| r as u32).collect();
        rates.extend((0..inner).map(|i| self.inner[usize::from(i > 0)] as u32));
        rates
    }

    /// The rate of each edge.
    pub fn edge_rates(&self) -> &[i32] {
        &self.outer
    }

    /// The inner rates (u and v; equal except for quads).
    pub fn inner_rates(&self) -> [i32; 2] {
        self.inner
    }

    /// Whether every edge and the inside share one rate.
    pub fn is_uniform(&self) -> bool {
        self.uniform
    }

    /// The number of coordinates.
    pub fn num_coords(&self) -> usize {
        self.boundary + self.interior
    }

    /// The number of boundary coordinates (they come first).
    pub fn num_boundary_coords(&self) -> usize {
        self.boundary
    }

    /// The number of interior coordinates.
    pub fn num_interior_coords(&self) -> usize {
        self.interior
    }

    /// The number of coordinates inside edge `edge` (its ends excluded).
    pub fn num_edge_coords(&self, edge: usize) -> Result<usize> {
        Ok(self.outer[self.check_edge(edge)?] as usize - 1)
    }

    /// Every coordinate: the boundary ones, then the interior ones.
    pub fn coords<R: Real>(&self) -> Result<Vec<[R; 2]>> {
        let mut out = Vec::new();
        alloc::reserve(&mut out, self.num_coords())?;
        self.push_boundary(&mut out);
        self.push_interior(&mut out);
        Ok(out)
    }

    /// The boundary coordinates: counter-clockwise from vertex 0, each edge
    /// from its first vertex.
    pub fn boundary_coords<R: Real>(&self) -> Result<Vec<[R; 2]>> {
        let mut out = Vec::new();
        alloc::reserve(&mut out, self.boundary)?;
        self.push_boundary(&mut out);
        Ok(out)
    }

    /// The interior coordinates, ring by ring inward.
    pub fn interior_coords<R: Real>(&self) -> Result<Vec<[R; 2]>> {
        let mut out = Vec::new();
        alloc::reserve(&mut out, self.interior)?;
        self.push_interior(&mut out);
        Ok(out)
    }

    /// The coordinate of the face's vertex `vertex`.
    pub fn vertex_coord<R: Real>(&self, vertex: usize) -> Result<[R; 2]> {
        Ok(self.param.vertex_coord(self.check_edge(vertex)?))
    }

    /// The coordinates inside edge `edge`, from its first vertex (its ends
    /// excluded).
    pub fn edge_coords<R: Real>(&self, edge: usize) -> Result<Vec<[R; 2]>> {
        let res = self.outer[self.check_edge(edge)?];
        let mut out = Vec::new();
        alloc::reserve(&mut out, res as usize - 1)?;
        match self.param.kind() {
            ParameterizationType::Quad => coords::quad::edge(edge, res, &mut out),
            ParameterizationType::Triangle => coords::tri::edge(edge, res, &mut out),
            ParameterizationType::QuadSubfaces => {
                coords::qsub::edge(&self.param, edge, res, &mut out)
            }
        }
        Ok(out)
    }

    /// The number of facets.
    pub fn num_facets(&self) -> usize {
        self.facets
    }

    /// The number of indices per facet.
    pub fn facet_size(&self) -> usize {
        self.facet_size.indices()
    }

    /// The facets, [`facet_size`](Self::facet_size) coordinate indices each
    /// (counter-clockwise in (u, v)); with 4 indices per facet a triangle's
    /// last is -1.
    pub fn facets(&self) -> Result<Vec<i32>> {
        let size = self.facet_size();
        let mut indices = Vec::new();
        alloc::reserve(&mut indices, self.facets * size)?;
        let mut sink = FacetSink { indices, size };
        let n = self.face_size() as i32;
        let tri = self.triangulate;
        match self.form {
            Form::Single if n == 3 => sink.tri(0, 1, 2),
            Form::Single => sink.quad([0, 1, 2, 3], 0),
            Form::SplitQuad => sink.quad([0, 1, 2, 3], i32::from(tri)),
            Form::Fan => sink.fan(self.facets as i32, 0),
            Form::Segmented => facets::quad::segmented(self.inner, tri, &mut sink),
            Form::Rings => {
                let nb = self.boundary as i32;
                let (outer, inner) = (&self.outer[..], self.inner);
                match (self.param.kind(), self.uniform) {
                    (ParameterizationType::Quad, true) => {
                        facets::quad::uniform(inner[0], tri, &mut sink)
                    }
                    (ParameterizationType::Quad, false) => {
                        facets::quad::non_uniform(outer, inner, nb, tri, &mut sink)
                    }
                    (ParameterizationType::Triangle, true) => {
                        facets::tri::uniform(inner[0], &mut sink)
                    }
                    (ParameterizationType::Triangle, false) => {
                        facets::tri::non_uniform(outer, inner[0], nb, &mut sink)
                    }
                    (ParameterizationType::QuadSubfaces, true) => {
                        facets::qsub::uniform(n, inner[0], tri, &mut sink)
                    }
                    (ParameterizationType::QuadSubfaces, false) => {
                        facets::qsub::non_uniform(outer, inner[0], nb, tri, &mut sink)
                    }
                }
            }
        }
        debug_assert_eq!(sink.len(), self.facets, "facet count of {self:?}");
        Ok(sink.indices)
    }

    /// Renumbers `facets` (as [`facets`](Self::facets) returns them) by `map`.
    /// Refused, leaving `facets` as it was: a buffer of another length, an
    /// index the map does not cover, or an offset overflowing 32 bits.
    pub fn transform_facet_coord_indices(
        &self,
        facets: &mut [i32],
        map: CoordIndexMap,
    ) -> Result<()> {
        let size = self.facet_size();
        let refuse = |reason: String| Err(Error::Tessellation { reason });
        if facets.len() != self.facets * size {
            return refuse(format!(
                "the facet buffer has {} indices, the pattern {} ({} facets of {size})",
                facets.len(),
                self.facets * size,
                self.facets
            ));
        }
        let nb = self.boundary;
        let new_index = |index: i32| -> Option<i32> {
            let i = usize::try_from(index).ok()?;
            match map {
                CoordIndexMap::Offset(offset) => index.checked_add(offset),
                CoordIndexMap::Boundary {
                    boundary,
                    interior_offset,
                } => {
                    if i < nb {
                        boundary.get(i).copied()
                    } else {
                        index.checked_add(interior_offset)
                    }
                }
                CoordIndexMap::Explicit { boundary, interior } => {
                    if i < nb {
                        boundary.get(i).copied()
                    } else {
                        interior.get(i - nb).copied()
                    }
                }
            }
        };
        // Check every index first, so a refusal changes nothing.
        if let Some(&bad) = facets.iter().find(|&&i| i >= 0 && new_index(i).is_none()) {
            return refuse(format!(
                "coordinate index {bad} is not covered by the map (or overflows)"
            ));
        }
        for index in facets.iter_mut().filter(|i| **i >= 0) {
            *index = new_index(*index).unwrap_or(*index);
        }
        Ok(())
    }

    fn check_edge(&self, edge: usize) -> Result<usize> {
        if edge < self.face_size() {
            Ok(edge)
        } else {
            Err(Error::Tessellation {
                reason: format!("vertex or edge {edge} of a {}-sided face", self.face_size()),
            })
        }
    }

    fn push_boundary<R: Real>(&self, out: &mut Vec<[R; 2]>) {
        match self.param.kind() {
            ParameterizationType::Quad => coords::quad::boundary(&self.outer, out),
            ParameterizationType::Triangle => coords::tri::boundary(&self.outer, out),
            ParameterizationType::QuadSubfaces => {
                coords::qsub::boundary(&self.param, &self.outer, out)
            }
        }
    }

    fn push_interior<R: Real>(&self, out: &mut Vec<[R; 2]>) {
        match self.interior {
            0 => {}
            1 => out.push(self.param.center_coord()),
            _ => match self.param.kind() {
                ParameterizationType::Quad => coords::quad::interior(self.inner, out),
                ParameterizationType::Triangle => coords::tri::interior(self.inner[0], out),
                ParameterizationType::QuadSubfaces => {
                    coords::qsub::interior(&self.param, self.inner[0], out)
                }
            },
        }
    }
}
