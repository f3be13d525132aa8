//! A model's mass matrix as RADAU5 and RODAS5P apply it.

use crate::model::{dense_mass_matrix, Model};

/// A model's mass matrix as the stiff methods apply it: its diagonal
/// (ones where the model has none, or a general matrix) and, for a general
/// matrix, the dense one (`apply_mass`); Hairer's IMAS = 1.
pub(crate) struct Mass {
    /// M's diagonal, or ones.
    pub(crate) diagonal: Vec<f64>,
    /// M row-major, or empty where it is diagonal.
    pub(crate) dense: Vec<f64>,
}

impl Mass {
    /// `model`'s mass matrix.
    pub(crate) fn of<M: Model>(model: &M) -> Mass {
        let n = M::STATES;
        let diagonal = M::MASS.diagonal();
        Mass {
            diagonal: if diagonal.len() == n { diagonal.to_vec() } else { vec![1.0; n] },
            dense: if M::MASS.pattern().is_empty() { Vec::new() } else { dense_mass_matrix(model) },
        }
    }

    /// What the factorisation of `M/h − J` reads: the model's own
    /// diagonal (empty for the identity), or the dense matrix.
    pub(crate) fn for_factorisation<M: Model>(&self) -> &[f64] {
        if self.dense.is_empty() {
            M::MASS.diagonal()
        } else {
            &self.dense
        }
    }
}
