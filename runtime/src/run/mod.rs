//! Checks a run's request and hands it to the method.

mod checks;
pub(crate) mod hybrid;
pub(crate) mod initialization;

pub use hybrid::MAX_EVENT_ITERATIONS;
pub(crate) mod observables;

use crate::error::Error;
use crate::model::{has_mass_matrix, Model};
use crate::options::Options;
use crate::solution::{InitialCorrection, Solution};
use crate::step::Problem;

/// Running a model: `model.simulate(t0, t1, &options)`, for every
/// [`Model`] (brought into scope by `daegen::prelude`).
pub trait Simulate: Model + Clone + Send + Sync + 'static {
    /// Integrates from the model's initial state at `t0` to `t1`; see
    /// [`crate::Options`] and [`crate::Solution`].
    fn simulate(&self, t0: f64, t1: f64, options: &Options) -> Result<Solution, Error> {
        simulate(self, t0, t1, options)
    }

    /// Integrates from the state `y0` (ordered as
    /// [`crate::ModelInfo::states`]) at `t0` to `t1`: to continue after a
    /// terminal event from a changed state.
    fn simulate_from(
        &self,
        t0: f64,
        y0: &[f64],
        t1: f64,
        options: &Options,
    ) -> Result<Solution, Error> {
        simulate_from(self, t0, y0, t1, options)
    }
}

impl<M: Model + Clone + Send + Sync + 'static> Simulate for M {}

/// Integrates `model` from its initial state at `t0` to `t1` with `options`.
pub fn simulate<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t0: f64,
    t1: f64,
    options: &Options,
) -> Result<Solution, Error> {
    let mut y0 = vec![0.0; M::STATES];
    model.initial_state(&mut y0);
    simulate_from(model, t0, &y0, t1, options)
}

/// How a model of this type is integrated, for [`crate::Stats::formulation`].
fn formulation<M: Model>() -> &'static str {
    if !M::INDEX2_COMPONENTS.is_empty() {
        return "DAE in mass-matrix form with RADAU5: the Gear–Gupta–Leimkuhler index-2 form (position and velocity constraints kept by the multipliers mu, no projection)";
    }
    if !M::MASS.pattern().is_empty() {
        return "DAE in mass-matrix form: M y' = f(t, y) with the singular mass matrix as written (index 1)";
    }
    if !M::MASS.diagonal().is_empty() {
        return "DAE in mass-matrix form: the algebraic equations kept as written (index 1)";
    }
    match (M::INDEX, M::CONSTRAINTS.is_empty()) {
        (0, true) => "ODE",
        (0, false) => "ODE, projected onto its invariants after every step",
        (_, true) => "DAE solved for its algebraic variables at each evaluation (index 1)",
        _ => "DAE: index-1 form (constraints differentiated until they determine the unknowns), projected onto the constraints and their hidden levels after every step",
    }
}

/// Notes the method and formulation in the solution's statistics, on
/// success and on failure alike.
fn labelled<M: Model>(
    result: Result<Solution, Error>,
    method: &'static str,
) -> Result<Solution, Error> {
    let label = |s: &mut Solution| {
        let stats = s.stats_mut();
        if stats.method.is_empty() {
            stats.method = method;
        }
        // A run handed to another form of the model keeps that form's label.
        if stats.formulation.is_empty() {
            stats.formulation = formulation::<M>();
        }
    };
    match result {
        Ok(mut s) => {
            label(&mut s);
            s.finish_run();
            Ok(s)
        }
        Err(mut e) => {
            if let Some(s) = e.partial_solution_mut() {
                label(s);
                s.finish_run();
            }
            Err(e)
        }
    }
}

/// Integrates `model` from the state `y0` (in the order of
/// [`crate::ModelInfo::states`]) at `t0` to `t1` with `options`: to restart
/// after a terminal event, say, from a changed state.
pub fn simulate_from<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t0: f64,
    y0: &[f64],
    t1: f64,
    options: &Options,
) -> Result<Solution, Error> {
    let problem = Problem { model, t0, t1, y0, options };
    labelled::<M>(checked_run(problem), options.method.name())
}

/// The values initialization moved by more than `rtol·|given| + atol`.
fn initial_corrections<M: Model>(
    given: &[f64],
    used: &[f64],
    options: &Options,
) -> Vec<InitialCorrection> {
    // The model's own states: the sensitivities of the initial values move
    // with them by construction.
    let own = M::STATES / (1 + M::SENSITIVITY_COLUMNS);
    given
        .iter()
        .zip(used)
        .take(own)
        .enumerate()
        .filter(|(_, (g, u))| (*u - *g).abs() > options.rtol * g.abs() + options.atol)
        .map(|(i, (&given, &used))| InitialCorrection { name: M::INFO.states[i], given, used })
        .collect()
}

/// `Options::strict_initial_values`: the moved values as an error, naming
/// the constraint most violated at the values given.
fn inconsistent_start<M: Model>(
    model: &M,
    t0: f64,
    given: &[f64],
    corrections: &[InitialCorrection],
    solution: Solution,
) -> Error {
    let mut residuals = vec![0.0; M::CONSTRAINTS.len()];
    model.constraints(t0, given, &mut residuals);
    let worst =
        (0..residuals.len()).max_by(|&a, &b| residuals[a].abs().total_cmp(&residuals[b].abs()));
    let (constraint, level) = match worst {
        Some(r) => (M::CONSTRAINTS[r].equation, M::CONSTRAINTS[r].level),
        // A mass-matrix model: its algebraic equation, by the value it solves for.
        None => (corrections[0].name, 0),
    };
    let moves: Vec<String> = corrections
        .iter()
        .map(|c| format!("`{}` from {} to {}", c.name, c.given, c.used))
        .collect();
    Error::Constraint {
        t: t0,
        constraint,
        level,
        message: format!(
            "the initial values do not satisfy it, and strict_initial_values(true) forbids moving them (initialization would move {}); give consistent values, or allow the repair and read Solution::initial_corrections()",
            moves.join(", ")
        ),
        partial: Box::new(solution),
    }
}

fn checked_run<M: Model + Clone + Send + Sync + 'static>(
    problem: Problem<'_, M>,
) -> Result<Solution, Error> {
    let Problem { model, t0, t1, y0, options } = problem;
    crate::run::checks::check_request(model, t0, y0, t1, options)?;
    // A thinned run keeps no dense output: it could not serve between the
    // stored steps.
    let thinned = options.dense_output(false);
    let options = if options.keep_every > 1 { &thinned } else { options };
    let mut solution = observables::solution_of(model);
    solution.configure(options, t0, t1);
    let mut y0 = y0.to_vec();
    // Relations start as they hold there; a run that continues another
    // keeps them as the events left them (at a crossing, the value there
    // is ambiguous).
    if !options.continues {
        model.start_relations(t0, &mut y0);
    }
    let given = y0.clone();
    let solution = initialization::solve_initial_equations(model, t0, &mut y0, solution)?;
    let solution =
        crate::step::projection::consistent_initial_values(model, t0, &mut y0, solution)?;
    let mut solution =
        crate::step::projection::consistent_algebraic_components(model, t0, &mut y0, solution)?;
    let corrections = initial_corrections::<M>(&given, &y0, options);
    // The states the initial equations decide move by request.
    let decided =
        |c: &InitialCorrection| M::INITIAL_FREE.iter().any(|&j| M::INFO.states[j] == c.name);
    if options.strict_initial_values && !corrections.iter().all(decided) {
        return Err(inconsistent_start(model, t0, &given, &corrections, solution));
    }
    solution.set_initial_corrections(corrections);
    if options.formulation == crate::options::Formulation::MassMatrix && !has_mass_matrix::<M>() {
        if M::INFO.is_hybrid() && !(M::INDEX == 0 && M::INFO.algebraics.is_empty()) {
            return Err(Error::InvalidOptions {
                message: format!(
                    "{} has events that act, clocks or inputs, which its mass-matrix form does not carry: use Formulation::IndexOneProjected",
                    M::INFO.name
                ),
            });
        }
        if M::INDEX == 0 && M::INFO.algebraics.is_empty() {
            // An ODE has no other form: the option does not apply (and
            // stats().formulation says "ODE").
        } else {
            let mass_options = options.formulation(crate::options::Formulation::IndexOneProjected);
            // The model's own initialization found the degrees of freedom
            // and moved the initial values.
            let dof = solution.degrees_of_freedom_found();
            let corrections = solution.initial_corrections().to_vec();
            let carry = |s: &mut Solution| {
                if let Some(dof) = dof {
                    s.set_degrees_of_freedom(dof);
                }
                s.set_initial_corrections(corrections.clone());
            };
            return match model.simulate_mass_form(t0, &y0, t1, &mass_options) {
                Some(Ok(mut s)) => {
                    carry(&mut s);
                    Ok(s)
                }
                Some(Err(mut e)) => {
                    if let Some(s) = e.partial_solution_mut() {
                        carry(s);
                    }
                    Err(e)
                }
                None if M::SENSITIVITY_COLUMNS > 0 => Err(Error::InvalidOptions {
                    message: format!(
                        "{} carries sensitivities, which are generated for the index-1 form with projection only: use Formulation::IndexOneProjected",
                        M::INFO.name
                    ),
                }),
                None => Err(Error::InvalidOptions {
                    message: format!(
                        "{} has no mass-matrix form (its differential equations do not solve symbolically for the highest derivatives, or a constraint needs more than two differentiations): use Formulation::IndexOneProjected",
                        M::INFO.name
                    ),
                }),
            };
        }
    }
    if let Some(mut p) = crate::step::projection::Projector::new(model) {
        if let Ok(r) = p.project(t0, &mut y0, 0, None) {
            solution.note_constraint_residuals(r);
        }
    }
    solution.push_initial(t0, &y0);
    let problem = Problem { model, t0, t1, y0: &y0, options };
    let integrate = crate::methods::integrator::<M>(options.method);
    // A model that switches in the time alone (a step source) is run from
    // instant to instant as a hybrid one, each switch stepped to exactly.
    if M::INFO.is_hybrid() || !model.input_breakpoints().is_empty() {
        return hybrid::integrate_hybrid(integrate, problem, solution);
    }
    integrate(problem, solution)
}
