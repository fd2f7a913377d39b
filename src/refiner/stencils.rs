//! Stencil tables: every refined (or limit) vertex as a weighted sum of base
//! vertices, built by running the refinement masks on sparse rows.

use super::limit::LimitMasks;
use super::{Kind, Refiner, Source};
use crate::error::Result;
use crate::stencil::{LimitStencilTable, StencilTable};

/// Sparse rows under construction, merged through a dense scratch array.
struct RowBuilder {
    dense: Vec<f64>,
    touched: Vec<u32>,
    seen: Vec<bool>,
}

impl RowBuilder {
    fn new(base: usize) -> Self {
        RowBuilder {
            dense: vec![0.0; base],
            touched: Vec::new(),
            seen: vec![false; base],
        }
    }

    fn add_row(&mut self, indices: &[u32], weights: &[f64], w: f64) {
        for (&i, &x) in indices.iter().zip(weights) {
            let iu = i as usize;
            if !self.seen[iu] {
                self.seen[iu] = true;
                self.touched.push(i);
            }
            self.dense[iu] += x * w;
        }
    }

    /// Moves the accumulated row into `table`, in order of first contribution.
    fn finish_into(&mut self, table: &mut StencilTable) {
        table.offsets.push(table.indices.len() as u32);
        table.sizes.push(self.touched.len() as u32);
        for &i in &self.touched {
            let iu = i as usize;
            table.indices.push(i);
            table.weights.push(self.dense[iu]);
            self.dense[iu] = 0.0;
            self.seen[iu] = false;
        }
        self.touched.clear();
    }
}

/// Rows stored in the order they are produced, with a map from vertex to row.
struct Rows {
    table: StencilTable,
    row_of: Vec<u32>,
}

impl Rows {
    fn get(&self, v: u32) -> (&[u32], &[f64]) {
        self.table.row(self.row_of[v as usize] as usize)
    }

    /// The same rows in vertex order.
    fn into_table(self) -> StencilTable {
        let mut out = StencilTable::default();
        for &r in &self.row_of {
            let (i, w) = self.table.row(r as usize);
            out.offsets.push(out.indices.len() as u32);
            out.sizes.push(i.len() as u32);
            out.indices.extend_from_slice(i);
            out.weights.extend_from_slice(w);
        }
        out
    }
}

impl Refiner {
    fn rows_of_level(&self, level: usize) -> Rows {
        let base = self.levels[0].vertex_count;
        if level == 0 {
            let table = StencilTable {
                sizes: vec![1; base],
                offsets: (0..base as u32).collect(),
                indices: (0..base as u32).collect(),
                weights: vec![1.0; base],
            };
            return Rows {
                table,
                row_of: (0..base as u32).collect(),
            };
        }
        let prev = self.rows_of_level(level - 1);
        let n = self.levels[level].vertex_count;
        let mut rows = Rows {
            table: StencilTable::default(),
            row_of: vec![0; n],
        };
        let mut builder = RowBuilder::new(base);
        self.walk_masks::<f64>(Kind::Vertex, level, |child, terms| {
            for &(source, w) in terms {
                match source {
                    Source::Parent(p) => {
                        let (i, x) = prev.get(p);
                        builder.add_row(i, x, w);
                    }
                    Source::Child(c) => {
                        let (i, x) = rows.get(c);
                        builder.add_row(i, x, w);
                    }
                }
            }
            rows.row_of[child as usize] = rows.table.sizes.len() as u32;
            builder.finish_into(&mut rows.table);
        });
        rows
    }

    /// The stencil table mapping base vertices to the vertices of the last
    /// level (as `Far::StencilTableFactory` with vertex interpolation and no
    /// intermediate levels). Weights are computed in `f64`.
    pub fn stencil_table(&self) -> Result<StencilTable> {
        Ok(self.rows_of_level(self.levels.len() - 1).into_table())
    }

    /// Stencils of the limit positions and both tangents at the vertices of
    /// the last level, from base vertices.
    pub fn limit_stencil_table(&self) -> Result<LimitStencilTable> {
        let last = self.levels.len() - 1;
        if !self.levels[last].has_full_topology() {
            return Err(crate::Error::InvalidArgument(
                "limit stencils need full topology in the last level (refine with full_topology_in_last_level)".into(),
            ));
        }
        let rows = self.rows_of_level(last).into_table();
        let level = &self.levels[last];
        let base = self.levels[0].vertex_count;
        let mut builders = [
            RowBuilder::new(base),
            RowBuilder::new(base),
            RowBuilder::new(base),
        ];
        let mut out = LimitStencilTable::default();
        let mut masks = LimitMasks::<f64>::new();
        for v in 0..level.vertex_count {
            let has_masks = masks.compute(self, level, v, true);
            let tables = [&mut out.positions, &mut out.du, &mut out.dv];
            for (k, (builder, table)) in builders.iter_mut().zip(tables).enumerate() {
                if has_masks {
                    let mask = [&masks.pos, &masks.tan1, &masks.tan2][k];
                    for (&p, &w) in masks.face_points.iter().zip(&mask.face) {
                        let (i, x) = rows.row(p as usize);
                        builder.add_row(i, x, w);
                    }
                    for (&p, &w) in masks.edge_points.iter().zip(&mask.edge) {
                        let (i, x) = rows.row(p as usize);
                        builder.add_row(i, x, w);
                    }
                    let (i, x) = rows.row(v);
                    builder.add_row(i, x, mask.vertex[0]);
                } else if k == 0 {
                    let (i, x) = rows.row(v);
                    builder.add_row(i, x, 1.0);
                }
                builder.finish_into(table);
            }
        }
        Ok(out)
    }
}
