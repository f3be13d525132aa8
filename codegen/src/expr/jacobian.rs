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

/// Past this estimate of one row's symbolic derivatives (the operations
/// reaching an entry of f times the variables it reads), the Jacobian is
/// differenced: a robot's acceleration reads every joint through a
/// thousand operations, and its symbolic row would be many times f's code
/// and compile time, where differences cost one evaluation of f per state
/// at run time. A grid's rows read a few neighbours through a few
/// operations each, however many rows it has, and keep their symbolic
/// Jacobian.
pub const SYMBOLIC_JACOBIAN_ROW: usize = 5000;

/// Whether f's Jacobian is worth writing symbolically (see
/// [`SYMBOLIC_JACOBIAN_ROW`]).
pub fn symbolic_jacobian_pays(g: &Graph, f: &[Id]) -> bool {
    let cost = |&e: &Id| g.reachable(&[e]).len() * g.free_symbols(e).len();
    let worst = f.iter().map(cost).max().unwrap_or(0);
    worst <= SYMBOLIC_JACOBIAN_ROW
}
