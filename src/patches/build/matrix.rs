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

/// Sets a row's entries in order.
pub(super) fn set_all<R: Real>(row: &mut Row<R>, entries: &[(usize, R)]) {
    for (i, &(column, weight)) in entries.iter().enumerate() {
        row.set(i, column, weight);
    }
}

/// Copies `from` into `to` over `to`'s size (`SparseMatrixRow::Copy`).
pub(super) fn copy_row<R: Real>(to: &mut Row<R>, from: &Row<R>) {
    for i in 0..to.len().min(from.len()) {
        to.columns[i] = from.columns[i];
        to.weights[i] = from.weights[i];
    }
}

/// The full-row scratch space of combinations of rows: a weight per source
/// point and whether it was touched.
pub(super) type Scratch<R> = (Vec<R>, Vec<bool>);

/// Adds `coefficient ×` each row of `terms` into the full-row scratch
/// (`_addSparsePointToFullRow`); columns past the source points are
/// dropped, as OpenSubdiv's output loop never reads them.
pub(super) fn accumulate<R: Real>(
    m: &Matrix<R>,
    terms: &[(usize, R)],
    weights: &mut [R],
    used: &mut [bool],
) {
    weights.iter_mut().for_each(|w| *w = R::ZERO);
    used.iter_mut().for_each(|u| *u = false);
    for &(row, s) in terms {
        let row = &m.rows[row];
        for (&i, &w) in row.columns.iter().zip(&row.weights) {
            if let Some(x) = weights.get_mut(i) {
                *x += s * w;
                used[i] = true;
            }
        }
    }
}

/// Writes the touched columns of the scratch into `row` in column order,
/// over the row's size, padded with zero weights on column `pad` when
/// given.
pub(super) fn write_row<R: Real>(
    row: &mut Row<R>,
    weights: &[R],
    used: &[bool],
    pad: Option<usize>,
) {
    let size = row.len();
    row.columns.clear();
    row.weights.clear();
    for (i, (&u, &w)) in used.iter().zip(weights).enumerate() {
        if u && row.columns.len() < size {
            row.columns.push(i);
            row.weights.push(w);
        }
    }
    if let Some(column) = pad {
        while row.columns.len() < size {
            row.columns.push(column);
            row.weights.push(R::ZERO);
        }
    }
}

/// Row `out` as a combination of rows (`_combineSparsePointsInFullRow`;
/// `out` may be one of them).
pub(super) fn combine<R: Real>(
    m: &mut Matrix<R>,
    out: usize,
    terms: &[(usize, R)],
    (weights, used): &mut Scratch<R>,
    pad: Option<usize>,
) {
    accumulate(m, terms, weights, used);
    write_row(&mut m.rows[out], weights, used, pad);
}
