//! The cases of the step-loop measurement (bench `--loop`): the models,
//! the options of each case, one run and one batch of right-hand-side
//! evaluations.

use crate::{allocations_so_far, Arenstorf, Lorenz, ARENSTORF_T};
use daegen::prelude::*;

/// Lorenz with an event watched that never fires (z stays below 60).
#[dae_model]
fn lorenz_watched() {
    let sigma = param(10.0);
    let r = param(28.0);
    let b = param(8.0 / 3.0);
    let x = state(1.0);
    let y = state(0.0);
    let z = state(0.0);
    der(x) == sigma * (y - x);
    der(y) == x * (r - z) - y;
    der(z) == x * y - b * z;
    /// Never reached: the attractor stays below z = 50.
    let far = event(z - 1000.0);
}

/// The method a name on the command line stands for.
pub fn method(name: &str) -> Method {
    match name {
        "Dop853" => Method::Dop853,
        "Taylor" => Method::Taylor,
        "Radau5" => Method::Radau5,
        "Rodas5P" => Method::Rodas5P,
        _ => Method::Dopri5,
    }
}

/// The options of `case` for `method` at `tol` over `[0, t1]`.
fn options(case: &str, method: Method, tol: f64) -> Options {
    let base = Options::new().method(method).tolerance(tol);
    let least = base.stiffness_detection(false).dense_output(false).keep_every(usize::MAX);
    match case {
        "least" => least,
        "stiffness test" => least.stiffness_detection(true),
        "every step kept" => least.stiffness_detection(true).keep_every(1),
        // `Options::new()`'s own: the stiffness test, every step kept with
        // its dense output.
        _ => base,
    }
}

/// The problems: name, end time.
const PROBLEMS: [(&str, f64); 2] = [("lorenz", 20.0), ("arenstorf", ARENSTORF_T)];

/// One run of `case` on `problem` over `spans` times its interval:
/// (steps, evaluations, allocations).
pub fn run(
    problem: &str,
    method: Method,
    case: &str,
    tol: f64,
    spans: f64,
) -> (usize, usize, usize) {
    let t1 = spans * PROBLEMS.iter().find(|p| p.0 == problem).map_or(1.0, |p| p.1);
    if case == "ode_solvers" {
        return match problem {
            "lorenz" => peer::<Lorenz, 3>(method, tol, t1),
            _ => peer::<Arenstorf, 4>(method, tol, t1),
        };
    }
    let opts = options(case, method, tol);
    let before = allocations_so_far();
    let sol = match (problem, case) {
        ("lorenz", "event") => LorenzWatched::default().simulate(0.0, t1, &opts),
        ("lorenz", _) => Lorenz::default().simulate(0.0, t1, &opts),
        _ => Arenstorf::default().simulate(0.0, t1, &opts),
    };
    let allocations = allocations_so_far() - before;
    let sol = sol.expect("the run");
    let s = sol.stats();
    (s.steps + s.rejected, s.rhs_evals, allocations)
}

/// The model's generated right-hand side as an `ode_solvers` system.
struct Peered<M>(M);

impl<M: Model, const N: usize> ode_solvers::System<f64, ode_solvers::SVector<f64, N>>
    for Peered<M>
{
    fn system(
        &self,
        t: f64,
        y: &ode_solvers::SVector<f64, N>,
        dy: &mut ode_solvers::SVector<f64, N>,
    ) {
        let _ = self.0.rhs(t, y.as_slice(), dy.as_mut_slice());
    }
}

/// One run of `ode_solvers`' pair on the same right-hand side, set up as
/// the sweep sets it up (every step kept, Hairer's controllers, the
/// stiffness test every 1000 steps): (steps, evaluations, allocations).
fn peer<M: Model + Default, const N: usize>(
    method: Method,
    tol: f64,
    t1: f64,
) -> (usize, usize, usize) {
    let mut y = [0.0; N];
    M::default().initial_state(&mut y);
    let y0 = ode_solvers::SVector::<f64, N>::from_column_slice(&y);
    let sparse = ode_solvers::OutputType::Sparse;
    let before = allocations_so_far();
    // Hairer's controller constants of each pair, as the sweep gives them.
    macro_rules! integrate {
        ($pair:ident, $beta:expr, $min:expr, $max:expr) => {{
            let system = Peered(M::default());
            let (maxn, nstiff) = (10_000_000, 1000);
            let mut s = ode_solvers::$pair::from_param(
                system, 0.0, t1, t1, y0, tol, tol, 0.9, $beta, $min, $max, t1, 0.0, maxn, nstiff,
                sparse,
            );
            s.integrate().expect("the run")
        }};
    }
    let stats = if method == Method::Dop853 {
        integrate!(Dop853, 0.0, 0.333, 6.0)
    } else {
        integrate!(Dopri5, 0.04, 0.2, 10.0)
    };
    let allocations = allocations_so_far() - before;
    (
        stats.accepted_steps as usize + stats.rejected_steps as usize,
        stats.num_eval as usize,
        allocations,
    )
}

/// `reps` evaluations of `problem`'s right-hand side at its start.
pub fn evaluations(problem: &str, reps: usize) -> f64 {
    fn many<M: Model + Default>(reps: usize) -> f64 {
        let m = M::default();
        let mut y = vec![0.0; M::STATES];
        m.initial_state(&mut y);
        let mut dy = vec![0.0; M::STATES];
        let mut acc = 0.0;
        for k in 0..reps {
            y[0] += 1e-300 * k as f64;
            let _ = m.rhs(0.0, std::hint::black_box(&y), &mut dy);
            acc += dy[0];
        }
        acc
    }
    match problem {
        "lorenz" => many::<Lorenz>(reps),
        _ => many::<Arenstorf>(reps),
    }
}

/// `reps` evaluations of `problem`'s right-hand side one after another,
/// each at `y + h k` from the one before: what a stage costs at the least
/// (its evaluation's latency and one product and sum), the floor of an
/// explicit pair's step.
pub fn chained_evaluations(problem: &str, reps: usize) -> f64 {
    fn chain<M: Model + Default>(reps: usize) -> f64 {
        let m = M::default();
        let mut y = vec![0.0; M::STATES];
        m.initial_state(&mut y);
        let y0 = y.clone();
        let mut k = vec![0.0; M::STATES];
        let h = std::hint::black_box(1e-9);
        for _ in 0..reps {
            let _ = m.rhs(0.0, &y, &mut k);
            for ((s, y0), k) in y.iter_mut().zip(&y0).zip(&k) {
                *s = y0 + h * k;
            }
        }
        y[0]
    }
    match problem {
        "lorenz" => chain::<Lorenz>(reps),
        _ => chain::<Arenstorf>(reps),
    }
}

/// `PROBLEM METHOD CASE TOL REPS` (or `PROBLEM rhs - - REPS`): what
/// callgrind counts.
pub fn loop_one(args: &[String]) {
    let reps: usize = args[4].parse().unwrap_or(1);
    if args[1] == "rhs" {
        std::hint::black_box(evaluations(&args[0], reps));
        return;
    }
    let method = method(&args[1]);
    let tol: f64 = args[3].parse().unwrap_or(1e-6);
    for _ in 0..reps {
        std::hint::black_box(run(&args[0], method, &args[2], tol, 1.0));
    }
}
