//! Our side of a work-precision diagram: each method of a registered model
//! over its tolerances (or step counts), error against the reference.

use crate::{median_time, Record, Settings};
use daegen::runtime::bench::{Bench, Benchmark, Reference};
use daegen::{Method, Options, Simulate};

/// max |y − ref| / max(1, |ref|): relative where the reference is large,
/// absolute where it is small (the IVP test set's mixed error).
pub fn mixed_error(got: &[f64], reference: &[f64]) -> f64 {
    if got.len() != reference.len() {
        return f64::INFINITY;
    }
    got.iter()
        .zip(reference)
        .map(|(g, r)| {
            let e = (g - r).abs() / r.abs().max(1.0);
            if e.is_nan() {
                f64::INFINITY
            } else {
                e
            }
        })
        .fold(0.0, f64::max)
}

/// How a method is named in reports.
pub(crate) fn method_name(method: Method) -> String {
    match method {
        Method::Dopri5 => "DOPRI5".into(),
        Method::Dop853 => "DOP853".into(),
        Method::Radau5 => "RADAU5".into(),
        Method::Rodas5P => "RODAS5P".into(),
        Method::Rk4 => "RK4".into(),
        Method::Rk38 => "RK 3/8".into(),
        Method::TaylorFixed { order, .. } => format!("Taylor order {order} (fixed step)"),
        other => format!("{other:?}"),
    }
}

/// A fixed-step method with step `h`, or `None` for an adaptive one.
fn with_step(method: Method, h: f64) -> Option<Method> {
    match method {
        Method::TaylorFixed { order, .. } => Some(Method::TaylorFixed { order, step: h }),
        Method::Euler
        | Method::BackwardEuler
        | Method::Rk4
        | Method::Rk38
        | Method::Midpoint
        | Method::Heun
        | Method::Ralston => Some(method),
        _ => None,
    }
}

/// The reference values at the end time: given, or a run of another method.
pub fn reference_values<M: Benchmark>(bench: &Bench) -> Result<Vec<f64>, String> {
    match &bench.reference {
        Reference::Values(v) => Ok(v.clone()),
        Reference::Run { method, tol } => {
            let options = Options::new()
                .method(*method)
                .rtol(*tol)
                .atol(tol * bench.atol_factor)
                .dense_output(false)
                .max_steps(10_000_000);
            M::default()
                .simulate(0.0, bench.t_end, &options)
                .map(|s| s.final_state().to_vec())
                .map_err(|e| format!("the reference run ({method:?} at {tol:e}) failed: {e}"))
        }
    }
}

/// One run of ours in a sweep.
pub struct PlannedRun {
    /// The method as reports name it (`daegen DOP853`).
    pub method: String,
    /// The relative tolerance, or for a fixed-step method the step size.
    pub tol: f64,
    /// The run's options.
    pub options: Options,
}

/// The runs of a sweep of `M`: every method over its tolerances (or step
/// counts for fixed-step methods), method by method.
pub fn plan<M: Benchmark>(settings: &Settings) -> Vec<PlannedRun> {
    let bench = M::bench();
    let mut out = Vec::new();
    for &method in &bench.methods {
        let name = format!("daegen {}", method_name(method));
        match with_step(method, 1.0) {
            Some(_) => out.extend(bench.steps.iter().map(|&n| {
                let h = bench.t_end / n as f64;
                let m = with_step(method, h).unwrap_or(method);
                let options = Options::new().method(m).step(h).dense_output(false);
                PlannedRun { method: name.clone(), tol: h, options }
            })),
            None => out.extend(
                bench.tolerances.iter().filter(|&&tol| tol >= settings.tightest).map(|&tol| {
                    let options = Options::new()
                        .method(method)
                        .rtol(tol)
                        .atol(tol * bench.atol_factor)
                        .dense_output(false);
                    PlannedRun { method: name.clone(), tol, options }
                }),
            ),
        }
    }
    out
}

/// Times one planned run of `M` (median of repeats after a warm-up) and
/// measures its error against `reference`.
pub fn run_planned<M: Benchmark>(
    model: &M,
    run: &PlannedRun,
    settings: &Settings,
    reference: &[f64],
) -> Record {
    let t_end = M::bench().t_end;
    let (seconds, result) = median_time(settings, || model.simulate(0.0, t_end, &run.options));
    let (error, stats) = match &result {
        Ok(sol) => (mixed_error(sol.final_state(), reference), sol.stats()),
        Err(_) => (f64::INFINITY, Default::default()),
    };
    Record {
        problem: M::NAME.to_string(),
        method: run.method.clone(),
        tol: run.tol,
        error,
        seconds,
        steps: stats.steps,
        rejected: stats.rejected,
        rhs_evals: stats.rhs_evals,
        jacobian_evals: stats.jacobian_evals,
    }
}
