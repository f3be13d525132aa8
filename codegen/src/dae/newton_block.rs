//! Algebraic equations nonlinear in their algebraic variables, solved by
//! Newton's method at each evaluation: a reaction rate quadratic in a
//! concentration at quasi-steady state, a diode's exponential in a node
//! voltage. With their values known, the rest of the model is linear in
//! its unknowns and reduces as before, so every method runs the model (an
//! explicit pair solves them at every stage), not only RADAU5 on the
//! mass-matrix form.
//!
//! The block is the smallest set of algebraic variables closed under the
//! derivative-free, undifferentiated equations that involve them, starting
//! from the variables that enter some such equation nonlinearly; it must
//! have as many equations as variables. Its Jacobian ∂g/∂z is generated;
//! where it is singular the model is not of index 1 there, and the run says
//! so naming the equations.

use crate::dae::system::NewtonBlock;
use crate::{Graph, Id, SymbolId};

/// What the finder reads of the reduced model.
pub struct Candidates<'a> {
    /// Each equation's residual after index reduction.
    pub residuals: &'a [Id],
    /// How often each was differentiated.
    pub differentiations: &'a [usize],
    /// The highest derivatives of the states.
    pub highest: &'a [SymbolId],
    /// The algebraic variables, their names and guesses.
    pub algebraics: &'a [(SymbolId, String, Id)],
    /// The equations as written.
    pub texts: &'a [String],
}

/// The Newton block of the model, `None` when no algebraic equation is
/// nonlinear in an algebraic variable, or when the closure does not square
/// (the mass-matrix form then remains the only way).
pub fn find(g: &mut Graph, model: &Candidates<'_>) -> crate::Result<Option<NewtonBlock>> {
    let algebraic_index = |s: SymbolId| model.algebraics.iter().position(|a| a.0 == s);
    // Derivative-free, undifferentiated equations, with their variables.
    let mut algebraic_equations: Vec<(usize, Vec<usize>)> = Vec::new();
    for (e, &r) in model.residuals.iter().enumerate() {
        if model.differentiations[e] > 0 {
            continue;
        }
        let symbols = g.free_symbols(r);
        if symbols.iter().any(|s| model.highest.contains(s)) {
            continue;
        }
        let variables: Vec<usize> = symbols.iter().filter_map(|&s| algebraic_index(s)).collect();
        if !variables.is_empty() {
            algebraic_equations.push((e, variables));
        }
    }
    // The seeds: variables some algebraic equation is nonlinear in.
    let mut in_block = vec![false; model.algebraics.len()];
    for (e, variables) in &algebraic_equations {
        for &a in variables {
            let d = g.partial(model.residuals[*e], model.algebraics[a].0)?;
            let nonlinear = g.free_symbols(d).iter().any(|&s| algebraic_index(s).is_some());
            if nonlinear {
                for &b in variables {
                    in_block[b] = true;
                }
            }
        }
    }
    if !in_block.contains(&true) {
        return Ok(None);
    }
    // Close over the algebraic equations that involve a block variable.
    let mut equations: Vec<usize> = Vec::new();
    loop {
        let mut grew = false;
        for (e, variables) in &algebraic_equations {
            if equations.contains(e) || !variables.iter().any(|&a| in_block[a]) {
                continue;
            }
            equations.push(*e);
            for &a in variables {
                grew |= !in_block[a];
                in_block[a] = true;
            }
        }
        if !grew {
            break;
        }
    }
    equations.sort_unstable();
    let members: Vec<usize> = (0..in_block.len()).filter(|&a| in_block[a]).collect();
    if members.len() != equations.len() {
        return Ok(None);
    }
    Ok(Some(NewtonBlock {
        unknowns: members.iter().map(|&a| model.algebraics[a].0).collect(),
        names: members.iter().map(|&a| model.algebraics[a].1.clone()).collect(),
        guesses: members.iter().map(|&a| model.algebraics[a].2).collect(),
        residuals: equations.iter().map(|&e| model.residuals[e]).collect(),
        texts: equations.iter().map(|&e| model.texts[e].clone()).collect(),
        equations,
    }))
}
