//! Errors of a run: what went wrong, where, and the solution up to there.

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
        /// The accepted steps.
        partial: Box<Solution>,
    },
    /// The iteration matrix `γ/h·I − J` was singular five times in a row.
    SingularMatrix {
        /// Time reached.
        t: f64,
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
    /// A time outside the solution's interval.
    OutOfRange {
        /// The time asked for.
        t: f64,
        /// The interval covered.
        interval: (f64, f64),
    },
}

impl Error {
    /// The partial solution, to label it.
    pub(crate) fn partial_solution_mut(&mut self) -> Option<&mut Solution> {
        match self {
            Error::NonFinite { partial, .. }
            | Error::Evaluation { partial, .. }
            | Error::MaxSteps { partial, .. }
            | Error::StepSizeUnderflow { partial, .. }
            | Error::NewtonFailure { partial, .. }
            | Error::SingularMatrix { partial, .. }
            | Error::Constraint { partial, .. } => Some(partial),
            _ => None,
        }
    }

    /// The solution computed before the failure, if the run got that far.
    pub fn partial_solution(&self) -> Option<&Solution> {
        match self {
            Error::NonFinite { partial, .. }
            | Error::Evaluation { partial, .. }
            | Error::MaxSteps { partial, .. }
            | Error::StepSizeUnderflow { partial, .. }
            | Error::NewtonFailure { partial, .. }
            | Error::SingularMatrix { partial, .. }
            | Error::Constraint { partial, .. } => Some(partial),
            _ => None,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { t, variable, .. } => {
                write!(f, "state `{variable}` became non-finite at t = {t}; check the model's domain or reduce the step")
            }
            Error::Evaluation { t, cause, .. } => {
                write!(f, "the model could not be evaluated at t = {t}: {cause:?}")
            }
                        Error::StepSizeUnderflow { t, h, .. } => write!(
                f,
                "the step size fell to {h:e} at t = {t}: the problem may be stiff (use Method::Radau5), singular there, or the tolerances too tight"
            ),
                        Error::NewtonFailure { t, h, .. } => write!(
                f,
                "Newton's method did not converge at t = {t} even with steps down to {h:e}: the model may be singular there"
            ),
            Error::SingularMatrix { t, .. } => {
                write!(f, "the Newton matrix was singular at t = {t} five times in a row: check the Jacobian and the model near there")
            }
            Error::MaxSteps { t, max_steps, .. } => {
                write!(f, "stopped at t = {t} after {max_steps} steps; raise Options::max_steps or the step size")
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
            Error::InvalidOptions { message } => write!(f, "invalid options: {message}"),
            Error::MethodNotAvailable { method } => {
                write!(
                    f,
                    "{method:?} is not available yet; use Method::Rk4, Rk38 or Euler"
                )
            }
            Error::UnknownName { name, known } => write!(
                f,
                "no variable or output named `{name}`; known: {}",
                known.join(", ")
            ),
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
