//! The change-of-basis matrix of an end cap (`Far::SparseMatrix` as the
//! patch builders use it): one row per patch point, each a list of (source
//! point, weight) entries sized before it is filled.

use crate::real::Real;

/// One row: its source points and weights, of a fixed size.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Row<R> {
    pub columns: Vec<usize>,
    pub weights: Vec<R>,
}

impl<R: Real> Row<R> {
    /// Number of entries.
    pub fn len(&self) -> usize {
        self.columns.len()
    }

    /// Sets entry `i`; an entry past the row's size is dropped (OpenSubdiv
    /// writes one past a boundary edge point's row into the next row, which
    /// is written over afterwards).
    pub fn set(&mut self, i: usize, column: usize, weight: R) {
        if i < self.columns.len() {
            self.columns[i] = column;
            self.weights[i] = weight;
        }
    }
}

/// A matrix of rows over `columns` source points.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Matrix<R> {
    pub rows: Vec<Row<R>>,
    pub columns: usize,
}

impl<R: Real> Matrix<R> {
    /// Makes this rows of the given sizes (entries zeroed) over `columns`
    /// source points, reusing the rows' storage: one matrix serves every
    /// end cap of a table.
    pub fn reset(&mut self, sizes: &[usize], columns: usize) {
        self.columns = columns;
        self.rows.resize_with(sizes.len(), Row::default);
        for (row, &n) in self.rows.iter_mut().zip(sizes) {
            row.columns.clear();
            row.columns.resize(n, 0);
            row.weights.clear();
            row.weights.resize(n, R::ZERO);
        }
    }

    /// Merges repeated corner points within each row, adding their weights
    /// to the first entry (`_removeValence2Duplicates`): an interior corner
    /// of valence 2 puts the same corners in its neighbours' rings twice.
    pub fn merge_repeated_corners(&mut self) {
        for row in &mut self.rows {
            let mut first: [Option<usize>; 4] = [None; 4];
            let (mut columns, mut weights) = (Vec::with_capacity(row.len()), Vec::new());
            for (&c, &w) in row.columns.iter().zip(&row.weights) {
                if c < 4 {
                    if let Some(at) = first[c] {
                        let sum: &mut R = &mut weights[at];
                        *sum += w;
                        continue;
                    }
                    first[c] = Some(columns.len());
                }
                columns.push(c);
                weights.push(w);
            }
            row.columns = columns;
            row.weights = weights;
        }
    }
}
