//! Models with modes (`if on { .. } else { .. }` on discrete booleans,
//! `if gear == 2 { .. }` on discrete integers): each mode's equations are
//! sorted, reduced and solved alone, at compile time, and the reduced
//! systems joined into one that reads the discrete values,
//! `Σ_modes [the values are the mode's] · f_mode`. Each bracket is a
//! product, over the mode variables, of the Lagrange polynomial that is 1
//! at the mode's value and 0 at the variable's other values: `b` and
//! `1 − b` for a boolean, exact; for an integer `(v − c₁)(v − c₂)…/D`,
//! exact where D is a power of two and else to rounding. Every mode must
//! reduce to an explicit ODE in the same states (a diode conducting or
//! blocking, a contact sticking or slipping, a gearbox in each gear); at
//! most [`MAX_MODES`] modes. Beyond, the modes factor (`blended`): each
//! group of discrete values read together in guards has its branches'
//! equations blended, and the model is reduced once.

use crate::dae::system::{FirstOrder, SlotAction, SlotDerivative};
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::{Graph, Id, SymbolId};

/// The most modes, each analysed at compile time.
pub const MAX_MODES: usize = 64;

/// A discrete value that selects equations and the values it can take.
struct ModeVariable {
    symbol: SymbolId,
    values: Vec<i64>,
}

/// The structure and reduction of `ir` by `reduce_all` (the pipeline's
/// steps): at once for a model without modes, mode by mode and joined for
/// one with.
pub fn reduce_modes(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    reduce_all: fn(&mut Ctxt, &mut ModelIr) -> Option<FirstOrder>,
) -> Option<FirstOrder> {
    let Some(first_guarded) = ir.equations.iter().find(|e| !e.mode.is_empty()) else {
        return reduce_all(cx, ir);
    };
    let first_guarded = first_guarded.origin.clone();
    let variables = match mode_variables(ir) {
        Ok(v) => v,
        Err((message, origin)) => {
            cx.error_at(origin.as_ref().unwrap_or(&first_guarded), message);
            return None;
        }
    };
    let count: usize = variables.iter().map(|v| v.values.len()).product();
    if count > MAX_MODES {
        // Too many to analyse each: each group's branches blended into
        // equations that hold in every mode, the whole reduced once.
        return match blended(ir, &variables) {
            Ok(()) => reduce_all(cx, ir),
            Err(message) => {
                cx.error_at(&first_guarded, format!("the discrete values selecting equations make {count} modes, more than the {MAX_MODES} analysed at compile time one by one, and they cannot be combined into one system: {message}"));
                None
            }
        };
    }
    let all = std::mem::take(&mut ir.equations);
    let mut systems = Vec::with_capacity(count);
    for mode in 0..count {
        let values = values_of(&variables, mode);
        let value_of =
            |s: SymbolId| variables.iter().position(|v| v.symbol == s).map(|k| values[k]);
        ir.equations = all
            .iter()
            .filter(|e| e.mode.iter().all(|g| value_of(g.mode).is_some_and(|v| g.holds_at(v))))
            .cloned()
            .collect();
        let system = reduce_all(cx, ir).filter(|_| cx.is_ok());
        let mode_name = mode_name(&ir.graph, &variables, &values);
        let system = match system.map(|s| explicit(s, &mode_name)) {
            Some(Ok(s)) => s,
            Some(Err(message)) => {
                cx.error_at(&first_guarded, message);
                ir.equations = all;
                return None;
            }
            None => {
                cx.error_at(&first_guarded, format!("in the mode {mode_name}, the equations that hold do not determine the model (the errors above): each mode needs one equation per unknown"));
                ir.equations = all;
                return None;
            }
        };
        systems.push(system);
    }
    ir.equations = all;
    match join(&mut ir.graph, &variables, systems) {
        Ok(mut joined) => {
            // Its per-equation records are mode 0's, numbered in that
            // mode's equations: none is differentiated (no mode has
            // constraints), and none is told of as combined.
            joined.differentiations = vec![0; ir.equations.len()];
            joined.combined.clear();
            Some(joined)
        }
        Err(e) => {
            cx.error_at(&first_guarded, e);
            None
        }
    }
}

/// Groups of mode variables read together in guards: the variables of
/// each guarded equation, joined where they share one (a clutch's own
/// booleans form its group). Each group's modes select the same number of
/// equations (as Modelica requires of an `if` on variables); the k-th
/// equation of every mode of the group is blended into one,
/// `Σ_modes [the values are the mode's] · residual_k = 0`, which holds in
/// every mode. Then N independent switches cost one analysis, not 2^N:
/// the blocks their coefficients make are solved at run time, with
/// pivoting (a coefficient that switches may vanish in some mode).
fn blended(ir: &mut ModelIr, variables: &[ModeVariable]) -> Result<(), String> {
    let mut group: Vec<usize> = (0..variables.len()).collect();
    fn root(group: &mut [usize], k: usize) -> usize {
        let mut r = k;
        while group[r] != r {
            r = group[r];
        }
        group[k] = r;
        r
    }
    let index_of = |s: SymbolId| variables.iter().position(|v| v.symbol == s);
    for e in ir.equations.iter().filter(|e| !e.mode.is_empty()) {
        let ks: Vec<usize> = e.mode.iter().filter_map(|m| index_of(m.mode)).collect();
        for w in ks.windows(2) {
            let (a, b) = (root(&mut group, w[0]), root(&mut group, w[1]));
            group[a] = b;
        }
    }
    let roots: Vec<usize> = (0..variables.len()).map(|k| root(&mut group, k)).collect();
    for v in variables {
        ir.graph.mark_switching(v.symbol);
    }
    let mut groups: Vec<usize> = roots.clone();
    groups.sort_unstable();
    groups.dedup();
    let mut replaced = vec![false; ir.equations.len()];
    let mut blended_equations = Vec::new();
    for &r in &groups {
        let owned: Vec<ModeVariable> = variables
            .iter()
            .enumerate()
            .filter(|(k, _)| roots[*k] == r)
            .map(|(_, v)| ModeVariable { symbol: v.symbol, values: v.values.clone() })
            .collect();
        let count: usize = owned.iter().map(|v| v.values.len()).product();
        if count > MAX_MODES {
            let names: Vec<String> =
                owned.iter().map(|v| format!("`{}`", ir.graph.symbol(v.symbol).name)).collect();
            return Err(format!("{} select equations together in {count} modes", names.join(", ")));
        }
        let in_group = |e: &crate::front::ir::Equation| {
            e.mode.first().is_some_and(|m| owned.iter().any(|v| v.symbol == m.mode))
        };
        let mut selected: Vec<Vec<usize>> = Vec::with_capacity(count);
        for mode in 0..count {
            let values = values_of(&owned, mode);
            let value_of =
                |s: SymbolId| owned.iter().position(|v| v.symbol == s).map(|k| values[k]);
            let holds = |e: &crate::front::ir::Equation| {
                e.mode.iter().all(|g| value_of(g.mode).is_some_and(|v| g.holds_at(v)))
            };
            selected.push(
                (0..ir.equations.len())
                    .filter(|&e| in_group(&ir.equations[e]) && holds(&ir.equations[e]))
                    .collect(),
            );
        }
        let n = selected[0].len();
        if let Some(mode) = selected.iter().position(|s| s.len() != n) {
            let name = mode_name(&ir.graph, &owned, &values_of(&owned, mode));
            return Err(format!("{} equations hold {name}, {n} in another: give each branch of an `if` on them as many equations", selected[mode].len()));
        }
        let g = &mut ir.graph;
        for k in 0..n {
            let mut terms = Vec::with_capacity(count);
            for (mode, equations) in selected.iter().enumerate() {
                let values = values_of(&owned, mode);
                let mut factors = Vec::with_capacity(owned.len() + 1);
                for (v, &value) in owned.iter().zip(&values) {
                    factors.push(lagrange(g, v, value).map_err(|e| e.to_string())?);
                }
                let e = &ir.equations[equations[k]];
                factors.push(g.sub(e.lhs, e.rhs).map_err(|e| e.to_string())?);
                terms.push(g.product(&factors).map_err(|e| e.to_string())?);
            }
            let residual = g.sum(&terms).map_err(|e| e.to_string())?;
            let first = &ir.equations[selected[0][k]];
            blended_equations.push(crate::front::ir::Equation {
                lhs: residual,
                rhs: g.zero(),
                origin: first.origin.clone(),
                is_constraint: false,
                mode: Vec::new(),
            });
        }
        for equations in &selected {
            for &e in equations {
                replaced[e] = true;
            }
        }
    }
    let mut k = 0;
    ir.equations.retain(|_| {
        k += 1;
        !replaced[k - 1]
    });
    ir.equations.extend(blended_equations);
    Ok(())
}

/// The discrete values that select equations, in order of first use, each
/// with the values it takes: 0 and 1 for a boolean; for an integer, its
/// start, the values its conditions name and the constants its actions
/// set (an action setting it to anything but a constant is an error, with
/// the action's tokens).
fn mode_variables(
    ir: &ModelIr,
) -> Result<Vec<ModeVariable>, (String, Option<proc_macro2::TokenStream>)> {
    let g = &ir.graph;
    let mut variables: Vec<ModeVariable> = Vec::new();
    for guard in ir.equations.iter().flat_map(|e| &e.mode) {
        let k = match variables.iter().position(|v| v.symbol == guard.mode) {
            Some(k) => k,
            None => {
                variables.push(ModeVariable { symbol: guard.mode, values: Vec::new() });
                variables.len() - 1
            }
        };
        let tested = if guard.boolean { vec![0, 1] } else { guard.values.clone() };
        variables[k].values.extend(tested);
    }
    let actions =
        ir.events.iter().flat_map(|e| &e.actions).chain(ir.clocks.iter().flat_map(|c| &c.actions));
    for v in &mut variables {
        let name = &g.symbol(v.symbol).name;
        let boolean =
            ir.equations.iter().flat_map(|e| &e.mode).all(|m| m.mode != v.symbol || m.boolean);
        let start = ir.states.iter().find(|s| s.symbol == v.symbol).map(|s| s.init);
        let whole = |id: crate::Id| g.as_number(id).and_then(|n| n.as_integer());
        if !boolean {
            match start.and_then(whole) {
                Some(value) => v.values.push(value),
                None => {
                    return Err((
                        format!(
                            "the integer mode `{name}` starts at a whole number: `discrete(1)`"
                        ),
                        None,
                    ))
                }
            }
        }
        for action in actions.clone().filter(|a| a.target == v.symbol) {
            match whole(action.value) {
                Some(value) => v.values.push(value),
                None if boolean => {}
                None => match values_set_by(ir, action.value) {
                    Some(values) => v.values.extend(values),
                    None => return Err((format!("the integer mode `{name}` is set to whole numbers, each a mode analysed at compile time: `.reinit({name}, 2)`, or `.reinit({name}, if w > 20.0 {{ 3 }} else {{ 2 }})`"), Some(action.origin.clone()))),
                },
            }
        }
        v.values.sort_unstable();
        v.values.dedup();
    }
    Ok(variables)
}

/// Every whole number `value`, an expression of relations alone (`if w >
/// 20.0 { 3 } else { 2 }`), can take, each relation's boolean 0 or 1;
/// `None` where it reads anything else or gives a number that is not
/// whole.
fn values_set_by(ir: &ModelIr, value: Id) -> Option<Vec<i64>> {
    let g = &ir.graph;
    let booleans = g.free_symbols(value);
    let relation = |s: &SymbolId| ir.relations.iter().any(|r| r.discrete == *s);
    if booleans.is_empty() || booleans.len() > 10 || !booleans.iter().all(relation) {
        return None;
    }
    let mut values = Vec::with_capacity(1 << booleans.len());
    for assignment in 0..1usize << booleans.len() {
        let bit = |s: SymbolId| {
            let k = booleans.iter().position(|&b| b == s).unwrap_or(0);
            ((assignment >> k) & 1) as f64
        };
        let v = g.eval(&[value], &bit)[0];
        if v.fract() != 0.0 || !v.is_finite() {
            return None;
        }
        values.push(v as i64);
    }
    Some(values)
}

/// The values of the mode variables in mode number `mode` (mixed radix).
fn values_of(variables: &[ModeVariable], mut mode: usize) -> Vec<i64> {
    variables
        .iter()
        .map(|v| {
            let value = v.values[mode % v.values.len()];
            mode /= v.values.len();
            value
        })
        .collect()
}

/// `on` is true and `gear` is 2, for messages.
fn mode_name(g: &Graph, variables: &[ModeVariable], values: &[i64]) -> String {
    let boolean = |v: &ModeVariable| v.values == [0, 1];
    let parts: Vec<String> = variables
        .iter()
        .zip(values)
        .map(|(v, &value)| match boolean(v) {
            true => format!("`{}` is {}", g.symbol(v.symbol).name, value == 1),
            false => format!("`{}` is {value}", g.symbol(v.symbol).name),
        })
        .collect();
    format!("where {}", parts.join(" and "))
}

/// The polynomial in `v` that is 1 at `value` and 0 at its other values:
/// Π (v − c)/(value − c).
fn lagrange(g: &mut Graph, v: &ModeVariable, value: i64) -> crate::Result<Id> {
    let x = g.symbol_node(v.symbol);
    if v.values == [0, 1] {
        // A boolean: b and 1 − b.
        let one = g.one();
        return if value == 1 { Ok(x) } else { g.sub(one, x) };
    }
    let mut factors = Vec::with_capacity(v.values.len());
    let mut denominator = 1i64;
    for &c in v.values.iter().filter(|&&c| c != value) {
        let c_id = g.int(c);
        factors.push(g.sub(x, c_id)?);
        denominator *= value - c;
    }
    let numerator = g.product(&factors)?;
    let denominator = g.int(denominator);
    g.div(numerator, denominator)
}

/// `sys` if it is an explicit ODE, or why a mode must be one.
fn explicit(sys: FirstOrder, mode: &str) -> Result<FirstOrder, String> {
    let explicit = sys.derivatives.iter().all(|d| matches!(d, SlotDerivative::Explicit(_)))
        && sys.algebraics.iter().all(|d| matches!(d, SlotDerivative::Explicit(_)));
    if !explicit || !sys.blocks.is_empty() || sys.newton.is_some() || sys.mass_only {
        return Err(format!("in the mode {mode}, the equations are solved at run time (a linear or nonlinear block): each mode must solve symbolically to an explicit ODE"));
    }
    if !sys.invariants.is_empty() {
        return Err(format!("in the mode {mode}, the equations have index {} (constraints the states must keep): each mode must be an ODE in the same states; write the constrained mode with its constraint differentiated (a sticking contact as `der(v) == a_belt`)", sys.index));
    }
    Ok(sys)
}

/// The systems of every mode (in the order of [`values_of`]) as one.
fn join(
    g: &mut Graph,
    variables: &[ModeVariable],
    systems: Vec<FirstOrder>,
) -> crate::Result<FirstOrder> {
    let indicators: Vec<Id> = (0..systems.len())
        .map(|mode| {
            let values = values_of(variables, mode);
            let factors = variables
                .iter()
                .zip(&values)
                .map(|(v, &value)| lagrange(g, v, value))
                .collect::<crate::Result<Vec<Id>>>()?;
            g.product(&factors)
        })
        .collect::<crate::Result<_>>()?;
    let names = |s: &FirstOrder| s.slots.iter().map(|x| x.name.clone()).collect::<Vec<_>>();
    if systems.iter().any(|s| names(s) != names(&systems[0])) {
        return Err(crate::Error::Unsupported {
            message: "the modes reduce to different states: each mode must keep the same states"
                .into(),
        });
    }
    let blend = |g: &mut Graph, values: Vec<Id>| -> crate::Result<Id> {
        if values.iter().all(|&v| v == values[0]) {
            return Ok(values[0]);
        }
        let terms = values
            .iter()
            .zip(&indicators)
            .map(|(&v, &i)| g.mul(i, v))
            .collect::<crate::Result<Vec<Id>>>()?;
        g.sum(&terms)
    };
    let explicit_of = |d: &SlotDerivative| match d {
        SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => *e,
        // `explicit` let no block through.
        SlotDerivative::Block { .. } => Id(0),
    };
    let first = &systems[0];
    let mut derivatives = Vec::with_capacity(first.derivatives.len());
    for i in 0..first.derivatives.len() {
        let values = systems.iter().map(|s| explicit_of(&s.derivatives[i])).collect();
        derivatives.push(SlotDerivative::Explicit(blend(g, values)?));
    }
    let mut algebraics = Vec::with_capacity(first.algebraics.len());
    for i in 0..first.algebraics.len() {
        let values = systems.iter().map(|s| explicit_of(&s.algebraics[i])).collect();
        algebraics.push(SlotDerivative::Explicit(blend(g, values)?));
    }
    let mut outputs = Vec::with_capacity(first.outputs.len());
    for i in 0..first.outputs.len() {
        outputs.push(blend(g, systems.iter().map(|s| s.outputs[i]).collect())?);
    }
    let mut events = Vec::with_capacity(first.events.len());
    for i in 0..first.events.len() {
        events.push(blend(g, systems.iter().map(|s| s.events[i]).collect())?);
    }
    let mut initial = Vec::with_capacity(first.initial.len());
    for i in 0..first.initial.len() {
        initial.push(blend(g, systems.iter().map(|s| s.initial[i]).collect())?);
    }
    let mut actions = first.actions.clone();
    for (t, trigger) in actions.iter_mut().enumerate() {
        for (a, action) in trigger.iter_mut().enumerate() {
            let value = blend(g, systems.iter().map(|s| s.actions[t][a].value).collect())?;
            *action = SlotAction { slot: action.slot, value };
        }
    }
    let mut joined = systems.into_iter().next().ok_or_else(|| crate::Error::Unsupported {
        message: "a model with modes has at least one".into(),
    })?;
    joined.derivatives = derivatives;
    joined.algebraics = algebraics;
    joined.outputs = outputs;
    joined.events = events;
    joined.initial = initial;
    joined.actions = actions;
    Ok(joined)
}
