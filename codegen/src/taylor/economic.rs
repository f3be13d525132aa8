//! The derivatives of the economic Taylor scheme (course notes §1.3.1):
//! `y^(k) = D_k(t, y, y', ..., y^(k-1))`, with `D_1 = f` and `D_{k+1}` the
//! total time derivative of `D_k`, where each `y^(j)` is a symbol whose time
//! derivative is `y^(j+1)`.

use crate::error::Result;
use crate::expr::diff::VectorField;
use crate::expr::graph::Graph;
use crate::expr::node::{Id, SymbolId};

/// `[D_1, ..., D_order]`, each a vector over `states`, for `y' = rhs(t, y)`.
/// `D_k` reads `t`, the states and the derivative symbols `der(y)`, ...,
/// `der^(k-1)(y)` (see [`Graph::derivative`]); shared subexpressions are shared
/// across all orders.
pub fn economic_taylor_derivatives(
    g: &mut Graph,
    time: SymbolId,
    states: &[SymbolId],
    rhs: &[Id],
    order: usize,
) -> Result<Vec<Vec<Id>>> {
    let mut field = VectorField::new();
    let one = g.one();
    field.set(time, one);
    for &y in states {
        for j in 0..order as u32 {
            let this = g.derivative(y, j)?;
            let next = g.derivative(y, j + 1)?;
            if let Some(s) = g.as_symbol(this) {
                field.set(s, next);
            }
        }
    }
    let mut out: Vec<Vec<Id>> = Vec::with_capacity(order);
    if order == 0 {
        return Ok(out);
    }
    out.push(rhs.to_vec());
    while out.len() < order {
        let last = out[out.len() - 1].clone();
        let next =
            last.iter().map(|&d| g.total_derivative(d, &mut field)).collect::<Result<Vec<_>>>()?;
        out.push(next);
    }
    Ok(out)
}
