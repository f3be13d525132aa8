//! Repeats one solve many times for `perf`: `cargo run --release --example
//! profile -- MODEL METHOD TOL [REPEATS]` (MODEL: kepler, arenstorf, oss;
//! METHOD: taylor, taylor-compact, dop853, dopri5). Prints the mean time per
//! solve and the steps; no peers, no timing harness in the profile.

use daegen::prelude::*;
use std::time::Instant;

include!("../../tests/models/kepler.rs");
include!("../../tests/models/arenstorf.rs");
include!("../../tests/models/outer_solar_system.rs");

kepler_model!(
    taylor = 1,
    unroll = [5, 6, 7, 8, 10, 11, 12, 13, 14, 15, 16, 18]
);
arenstorf_model!(
    taylor = 1,
    unroll = [5, 6, 7, 8, 10, 11, 12, 13, 14, 15, 16, 18]
);
outer_solar_system_model!(taylor = 1, unroll = [12, 13, 14, 15, 16, 18]);

fn run<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t1: f64,
    opts: &Options,
    repeats: usize,
) -> Vec<f64> {
    let mut last = Vec::new();
    let mut steps = 0;
    let start = Instant::now();
    for _ in 0..repeats {
        let sol = model.simulate(0.0, t1, opts).expect("solve");
        steps = sol.stats().steps;
        last = sol.final_state().to_vec();
    }
    let per = start.elapsed().as_secs_f64() / repeats as f64;
    println!(
        "{:.3e} s per solve, {steps} steps, {:.3e} s per step",
        per,
        per / steps as f64
    );
    last
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args[1] == "tape" {
        return match args[2].as_str() {
            "arenstorf" => dump_tape(&Arenstorf::default()),
            "kepler" => dump_tape(&Kepler::default()),
            _ => dump_tape(&OuterSolarSystem::default()),
        };
    }
    let (model, method, tol) = (&args[1], &args[2], args[3].parse::<f64>().unwrap());
    let repeats = args.get(4).map_or(1000, |r| r.parse().unwrap());
    let mut opts = Options::new().rtol(tol).atol(tol).dense_output(false);
    opts = match method.as_str() {
        "taylor" => opts.method(Method::Taylor),
        "taylor-compact" => opts.method(Method::Taylor).taylor_compact(true),
        "dop853" => opts.method(Method::Dop853),
        "dopri5" => opts.method(Method::Dopri5),
        other => panic!("unknown method {other}"),
    };
    match model.as_str() {
        "kepler" => {
            let t1 = 20.0 * std::f64::consts::PI;
            let y = run(&Kepler::default(), t1, &opts, repeats);
            let exact = kepler_exact(t1);
            let error = y
                .iter()
                .zip(exact)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            println!("error at t1 {error:.2e}");
        }
        "arenstorf" => {
            let y = run(&Arenstorf::default(), ARENSTORF_T, &opts, repeats);
            let error = y
                .iter()
                .zip(ARENSTORF_Y0)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            println!("error at t1 {error:.2e}");
        }
        "oss" => {
            run(&OuterSolarSystem::default(), 20000.0, &opts, repeats);
        }
        other => panic!("unknown model {other}"),
    }
}

#[allow(dead_code)]
fn dump_tape<M: Model>(model: &M) {
    if let Some((ops, outs)) = model.taylor_tape() {
        for (i, op) in ops.iter().enumerate() {
            println!("u{i} = {op:?}");
        }
        println!("outputs {outs:?}");
    }
}
