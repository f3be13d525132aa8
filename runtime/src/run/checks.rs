//! What a run's request must satisfy before the first step: the interval,
//! every option, the model's parameters and the initial state. Each
//! failure names the option, parameter or state and says what to write.

use crate::error::Error;
use crate::model::{has_mass_matrix, Model};
use crate::options::{LinearSolver, Method, Options};

/// `Err(InvalidOptions)` with `message`.
fn invalid(message: String) -> Result<(), Error> {
    Err(Error::InvalidOptions { message })
}

/// Checks the request of a run of `model` from `y0` at `t0` to `t1`.
pub(crate) fn check_request<M: Model>(
    model: &M,
    t0: f64,
    y0: &[f64],
    t1: f64,
    options: &Options,
) -> Result<(), Error> {
    if y0.len() != M::STATES {
        return invalid(format!(
            "the initial state has {} values but {} has {} states ({})",
            y0.len(),
            M::INFO.name,
            M::STATES,
            M::INFO.states.join(", ")
        ));
    }
    if !t0.is_finite() || !t1.is_finite() {
        return invalid(format!("the interval [{t0}, {t1}] must be finite"));
    }
    check_options::<M>(options)?;
    if let Some(times) = &options.output_times {
        check_output_times(times, t0, t1, options)?;
    }
    for (k, &name) in M::INFO.parameters.iter().enumerate() {
        let value = model.parameter(k);
        if !value.is_finite() {
            return Err(Error::NonFiniteParameter { parameter: name, value });
        }
    }
    if let Some(condition) = model.degenerate_parameters() {
        return Err(Error::DegenerateParameters { model: M::INFO.name, condition });
    }
    if let Some(i) = y0.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFiniteInitialValue { variable: M::INFO.states[i], value: y0[i] });
    }
    Ok(())
}

/// Every option on its own and against the others.
fn check_options<M: Model>(options: &Options) -> Result<(), Error> {
    for (name, value) in [("rtol", options.rtol), ("atol", options.atol)] {
        if !(value.is_finite() && value >= 0.0) {
            return invalid(format!("{name}({value}): a tolerance must be finite and ≥ 0"));
        }
    }
    if options.rtol < 1e-15 && options.atol == 0.0 {
        return invalid(format!(
            "rtol({}) with atol(0): no error is small enough; give rtol ≥ 1e-15 or atol > 0",
            options.rtol
        ));
    }
    let positive = |name: &str, value: Option<f64>| match value {
        Some(h) if !(h.is_finite() && h > 0.0) => invalid(format!(
            "{name}({h}): a step must be positive and finite (its direction follows t0 → t1)"
        )),
        _ => Ok(()),
    };
    positive("step", options.step)?;
    positive("initial_step", options.initial_step)?;
    positive("max_step", options.max_step)?;
    if !(options.min_step.is_finite() && options.min_step >= 0.0) {
        return invalid(format!(
            "min_step({}): the smallest step must be finite and ≥ 0",
            options.min_step
        ));
    }
    if let Some(max) = options.max_step.filter(|&max| max < options.min_step) {
        return invalid(format!(
            "max_step({max}) is below min_step({}): no step is allowed",
            options.min_step
        ));
    }
    if options.max_steps == 0 {
        return invalid("max_steps(0): a run needs at least one step".to_string());
    }
    if let Some(message) = options.method.refusal::<M>() {
        return invalid(message);
    }
    if let Method::TaylorFixed { step, .. } = options.method {
        if !(step.is_finite() && step > 0.0) {
            return invalid(format!(
                "TaylorFixed {{ step: {step}, .. }}: the step must be positive and finite"
            ));
        }
    }
    if let Some(order) = options.taylor_order.filter(|&p| p < 2) {
        return invalid(format!(
            "taylor_order({order}): the adaptive Taylor method needs an order of 2 or more"
        ));
    }
    let mass_form = options.formulation == crate::options::Formulation::MassMatrix
        && !(M::INDEX == 0 && M::INFO.algebraics.is_empty());
    if mass_form && !matches!(options.method, Method::Radau5 | Method::Rodas5P | Method::Auto) {
        return invalid(format!(
            "Formulation::MassMatrix runs {} with RADAU5 or RODAS5P only: use Method::Radau5 (or Method::Auto, or Method::Rodas5P for an index-1 model), or Formulation::IndexOneProjected for {:?}",
            M::INFO.name,
            options.method
        ));
    }
    if options.linear_solver == LinearSolver::Krylov {
        check_krylov::<M>(options)?;
    }
    if options.keep_every == 0 {
        return invalid("keep_every(0): k ≥ 1 (1 keeps every step)".to_string());
    }
    Ok(())
}

/// `LinearSolver::Krylov`: RODAS5P (alone or under `Auto`) on a model
/// whose generated Jacobian gives the matrix's pattern, without a mass
/// matrix.
fn check_krylov<M: Model>(options: &Options) -> Result<(), Error> {
    if !matches!(options.method, Method::Rodas5P | Method::Auto) {
        return invalid(format!(
            "LinearSolver::Krylov solves RODAS5P's linear systems only; {:?} factors its own: use Method::Rodas5P (or Method::Auto), or LinearSolver::Direct",
            options.method
        ));
    }
    if has_mass_matrix::<M>() {
        return invalid(format!(
            "{} has a mass matrix, which LinearSolver::Krylov does not precondition: use LinearSolver::Direct",
            M::INFO.name
        ));
    }
    if M::SENSITIVITY_COLUMNS > 0 {
        return invalid(format!(
            "{} carries sensitivities, whose linear systems are solved through the base model's factorisation: use LinearSolver::Direct",
            M::INFO.name
        ));
    }
    if M::JACOBIAN.pattern().is_empty() {
        return invalid(format!(
            "{} has no generated Jacobian (it is differenced), whose pattern and values LinearSolver::Krylov needs for its products and preconditioner: use LinearSolver::Direct",
            M::INFO.name
        ));
    }
    Ok(())
}

/// `output_times`: finite, inside the interval, in its direction, and not
/// with the options that would leave nothing to interpolate them from.
fn check_output_times(times: &[f64], t0: f64, t1: f64, options: &Options) -> Result<(), Error> {
    if options.keep_every > 1 {
        return invalid(format!(
            "output_times and keep_every({}) both choose what to store: use one",
            options.keep_every
        ));
    }
    if !options.dense_output {
        return invalid(
            "output_times interpolates in the steps with their dense output: drop dense_output(false)"
                .to_string(),
        );
    }
    let (lo, hi) = (t0.min(t1), t0.max(t1));
    if let Some(t) = times.iter().find(|t| !(lo..=hi).contains(*t)) {
        return invalid(format!(
            "output_times: {t} lies outside the interval [{t0}, {t1}]; give times from t0 to t1"
        ));
    }
    let forward = t1 >= t0;
    if let Some(k) = (1..times.len()).find(|&k| {
        if forward {
            times[k] <= times[k - 1]
        } else {
            times[k] >= times[k - 1]
        }
    }) {
        let order = if forward { "increasing" } else { "decreasing" };
        return invalid(format!(
            "output_times must be strictly {order} (the direction from t0 to t1): {} is followed by {}",
            times[k - 1], times[k]
        ));
    }
    Ok(())
}
