//! `Method::Auto`: an explicit pair while the problem is non-stiff and a
//! stiff method where it is stiff, switching both ways as often as the
//! problem changes (after LSODA, Petzold 1983, and DifferentialEquations.jl's
//! `AutoTsit5(Rodas5())`).
//!
//! - The pair is DOPRI5 for rtol ≥ 1e-7 and DOP853 below, where its higher
//!   order pays (Hairer, Nørsett, Wanner I §II.10).
//! - The stiff method is RODAS5P for rtol ≥ [`ROSENBROCK_FROM`] on
//!   systems of [`ROSENBROCK_STATES`] states or more, and RADAU5 otherwise:
//!   one factorisation and no Newton iteration a step pays where few digits
//!   are asked of a large system, RADAU5's reuse of its matrices where many
//!   are (measured on the Brusselators of `bench --large`, time at matched
//!   error over CVODE's: RODAS5P 0.45–0.64×, RADAU5 0.71–0.83× at rtol
//!   1e-3 and 1e-4; from 1e-5 on RADAU5 is ahead). On problems of one to
//!   three states RODAS5P at rtol 1e-4 took 1.5–2.8× RADAU5's time, far
//!   more accurate than asked (`bench --auto`), so they keep RADAU5.
//! - A stiff step costs `K` of the pair's ([`step_cost_ratio`], from the
//!   model's size and sparsity): the stiff method pays where its steps are
//!   more than `K` times the pair's.
//! - The pair hands over when h·ρ(J) stays above a fraction of
//!   its stability boundary, and above [`STIFFNESS_RATIO`] times the
//!   step's relative change of the solution, for [`CONFIRMATIONS`] steps:
//!   the fraction grows
//!   with `K`, from 0.1 where the stiff step is as cheap as the pair's (a
//!   pair held well inside its stability region by the error of a stiff
//!   component, [`crate::step::stiffness`]) to 0.9, Hairer's own test,
//!   where it is dear.
//! - The stiff method hands back, once its step has settled, when it is no
//!   longer `K` times the pair's (compared as h·ρ, so a change of ρ counts).
//! - A hand-over given back within [`TRIAL_STEPS`] steps did not pay (a
//!   non-stiff problem at a loose tolerance); the pair then waits for
//!   Hairer's own test before trying again.

use crate::error::Error;
use crate::methods::adaptive::{self, EmbeddedPair, Stiffness};
use crate::methods::dop853::Dop853;
use crate::methods::dopri5::Dopri5;
use crate::methods::{radau5, rodas5p};
use crate::model::{has_mass_matrix, Model};
use crate::options::Options;
use crate::solution::Solution;
use crate::step::stiffness::{Finish, NonStiffWatch, StiffnessTest};
use crate::step::Problem;

/// Steps with h·ρ above the threshold that decide the pair is held back.
pub(crate) const CONFIRMATIONS: usize = 8;
/// How many times faster than the solution itself the Jacobian's fastest
/// mode must be for a step to count as held back by it: a step of a
/// non-stiff problem changes the solution about as much as h·ρ says, one of
/// a stiff problem far less (the filter above: h·ρ ≈ 1.5 while the
/// solution moves 1 %).
const STIFFNESS_RATIO: f64 = 20.0;
/// Steps in a row that decide the stiff method is no longer ahead.
const CALM_STEPS: usize = 3;
/// A stiff stretch shorter than this was a trial that did not pay.
const TRIAL_STEPS: usize = 20;
/// The rtol from which a large system's stiff method is RODAS5P.
pub(crate) const ROSENBROCK_FROM: f64 = 5e-5;
/// The states from which a system counts as large (where a factorisation
/// outweighs the right-hand sides of a step).
pub(crate) const ROSENBROCK_STATES: usize = 64;

/// The method `Auto` hands stiff stretches to.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum StiffMethod {
    Radau5,
    Rodas5P,
}

impl StiffMethod {
    /// The stiff method for `M` at `options`' tolerance; RODAS5P at every
    /// tolerance where it would solve by GMRES, which only it does (and
    /// which beat RADAU5's sparse LU at every tolerance measured on 2-D
    /// grids, `bench --large`).
    fn for_problem<M: Model>(options: &Options) -> StiffMethod {
        let krylov = rodas5p::krylov_for::<M>(options.linear_solver);
        if krylov || (options.rtol >= ROSENBROCK_FROM && M::STATES >= ROSENBROCK_STATES) {
            StiffMethod::Rodas5P
        } else {
            StiffMethod::Radau5
        }
    }
}

/// Integrates `model` from `t0` to `t1` with the pair and the stiff
/// method in turn; a model with a singular mass matrix with RADAU5 alone.
pub(crate) fn integrate<M: Model>(
    problem: Problem<'_, M>,
    solution: Solution,
) -> Result<Solution, Error> {
    if has_mass_matrix::<M>() {
        // A singular mass matrix: only RADAU5 integrates it.
        let mut solution = solution;
        solution.stats_mut().method = "Radau5";
        return radau5::integrate(problem, solution);
    }
    let stiff = StiffMethod::for_problem::<M>(problem.options);
    if problem.options.rtol >= 1e-7 {
        switching::<M, Dopri5>(problem, 0, stiff, solution)
    } else {
        switching::<M, Dop853>(problem, 1, stiff, solution)
    }
}

/// The chain of methods that ran, for [`crate::Stats::method`].
fn chain(pair: usize, stiff: StiffMethod, segments: usize) -> &'static str {
    const ROSENBROCK_CHAINS: [[&str; 5]; 2] = [
        [
            "Dopri5",
            "Dopri5→Rodas5P",
            "Dopri5→Rodas5P→Dopri5",
            "Dopri5→Rodas5P→Dopri5→Rodas5P",
            "Dopri5⇄Rodas5P",
        ],
        [
            "Dop853",
            "Dop853→Rodas5P",
            "Dop853→Rodas5P→Dop853",
            "Dop853→Rodas5P→Dop853→Rodas5P",
            "Dop853⇄Rodas5P",
        ],
    ];
    if stiff == StiffMethod::Rodas5P {
        return ROSENBROCK_CHAINS[pair][segments.clamp(1, 5) - 1];
    }
    const CHAINS: [[&str; 5]; 2] = [
        [
            "Dopri5",
            "Dopri5→Radau5",
            "Dopri5→Radau5→Dopri5",
            "Dopri5→Radau5→Dopri5→Radau5",
            "Dopri5⇄Radau5",
        ],
        [
            "Dop853",
            "Dop853→Radau5",
            "Dop853→Radau5→Dop853",
            "Dop853→Radau5→Dop853→Radau5",
            "Dop853⇄Radau5",
        ],
    ];
    CHAINS[pair][segments.clamp(1, 5) - 1]
}

/// The cost of a stiff step over the pair's, counted in floating-point
/// operations: a right-hand side costs about one operation per non-zero of
/// its Jacobian and per state; a RADAU5 step takes about two Newton
/// iterations (three right-hand sides each, one solve with both Newton
/// matrices) plus its error estimate, and forms new matrices on 0.7 of its
/// steps (measured on Robertson, Van der Pol, HIRES and OREGO: 0.5 to 1);
/// a RODAS5P step evaluates the Jacobian, factors the real matrix alone
/// (a fifth of RADAU5's pair) and takes eight right-hand sides and eight
/// solves with it; each stage of the pair adds one right-hand side and a
/// vector update.
pub(crate) fn step_cost_ratio<M: Model, P: EmbeddedPair>(stiff: StiffMethod) -> f64 {
    let n = M::STATES as f64;
    let rhs = (M::JACOBIAN.pattern().len() as f64).max(n) + n;
    let (factorisation, solve) = radau5::newton_operations::<M>();
    let step = match stiff {
        StiffMethod::Radau5 => 7.0 * rhs + 0.7 * (factorisation + rhs) + 2.5 * solve + 40.0 * n,
        StiffMethod::Rodas5P => 9.0 * rhs + factorisation / 5.0 + 8.0 * solve / 5.0 + 8.0 * 8.0 * n,
    };
    let stages = P::STAGES as f64;
    let pair = (stages - 1.0) * rhs + stages * 2.0 * n * stages / 2.0;
    step / pair
}

fn switching<M: Model, P: EmbeddedPair>(
    problem: Problem<'_, M>,
    pair: usize,
    stiff: StiffMethod,
    mut solution: Solution,
) -> Result<Solution, Error> {
    let Problem { t0, y0, options, .. } = problem;
    let ratio = step_cost_ratio::<M, P>(stiff);
    let mut threshold = (0.1 * ratio).clamp(0.1, 0.9);
    let (mut t, mut y, mut h) = (t0, y0.to_vec(), options.initial_step);
    let mut segments = 0usize;
    // A hybrid run restarts the method at each instant: the switches of
    // the stretches before count too, a stretch that did not switch keeps
    // the chain they made, and switches in several stretches read `⇄`.
    let before = solution.stats().switches;
    // Labels the solution (or the partial one of an error) with the
    // methods so far.
    let label = |solution: &mut Solution, segments: usize| {
        let stats = solution.stats_mut();
        match (before, segments) {
            (0, _) => stats.method = chain(pair, stiff, segments),
            (_, 2..) => stats.method = chain(pair, stiff, 5),
            _ => {}
        }
        stats.switches = before + segments.saturating_sub(1);
    };
    let labelled = |result: Result<(Solution, Finish), Error>, segments: usize| match result {
        Ok((mut s, finish)) => {
            label(&mut s, segments);
            Ok((s, finish))
        }
        Err(mut e) => {
            if let Some(s) = e.partial_solution_mut() {
                label(s, segments);
            }
            Err(e)
        }
    };
    loop {
        // The explicit pair until the problem turns stiff.
        segments += 1;
        let phase = remaining(options, &solution, h);
        let test = StiffnessTest::new(threshold * P::STIFFNESS_BOUND, CONFIRMATIONS)
            .with_ratio(STIFFNESS_RATIO);
        let stretch = Problem { t0: t, y0: &y, options: &phase, ..problem };
        let result = adaptive::integrate::<M, P>(stretch, Stiffness::Switch(test), solution);
        let h_rho;
        (solution, (t, h, h_rho)) = match labelled(result, segments)? {
            (s, Finish::StiffAt { t, h, h_rho }) => (s, (t, Some(h.abs()), h_rho)),
            (s, _) => return Ok(s),
        };
        y.copy_from_slice(solution.final_state());
        // The stiff method while its steps stay well ahead of the pair's.
        segments += 1;
        let steps_before = solution.stats().steps;
        let phase = remaining(options, &solution, h);
        let watch = NonStiffWatch { below: ratio * h_rho, confirmations: CALM_STEPS };
        let stretch = Problem { t0: t, y0: &y, options: &phase, ..problem };
        let result = match stiff {
            StiffMethod::Radau5 => radau5::integrate_watching(stretch, Some(watch), solution),
            StiffMethod::Rodas5P => rodas5p::integrate_watching(stretch, Some(watch), solution),
        };
        let rho_h;
        (solution, (t, rho_h)) = match labelled(result, segments)? {
            (s, Finish::NonStiffAt { t, h }) => (s, (t, h)),
            (s, _) => return Ok(s),
        };
        if solution.stats().steps - steps_before < TRIAL_STEPS {
            // The stiff method did not pay here: wait for the pair to sit
            // at its stability boundary before trying again.
            threshold = 0.9;
        }
        h = Some(rho_h.abs());
        y.copy_from_slice(solution.final_state());
    }
}

/// The options of the next stretch: the steps left of `max_steps`, and the
/// step the last stretch ended with as the first.
fn remaining(options: &Options, solution: &Solution, h: Option<f64>) -> Options {
    let stats = solution.stats();
    let mut phase =
        options.max_steps(options.max_steps.saturating_sub(stats.steps + stats.rejected).max(1));
    if let Some(h) = h {
        phase = phase.initial_step(h);
    }
    phase
}
