//! The degrees of freedom of a scene at its initial configuration,
//! `DOF = n − rank Φ_q` (course notes eq. 4.23), and the joints whose rows
//! are implied by the others there (redundant joints, which make the
//! reactions undetermined and the run fail).
//!
//! Φ_q is evaluated numerically at the initial values with the parameters'
//! defaults; rows are taken in declaration order and each is reduced against
//! the ones kept before it (modified Gram–Schmidt, twice), so the joint
//! reported is the last one that adds nothing. Grübler's count (coordinates
//! minus rows) cannot see redundancy: a spatial four-bar with four revolute
//! joints has 18 − 20 = −2 by it, and moves.

use super::Scene;
use crate::front::lower::Lower;
use crate::{Graph, Id, SymbolId, SymbolKind};
use std::collections::HashMap;

/// What the rank of Φ_q says about a scene.
pub(crate) struct Mobility {
    /// rank Φ_q at the initial configuration.
    pub rank: usize,
    /// Rows that add nothing to the rows before them.
    pub redundant: Vec<usize>,
}

/// A row counts as dependent when what is left of it after removing its
/// components along the kept rows is this small relative to its norm.
const RELATIVE_TOLERANCE: f64 = 1e-9;

impl Lower<'_, Scene> {
    /// The values of the parameters (their defaults) and of the states
    /// (their initial values) at the start.
    pub(crate) fn start_values(&self) -> HashMap<SymbolId, f64> {
        let mut values = HashMap::new();
        let by_name: HashMap<String, f64> =
            self.params.iter().map(|p| (p.ident.to_string(), p.default)).collect();
        let parameter = |g: &Graph, s: SymbolId| -> f64 {
            let sym = g.symbol(s);
            match sym.kind {
                SymbolKind::Parameter => by_name.get(&sym.name).copied().unwrap_or(f64::NAN),
                _ => f64::NAN,
            }
        };
        for state in &self.states {
            let v = self.g.eval(&[state.init], &|s| parameter(&self.g, s))[0];
            values.insert(state.symbol, v);
        }
        for p in &self.params {
            if let Some(s) = self.g.symbol_named(&p.ident.to_string()) {
                values.insert(s, p.default);
            }
        }
        values
    }

    /// The value of `id` at the start (NaN where something has no value).
    pub(crate) fn numeric(&self, id: Id) -> f64 {
        let values = self.start_values();
        self.g.eval(&[id], &|s| values.get(&s).copied().unwrap_or(f64::NAN))[0]
    }

    /// rank Φ_q at the initial configuration, or `None` when it cannot be
    /// evaluated there (a row or a default is not finite).
    pub(crate) fn mobility(&mut self) -> Option<Mobility> {
        let values = self.start_values();
        let value =
            |g: &Graph, id: Id| g.eval(&[id], &|s| values.get(&s).copied().unwrap_or(f64::NAN))[0];
        let rows: Vec<Id> = self.scene.rows.iter().map(|&(row, _)| row).collect();
        let mut jacobian: Vec<Vec<f64>> = Vec::with_capacity(rows.len());
        for &row in &rows {
            let mut line = Vec::new();
            for body in self.scene.bodies.clone() {
                for s in [body.x, body.y, body.theta] {
                    let d = self.g.partial(row, s).ok()?;
                    line.push(value(&self.g, d));
                }
            }
            for b in 0..self.scene.spatial.len() {
                let columns = self.spatial_jacobian_columns(b, row, &value).ok()?;
                line.extend(columns);
            }
            if line.iter().any(|x| !x.is_finite()) {
                return None;
            }
            jacobian.push(line);
        }
        let mut kept: Vec<Vec<f64>> = Vec::new();
        let mut redundant = Vec::new();
        for (r, line) in jacobian.into_iter().enumerate() {
            let norm = line.iter().map(|x| x * x).sum::<f64>().sqrt();
            let mut rest = line;
            for _ in 0..2 {
                for k in &kept {
                    let along: f64 = rest.iter().zip(k).map(|(a, b)| a * b).sum();
                    for (x, y) in rest.iter_mut().zip(k) {
                        *x -= along * y;
                    }
                }
            }
            let left = rest.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm == 0.0 || left <= RELATIVE_TOLERANCE * norm {
                redundant.push(r);
            } else {
                kept.push(rest.into_iter().map(|x| x / left).collect());
            }
        }
        Some(Mobility { rank: kept.len(), redundant })
    }

    /// The joint a scene row belongs to: its name and statement.
    pub(crate) fn joint_of_row(
        &self,
        row: usize,
    ) -> Option<(String, usize, proc_macro2::TokenStream)> {
        self.scene
            .joint_rows
            .iter()
            .find(|(_, rows, _)| rows.contains(&row))
            .map(|(name, rows, origin)| (name.clone(), row - rows.start, origin.clone()))
    }
}
