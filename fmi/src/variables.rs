//! The variables a model shows an importer, each with its value reference
//! (the same in FMI 2.0 and 3.0), in this order:
//!
//! | value references | variables | causality, variability, initial |
//! |---|---|---|
//! | 0 | `time` | independent |
//! | 1 … n | the states, in the model's order (`x`, `der(x)` for a second-order `x`) | local, continuous (discrete for a discrete value), exact (approx for a DAE's, which initialization may move) |
//! | next | each state's derivative not itself a state, `der(x)` | local, continuous, calculated, `derivative` = its state |
//! | next | the parameters | parameter, tunable, exact |
//! | next | the inputs | input, continuous |
//! | next | the outputs | output, continuous, calculated |
//! | next | the algebraic variables | local, continuous, calculated |
//! | next | the event functions, by the event's name | local, continuous, calculated |
//! | next | `solver.method`, `solver.tolerance`: how co-simulation steps | parameter, fixed, exact (a string, a real) |
//!
//! A second-order state's rate is a state itself: `der(x)` is then both
//! the derivative of `x` and a state, whose own derivative is
//! `der(x,2)`, as FMI allows.

use daegen_runtime::Model;

/// FMI's causality of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    /// The independent variable, the time.
    Independent,
    /// Set before a run (and between steps where tunable).
    Parameter,
    /// Set by the importer.
    Input,
    /// Read by the importer.
    Output,
    /// Internal, readable.
    Local,
}

/// What a variable is in the model: where its value comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// The time.
    Time,
    /// Component `i` of the state vector.
    State(usize),
    /// The rate of component `i` of the state vector, from the right-hand
    /// side.
    Derivative(usize),
    /// Parameter `k` of [`daegen_runtime::ModelInfo::parameters`].
    Parameter(usize),
    /// Input `k` of [`daegen_runtime::ModelInfo::inputs`].
    Input(usize),
    /// `Model::output(k, ..)`: an output, then the algebraic variables.
    Output(usize),
    /// Event function `k` of [`daegen_runtime::ModelInfo::events`].
    EventFunction(usize),
    /// The method co-simulation steps with (a string: `Auto`, `Dop853`, …).
    SolverMethod,
    /// The relative tolerance co-simulation steps to.
    SolverTolerance,
}

/// The method co-simulation uses unless the importer sets `solver.method`.
pub const DEFAULT_METHOD: &str = "Auto";

/// The tolerance co-simulation uses when neither `solver.tolerance` (whose
/// start, 0, means "not set") nor the experiment gives one.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// FMI's variability.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    /// Changes between events (states, their rates, outputs).
    Continuous,
    /// Changes only at events (a discrete value).
    Discrete,
    /// Changes only when the importer sets it (a parameter).
    Tunable,
    /// Set before initialization only.
    Fixed,
}

/// FMI's `initial`: how the start value is known.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Initial {
    /// The start value is the value.
    Exact,
    /// The start value is a guess initialization may move.
    Approx,
    /// Computed from the others.
    Calculated,
}

/// One variable as an importer sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Its name (`x`, `der(x)`, `motor.emf.i`).
    pub name: String,
    /// Its value reference.
    pub value_reference: u32,
    /// Its doc comment.
    pub description: String,
    /// Causality.
    pub causality: Causality,
    /// Variability.
    pub variability: Variability,
    /// How its start value is known (`None` for the time and inputs).
    pub initial: Option<Initial>,
    /// Its start value, where it has one.
    pub start: Option<f64>,
    /// The start value of a string variable (which has no `start`).
    pub text: Option<&'static str>,
    /// What it is in the model.
    pub role: Role,
    /// For a derivative, the position in the list of the state it is the
    /// derivative of.
    pub derivative_of: Option<usize>,
    /// For a continuous state, its index in the model's state vector.
    pub state: Option<usize>,
}

impl Variable {
    fn new(
        name: impl Into<String>,
        value_reference: usize,
        description: &str,
        role: Role,
    ) -> Variable {
        Variable {
            role,
            text: None,
            name: name.into(),
            value_reference: value_reference as u32,
            description: description.to_string(),
            causality: Causality::Local,
            variability: Variability::Continuous,
            initial: Some(Initial::Calculated),
            start: None,
            derivative_of: None,
            state: None,
        }
    }
}

/// Every variable of `model` with its start values (this instance's
/// parameters and initial state), in the order of the module's table.
pub fn fmi_variables<M: Model>(model: &M) -> Vec<Variable> {
    let info = &M::INFO;
    let mut y0 = vec![0.0; M::STATES];
    model.initial_state(&mut y0);
    // A DAE's given states are guesses its initialization may move.
    let constrained = !M::CONSTRAINTS.is_empty() || !info.algebraics.is_empty();
    let mut out: Vec<Variable> = Vec::new();
    let mut time = Variable::new("time", 0, "the time", Role::Time);
    time.causality = Causality::Independent;
    time.initial = None;
    out.push(time);
    for (i, name) in info.states.iter().enumerate() {
        let doc = info.state_docs.get(i).copied().unwrap_or("");
        let mut v = Variable::new(*name, out.len(), doc, Role::State(i));
        v.start = Some(y0[i]);
        v.state = Some(i);
        if info.discrete.contains(name) {
            v.variability = Variability::Discrete;
            v.initial = Some(Initial::Exact);
        } else {
            v.initial = Some(if constrained { Initial::Approx } else { Initial::Exact });
        }
        out.push(v);
    }
    // Each continuous state's derivative: a state already, or a variable of its own.
    for (i, name) in info.states.iter().enumerate() {
        if info.discrete.contains(name) {
            continue;
        }
        let der = derivative_name(name);
        match out.iter().position(|v| v.name == der) {
            Some(k) => out[k].derivative_of = Some(1 + i),
            None => {
                let mut v = Variable::new(der, out.len(), "", Role::Derivative(i));
                v.description = format!("the rate of `{name}`");
                v.derivative_of = Some(1 + i);
                out.push(v);
            }
        }
    }
    for (k, name) in info.parameters.iter().enumerate() {
        let doc = info.parameter_docs.get(k).copied().unwrap_or("");
        let mut v = Variable::new(*name, out.len(), doc, Role::Parameter(k));
        v.causality = Causality::Parameter;
        v.variability = Variability::Tunable;
        v.initial = Some(Initial::Exact);
        v.start = Some(model.parameter(k));
        out.push(v);
    }
    let output_doc = |name: &str| {
        let k = info.outputs.iter().position(|o| *o == name);
        k.and_then(|k| info.output_docs.get(k)).copied().unwrap_or("")
    };
    for (j, name) in info.inputs.iter().enumerate() {
        let mut v = Variable::new(*name, out.len(), output_doc(name), Role::Input(j));
        v.causality = Causality::Input;
        v.initial = None;
        let k = info.outputs.iter().position(|o| o == name).unwrap_or(0);
        v.start = Some(model.output(k, 0.0, &y0));
        out.push(v);
    }
    for (k, name) in info.outputs.iter().enumerate().filter(|(_, o)| !info.inputs.contains(o)) {
        // Only the model's own outputs are outputs; the rest stay
        // readable as local variables.
        let mut v = Variable::new(*name, out.len(), output_doc(name), Role::Output(k));
        if info.declared_outputs.contains(name) {
            v.causality = Causality::Output;
        }
        out.push(v);
    }
    for (k, name) in info.algebraics.iter().enumerate() {
        let doc = info.algebraic_docs.get(k).copied().unwrap_or("");
        out.push(Variable::new(*name, out.len(), doc, Role::Output(info.outputs.len() + k)));
    }
    for (k, event) in info.events.iter().enumerate() {
        out.push(Variable::new(event.name, out.len(), event.doc, Role::EventFunction(k)));
    }
    let mut method = Variable::new(
        "solver.method",
        out.len(),
        "The method co-simulation steps with: Auto, Taylor, Dopri5, Dop853, Radau5 or Rodas5P.",
        Role::SolverMethod,
    );
    method.text = Some(DEFAULT_METHOD);
    let mut tolerance = Variable::new(
        "solver.tolerance",
        out.len() + 1,
        "The relative tolerance co-simulation steps to (the absolute one is 1e-3 of it); 0: the experiment's, else 1e-6.",
        Role::SolverTolerance,
    );
    tolerance.start = Some(0.0);
    for mut v in [method, tolerance] {
        v.causality = Causality::Parameter;
        v.variability = Variability::Fixed;
        v.initial = Some(Initial::Exact);
        out.push(v);
    }
    out
}

/// The name of the derivative of the state `name` in FMI's structured
/// naming: `der(x)`, and `der(x,2)` for the rate of `der(x)`.
fn derivative_name(name: &str) -> String {
    if let Some(inner) = name.strip_prefix("der(").and_then(|r| r.strip_suffix(')')) {
        let (base, order) = match inner.rsplit_once(',') {
            Some((base, k)) => (base, k.trim().parse::<u32>().unwrap_or(1)),
            None => (inner, 1),
        };
        return format!("der({base},{})", order + 1);
    }
    format!("der({name})")
}

/// `name` as FMI's structured naming convention accepts it: as it is when
/// it is a dotted path of identifiers (with `[i]` indices) or a `der(..)`
/// of one, else quoted (`'event(h)'`).
pub fn structured_name(name: &str) -> String {
    fn identifier(part: &str) -> bool {
        let base = part.split('[').next().unwrap_or("");
        let indexed = part[base.len()..].split('[').skip(1).all(|i| {
            i.strip_suffix(']')
                .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
        });
        let mut chars = base.chars();
        chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
            && indexed
    }
    let path = |s: &str| s.split('.').all(identifier);
    let derivative = name.strip_prefix("der(").and_then(|r| r.strip_suffix(')')).is_some_and(
        |inner| match inner.rsplit_once(',') {
            Some((base, k)) => path(base) && k.bytes().all(|b| b.is_ascii_digit()) && !k.is_empty(),
            None => path(inner),
        },
    );
    if derivative || path(name) {
        return name.to_string();
    }
    let escaped = name.replace('\\', "\\\\").replace('\'', "\\'");
    format!("'{escaped}'")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ball as the macro writes it: h and der(h), a parameter, an event.
    struct Ball;

    impl Model for Ball {
        const STATES: usize = 2;
        type State = [f64; 2];
        const INDEX: usize = 0;
        const INFO: daegen_runtime::ModelInfo = daegen_runtime::ModelInfo {
            name: "Ball",
            doc: "",
            states: &["h", "der(h)"],
            state_docs: &["Height (m).", "rate of `h`"],
            parameters: &["g"],
            parameter_docs: &["Gravity."],
            outputs: &[],
            output_docs: &[],
            declared_outputs: &[],
            equations: 1,
            events: &[daegen_runtime::EventInfo {
                name: "bounce",
                direction: daegen_runtime::EventDirection::Falling,
                terminal: false,
                resets: &["der(h)"],
                doc: "",
            }],
            clocks: &[],
            discrete: &[],
            inputs: &[],
            algebraics: &[],
            algebraic_docs: &[],
            structure: daegen_runtime::StructureInfo::NONE,
            components: &[],
        };
        fn initial_state(&self, y: &mut [f64]) {
            y.copy_from_slice(&[10.0, 0.0]);
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), daegen_runtime::EvalError> {
            dy[0] = y[1];
            dy[1] = -9.81;
            Ok(())
        }
        fn parameter(&self, index: usize) -> f64 {
            if index == 0 {
                9.81
            } else {
                f64::NAN
            }
        }
    }

    #[test]
    fn a_second_order_state_is_the_derivative_of_the_first() {
        let vars = fmi_variables(&Ball);
        let names: Vec<&str> = vars.iter().map(|v| v.name.as_str()).collect();
        assert_eq!(
            names,
            ["time", "h", "der(h)", "der(h,2)", "g", "bounce", "solver.method", "solver.tolerance"]
        );
        let refs: Vec<u32> = vars.iter().map(|v| v.value_reference).collect();
        assert_eq!(refs, [0, 1, 2, 3, 4, 5, 6, 7]);
        assert_eq!(vars[3].role, Role::Derivative(1));
        assert_eq!(vars[5].role, Role::EventFunction(0));
        // der(h) is a state and the derivative of h; der(h,2) is
        // der(h)'s.
        assert_eq!(vars[2].state, Some(1));
        assert_eq!(vars[2].derivative_of, Some(1));
        assert_eq!(vars[3].derivative_of, Some(2));
        assert_eq!(vars[1].start, Some(10.0));
        assert_eq!(vars[4].causality, Causality::Parameter);
        assert_eq!(vars[4].start, Some(9.81));
    }

    #[test]
    fn names_follow_the_structured_convention() {
        assert_eq!(derivative_name("x"), "der(x)");
        assert_eq!(derivative_name("der(x)"), "der(x,2)");
        assert_eq!(derivative_name("der(x,2)"), "der(x,3)");
        assert_eq!(structured_name("motor.emf.i"), "motor.emf.i");
        assert_eq!(structured_name("der(arm.theta)"), "der(arm.theta)");
        assert_eq!(structured_name("der(x,2)"), "der(x,2)");
        assert_eq!(structured_name("q[2]"), "q[2]");
        assert_eq!(structured_name("event(h)"), "'event(h)'");
        assert_eq!(structured_name("every(0.5)"), "'every(0.5)'");
    }
}
