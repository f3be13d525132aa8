//! Sparse Jacobians: only the entries whose derivative is not identically zero.

use crate::error::Result;
use crate::expr::graph::Graph;
use crate::expr::node::{Id, SymbolId};

/// A sparse Jacobian `∂outputs/∂wrt` in row-major order of its entries.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparseJacobian {
    /// Number of rows (outputs).
    pub rows: usize,
    /// Number of columns (symbols differentiated by).
    pub cols: usize,
    /// `(row, col, ∂output_row/∂wrt_col)`, sorted by row then column; every
    /// expression is non-zero.
    pub entries: Vec<(usize, usize, Id)>,
}

impl SparseJacobian {
    /// The entry expressions, in the order of `entries`.
    pub fn expressions(&self) -> Vec<Id> {
        self.entries.iter().map(|e| e.2).collect()
    }
}

impl Graph {
    /// The Jacobian of `outputs` with respect to `wrt`. Each output is only
    /// differentiated by the symbols it depends on, and entries that simplify
    /// to zero are dropped.
    pub fn jacobian(&mut self, outputs: &[Id], wrt: &[SymbolId]) -> Result<SparseJacobian> {
        let mut column_of = vec![usize::MAX; self.symbols().count()];
        for (j, s) in wrt.iter().enumerate() {
            column_of[s.index()] = j;
        }
        let zero = self.zero();
        let mut entries = Vec::new();
        for (i, &f) in outputs.iter().enumerate() {
            let mut columns: Vec<usize> = self
                .free_symbols(f)
                .into_iter()
                .map(|s| column_of[s.index()])
                .filter(|&j| j != usize::MAX)
                .collect();
            columns.sort_unstable();
            for j in columns {
                let d = self.partial(f, wrt[j])?;
                if d != zero {
                    entries.push((i, j, d));
                }
            }
        }
        Ok(SparseJacobian { rows: outputs.len(), cols: wrt.len(), entries })
    }
}
