//! Reduction to a first-order explicit system `y' = f(t, y)` (course notes
//! Example 1.1): each state of order k becomes k states `x, der(x), …,
//! der^(k-1)(x)`; the equations, linear in the highest derivatives `z`
//! (`E(t, y) z = g(t, y)`), are solved for `z` block by block —
//! symbolically when a block is one equation or has constant coefficients,
//! by a dense solve at run time otherwise.

use super::ctxt::Ctxt;
use super::ir::ModelIr;
use crate::{FxHashMap, Id, Number, SymbolId, SymbolKind};
use proc_macro2::TokenStream;

/// One first-order state of the reduced system.
pub struct Slot {
    /// `x`, `der(x)`, `q[1]`, ...
    pub name: String,
    /// The symbol it reads as.
    pub symbol: SymbolId,
    /// Its initial value (constants and parameters).
    pub init: Id,
}

/// How a slot's derivative is computed.
pub enum SlotDerivative {
    /// `f_i` as an expression.
    Explicit(Id),
    /// Unknown `row` of mass block `block`, solved at run time.
    Block {
        /// Which block.
        block: usize,
        /// Which of its unknowns.
        row: usize,
    },
}

/// `E z = g` for unknowns that no symbolic solve could separate.
pub struct MassBlock {
    /// Names of the unknowns, for the singular-matrix error.
    pub unknowns: Vec<String>,
    /// `E`, row-major, `k × k`.
    pub matrix: Vec<Id>,
    /// `g`.
    pub rhs: Vec<Id>,
}

/// The reduced system.
pub struct FirstOrder {
    /// States in solution order.
    pub slots: Vec<Slot>,
    /// `dy_i` for each slot.
    pub derivatives: Vec<SlotDerivative>,
    /// Blocks solved at run time.
    pub blocks: Vec<MassBlock>,
    /// Output values, with highest derivatives replaced by their solutions.
    pub outputs: Vec<Id>,
    /// Event functions, likewise.
    pub events: Vec<Id>,
}

struct Equation {
    residual: Id,
    unknowns: Vec<usize>,
    origin: TokenStream,
}

/// Reduces the model, or reports why it cannot.
pub fn reduce(cx: &mut Ctxt, ir: &mut ModelIr) -> Option<FirstOrder> {
    if dae_refused(cx, ir) {
        return None;
    }
    let g = &mut ir.graph;
    // Order of each state: the highest derivative any equation uses.
    let mut order = vec![0u32; ir.states.len()];
    let state_of: FxHashMap<SymbolId, usize> = ir
        .states
        .iter()
        .enumerate()
        .map(|(i, s)| (s.symbol, i))
        .collect();
    let mut residuals = Vec::with_capacity(ir.equations.len());
    for eq in &ir.equations {
        let r = match g.sub(eq.lhs, eq.rhs) {
            Ok(r) => r,
            Err(e) => {
                cx.error_at(&eq.origin, e);
                return None;
            }
        };
        for s in g.free_symbols(r) {
            if let SymbolKind::Derivative { of, order: k } = g.symbol(s).kind {
                if let Some(&i) = state_of.get(&of) {
                    order[i] = order[i].max(k);
                }
            }
        }
        residuals.push(r);
    }
    let mut ok = true;
    for (i, s) in ir.states.iter().enumerate() {
        if order[i] == 0 {
            let name = &s.name;
            cx.error_at(
                &s.origin,
                format!(
                    "state `{name}` has no equation for its derivative: add `der({name}) == ...;`"
                ),
            );
            ok = false;
        }
    }
    if !ok {
        return None;
    }
    // The unknowns z: highest derivatives, one per state.
    let mut z_symbols = Vec::with_capacity(ir.states.len());
    for (i, s) in ir.states.iter().enumerate() {
        let id = g.derivative(s.symbol, order[i]).ok()?;
        z_symbols.push(g.as_symbol(id)?);
    }
    let z_index: FxHashMap<SymbolId, usize> =
        z_symbols.iter().enumerate().map(|(j, &s)| (s, j)).collect();
    let mut equations = Vec::with_capacity(residuals.len());
    for (eq, &r) in ir.equations.iter().zip(&residuals) {
        let unknowns: Vec<usize> = g
            .free_symbols(r)
            .into_iter()
            .filter_map(|s| z_index.get(&s).copied())
            .collect();
        if unknowns.is_empty() {
            cx.error_at(&eq.origin, "this equation has no highest derivative of any state, so it is algebraic; DAE support is not there yet: write the model as an ODE");
            ok = false;
        }
        equations.push(Equation {
            residual: r,
            unknowns,
            origin: eq.origin.clone(),
        });
    }
    if !ok || !matched(cx, g, &ir.states, &equations, &z_symbols) {
        return None;
    }
    // Linear in z: E_ij = ∂r_i/∂z_j must not contain z; g = -r|_{z=0}.
    let n = z_symbols.len();
    let zero = g.zero();
    let mut e_matrix: Vec<Vec<(usize, Id)>> = Vec::with_capacity(n);
    let z_zero: FxHashMap<SymbolId, Id> = z_symbols.iter().map(|&s| (s, zero)).collect();
    let mut g_vec = Vec::with_capacity(n);
    for eq in &equations {
        let mut row = Vec::new();
        for &j in &eq.unknowns {
            let c = g.partial(eq.residual, z_symbols[j]).ok()?;
            if let Some(bad) = g
                .free_symbols(c)
                .into_iter()
                .find(|s| z_index.contains_key(s))
            {
                let name = g.symbol(bad).name.clone();
                cx.error_at(&eq.origin, format!("this equation is not linear in `{name}`: daegen needs the form `E(t, y) * der(..) == g(t, y)`"));
                return None;
            }
            if c != zero {
                row.push((j, c));
            }
        }
        let r0 = g.substitute(eq.residual, &z_zero).ok()?;
        g_vec.push(g.negate_terms(r0).ok()?);
        e_matrix.push(row);
    }
    let blocks = connected_blocks(&e_matrix, n);
    let mut solution: Vec<Option<Id>> = vec![None; n];
    let mut mass_blocks = Vec::new();
    let mut block_of: Vec<Option<(usize, usize)>> = vec![None; n];
    for (rows, cols) in blocks {
        let entry = |i: usize, j: usize| e_matrix[i].iter().find(|(c, _)| *c == j).map(|e| e.1);
        if rows.len() == 1 {
            let (i, j) = (rows[0], cols[0]);
            let e = entry(i, j).unwrap_or(zero);
            solution[j] = Some(g.div(g_vec[i], e).ok()?);
            continue;
        }
        let constant = rows
            .iter()
            .all(|&i| e_matrix[i].iter().all(|&(_, c)| g.as_number(c).is_some()));
        if constant {
            let m: Vec<Vec<Number>> = rows
                .iter()
                .map(|&i| {
                    cols.iter()
                        .map(|&j| {
                            entry(i, j)
                                .and_then(|c| g.as_number(c))
                                .unwrap_or(Number::ZERO)
                        })
                        .collect()
                })
                .collect();
            let rhs: Vec<Id> = rows.iter().map(|&i| g_vec[i]).collect();
            match solve_constant(g, m, rhs) {
                Some(z) => {
                    for (k, &j) in cols.iter().enumerate() {
                        solution[j] = Some(z[k]);
                    }
                }
                None => {
                    let names: Vec<String> = cols
                        .iter()
                        .map(|&j| format!("`{}`", g.symbol(z_symbols[j]).name))
                        .collect();
                    cx.error_at(&equations[rows[0]].origin, format!("the equations for {} are linearly dependent: one of them repeats the others", names.join(", ")));
                    return None;
                }
            }
            continue;
        }
        let b = mass_blocks.len();
        let mut matrix = Vec::with_capacity(rows.len() * cols.len());
        for &i in &rows {
            for &j in &cols {
                matrix.push(entry(i, j).unwrap_or(zero));
            }
        }
        for (k, &j) in cols.iter().enumerate() {
            block_of[j] = Some((b, k));
        }
        mass_blocks.push(MassBlock {
            unknowns: cols
                .iter()
                .map(|&j| g.symbol(z_symbols[j]).name.clone())
                .collect(),
            matrix,
            rhs: rows.iter().map(|&i| g_vec[i]).collect(),
        });
    }
    // Slots: x, der(x), ..., der^(k-1)(x) per state; dy of the last is z.
    let mut slots = Vec::new();
    let mut derivatives = Vec::new();
    let init_of: FxHashMap<SymbolId, Id> = ir.inits.iter().map(|i| (i.target, i.value)).collect();
    for (i, s) in ir.states.iter().enumerate() {
        for k in 0..order[i] {
            let id = g.derivative(s.symbol, k).ok()?;
            let symbol = g.as_symbol(id)?;
            let init = if k == 0 {
                s.init
            } else {
                init_of.get(&symbol).copied().unwrap_or(zero)
            };
            slots.push(Slot {
                name: g.symbol(symbol).name.clone(),
                symbol,
                init,
            });
            derivatives.push(if k + 1 < order[i] {
                SlotDerivative::Explicit(g.derivative(s.symbol, k + 1).ok()?)
            } else {
                match (solution[i], block_of[i]) {
                    (Some(z), _) => SlotDerivative::Explicit(z),
                    (None, Some((block, row))) => SlotDerivative::Block { block, row },
                    (None, None) => return None,
                }
            });
        }
    }
    for init in &ir.inits {
        let valid = slots.iter().any(|s| s.symbol == init.target)
            && !ir.states.iter().any(|s| s.symbol == init.target);
        if !valid {
            let name = g.symbol(init.target).name.clone();
            cx.error_at(&init.origin, format!("`{name}` follows from its equation, so it takes no initial value: `init` is for derivatives below the highest one the equations use"));
            ok = false;
        }
    }
    // Outputs may read highest derivatives: replace them by their solutions.
    let replace: FxHashMap<SymbolId, Id> = z_symbols
        .iter()
        .enumerate()
        .filter_map(|(j, &s)| solution[j].map(|z| (s, z)))
        .collect();
    let mut observe = |value: Id, origin: &TokenStream, what: &str| -> Option<Id> {
        let v = g.substitute(value, &replace).ok()?;
        if let Some(s) = g
            .free_symbols(v)
            .into_iter()
            .find(|s| z_index.contains_key(s))
        {
            let name = g.symbol(s).name.clone();
            cx.error_at(origin, format!("this {what} reads `{name}`, which is only known after a numerical solve; compute it from the states instead"));
            ok = false;
        }
        Some(v)
    };
    let mut outputs = Vec::with_capacity(ir.outputs.len());
    for o in &ir.outputs {
        outputs.push(observe(o.value, &o.origin, "output")?);
    }
    let mut events = Vec::with_capacity(ir.events.len());
    for e in &ir.events {
        events.push(observe(e.value, &e.origin, "event")?);
    }
    ok.then_some(FirstOrder {
        slots,
        derivatives,
        blocks: mass_blocks,
        outputs,
        events,
    })
}

/// Algebraic variables and constraints need the DAE pipeline.
fn dae_refused(cx: &mut Ctxt, ir: &ModelIr) -> bool {
    let mut refused = false;
    for a in &ir.algebraics {
        cx.error_at(&a.origin, format!("algebraic variable `{}`: DAE support is not there yet; write the model as an ODE (for a pendulum, in its angle)", a.name));
        refused = true;
    }
    for eq in ir.equations.iter().filter(|e| e.is_constraint) {
        cx.error_at(&eq.origin, "constraints need DAE support, which is not there yet; write the model as an ODE (for a pendulum, in its angle)");
        refused = true;
    }
    refused
}

/// A perfect matching of equations to highest derivatives (Kuhn's
/// augmenting paths); reports two equations for one derivative and
/// derivatives without an equation.
fn matched(
    cx: &mut Ctxt,
    g: &crate::Graph,
    states: &[super::ir::StateDecl],
    equations: &[Equation],
    z: &[SymbolId],
) -> bool {
    let n = z.len();
    let mut owner: Vec<Option<usize>> = vec![None; n];
    fn augment(e: usize, eqs: &[Equation], owner: &mut [Option<usize>], seen: &mut [bool]) -> bool {
        for &j in &eqs[e].unknowns {
            if !seen[j] {
                seen[j] = true;
                if owner[j].is_none_or(|other| augment(other, eqs, owner, seen)) {
                    owner[j] = Some(e);
                    return true;
                }
            }
        }
        false
    }
    let mut ok = true;
    for e in 0..equations.len() {
        let mut seen = vec![false; n];
        if !augment(e, equations, &mut owner, &mut seen) {
            let j = equations[e].unknowns[0];
            let name = g.symbol(z[j]).name.clone();

            cx.error_at(&equations[e].origin, format!("`{name}` already has an equation: remove one of the two (or there are more equations than states)"));
            if let Some(o) = owner[j] {
                cx.error_at(
                    &equations[o].origin,
                    format!("the other equation that determines `{name}`"),
                );
            }
            ok = false;
        }
    }
    for (j, o) in owner.iter().enumerate() {
        if o.is_none() {
            let name = g.symbol(z[j]).name.clone();
            // z[j] is the highest derivative of state j.
            let message = format!("no equation determines `{name}`: add `{name} == ...;` (there are fewer equations than states)");
            cx.error_at(&states[j].origin, message);
            ok = false;
        }
    }
    ok
}

/// Groups equations and unknowns that share non-zero coefficients.
fn connected_blocks(e: &[Vec<(usize, Id)>], n: usize) -> Vec<(Vec<usize>, Vec<usize>)> {
    // Union-find over unknowns; an equation joins all its unknowns.
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for row in e {
        if let Some(&(first, _)) = row.first() {
            for &(j, _) in row {
                let (a, b) = (find(&mut parent, first), find(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    let mut blocks: std::collections::BTreeMap<usize, (Vec<usize>, Vec<usize>)> =
        Default::default();
    for j in 0..n {
        let r = find(&mut parent, j);
        blocks.entry(r).or_default().1.push(j);
    }
    for (i, row) in e.iter().enumerate() {
        if let Some(&(j, _)) = row.first() {
            let r = find(&mut parent, j);
            blocks.entry(r).or_default().0.push(i);
        }
    }
    blocks.into_values().collect()
}

/// `z = M⁻¹ g` for a constant matrix, by Gaussian elimination with exact
/// rational pivots (largest magnitude for floats); `None` if singular.
fn solve_constant(
    g: &mut crate::Graph,
    mut m: Vec<Vec<Number>>,
    mut rhs: Vec<Id>,
) -> Option<Vec<Id>> {
    let k = m.len();
    for col in 0..k {
        let pivot = (col..k)
            .filter(|&r| !m[r][col].is_zero())
            .max_by(|&a, &b| {
                m[a][col]
                    .abs()
                    .to_f64()
                    .total_cmp(&m[b][col].abs().to_f64())
            })?;
        m.swap(col, pivot);
        rhs.swap(col, pivot);
        for row in col + 1..k {
            if m[row][col].is_zero() {
                continue;
            }
            let factor = m[row][col].checked_mul(reciprocal(m[col][col])?)?;
            let (above, below) = m.split_at_mut(row);
            for (target, &p) in below[0][col..].iter_mut().zip(&above[col][col..]) {
                *target = target.checked_add(factor.checked_mul(p)?.negated())?;
            }
            let f = g.num(factor.negated());
            let scaled = g.mul(f, rhs[col]).ok()?;
            rhs[row] = g.add(rhs[row], scaled).ok()?;
        }
    }
    let mut z = vec![g.zero(); k];
    for row in (0..k).rev() {
        let mut acc = rhs[row];
        for c in row + 1..k {
            let coefficient = g.num(m[row][c].negated());
            let t = g.mul(coefficient, z[c]).ok()?;
            acc = g.add(acc, t).ok()?;
        }
        let inv = g.num(reciprocal(m[row][row])?);
        z[row] = g.mul(inv, acc).ok()?;
    }
    Some(z)
}

fn reciprocal(n: Number) -> Option<Number> {
    n.pow(Number::MINUS_ONE)
}
