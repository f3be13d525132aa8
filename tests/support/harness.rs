//! Every method of [`Method::ALL`] on one problem. Each method either
//! meets the problem's bound for its kind of method, fails the way its
//! documentation says it fails on a problem beyond it (an explicit pair
//! stops with `Error::Stiff`, …), or is refused before the first step
//! with its [`Method::refusal`], word for word.
//!
//! The adaptive methods run at each of the problem's tolerances and must
//! keep the error within `bound · tol`. The fixed-step methods take the
//! runtime's default step, the interval over 1000 (`Options::step`'s
//! default; `TaylorFixed` is given the same step), and their bound follows
//! from their order p: each of the (t1 − t0)/h steps makes a local error
//! of about (h/τ)^(p+1), τ the problem's shortest time scale, which the
//! problem amplifies by its `bound`, so the global error stays below
//! `bound · (t1 − t0)/τ · (h/τ)^p`. Where that is 1 or more no digit is
//! promised: the run ends with a finite state, or with `Error::NonFinite`
//! where a step longer than τ carries a state out of the model's domain
//! (a concentration below zero under a square root), or backward Euler, whose
//! Newton iteration does not converge on a step that large, halves it
//! until it stops with `Error::StepSizeUnderflow`. An explicit
//! method whose h·ρ(J) lies beyond its stability boundary on the negative
//! real axis is unstable there, and may end in `Error::NonFinite` or any
//! error.

use daegen::prelude::*;

/// What the harness asks of a method, by the kind of method it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Adaptive and stable on stiff problems (`Radau5`, `Rodas5P`, and
    /// `Auto`, which switches to them): within `bound · tol` everywhere.
    Stiff,
    /// An adaptive explicit pair: within `bound · tol`, or, on a stiff
    /// problem, stopped by its stiffness test with `Error::Stiff`.
    ExplicitPair,
    /// The adaptive Taylor method: within `bound · tol`, or, on a stiff
    /// problem, which holds its step at its stability limit (it has no
    /// stiffness test), stopped by `Options::max_steps` with
    /// `Error::MaxSteps`.
    Taylor,
    /// A fixed-step method of this order whose stability region reaches
    /// `boundary` along the negative real axis (∞: A-stable).
    FixedStep {
        /// Order of convergence.
        order: i32,
        /// |z| of the stability boundary on the negative real axis.
        boundary: f64,
    },
}

/// The kind of `method`. Every explicit fixed-step method here, the
/// Taylor scheme included, has for stability function the Taylor
/// polynomial of eᶻ of the degree of its order (HNW I §IV.2: all explicit
/// s-stage methods of order s ≤ 4 share it), so its boundary on the
/// negative real axis is that polynomial's, found by [`real_boundary`].
pub fn kind(method: Method) -> Kind {
    let explicit = |order| Kind::FixedStep { order, boundary: real_boundary(order) };
    match method {
        Method::Auto | Method::Radau5 | Method::Rodas5P => Kind::Stiff,
        Method::Dopri5 | Method::Dop853 => Kind::ExplicitPair,
        Method::Taylor => Kind::Taylor,
        Method::Euler => explicit(1),
        Method::BackwardEuler => Kind::FixedStep { order: 1, boundary: f64::INFINITY },
        Method::Midpoint | Method::Heun | Method::Ralston => explicit(2),
        Method::Rk4 | Method::Rk38 => explicit(4),
        Method::TaylorFixed { order, .. } => explicit(order as i32),
    }
}

/// The largest x with |Σₖ₌₀ᵖ (−y)ᵏ/k!| ≤ 1 for every y in [0, x]: where
/// the stability region of a method with that stability polynomial ends
/// on the negative real axis (2 for p = 1 and 2, 2.785 for p = 4).
pub fn real_boundary(p: i32) -> f64 {
    let stable = |y: f64| {
        let (mut term, mut sum) = (1.0, 1.0);
        for k in 1..=p {
            term *= -y / f64::from(k);
            sum += term;
        }
        sum.abs() <= 1.0 + 1e-12
    };
    let dy = 1e-4;
    let mut y = 0.0;
    while stable(y + dy) {
        y += dy;
    }
    y
}

/// Whether `method` chooses its own steps from the tolerances.
pub fn is_adaptive(method: Method) -> bool {
    !matches!(kind(method), Kind::FixedStep { .. })
}

/// The methods of [`Method::ALL`] that choose their steps from the
/// tolerances (and keep each step's continuous extension as their dense
/// output).
pub fn adaptive_methods() -> impl Iterator<Item = Method> {
    Method::ALL.into_iter().filter(|&m| is_adaptive(m))
}

/// The methods of [`Method::ALL`] that take a fixed step.
pub fn fixed_step_methods() -> impl Iterator<Item = Method> {
    Method::ALL.into_iter().filter(|&m| !is_adaptive(m))
}

/// Whether `method` is an adaptive explicit pair (DOPRI5, DOP853): an
/// error estimate from an embedded formula and a stiffness test.
pub fn is_explicit_pair(method: Method) -> bool {
    kind(method) == Kind::ExplicitPair
}

/// Whether `method` is adaptive and stable on stiff problems (RADAU5,
/// RODAS5P, and `Auto`, which switches to them).
pub fn is_stiff_method(method: Method) -> bool {
    kind(method) == Kind::Stiff
}

/// Whether `method` solves a linear system with the Jacobian every step
/// (a Newton iteration or a Rosenbrock stage): the stiff methods and the
/// A-stable fixed-step ones (backward Euler).
pub fn is_implicit(method: Method) -> bool {
    match kind(method) {
        Kind::Stiff => true,
        Kind::FixedStep { boundary, .. } => boundary.is_infinite(),
        Kind::ExplicitPair | Kind::Taylor => false,
    }
}

/// Whether `method` steps a non-stiff problem at a tight tolerance (rtol
/// 1e-10 and below) with a formula of order 8 or more: DOP853, the
/// adaptive Taylor method (whose order grows with the digits asked), and
/// `Auto`, whose pair is DOP853 below rtol 1e-7. Not DOPRI5, RADAU5 and
/// RODAS5P (order 5) nor the fixed-step methods: where a test asks for
/// nearly every digit over a long run, their error grows past it.
pub fn is_high_order_at_tight_tolerances(method: Method) -> bool {
    matches!(method, Method::Dop853 | Method::Taylor | Method::Auto)
}

/// The methods of [`Method::ALL`] that run models of type `M` (those
/// [`Method::refusal`] does not refuse for `M`) and satisfy `keep`, in the
/// order of [`Method::ALL`]. A test that means "every method of some
/// class that runs this model" lists its methods by this, so that a method
/// added to [`Method::ALL`] is tested wherever it qualifies.
pub fn methods_for<M: Model>(keep: impl Fn(Method) -> bool) -> Vec<Method> {
    Method::ALL.into_iter().filter(|&m| m.refusal::<M>().is_none() && keep(m)).collect()
}

/// Every adaptive method (see [`is_adaptive`]) that runs models of type `M`.
pub fn adaptive_methods_for<M: Model>() -> Vec<Method> {
    methods_for::<M>(is_adaptive)
}

/// [`methods_for`] the type of `model`, for a type awkward to name (a
/// model with its sensitivities).
pub fn methods_running<M: Model>(_model: &M, keep: impl Fn(Method) -> bool) -> Vec<Method> {
    methods_for::<M>(keep)
}

/// Most steps any run of the harness may take: above the longest run
/// that meets its bound (Dopri5 on Lorenz at 1e-12, about 11 000), so that
/// a Taylor run held by stiffness stops early.
pub const MAX_STEPS: usize = 50_000;

/// A problem for every method: `model` from 0 to `t1`.
pub struct Problem<M> {
    /// The problem's name, for the messages.
    pub name: &'static str,
    /// The model, with the problem's parameters.
    pub model: M,
    /// End of the interval.
    pub t1: f64,
    /// The error of a solution against the reference at the end.
    pub error: fn(&Solution) -> f64,
    /// Tolerances of the adaptive methods' runs.
    pub tolerances: &'static [f64],
    /// `atol` is `rtol` times this (1 for most; below the smallest
    /// component for chemistry).
    pub atol_scale: f64,
    /// How much the problem amplifies local errors: an adaptive run stays
    /// within `bound · tol`.
    pub bound: f64,
    /// The solution's shortest time scale (a close approach, a period).
    pub time_scale: f64,
    /// Where the solution slows down after a fast transient (a reaction
    /// settling onto its slow manifold), its time scale from then on:
    /// stiffness is judged against it.
    pub settled_time_scale: Option<f64>,
    /// ρ(J) along the solution, the magnitude of its stiffest eigenvalue.
    pub stiffness: f64,
    /// RODAS5P with `LinearSolver::Krylov` too.
    pub gmres: bool,
}

impl<M> Problem<M> {
    /// Whether the problem is stiff: its Jacobian has eigenvalues over a
    /// hundred times faster than the solution changes (once settled).
    pub fn is_stiff(&self) -> bool {
        self.stiffness * self.settled_time_scale.unwrap_or(self.time_scale) > 100.0
    }

    /// The fixed-step methods' step: the runtime's default.
    pub fn fixed_step(&self) -> f64 {
        self.t1 / 1000.0
    }

    /// The bound of a fixed-step method of order `p` at
    /// [`Problem::fixed_step`] (see the module's documentation).
    pub fn fixed_bound(&self, p: i32) -> f64 {
        let h = self.fixed_step();
        self.bound * self.t1 / self.time_scale * (h / self.time_scale).powi(p)
    }
}

/// The name of the error a run ended with, for the table.
fn failure(e: &Error) -> String {
    let name = match e {
        Error::Stiff { .. } => "Stiff",
        Error::MaxSteps { .. } => "MaxSteps",
        Error::NonFinite { .. } => "NonFinite",
        Error::StepSizeUnderflow { .. } => "StepSizeUnderflow",
        Error::NewtonFailure { .. } => "NewtonFailure",
        Error::SingularMatrix { .. } => "SingularMatrix",
        Error::InvalidOptions { .. } => "InvalidOptions",
        _ => "other error",
    };
    match e.partial_solution() {
        Some(s) => format!("Error::{name} at t = {:.3e}", s.final_time()),
        None => format!("Error::{name}"),
    }
}

/// `method` with the problem's fixed step where it carries its own.
fn with_step(method: Method, step: f64) -> Method {
    match method {
        Method::TaylorFixed { order, .. } => Method::TaylorFixed { order, step },
        other => other,
    }
}

/// Runs every method on `problem`: one line of the table per run (its
/// statistics, its failure or its refusal), and a line for every run that
/// neither met its bound nor failed as documented.
pub fn run_every_method<M: Simulate>(problem: &Problem<M>) -> (String, Vec<String>) {
    let mut table = String::new();
    let mut beyond = Vec::new();
    let name = problem.name;
    for method in Method::ALL {
        let method = with_step(method, problem.fixed_step());
        let base = Options::new().method(method).max_steps(MAX_STEPS);
        if let Some(reason) = method.refusal::<M>() {
            match problem.model.simulate(0.0, problem.t1, &base) {
                Err(Error::InvalidOptions { message }) if message == reason => {}
                Err(e) => {
                    beyond.push(format!("{name} with {method:?}: {e}, not the refusal {reason}"))
                }
                Ok(_) => beyond.push(format!("{name} with {method:?} ran, not refused: {reason}")),
            }
            table.push_str(&format!("{:<21} refused: {reason}\n", method.name()));
            continue;
        }
        let kind = kind(method);
        let runs: Vec<(Options, String, Option<f64>)> = match kind {
            Kind::FixedStep { .. } => {
                let opts = match method {
                    Method::TaylorFixed { .. } => base.clone(),
                    _ => base.step(problem.fixed_step()),
                };
                vec![(opts, method.name().to_string(), None)]
            }
            _ => {
                let mut solvers = vec![(LinearSolver::Direct, method.name())];
                if method == Method::Rodas5P && problem.gmres {
                    solvers.push((LinearSolver::Krylov, "Rodas5P GMRES"));
                }
                let mut runs = Vec::new();
                for (linear, label) in solvers {
                    for &tol in problem.tolerances {
                        let opts = base
                            .clone()
                            .linear_solver(linear)
                            .rtol(tol)
                            .atol(tol * problem.atol_scale);
                        runs.push((opts, label.to_string(), Some(tol)));
                    }
                }
                runs
            }
        };
        for (opts, label, tol) in runs {
            let tol_text = tol.map(|t| format!("{t:.0e}")).unwrap_or_else(|| "h".to_string());
            let what = format!("{name} with {label} at {tol_text}");
            let result = problem.model.simulate(0.0, problem.t1, &opts);
            let line = match &result {
                Ok(sol) => {
                    let s = sol.stats();
                    let ran = if label.starts_with(s.method) {
                        label.clone()
                    } else {
                        format!("{label} ({})", s.method)
                    };
                    let iterations = match s.linear_iterations {
                        0 => String::new(),
                        k => format!(" {k:>5} GMRES it"),
                    };
                    format!(
                        "{ran:<21} {tol_text:<6} {:>5} steps {:>4} rejected {:>6} f {:>4} J{iterations}\n",
                        s.steps, s.rejected, s.rhs_evals, s.jacobian_evals
                    )
                }
                Err(e) => format!("{label:<21} {tol_text:<6} {}\n", failure(e)),
            };
            table.push_str(&line);
            let error = result.as_ref().map(|sol| (problem.error)(sol));
            let verdict = match (kind, tol) {
                (Kind::FixedStep { order, boundary }, _) => {
                    let h_rho = problem.fixed_step() * problem.stiffness;
                    let bound = problem.fixed_bound(order);
                    match &error {
                        _ if h_rho > boundary => Ok(()),
                        Ok(e) if bound >= 1.0 && e.is_finite() => Ok(()),
                        Err(Error::NonFinite { .. }) if bound >= 1.0 => Ok(()),
                        Err(Error::StepSizeUnderflow { .. })
                            if bound >= 1.0 && method == Method::BackwardEuler =>
                        {
                            Ok(())
                        }
                        Ok(e) if *e <= bound => Ok(()),
                        Ok(e) => Err(format!(
                            "error {e:e}, above {bound:e} (order {order}, h = {:e})",
                            problem.fixed_step()
                        )),
                        Err(e) => Err(e.to_string()),
                    }
                }
                (_, Some(tol)) => match &error {
                    Ok(e) if *e <= problem.bound * tol => Ok(()),
                    Ok(e) => Err(format!(
                        "error {e:e} = {:.1e} tol, above {:e}",
                        e / tol,
                        problem.bound * tol
                    )),
                    Err(Error::Stiff { .. })
                        if kind == Kind::ExplicitPair && problem.is_stiff() =>
                    {
                        Ok(())
                    }
                    Err(Error::MaxSteps { .. }) if kind == Kind::Taylor && problem.is_stiff() => {
                        Ok(())
                    }
                    Err(e) => Err(e.to_string()),
                },
                (_, None) => unreachable!("an adaptive run has a tolerance"),
            };
            if let Err(why) = verdict {
                beyond.push(format!("{what}: {why}"));
            }
        }
    }
    (table, beyond)
}
