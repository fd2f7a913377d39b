//! Face-varying interpolation: refining the values of one channel from a
//! level to the next with the scheme's masks, adapted to the channel's own
//! topology (the counterpart of `PrimvarRefiner::InterpolateFaceVarying`).
//!
//! Where the channel follows the vertex topology it is refined exactly like
//! vertex data, except that every neighbour's value is read through the
//! channel (a neighbouring vertex may carry several values). Elsewhere:
//!
//! * a point on a split (or linear) edge is the midpoint of the edge's two
//!   values as seen from one incident face — one such value per face;
//! * a vertex value tagged as a corner is copied;
//! * a crease value takes 3/4 of itself and 1/8 of each of the values at the
//!   two ends of its span; a semi-sharp value blends the corner and crease
//!   masks by the fractional weight of the sharpness that decays;
//! * with linear interpolation (option `All`, or the bilinear scheme), face
//!   points average the face's values, edge points are midpoints and
//!   vertex values are copied.
//!
//! Every value is accumulated term by term in the same order as OpenSubdiv,
//! from zero, so `f64` results agree to the last bit.

use super::Refiner;
use crate::error::{Buffer, Error, Result};
use crate::options::Scheme;
use crate::real::Real;
use crate::rules::{EdgeNeighborhood, Mask, Rule, VertexNeighborhood, crease};

/// Row `i` of a buffer of `width`-wide elements.
#[inline]
fn row<T>(data: &[T], i: u32, width: usize) -> &[T] {
    let i = i as usize * width;
    &data[i..i + width]
}

/// `acc += w · x`, component by component.
#[inline]
fn add<T: Real>(acc: &mut [T], x: &[T], w: T) {
    for (a, &s) in acc.iter_mut().zip(x) {
        *a += s * w;
    }
}

/// Writes `acc` into row `i` of `dst`.
#[inline]
fn put<T: Real>(dst: &mut [T], i: u32, acc: &[T]) {
    let i = i as usize * acc.len();
    dst[i..i + acc.len()].copy_from_slice(acc);
}

impl Refiner {
    /// Interpolates the values of face-varying `channel` (`width` components
    /// each) from level `level - 1` to `level`.
    ///
    /// `src` holds the channel's values at `level - 1` (at level 0, the
    /// mesh's own values); the result holds
    /// `width × (value count at level)` components, numbered as
    /// [`Refiner::level`] reports the channel's face values.
    pub fn interpolate_face_varying<T: Real>(
        &self,
        channel: usize,
        level: u32,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        crate::alloc::guard(Some(level), || {
            let levels = self.fvar.get(channel).ok_or(Error::NoSuchChannel {
                channel,
                count: self.fvar.len(),
            })?;
            if level == 0 || level > self.max_level() {
                return Err(Error::NoSuchLevel {
                    level,
                    first: 1,
                    last: self.max_level(),
                });
            }
            if width == 0 {
                return Err(Error::ZeroWidth);
            }
            let (parent, child) = (&levels[level as usize - 1], &levels[level as usize]);
            if src.len() != parent.value_count() * width {
                return Err(Error::BufferLength {
                    buffer: Buffer::FaceVaryingSource,
                    expected: parent.value_count() * width,
                    got: src.len(),
                });
            }
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, child.value_count() * width);
            self.interpolate_fvar_level(channel, level as usize, width, src, &mut dst);
            Ok(dst)
        })
    }

    /// One level of one channel: face points, edge points, vertex points.
    fn interpolate_fvar_level<T: Real>(
        &self,
        channel: usize,
        level: usize,
        width: usize,
        src: &[T],
        dst: &mut [T],
    ) {
        let parent = &self.levels[level - 1];
        let child = &self.levels[level];
        let r = &self.refinements[level - 1];
        let pf = &self.fvar[channel][level - 1];
        let cf = &self.fvar[channel][level];
        let scheme = self.rules.scheme();
        let linear = pf.is_linear() || scheme == Scheme::Bilinear;
        let mut acc = vec![T::ZERO; width];
        let mut mask = Mask::<T>::new();
        let half = T::from_f64(0.5);

        // Face points (none with Loop's split): the average of the face's values.
        if r.has_face_points() {
            for f in 0..parent.face_count() {
                let values = pf.face_values_of(parent, f);
                self.rules.face_vertex_mask(values.len(), &mut mask);
                acc.fill(T::ZERO);
                for (&x, &w) in values.iter().zip(&mask.vertex) {
                    add(&mut acc, row(src, x, width), w);
                }
                put(dst, cf.vertex_value_offset(r.face_child(f) as usize), &acc);
            }
        }

        // Edge points.
        let mut face_sizes = Vec::new();
        for e in 0..parent.edge_count() {
            let c = r.edge_child(e) as usize;
            let first = cf.vertex_value_offset(c);
            if cf.vertex_value_tags(c)[0].is_mismatch() {
                // One midpoint per value, from the face the value comes from.
                for i in 0..cf.vertex_value_count(c) {
                    let [a, b] = pf.edge_face_values(parent, e, i);
                    acc.fill(T::ZERO);
                    add(&mut acc, row(src, a, width), half);
                    add(&mut acc, row(src, b, width), half);
                    put(dst, first + i as u32, &acc);
                }
                continue;
            }
            let faces = parent.edge_faces_of(e);
            if linear {
                mask.reset(2, 0, 0);
                mask.vertex[0] = half;
                mask.vertex[1] = half;
            } else {
                face_sizes.clear();
                face_sizes.extend(
                    faces
                        .iter()
                        .map(|&f| parent.face_vertices.count(f as usize) as u32),
                );
                let s = parent.edge_sharpness_at(e);
                let hood = EdgeNeighborhood {
                    sharpness: s,
                    face_sizes: &face_sizes,
                };
                let p_rule = if s > 0.0 { Rule::Crease } else { Rule::Smooth };
                self.rules
                    .edge_vertex_mask(&hood, p_rule, child.vertex_tag(c).rule(), &mut mask);
            }
            let [a, b] = pf.edge_face_values(parent, e, 0);
            acc.fill(T::ZERO);
            add(&mut acc, row(src, a, width), mask.vertex[0]);
            add(&mut acc, row(src, b, width), mask.vertex[1]);
            for (&f, &w) in faces.iter().zip(&mask.face) {
                let f = f as usize;
                if mask.face_weights_for_centers {
                    let centre = cf.vertex_value_offset(r.face_child(f) as usize);
                    add(&mut acc, row(dst, centre, width), w);
                } else {
                    // Loop: the value at the face's corner opposite the edge.
                    let edges = parent.face_edges_of(f);
                    let k = edges.iter().position(|&x| x as usize == e).unwrap_or(0);
                    let values = pf.face_values_of(parent, f);
                    add(&mut acc, row(src, values[(k + 2) % values.len()], width), w);
                }
            }
            put(dst, first, &acc);
        }

        // Vertex points.
        let mut edge_sharpness = Vec::new();
        let mut child_edge_sharpness = Vec::new();
        let mut edge_values = Vec::new();
        let corner_weight = T::from_f64(0.75);
        let end_weight = T::from_f64(0.125);
        for v in 0..parent.vertex_count {
            let c = r.vertex_child(v) as usize;
            let first = cf.vertex_value_offset(c);
            let c_tags = cf.vertex_value_tags(c);
            if !c_tags[0].is_mismatch() {
                let own = pf.vertex_value(v, 0);
                acc.fill(T::ZERO);
                if linear {
                    add(&mut acc, row(src, own, width), T::ONE);
                    put(dst, first, &acc);
                    continue;
                }
                // The vertex's own mask, applied to the channel's values.
                let edges = parent.vertex_edges_of(v);
                let faces = parent.vertex_faces_of(v);
                edge_sharpness.clear();
                edge_sharpness.extend(edges.iter().map(|&e| parent.edge_sharpness_at(e as usize)));
                child_edge_sharpness.resize(edges.len(), 0.0);
                crease::subdivide_edge_sharpnesses_around_vertex(
                    self.options.creasing,
                    &edge_sharpness,
                    &mut child_edge_sharpness,
                );
                let hood = VertexNeighborhood {
                    sharpness: parent.vertex_sharpness_at(v),
                    edge_sharpness: &edge_sharpness,
                    face_count: faces.len(),
                    child_sharpness: child.vertex_sharpness_at(c),
                    child_edge_sharpness: &child_edge_sharpness,
                };
                let p_rule = parent.vertex_tag(v).rule();
                let c_rule = child.vertex_tag(c).rule();
                self.rules
                    .vertex_vertex_mask(&hood, p_rule, c_rule, &mut mask);
                for (&f, &w) in faces.iter().zip(&mask.face) {
                    let centre = cf.vertex_value_offset(r.face_child(f as usize) as usize);
                    add(&mut acc, row(dst, centre, width), w);
                }
                if !mask.edge.is_empty() {
                    pf.vertex_edge_values(parent, v, &mut edge_values);
                    for (&x, &w) in edge_values.iter().zip(&mask.edge) {
                        add(&mut acc, row(src, x, width), w);
                    }
                }
                add(&mut acc, row(src, own, width), mask.vertex[0]);
                put(dst, first, &acc);
                continue;
            }
            // Each value on its own: a corner, a crease, or a corner decaying
            // into a crease.
            let p_tags = pf.vertex_value_tags(v);
            for (s, &tag) in c_tags.iter().enumerate() {
                let own = pf.vertex_value(v, s);
                acc.fill(T::ZERO);
                if linear || tag.is_corner() {
                    add(&mut acc, row(src, own, width), T::ONE);
                } else {
                    let [e0, e1] = pf.crease_end_values(parent, v, s);
                    let (mut vw, mut ew) = (corner_weight, end_weight);
                    if p_tags[s].is_semi_sharp() {
                        // A value sharpened by its sibling decays with it.
                        let from = if p_tags[s].is_dep_sharp() {
                            (s == 0) as usize
                        } else {
                            s
                        };
                        let w =
                            pf.fractional_weight(parent, child, v, from, c, self.options.creasing);
                        let corner = T::from_f32(w);
                        let crease = T::ONE - corner;
                        vw = crease * corner_weight + corner;
                        ew = crease * end_weight;
                    }
                    add(&mut acc, row(src, e0, width), ew);
                    add(&mut acc, row(src, e1, width), ew);
                    add(&mut acc, row(src, own, width), vw);
                }
                put(dst, first + s as u32, &acc);
            }
        }
    }
}

impl Refiner {
    /// Limit values of face-varying `channel` at the last level, from its
    /// values at that level (`PrimvarRefiner::LimitFaceVarying`): the vertex
    /// limit mask where the channel is continuous, the crease limit (2/3 and
    /// 1/6, 1/6 along the channel's boundary) or the value itself (corners)
    /// where it is split, and the values unchanged for a linear channel.
    pub fn limit_face_varying<T: Real>(
        &self,
        channel: usize,
        width: usize,
        src: &[T],
    ) -> Result<Vec<T>> {
        crate::alloc::guard(None, || {
            let levels = self.fvar.get(channel).ok_or(Error::NoSuchChannel {
                channel,
                count: self.fvar.len(),
            })?;
            if width == 0 {
                return Err(Error::ZeroWidth);
            }
            let level = self.levels.last().expect("base level");
            if !level.has_full_topology() {
                return Err(Error::NeedsFullTopology);
            }
            let fvar = levels.last().expect("base channel");
            if src.len() != fvar.value_count() * width {
                return Err(Error::BufferLength {
                    buffer: Buffer::FaceVaryingSource,
                    expected: fvar.value_count() * width,
                    got: src.len(),
                });
            }
            let mut dst = crate::alloc::vec_or_unwind(T::ZERO, src.len());
            let mut acc = vec![T::ZERO; width];
            let mut mask = crate::rules::Mask::<T>::new();
            let mut edge_sharpness = Vec::new();
            let mut edge_values = Vec::new();
            let row = |i: u32| &src[i as usize * width..(i as usize + 1) * width];
            let add = |acc: &mut [T], r: &[T], w: T| {
                for (a, &s) in acc.iter_mut().zip(r) {
                    *a += s * w;
                }
            };
            // OpenSubdiv writes these two weights as single-precision literals.
            let sixth = T::from_f32(1.0f32 / 6.0f32);
            let two_thirds = T::from_f32(2.0f32 / 3.0f32);
            for v in 0..level.vertex_count {
                let count = fvar.vertex_value_count(v);
                let edges = level.vertex_edges_of(v);
                let store = |dst: &mut [T], value: u32, acc: &[T]| {
                    let i = value as usize * width;
                    dst[i..i + width].copy_from_slice(acc);
                };
                if edges.is_empty() || fvar.is_linear() {
                    for s in 0..count {
                        let value = fvar.vertex_value(v, s);
                        store(&mut dst, value, row(value));
                    }
                    continue;
                }
                let tags = fvar.vertex_value_tags(v);
                if !tags[0].is_mismatch() {
                    edge_sharpness.clear();
                    edge_sharpness
                        .extend(edges.iter().map(|&e| level.edge_sharpness_at(e as usize)));
                    let faces = level.vertex_faces_of(v);
                    let hood = crate::rules::VertexNeighborhood {
                        sharpness: level.vertex_sharpness_at(v),
                        edge_sharpness: &edge_sharpness,
                        face_count: faces.len(),
                        child_sharpness: level.vertex_sharpness_at(v),
                        child_edge_sharpness: &[],
                    };
                    self.rules.vertex_limit_position_mask(
                        &hood,
                        level.vertex_tag(v).rule(),
                        &mut mask,
                    );
                    let value = fvar.vertex_value(v, 0);
                    acc.fill(T::ZERO);
                    if !mask.face.is_empty() {
                        for ((&f, &k), &w) in faces
                            .iter()
                            .zip(level.vertex_face_locals(v))
                            .zip(&mask.face)
                        {
                            let values = fvar.face_values_of(level, f as usize);
                            add(&mut acc, row(values[(k as usize + 2) % values.len()]), w);
                        }
                    }
                    if !mask.edge.is_empty() {
                        fvar.vertex_edge_values(level, v, &mut edge_values);
                        for (&ev, &w) in edge_values.iter().zip(&mask.edge) {
                            add(&mut acc, row(ev), w);
                        }
                    }
                    add(&mut acc, row(value), mask.vertex[0]);
                    store(&mut dst, value, &acc);
                } else {
                    for (s, tag) in tags.iter().enumerate().take(count) {
                        let value = fvar.vertex_value(v, s);
                        if tag.is_corner() {
                            store(&mut dst, value, row(value));
                        } else {
                            let [a, b] = fvar.crease_end_values(level, v, s);
                            acc.fill(T::ZERO);
                            add(&mut acc, row(a), sixth);
                            add(&mut acc, row(b), sixth);
                            add(&mut acc, row(value), two_thirds);
                            store(&mut dst, value, &acc);
                        }
                    }
                }
            }
            Ok(dst)
        })
    }
}
