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
//!
//! A second-order state's rate is a state itself: `der(x)` is then both
//! the derivative of `x` and a state, whose own derivative is
//! `der(der(x))`, as FMI allows.

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

/// FMI's variability.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    /// Changes between events (states, their rates, outputs).
    Continuous,
    /// Changes only at events (a discrete value).
    Discrete,
    /// Changes only when the importer sets it (a parameter).
    Tunable,
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
    /// For a derivative, the position in the list of the state it is the
    /// derivative of.
    pub derivative_of: Option<usize>,
    /// For a continuous state, its index in the model's state vector.
    pub state: Option<usize>,
}

impl Variable {
    fn new(name: impl Into<String>, value_reference: usize, description: &str) -> Variable {
        Variable {
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
    let mut time = Variable::new("time", 0, "the time");
    time.causality = Causality::Independent;
    time.initial = None;
    out.push(time);
    for (i, name) in info.states.iter().enumerate() {
        let mut v = Variable::new(*name, out.len(), info.state_docs.get(i).copied().unwrap_or(""));
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
        let der = format!("der({name})");
        match out.iter().position(|v| v.name == der) {
            Some(k) => out[k].derivative_of = Some(1 + i),
            None => {
                let mut v = Variable::new(der, out.len(), "");
                v.description = format!("the rate of `{name}`");
                v.derivative_of = Some(1 + i);
                out.push(v);
            }
        }
    }
    for (k, name) in info.parameters.iter().enumerate() {
        let mut v =
            Variable::new(*name, out.len(), info.parameter_docs.get(k).copied().unwrap_or(""));
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
    for name in info.inputs {
        let mut v = Variable::new(*name, out.len(), output_doc(name));
        v.causality = Causality::Input;
        v.initial = None;
        let k = info.outputs.iter().position(|o| o == name).unwrap_or(0);
        v.start = Some(model.output(k, 0.0, &y0));
        out.push(v);
    }
    for name in info.outputs.iter().filter(|o| !info.inputs.contains(o)) {
        let mut v = Variable::new(*name, out.len(), output_doc(name));
        v.causality = Causality::Output;
        out.push(v);
    }
    for (k, name) in info.algebraics.iter().enumerate() {
        out.push(Variable::new(
            *name,
            out.len(),
            info.algebraic_docs.get(k).copied().unwrap_or(""),
        ));
    }
    for event in info.events {
        out.push(Variable::new(event.name, out.len(), event.doc));
    }
    out
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
        assert_eq!(names, ["time", "h", "der(h)", "der(der(h))", "g", "bounce"]);
        let refs: Vec<u32> = vars.iter().map(|v| v.value_reference).collect();
        assert_eq!(refs, [0, 1, 2, 3, 4, 5]);
        // der(h) is a state and the derivative of h; der(der(h)) is
        // der(h)'s.
        assert_eq!(vars[2].state, Some(1));
        assert_eq!(vars[2].derivative_of, Some(1));
        assert_eq!(vars[3].derivative_of, Some(2));
        assert_eq!(vars[1].start, Some(10.0));
        assert_eq!(vars[4].causality, Causality::Parameter);
        assert_eq!(vars[4].start, Some(9.81));
    }
}
