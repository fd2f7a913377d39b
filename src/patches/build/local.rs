//! Local points (`PatchTableBuilder::LocalPointHelper`): the points of end
//! caps, numbered after every level's vertices, each with a stencil over
//! those vertices (a row of the patch's change-of-basis matrix) and a
//! varying stencil (the patch corner it follows). Neighbouring Gregory and
//! bilinear end caps share the points of a common corner or edge when
//! asked (`shareEndCapPatchPoints`): the first patch to need one creates
//! it. A face-varying channel's end caps have local points of their own,
//! numbered after the channel's values of every level, shared through the
//! channel's corner values and the edges it is continuous across.

use super::Builder;
use super::matrix::Matrix;
use crate::patches::PatchType;
use crate::real::Real;
use crate::stencil::{StencilRows, StencilTable};
use crate::topology::Level;
use crate::topology::fvar::ChannelLevel;

/// Which corner or edge a patch point may be shared through: the corner's
/// or edge's index in the face (low 4 bits), and whether it is a corner,
/// or the point at the beginning or the end of an edge.
const CORNER: u8 = 0x10;
const EDGE_BEGIN: u8 = 0x20;
const EDGE_END: u8 = 0x40;

/// The sharing of each point of a patch type, if it shares at all.
fn share_bits(patch_type: PatchType) -> Option<&'static [u8]> {
    const LINEAR: [u8; 4] = [0x10, 0x11, 0x12, 0x13];
    const GREGORY: [u8; 20] = [
        0x10, 0x20, 0x43, 0, 0, 0x11, 0x21, 0x40, 0, 0, 0x12, 0x22, 0x41, 0, 0, 0x13, 0x23, 0x42,
        0, 0,
    ];
    match patch_type {
        PatchType::Quads => Some(&LINEAR),
        PatchType::GregoryBasis => Some(&GREGORY),
        _ => None,
    }
}

/// The patch corner whose point each patch point's varying value follows.
fn varying_corners(patch_type: PatchType) -> &'static [usize] {
    const LINEAR: [usize; 4] = [0, 1, 2, 3];
    const BSPLINE: [usize; 16] = [0, 0, 1, 1, 0, 0, 1, 1, 3, 3, 2, 2, 3, 3, 2, 2];
    const BOX_SPLINE: [usize; 12] = [0, 0, 1, 0, 0, 1, 1, 2, 2, 1, 2, 2];
    const GREGORY: [usize; 20] = [0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3];
    const GREGORY_TRIANGLE: [usize; 18] = [0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 0, 1, 2];
    match patch_type {
        PatchType::GregoryBasis => &GREGORY,
        PatchType::GregoryTriangle => &GREGORY_TRIANGLE,
        PatchType::Regular => &BSPLINE,
        PatchType::Loop => &BOX_SPLINE,
        _ => &LINEAR,
    }
}

/// The local points made so far.
pub(super) struct LocalPoints<R> {
    /// Index of the first local point: every level's vertices.
    first: u32,
    count: u32,
    share: bool,
    /// B-spline end caps keep source points their matrix copies.
    reuse_sources: bool,
    /// Stencils computed in the precision of the patch table's options,
    /// kept as the table holds them (weights widened to `f64`), in tables:
    /// tens of megabytes on a large mesh, on huge pages rather than faulted
    /// in 4 KiB at a time.
    stencils: StencilRows,
    varying: Option<StencilRows>,
    shared_corners: Vec<Vec<u32>>,
    shared_edges: Vec<Vec<u32>>,
    real: std::marker::PhantomData<R>,
}

impl<R: Real> LocalPoints<R> {
    pub fn new(first: u32, share: bool, reuse_sources: bool, varying: bool, levels: usize) -> Self {
        LocalPoints {
            first,
            count: 0,
            share,
            reuse_sources,
            stencils: StencilRows::with_capacity(0, 0),
            varying: varying.then(|| StencilRows::with_capacity(0, 0)),
            shared_corners: vec![Vec::new(); levels],
            shared_edges: vec![Vec::new(); levels],
            real: std::marker::PhantomData,
        }
    }

    /// Room for about `patches` end caps of `rows` points with `entries`
    /// stencil entries each, asked for before any point is appended (later,
    /// it does nothing).
    pub fn reserve(&mut self, patches: usize, rows: usize, entries: usize) {
        if self.count > 0 {
            return;
        }
        self.stencils = StencilRows::with_capacity(patches * rows, patches * entries);
        if let Some(v) = &mut self.varying {
            *v = StencilRows::with_capacity(patches * rows, patches * rows);
        }
    }

    /// Number of local points.
    pub fn count(&self) -> usize {
        self.count as usize
    }

    /// The vertex and varying stencil tables (the latter empty when not
    /// asked for).
    pub fn finish(self) -> (StencilTable, StencilTable) {
        let varying = self.varying.map(StencilRows::finish).unwrap_or_default();
        (self.stencils.finish(), varying)
    }

    /// The points of one end cap (`AppendLocalPatchPoints`): a new local
    /// point per matrix row unless shared with a neighbour's (or, when
    /// reusing sources, a row that is one source point); `sources` are the
    /// matrix's columns as vertices of `level` (values of channel `fv`),
    /// `offset` that level's first vertex (value). The patch's points are
    /// pushed onto `points`.
    #[allow(clippy::too_many_arguments)]
    pub fn append(
        &mut self,
        builder: &Builder,
        level: usize,
        face: usize,
        matrix: &Matrix<R>,
        patch_type: PatchType,
        sources: &[u32],
        offset: u32,
        fv: Option<&ChannelLevel>,
        points: &mut Vec<u32>,
    ) {
        let l = &builder.levels[level];
        let bits = if self.share {
            share_bits(patch_type)
        } else {
            None
        };
        let corners = varying_corners(patch_type);
        let source = |column: usize| sources.get(column).copied().unwrap_or(0) + offset;
        // What the shared points are found by, read once for the patch.
        let keys = match bits {
            Some(_) => self.share_keys(l, level, face, fv),
            None => ShareKeys::default(),
        };
        points.reserve(matrix.rows.len());
        for (i, row) in matrix.rows.iter().enumerate() {
            if self.reuse_sources && row.len() == 1 {
                points.push(source(row.columns[0]));
                continue;
            }
            let next = self.first + self.count;
            let point = match bits.map(|b| b[i]) {
                Some(b) if b != 0 => self.shared(&keys, level, b, next),
                _ => next,
            };
            if point == next {
                self.stencils
                    .push_mapped(&row.columns, source, &row.weights, R::to_f64);
                if let Some(v) = &mut self.varying {
                    let corner = corners.get(i).copied().unwrap_or(0);
                    v.push_mapped(&[corner], source, &[R::ONE], R::to_f64);
                }
                self.count += 1;
            }
            points.push(point);
        }
    }

    /// The corners' and edges' slots in the shared-point tables of `level`
    /// for face `face` (the tables made the first time, as many entries as
    /// the level has vertices — values of channel `fv` — and twice its
    /// edges): a corner's vertex, an edge's two slots in the order its
    /// lower-numbered vertex first, or none for a boundary edge (or one the
    /// channel is split across), which shares nothing.
    fn share_keys(
        &mut self,
        l: &Level,
        level: usize,
        face: usize,
        fv: Option<&ChannelLevel>,
    ) -> ShareKeys {
        if self.shared_corners[level].is_empty() {
            self.shared_corners[level] =
                vec![0; fv.map_or(l.vertex_count, ChannelLevel::value_count)];
        }
        if self.shared_edges[level].is_empty() {
            self.shared_edges[level] = vec![0; 2 * l.edge_count()];
        }
        let mut keys = ShareKeys::default();
        let corners = super::points::face_points(fv, l, face);
        for (key, &v) in keys.corners.iter_mut().zip(corners) {
            *key = Some(v as usize);
        }
        let verts = l.face_verts(face);
        let n = verts.len();
        for (k, (key, &e)) in keys.edges.iter_mut().zip(l.face_edges_of(face)).enumerate() {
            if l.edge_tag(e as usize).boundary()
                || fv.is_some_and(|c| c.edge_tag(e as usize).is_mismatch())
            {
                continue;
            }
            // The edge's two points are told apart by the vertex they are
            // nearer: its lower-numbered end first (every face around the
            // edge names the same two vertices, so they agree without
            // reading the edge's own vertices).
            let (a, b) = (verts[k], verts[if k + 1 == n { 0 } else { k + 1 }]);
            *key = Some((2 * e as usize, a > b));
        }
        keys
    }

    /// The local point already made for the corner or edge `bits` names
    /// (its slot in `keys`), or `next` (recorded for the next patch)
    /// (`findSharedCornerPoint`, `findSharedEdgePoint`). The tables hold
    /// each point plus one, 0 for none yet (zeroed tables: pages no end cap
    /// reaches are never touched).
    fn shared(&mut self, keys: &ShareKeys, level: usize, bits: u8, next: u32) -> u32 {
        let k = (bits & 0x0f) as usize;
        let slot = if bits & CORNER != 0 {
            let Some(v) = keys.corners.get(k).copied().flatten() else {
                return next;
            };
            self.shared_corners[level].get_mut(v)
        } else if bits & (EDGE_BEGIN | EDGE_END) != 0 {
            let Some((at, flipped)) = keys.edges.get(k).copied().flatten() else {
                return next;
            };
            let end = ((bits & EDGE_END != 0) != flipped) as usize;
            self.shared_edges[level].get_mut(at + end)
        } else {
            return next;
        };
        match slot {
            Some(s) if *s == 0 => {
                *s = next + 1;
                next
            }
            Some(s) => *s - 1,
            None => next,
        }
    }
}

/// Where each corner's and edge's shared points are kept
/// ([`LocalPoints::share_keys`]): a corner's slot in the corner table, an
/// edge's first slot in the edge table and whether its points are taken
/// in reverse; none where nothing is shared.
#[derive(Debug, Default, Clone, Copy)]
struct ShareKeys {
    corners: [Option<usize>; 4],
    edges: [Option<(usize, bool)>; 4],
}
