//! Errors of a run: what went wrong, where, and the solution up to there.
//!
//! Every error of a run keeps the accepted steps (`partial`, reachable with
//! [`Error::partial_solution`]); a request refused before the first step
//! (options, parameters, initial values) has none. None is a panic, and no
//! run ends with a silent NaN. Each row is checked by the test named.
//!
//! | error | cause | remedy | test |
//! |---|---|---|---|
//! | [`Error::NonFinite`] | a state became NaN or ±∞ during the run (a pole, `sqrt` of a negative) | check the model near `t` and `variable`; a finite-time blow-up is real | `tests/nonstiff.rs` `a_singularity_stops_the_run_with_an_error_and_the_partial_solution`, `tests/taylor_adaptive.rs` `a_finite_time_blow_up_is_an_error_at_the_pole`, `tests/models.rs` `bad_requests_are_errors_not_panics` |
//! | [`Error::Evaluation`] | the model could not be evaluated: a singular mass-matrix block at run time, nonlinear algebraic equations Newton cannot solve or whose Jacobian is singular (not index 1 there), Taylor derivatives of an order not generated | the message names the block, the equations, or the `#[dae_model(taylor = p)]` to write | `tests/taylor_fixed.rs` `an_order_above_the_generated_one_is_refused`, `tests/implicit_daes.rs` `a_singular_algebraic_jacobian_at_the_start_names_the_equation` |
//! | [`Error::StepSizeUnderflow`] | the step fell below the time's precision or `min_step`: a singularity, tolerances too tight; for backward Euler, a step halved 30 times without resolving the solution | the message says what to try for the method that ran | `tests/stiff.rs` `a_minimum_step_stops_the_run_early` |
//! | [`Error::NewtonFailure`] | the implicit method's Newton iteration failed as the step shrank; `tried` says what it tried | a smaller step for backward Euler; for RADAU5 a wrong or discontinuous model near `t` | `tests/stiff.rs` `newton_failures_are_reported_with_the_time_and_what_was_tried` |
//! | [`Error::SingularMatrix`] | the Newton matrix stayed singular as the step shrank: a Jacobian that is not finite, or a singular model | look at the model and its Jacobian at `t` | `tests/stiff.rs` `a_newton_matrix_that_stays_singular_is_an_error_with_the_time` |
//! | [`Error::Stiff`] | `Dopri5` or `Dop853` held at its stability boundary (Hairer's test) | `Radau5` or `Auto`, or `Options::stiffness_detection(false)` | `tests/stiff.rs` `an_explicit_pair_stops_where_the_problem_turns_stiff` |
//! | [`Error::MaxSteps`] | more steps than `Options::max_steps` | raise the limit; a stiff method if the problem is stiff | `tests/nonstiff.rs` `a_stiff_problem_hits_the_step_limit_with_a_clear_error` |
//! | [`Error::Constraint`] | inconsistent initial values projection cannot repair, redundant constraints, a singular constraint Jacobian (a mechanism at a dead point) | consistent initial values, remove the redundant joint, avoid the singular configuration | `tests/dae.rs` `unrepairable_or_redundant_constraints_are_errors_that_name_the_constraint` |
//! | [`Error::EventChatter`] | a terminal event fires again within ~1e-13 (relative) of the start: restarts at its crossings make no progress (Zeno) | stop the restarts there, e.g. below a rebound speed | `tests/events.rs` `restarting_at_accumulating_bounces_ends_in_a_chatter_error_at_the_zeno_time` |
//! | [`Error::ZenoEvents`] | an event fires again within `Options::min_event_interval` of its last firing: its firings accumulate (a bouncing ball coming to rest) | a terminal event or a mode that holds the rest state; the message says where they accumulate | `tests/hybrid.rs` `bounces_accumulate_at_the_zeno_time` |
//! | [`Error::EventLoop`] | the actions at one instant fire further events round after round, more than `MAX_EVENT_ITERATIONS` times | conditions that hold after their own actions | `tests/hybrid.rs` `actions_that_fire_each_other_forever_are_an_error` |
//! | [`Error::NonFiniteParameter`] | a parameter field is NaN or ±∞ | a finite value | `tests/models.rs` `bad_requests_are_errors_not_panics` |
//! | [`Error::DegenerateParameters`] | a parameter value zeroes a coefficient the macro divided by to combine the equations (a capacitance of 0) | a nonzero value | `tests/implicit_daes.rs` `a_capacitance_of_zero_changes_the_rank_and_is_refused` |
//! | [`Error::NonFiniteInitialValue`] | an initial value is NaN or ±∞ | a finite value | `tests/models.rs` `bad_requests_are_errors_not_panics` |
//! | [`Error::InvalidOptions`] | an option out of range (tolerances, steps, `max_steps`, `keep_every`), `max_step` below `min_step`, a method the model cannot run | the message names the option and says what to write | `tests/models.rs` `bad_requests_are_errors_not_panics`, `tests/taylor_adaptive.rs` `integrates_backwards_and_refuses_models_without_a_tape` |
//! | [`Error::MethodNotAvailable`] | reserved: every [`crate::Method`] is implemented | — | — |
//! | [`Error::UnknownName`] | `Solution::at`/`last` with a name that is no state, algebraic variable or output | use one of `known` | `tests/models.rs` `bad_requests_are_errors_not_panics` |
//! | [`Error::Thinned`] | `Solution::at` between the steps a `keep_every` run kept | ask at `Solution::times`, or keep every step | `tests/long_runs.rs` `keep_every_thins_the_stored_steps_and_at_refuses_between_them` |
//! | [`Error::NotStored`] | `Solution::at` or `sample` at a time an `output_times` run did not store | ask at `Solution::times`, or add the time to `output_times` | `tests/results_out.rs` `output_times_store_those_times_at_the_methods_order` |
//! | [`Error::Io`] | writing a CSV file failed | the message carries the system's reason | `tests/results_out.rs` `a_failing_writer_is_an_error_not_a_panic` |
//! | [`Error::OutOfRange`] | `Solution::at` outside the integrated interval | ask within `interval` | `tests/models.rs` `bad_requests_are_errors_not_panics` |

use crate::solution::Solution;
use std::fmt;

/// A failed run or a bad request to a [`Solution`].
#[derive(Debug)]
pub enum Error {
    /// A state became NaN or infinite.
    NonFinite {
        /// Time of the step that produced it.
        t: f64,
        /// The first non-finite state, by name.
        variable: &'static str,
        /// The accepted steps before it.
        partial: Box<Solution>,
    },
    /// The model could not be evaluated (a singular mass matrix, say).
    Evaluation {
        /// Time of the evaluation.
        t: f64,
        /// What failed.
        cause: crate::EvalError,
        /// The accepted steps before it.
        partial: Box<Solution>,
    },
    /// The step size became too small for the time's precision: the
    /// problem is too stiff for an explicit method, singular, or the
    /// tolerances are too tight.
    StepSizeUnderflow {
        /// Time reached.
        t: f64,
        /// The last step tried.
        h: f64,
        /// The accepted steps.
        partial: Box<Solution>,
    },
    /// Newton's method for an implicit method kept failing while the step
    /// shrank to nothing: the problem is singular there, or the Jacobian wrong.
    NewtonFailure {
        /// Time reached.
        t: f64,
        /// The last step tried.
        h: f64,
        /// What the iteration tried before giving up.
        tried: String,
        /// The accepted steps.
        partial: Box<Solution>,
    },
    /// The iteration matrix `γ/h·I − J` stayed singular while the step
    /// shrank (five times in a row for RADAU5; for backward Euler, which
    /// halves a step whose matrix is singular, down to 2⁻³⁰ of it).
    SingularMatrix {
        /// Time reached.
        t: f64,
        /// The step that made it singular.
        h: f64,
        /// The accepted steps.
        partial: Box<Solution>,
    },
    /// The problem turned stiff for an explicit method: its step is held
    /// at the edge of its stability region, not by accuracy (Hairer's
    /// test, as in `dopri5.f` and `dop853.f`).
    Stiff {
        /// Time reached.
        t: f64,
        /// Where the steps held by stability began.
        onset: f64,
        /// The last step.
        h: f64,
        /// h·ρ(J) estimated at that step.
        h_rho: f64,
        /// The accepted steps.
        partial: Box<Solution>,
    },
    /// More steps than [`crate::Options::max_steps`] allow.
    MaxSteps {
        /// Time reached.
        t: f64,
        /// The limit.
        max_steps: usize,
        /// The accepted steps.
        partial: Box<Solution>,
    },
    /// A constraint could not be satisfied: inconsistent initial values that
    /// projection cannot repair, redundant constraints (a rank-deficient
    /// constraint Jacobian), or a projection that diverged after a step.
    Constraint {
        /// Time of the failure.
        t: f64,
        /// The constraint, as the model wrote it.
        constraint: &'static str,
        /// 0 for the constraint, 1 for its velocity level, ...
        level: usize,
        /// What went wrong and what to do.
        message: String,
        /// The accepted steps before it.
        partial: Box<Solution>,
    },
    /// A terminal event fired again within a few rounding errors of the
    /// start of the run: its crossings accumulate there (Zeno behaviour, a
    /// ball bouncing ever lower), and restarting once more cannot progress.
    EventChatter {
        /// The time the crossings accumulate at.
        t: f64,
        /// The event, by name.
        event: &'static str,
        /// How long after the start it fired again.
        after: f64,
        /// The run up to it.
        partial: Box<Solution>,
    },
    /// An event fired again sooner than
    /// [`crate::Options::min_event_interval`] after its last firing: its
    /// firings accumulate (Zeno behaviour: a ball whose bounces shorten
    /// geometrically comes to rest after infinitely many in finite time).
    ZenoEvents {
        /// The time of the last firing.
        t: f64,
        /// The event, by name.
        event: &'static str,
        /// Where the firings accumulate, extrapolated from the last three
        /// (Aitken's Δ²: a geometric series of intervals sums exactly).
        accumulation: f64,
        /// How often it fired.
        count: usize,
        /// The run up to the last firing, its actions applied.
        partial: Box<Solution>,
    },
    /// Actions at one instant kept firing further events: after
    /// [`crate::MAX_EVENT_ITERATIONS`] rounds the state still changes.
    EventLoop {
        /// The instant.
        t: f64,
        /// The events and clocks that fired in the last round.
        events: Vec<&'static str>,
        /// The run up to the instant, before its actions.
        partial: Box<Solution>,
    },
    /// A parameter of the model is NaN or infinite.
    NonFiniteParameter {
        /// The parameter, by name.
        parameter: &'static str,
        /// Its value.
        value: f64,
    },
    /// The parameters make zero a coefficient the macro divided by when it
    /// combined the model's equations (see
    /// [`crate::Model::degenerate_parameters`]): the equations then combine
    /// differently from the generated code.
    DegenerateParameters {
        /// The model.
        model: &'static str,
        /// Which coefficient: "the coefficient of `der(y1)` in `…`".
        condition: &'static str,
    },
    /// An initial value is NaN or infinite.
    NonFiniteInitialValue {
        /// The state, by name.
        variable: &'static str,
        /// Its value.
        value: f64,
    },
    /// The options or the interval are unusable (a non-positive step, say).
    InvalidOptions {
        /// What is wrong and how to fix it.
        message: String,
    },
    /// The method is not implemented yet.
    MethodNotAvailable {
        /// The method asked for.
        method: crate::Method,
    },
    /// No state, algebraic variable or output has this name.
    UnknownName {
        /// The name asked for.
        name: String,
        /// The names there are.
        known: Vec<&'static str>,
    },
    /// A time between the steps a solution kept
    /// ([`crate::Options::keep_every`]), where it knows nothing.
    Thinned {
        /// The time asked for.
        t: f64,
        /// One step in this many was kept.
        keep_every: usize,
    },
    /// A time a solution stored at [`crate::Options::output_times`] did
    /// not store.
    NotStored {
        /// The time asked for.
        t: f64,
    },
    /// Writing results failed.
    Io {
        /// What was being written, and the system's reason.
        message: String,
    },
    /// A time outside the solution's interval.
    OutOfRange {
        /// The time asked for.
        t: f64,
        /// The interval covered.
        interval: (f64, f64),
    },
}

/// The errors of a run, which keep the solution up to the failure: one
/// list for both borrows of it.
macro_rules! with_partial {
    ($error:expr, $partial:ident => $found:expr) => {
        match $error {
            Error::NonFinite { $partial, .. }
            | Error::Evaluation { $partial, .. }
            | Error::MaxSteps { $partial, .. }
            | Error::Stiff { $partial, .. }
            | Error::StepSizeUnderflow { $partial, .. }
            | Error::NewtonFailure { $partial, .. }
            | Error::SingularMatrix { $partial, .. }
            | Error::EventChatter { $partial, .. }
            | Error::ZenoEvents { $partial, .. }
            | Error::EventLoop { $partial, .. }
            | Error::Constraint { $partial, .. } => Some($found),
            _ => None,
        }
    };
}

impl Error {
    /// The partial solution, to label it.
    pub(crate) fn partial_solution_mut(&mut self) -> Option<&mut Solution> {
        with_partial!(self, partial => &mut **partial)
    }

    /// The solution computed before the failure, if the run got that far.
    pub fn partial_solution(&self) -> Option<&Solution> {
        with_partial!(self, partial => &**partial)
    }
}

impl Error {
    /// The method that ran, as [`crate::Stats::method`] names it ("" when
    /// the run did not start).
    fn method(&self) -> &'static str {
        self.partial_solution().map(|s| s.stats().method).unwrap_or("")
    }

    /// Whether the method that failed was an implicit one (RADAU5,
    /// RODAS5P, backward Euler, or `Auto` after it switched to a stiff one).
    fn failed_implicit(&self) -> bool {
        let method = self.method();
        method.ends_with("Radau5")
            || method.ends_with("Rodas5P")
            || method.contains("BackwardEuler")
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { t, variable, .. } => {
                write!(f, "state `{variable}` became non-finite at t = {t}; check the model's domain or reduce the step")
            }
            Error::Evaluation { t, cause, .. } => {
                write!(f, "the model could not be evaluated at t = {t}: {cause}")
            }
            Error::StepSizeUnderflow { t, h, .. } => {
                write!(f, "the step size fell to {h:e} at t = {t}: ")?;
                if self.method().contains("BackwardEuler") {
                    write!(f, "backward Euler halved its step that far without resolving the solution; use Method::Radau5, which adapts its step to the solution, or check the model near there")
                } else if self.failed_implicit() {
                    write!(f, "the solution may be singular there (a pole, a discontinuity of the model or its Jacobian), or the tolerances too tight for the precision of t")
                } else {
                    write!(f, "the problem may be stiff there (use Method::Radau5 or Method::Auto), singular, or the tolerances too tight")
                }
            }
            Error::NewtonFailure { t, h, tried, .. } => {
                write!(f, "Newton's method did not converge at t = {t} with the step {h:e} ({tried}): ")?;
                if self.method().contains("BackwardEuler") {
                    write!(f, "take a smaller step (Options::step) or use Method::Radau5, which adapts its step")
                } else {
                    write!(f, "the model or its Jacobian may be discontinuous or singular there")
                }
            }
            Error::SingularMatrix { t, h, .. } => write!(
                f,
                "the Newton matrix stayed singular at t = {t} down to the step {h:e}: the Jacobian is not finite there (a square root or a division at zero, say) or the model is singular there"
            ),
            Error::Stiff {
                t, onset, h, h_rho, ..
            } => write!(
                f,
                "the problem is stiff from t = {onset} on: {}'s step is held at {h:e} by its stability (h·ρ(J) ≈ {h_rho:.2}, the edge of its stability region), not by accuracy; stopped at t = {t}. Use Method::Radau5 or Method::Auto (or Options::stiffness_detection(false) to go on anyway)",
                self.method()
            ),
            Error::MaxSteps { t, max_steps, .. } => {
                write!(f, "stopped at t = {t} after {max_steps} steps; raise Options::max_steps")?;
                if self.failed_implicit() {
                    write!(f, " or loosen the tolerances")
                } else {
                    write!(f, ", or use Method::Radau5 or Method::Auto if the problem is stiff")
                }
            }
            Error::Constraint {
                t,
                constraint,
                level,
                message,
                ..
            } => {
                let which = match level {
                    0 => String::new(),
                    1 => " (its velocity level)".to_string(),
                    2 => " (its acceleration level)".to_string(),
                    k => format!(" (its derivative of order {k})"),
                };
                write!(f, "constraint `{constraint}`{which} at t = {t}: {message}")
            }
            Error::EventChatter { t, event, after, .. } => write!(
                f,
                "event `{event}` fired again {after:e} after the start, at t = {t}: its crossings accumulate there (Zeno behaviour); stop restarting at this point, e.g. once the rebound speed or the time between events falls below a threshold"
            ),
            Error::ZenoEvents { t, event, accumulation, count, .. } => write!(
                f,
                "event `{event}` fired {count} times, the last at t = {t}, and its firings accumulate at t = {accumulation} (Zeno behaviour): stop the run there with a terminal event, or model what happens at rest (a `discrete` mode that holds the body still); Options::min_event_interval sets how close firings may be"
            ),
            Error::EventLoop { t, events, .. } => write!(
                f,
                "at t = {t} the actions keep firing events after {} rounds (last: `{}`): the actions undo each other; make one of the conditions hold after its own action",
                crate::MAX_EVENT_ITERATIONS,
                events.join("`, `")
            ),
            Error::NonFiniteParameter { parameter, value } => write!(
                f,
                "parameter `{parameter}` is {value}: every parameter must be finite"
            ),
            Error::DegenerateParameters { model, condition } => write!(
                f,
                "with these parameters {condition} is zero (or not finite): {model}'s equations were combined dividing by it, so the generated code does not hold; give it a nonzero value, or write the model for that case"
            ),
            Error::NonFiniteInitialValue { variable, value } => write!(
                f,
                "the initial value of `{variable}` is {value}: every initial value must be finite"
            ),
            Error::InvalidOptions { message } => write!(f, "invalid options: {message}"),
            Error::MethodNotAvailable { method } => {
                write!(f, "{method:?} is not available for this model")
            }
            Error::UnknownName { name, known } => write!(
                f,
                "no variable or output named `{name}`; known: {}",
                known.join(", ")
            ),
            Error::Thinned { t, keep_every } => write!(
                f,
                "t = {t} lies between the steps this solution kept (Options::keep_every({keep_every}) stores one step in {keep_every}): `at` answers only at its stored times (Solution::times); keep every step to interpolate between them"
            ),
            Error::NotStored { t } => write!(
                f,
                "t = {t} is not among the times this solution stored (Options::output_times): ask at Solution::times, or add t to output_times"
            ),
            Error::Io { message } => write!(f, "{message}"),
            Error::OutOfRange { t, interval } => {
                write!(
                    f,
                    "t = {t} is outside the solution's interval [{}, {}]",
                    interval.0, interval.1
                )
            }
        }
    }
}

impl std::error::Error for Error {}
