//! How to run a model: the method and its settings, as a by-value builder.

use std::sync::{Arc, Mutex};

/// An integration method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// An explicit pair while the problem is non-stiff, a stiff method
    /// where it is stiff, switching both ways as the problem changes:
    /// `Dopri5` for rtol ≥ 1e-7, `Dop853` for tighter tolerances (where its
    /// higher order pays, Hairer–Nørsett–Wanner I §II.10); `Rodas5P` for
    /// rtol ≥ 5e-5 on systems of 64 states or more, and at every tolerance
    /// where it solves by GMRES (see [`LinearSolver::Auto`]), `Radau5`
    /// otherwise. `stats().method` names the
    /// methods in the order they ran (`"Dopri5→Radau5"`), `stats().switches`
    /// counts the hand-overs. A singular mass matrix runs `Radau5` alone.
    Auto,
    /// Taylor series with adaptive order and step (Jorba–Zou; heyoka's
    /// step rule) from the model's AD tape, which every explicit model
    /// with a smooth right-hand side has (others refuse the run with the
    /// reason, `Model::TAYLOR_TAPE`).
    Taylor,
    /// The economic Taylor scheme of the given order with a fixed step
    /// (course notes §1.3.1); the model must be expanded with
    /// `#[dae_model(taylor = p)]`, p ≥ order.
    TaylorFixed {
        /// Order p of the series.
        order: usize,
        /// Step size.
        step: f64,
    },
    /// Explicit Euler, fixed step (order 1).
    Euler,
    /// Implicit Euler with Newton and the model's Jacobian, fixed step
    /// (order 1, L-stable). Newton converges to the tolerances (`rtol`,
    /// `atol`) and below the step's own local error. A step Newton cannot
    /// solve, or whose local error exceeds its share h/(t1 − t0) of a
    /// component's magnitude (a relaxation jump the step does not resolve),
    /// is taken in halves: counted in `stats().rejected`, and kept in the
    /// solution with the grid points.
    BackwardEuler,
    /// The classic Runge–Kutta method, fixed step (order 4).
    Rk4,
    /// Kutta's 3/8 rule, fixed step (order 4).
    Rk38,
    /// The midpoint rule, eq. 1.19 with γ = 1, fixed step (order 2).
    Midpoint,
    /// Heun's method, eq. 1.19 with γ = 1/2, fixed step (order 2).
    Heun,
    /// Ralston's method, eq. 1.19 with γ = 3/4, fixed step (order 2).
    Ralston,
    /// Dormand–Prince 5(4), adaptive, with 4th-order dense output. Stops
    /// with [`crate::Error::Stiff`] where the problem turns stiff (see
    /// [`Options::stiffness_detection`]). Each step's sum y + h·Σ b_j k_j
    /// is compensated (its rounding error carried into the next step), so
    /// long runs at tight tolerances do not lose digits to it.
    Dopri5,
    /// Hairer's DOP853, adaptive, with 7th-order dense output. Stops with
    /// [`crate::Error::Stiff`] where the problem turns stiff; its steps'
    /// sums are compensated as DOPRI5's.
    Dop853,
    /// Radau IIA of order 5 for stiff problems (Hairer–Wanner's RADAU5),
    /// with the generated Jacobian. As radau5.f, it works to the tolerance
    /// `0.1·rtol^(2/3)` and scales atol alike (see [`Options::rtol`]): at
    /// rtol = atol = 1e-10, to 2.2e-8: a pendulum swinging from 2.5 rad is
    /// 4.9e-9 off at t = 10, where `Dop853` at the same tolerance is 1.0e-9
    /// off.
    Radau5,
    /// Steinebach's RODAS5P, a stiffly accurate Rosenbrock method of
    /// order 5(4), with the generated Jacobian and ∂f/∂t: one real
    /// factorisation and eight linear solves a step, no Newton iteration.
    /// Cheaper than `Radau5` on stiff problems at loose tolerances
    /// (rtol ≥ 1e-6); it integrates mass-matrix models of index 1 but not
    /// the index-2 variables of higher-index ones (use `Radau5`).
    Rodas5P,
}

impl Method {
    /// Every method, each once, in the order of the enum: to run a
    /// problem through all of them. `TaylorFixed` stands here with order 4
    /// (that of `Rk4`, its fixed-step peer) and a step of 1e-3; the model
    /// must be expanded with `#[dae_model(taylor = 4)]` or higher, or the
    /// run is refused. To use other parameters, map the list:
    /// `Method::ALL.map(|m| match m { Method::TaylorFixed { .. } =>
    /// Method::TaylorFixed { order: 6, step: h }, m => m })`.
    pub const ALL: [Method; 14] = [
        Method::Auto,
        Method::Taylor,
        Method::TaylorFixed { order: 4, step: 1e-3 },
        Method::Euler,
        Method::BackwardEuler,
        Method::Rk4,
        Method::Rk38,
        Method::Midpoint,
        Method::Heun,
        Method::Ralston,
        Method::Dopri5,
        Method::Dop853,
        Method::Radau5,
        Method::Rodas5P,
    ];

    /// The variant's name without its parameters (`"TaylorFixed"`), as
    /// [`crate::Stats::method`] reports a run that did not switch.
    pub fn name(self) -> &'static str {
        match self {
            Method::Auto => "Auto",
            Method::Taylor => "Taylor",
            Method::TaylorFixed { .. } => "TaylorFixed",
            Method::Euler => "Euler",
            Method::BackwardEuler => "BackwardEuler",
            Method::Rk4 => "Rk4",
            Method::Rk38 => "Rk38",
            Method::Midpoint => "Midpoint",
            Method::Heun => "Heun",
            Method::Ralston => "Ralston",
            Method::Dopri5 => "Dopri5",
            Method::Dop853 => "Dop853",
            Method::Radau5 => "Radau5",
            Method::Rodas5P => "Rodas5P",
        }
    }
}

/// What [`Options::on_step`] sees of each accepted step.
#[derive(Clone, Copy, Debug)]
pub struct Step<'a> {
    /// The time reached.
    pub t: f64,
    /// The state there, in the order of [`crate::ModelInfo::states`].
    pub y: &'a [f64],
    /// Steps accepted so far, this one included.
    pub steps: usize,
    /// The states' names.
    pub names: &'static [&'static str],
}

impl Step<'_> {
    /// The state called `name`, if there is one.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.names.iter().position(|n| *n == name).and_then(|i| self.y.get(i).copied())
    }
}

/// Whether a run goes on after [`Options::on_step`] saw a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on.
    Continue,
    /// End the run here, successfully ([`crate::Solution::cancelled_at`]).
    Stop,
}

/// A callback that sees every accepted step.
pub(crate) type StepCallback = Arc<Mutex<dyn FnMut(&Step<'_>) -> Flow + Send>>;

/// Settings of a run. Build with `Options::new().method(..).rtol(..)`:
/// each setter returns a changed copy and leaves the options it was called
/// on as they were, so one `Options` can be the base of several.
#[derive(Clone)]
pub struct Options {
    pub(crate) method: Method,
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
    pub(crate) step: Option<f64>,
    pub(crate) initial_step: Option<f64>,
    pub(crate) max_step: Option<f64>,
    pub(crate) min_step: f64,
    pub(crate) max_steps: usize,
    pub(crate) taylor_compact: bool,
    pub(crate) taylor_order: Option<usize>,
    pub(crate) dense_output: bool,
    pub(crate) formulation: Formulation,
    pub(crate) linear_solver: LinearSolver,
    pub(crate) sensitivity_error_control: bool,
    pub(crate) keep_every: usize,
    pub(crate) stiffness_detection: bool,
    pub(crate) strict_initial_values: bool,
    pub(crate) output_times: Option<Arc<[f64]>>,
    pub(crate) on_step: Option<StepCallback>,
    pub(crate) progress: bool,
    /// The least time between two firings of one event before the run
    /// counts them as accumulating (`None`: 1e-10 of the run's length).
    pub(crate) min_event_interval: Option<f64>,
    /// The run continues one that ended at its start, whose instant there
    /// has acted.
    pub(crate) continues: bool,
}

impl std::fmt::Debug for Options {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Options")
            .field("method", &self.method)
            .field("rtol", &self.rtol)
            .field("atol", &self.atol)
            .field("step", &self.step)
            .field("initial_step", &self.initial_step)
            .field("max_step", &self.max_step)
            .field("min_step", &self.min_step)
            .field("max_steps", &self.max_steps)
            .field("taylor_compact", &self.taylor_compact)
            .field("taylor_order", &self.taylor_order)
            .field("dense_output", &self.dense_output)
            .field("formulation", &self.formulation)
            .field("linear_solver", &self.linear_solver)
            .field("sensitivity_error_control", &self.sensitivity_error_control)
            .field("keep_every", &self.keep_every)
            .field("stiffness_detection", &self.stiffness_detection)
            .field("strict_initial_values", &self.strict_initial_values)
            .field("output_times", &self.output_times.as_ref().map(|t| t.len()))
            .field("on_step", &self.on_step.is_some())
            .field("progress", &self.progress)
            .field("min_event_interval", &self.min_event_interval)
            .field("continues", &self.continues)
            .finish()
    }
}

/// Equal settings; two callbacks are equal when they are the same one.
impl PartialEq for Options {
    fn eq(&self, other: &Options) -> bool {
        let same_callback = match (&self.on_step, &other.on_step) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            _ => false,
        };
        self.method == other.method
            && self.rtol == other.rtol
            && self.atol == other.atol
            && self.step == other.step
            && self.initial_step == other.initial_step
            && self.max_step == other.max_step
            && self.min_step == other.min_step
            && self.max_steps == other.max_steps
            && self.taylor_compact == other.taylor_compact
            && self.taylor_order == other.taylor_order
            && self.dense_output == other.dense_output
            && self.formulation == other.formulation
            && self.linear_solver == other.linear_solver
            && self.sensitivity_error_control == other.sensitivity_error_control
            && self.keep_every == other.keep_every
            && self.stiffness_detection == other.stiffness_detection
            && self.strict_initial_values == other.strict_initial_values
            && self.output_times == other.output_times
            && same_callback
            && self.progress == other.progress
            && self.min_event_interval == other.min_event_interval
            && self.continues == other.continues
    }
}

/// How a DAE is integrated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Formulation {
    /// The index-1 form (constraints differentiated until they determine
    /// the unknowns) with any method, projected onto the constraints after
    /// every step. The default.
    #[default]
    IndexOneProjected,
    /// The mass-matrix form with RADAU5: the Gear–Gupta–Leimkuhler index-2
    /// form of a mechanism (no projection; for stiff mechanisms), or a
    /// semi-explicit index-1 DAE as written. The solution's states are the
    /// model's, then the algebraic variables, then the multipliers `mu[k]`.
    MassMatrix,
}

/// How the stiff methods solve their linear systems `γ·M − J`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LinearSolver {
    /// [`LinearSolver::Krylov`] for RODAS5P on models of 1000 states or
    /// more whose Jacobian's pattern calls for a sparse LU (two- and
    /// three-dimensional grids, which no renumbering bands and whose LU
    /// fills in), where `Method::Auto` then takes RODAS5P as its stiff
    /// method at every tolerance; [`LinearSolver::Direct`] otherwise, and
    /// always for RADAU5 and backward Euler. The default.
    #[default]
    Auto,
    /// An LU factorisation in the storage the generated Jacobian's pattern
    /// makes cheapest: banded after a reverse Cuthill–McKee renumbering,
    /// sparse after a minimum-degree one, or dense. Exact, and the faster
    /// one on banded and small systems.
    Direct,
    /// GMRES preconditioned by an incomplete LU in the Jacobian's own
    /// pattern (ILU(0)), each solve to a thousandth of the step's error
    /// weights: no fill-in, so it pays on large grids whose sparse LU fills
    /// in (SUNDIALS' cvDiurnal example on a 50 × 50 grid: 0.2–0.6× CVODE's
    /// time, against 1.1–3.5× with the sparse LU). `Method::Rodas5P` only
    /// (`Method::Auto` then runs RODAS5P on its stiff stretches), on models
    /// with a generated Jacobian and no mass matrix. Where GMRES fails three
    /// steps in a row, each with half the step before, the run factors the
    /// matrix from there on: `stats().linear_solver` then reads
    /// `"GMRES→sparse LU"` (or band, or dense). `stats().linear_iterations`
    /// counts the GMRES iterations.
    Krylov,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Auto,
            rtol: 1e-6,
            atol: 1e-9,
            step: None,
            initial_step: None,
            max_step: None,
            min_step: 0.0,
            max_steps: 10_000_000,
            taylor_compact: false,
            taylor_order: None,
            dense_output: true,
            formulation: Formulation::IndexOneProjected,
            linear_solver: LinearSolver::Auto,
            sensitivity_error_control: true,
            keep_every: 1,
            stiffness_detection: true,
            strict_initial_values: false,
            output_times: None,
            on_step: None,
            progress: false,
            min_event_interval: None,
            continues: false,
        }
    }
}

impl Options {
    /// `Method::Auto`, rtol 1e-6, atol 1e-9, default step, at most 10⁷ steps.
    pub fn new() -> Options {
        Options::default()
    }

    /// The integration method.
    pub fn method(&self, method: Method) -> Options {
        Options { method, ..self.clone() }
    }

    /// Relative tolerance of adaptive methods, the local error per step
    /// they aim at, relative to each component's size.
    ///
    /// `Radau5` works to `0.1·rtol^(2/3)`, as Hairer's radau5.f does, and
    /// scales `atol` by the same factor: at rtol = atol = 1e-10 it works to
    /// 2.2e-8, and a pendulum swinging from 2.5 rad is 4.9e-9 off in its
    /// angle at t = 10 where `Dop853` is 1.0e-9 off. With the default atol
    /// (1e-9) kept, tightening rtol can loosen atol: at rtol 1e-12 RADAU5
    /// works to an absolute 1e-6 and that pendulum ends 1.4e-7 off, worse
    /// than at rtol 1e-10 (2.5e-8); give both, with [`Options::tolerance`].
    pub fn rtol(&self, rtol: f64) -> Options {
        Options { rtol, ..self.clone() }
    }

    /// Absolute tolerance of adaptive methods.
    pub fn atol(&self, atol: f64) -> Options {
        Options { atol, ..self.clone() }
    }

    /// Both tolerances at once: `rtol(tol).atol(tol)`, the usual choice for
    /// solutions of order 1.
    pub fn tolerance(&self, tol: f64) -> Options {
        self.rtol(tol).atol(tol)
    }

    /// Step size of fixed-step methods (default: the interval over 1000).
    pub fn step(&self, step: f64) -> Options {
        Options { step: Some(step), ..self.clone() }
    }

    /// First step of adaptive methods (default: Hairer's estimate from f and
    /// its change along an Euler step).
    pub fn initial_step(&self, h: f64) -> Options {
        Options { initial_step: Some(h), ..self.clone() }
    }

    /// Largest step of adaptive methods (default: the whole interval).
    pub fn max_step(&self, h: f64) -> Options {
        Options { max_step: Some(h), ..self.clone() }
    }

    /// Smallest step adaptive methods may take before stopping with
    /// [`crate::Error::StepSizeUnderflow`] (default 0: only the precision of t limits it).
    pub fn min_step(&self, h: f64) -> Options {
        Options { min_step: h, ..self.clone() }
    }

    /// The bound on events per unit time: an event that fires again within
    /// `dt` of its last firing ends the run with
    /// [`crate::Error::ZenoEvents`], which says where its firings
    /// accumulate (a ball bouncing ever lower on a floor). By default 1e-10
    /// of the run's length. Clocks are not counted: their instants are
    /// their own.
    pub fn min_event_interval(&self, dt: f64) -> Options {
        Options { min_event_interval: Some(dt), ..self.clone() }
    }

    /// Whether the run continues one that ended at its start `t0` (a
    /// co-simulation step after the one before it): the clocks with an
    /// instant at `t0` acted at the end of that run and do not act again
    /// before the first step. Off by default: an instant at the start acts
    /// before the first step.
    pub fn continues(&self, continues: bool) -> Options {
        Options { continues, ..self.clone() }
    }

    /// Most steps a run may take before it stops with [`crate::Error::MaxSteps`].
    pub fn max_steps(&self, max_steps: usize) -> Options {
        Options { max_steps, ..self.clone() }
    }

    /// `Method::Taylor` interprets the model's tape (the compact layout)
    /// even where the macro emitted straight-line recurrences for the order
    /// in use (`#[dae_model(unroll = [..])]`, used by default): to compare
    /// the two layouts.
    pub fn taylor_compact(&self, compact: bool) -> Options {
        Options { taylor_compact: compact, ..self.clone() }
    }

    /// Fixes `Method::Taylor`'s order (2 or more) instead of choosing it
    /// from the tolerance and the model's cost per order
    /// (`daegen::runtime::taylor_order`); the step still follows ρ and the
    /// tolerance, by Jorba & Zou's rule (at their order, heyoka's steps),
    /// where an order the method picks takes a shorter step so that its
    /// error is not above theirs. To compare layouts or orders at equal
    /// footing.
    pub fn taylor_order(&self, order: usize) -> Options {
        Options { taylor_order: Some(order), ..self.clone() }
    }

    /// Whether adaptive methods keep each step's continuous extension for
    /// [`crate::Solution::at`] (default `true`). With `false` only the
    /// accepted steps are kept and `at` interpolates between them by the
    /// cubic Hermite polynomial through both ends and their derivatives,
    /// as for the fixed-step Runge–Kutta methods: less memory on long
    /// runs, and DOP853 saves the three extra stages of its dense output
    /// per step. A model with events keeps it anyway (events are located
    /// on it). Not with [`Options::output_times`], which interpolates on it.
    pub fn dense_output(&self, dense_output: bool) -> Options {
        Options { dense_output, ..self.clone() }
    }

    /// Stores only every `k`-th accepted step, and always the last one
    /// (default 1: every step): a run of 10⁶ steps with `k = 1000` keeps
    /// about a thousand states. Implies `dense_output(false)`; `at` then
    /// answers only at the stored times ([`crate::Error::Thinned`]
    /// between them); `stats()` still counts every step. Events are still
    /// located on every step's continuous extension.
    pub fn keep_every(&self, k: usize) -> Options {
        Options { keep_every: k, ..self.clone() }
    }

    /// Whether `Dopri5` and `Dop853` stop with [`crate::Error::Stiff`] when
    /// the problem turns stiff (default `true`): Hairer's test, h·ρ(J) at
    /// the edge of the stability region for 15 steps. With `false` they go
    /// on with steps held at that edge, as many as the problem takes.
    pub fn stiffness_detection(&self, detect: bool) -> Options {
        Options { stiffness_detection: detect, ..self.clone() }
    }

    /// Whether inconsistent initial values of a DAE are an error (`true`)
    /// instead of being moved onto the constraints (default `false`: moved,
    /// and listed in [`crate::Solution::initial_corrections`]). The error
    /// is an [`crate::Error::Constraint`] that names the values.
    pub fn strict_initial_values(&self, strict: bool) -> Options {
        Options { strict_initial_values: strict, ..self.clone() }
    }

    /// Stores the solution at these times only (SciPy's `t_eval`,
    /// DifferentialEquations.jl's `saveat`), each from the step that
    /// covers it by the method's own continuous extension (cubic Hermite
    /// for the fixed-step methods); the steps themselves are not kept, so
    /// memory stays that of the times asked for. The times must lie in the
    /// interval, strictly ordered in its direction; not with `keep_every`
    /// or `dense_output(false)` (the run is refused). `at` then answers at
    /// these times only ([`crate::Error::NotStored`] elsewhere); `last`
    /// and `final_state` give the end of the run. Events are still located
    /// on every step.
    pub fn output_times(&self, times: Vec<f64>) -> Options {
        Options { output_times: Some(times.into()), ..self.clone() }
    }

    /// Calls `callback` after every accepted step (after its events) with
    /// the time and state ([`Step`]); returning [`Flow::Stop`] ends the run
    /// there (a success: [`crate::Solution::cancelled_at`] says where).
    /// With [`Options::output_times`] (or `keep_every`) a run of any length
    /// keeps constant memory while the callback streams the steps. Copies
    /// of these options share the one callback.
    pub fn on_step(&self, callback: impl FnMut(&Step<'_>) -> Flow + Send + 'static) -> Options {
        Options { on_step: Some(Arc::new(Mutex::new(callback))), ..self.clone() }
    }

    /// Draws a progress bar on stderr (time reached of the interval, steps,
    /// steps per second) for a run that lasts over a second; off by default.
    pub fn progress(&self, show: bool) -> Options {
        Options { progress: show, ..self.clone() }
    }

    /// How a DAE is integrated (see [`Formulation`]); ODEs ignore it.
    pub fn formulation(&self, formulation: Formulation) -> Options {
        Options { formulation, ..self.clone() }
    }

    /// How the stiff methods solve their linear systems (default
    /// [`LinearSolver::Auto`]).
    pub fn linear_solver(&self, linear_solver: LinearSolver) -> Options {
        Options { linear_solver, ..self.clone() }
    }

    /// Whether the sensitivities of a model made by `with_sensitivities()`
    /// take part in the step's error test (default `true`). With `false`
    /// the adaptive methods control the model's own states alone, as
    /// CVODES does by default (`errconS`): the same steps as a run without
    /// sensitivities, and sensitivities as accurate as those steps make
    /// them, which is usually enough for fitting. `Method::Taylor` then
    /// takes its step from the model's own coefficients.
    pub fn sensitivity_error_control(&self, control: bool) -> Options {
        Options { sensitivity_error_control: control, ..self.clone() }
    }

    /// The method chosen.
    pub fn get_method(&self) -> Method {
        self.method
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_is_listed_once_under_its_own_name() {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        for (k, name) in names.iter().enumerate() {
            assert!(!names[..k].contains(name), "{name} is listed twice");
        }
    }
}
