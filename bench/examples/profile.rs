//! Repeats one solve many times for `perf`: `cargo run --release --example
//! profile -- MODEL METHOD TOL [REPEATS]` (MODEL: kepler, arenstorf, oss, lorenz;
//! METHOD: taylor, taylor:ORDER (the order fixed), taylor-compact, dop853,
//! dopri5). Prints the mean time per solve, the steps and, for Kepler and
//! Arenstorf, the error at the end against the exact or periodic solution;
//! `profile -- tape MODEL` prints the model's Taylor tape and `profile --
//! orders MODEL` the order `Method::Taylor` picks at each tolerance. No
//! peers and no timing harness in the profile.

// Jorba & Zou's odd orders are unrolled too, to time ours against theirs
// (`Options::taylor_order`): their "`unroll` order is odd" warnings are
// expected here.
#![allow(deprecated)]

use daegen::prelude::*;
use std::time::Instant;

include!("../../tests/models/kepler.rs");
include!("../../tests/models/arenstorf.rs");
include!("../../tests/models/outer_solar_system.rs");
include!("../../tests/models/lorenz.rs");

// Jorba & Zou's orders and those `Method::Taylor` picks, 1e-9 … 1e-15.
kepler_model!(taylor = 1, unroll = [12, 13, 14, 15, 16, 17, 18, 19, 20, 22, 24]);
arenstorf_model!(taylor = 1, unroll = [12, 13, 14, 15, 16, 17, 18, 19, 20, 22, 24]);
outer_solar_system_model!(taylor = 1, unroll = [12, 14, 15, 16, 18, 20, 22]);
lorenz_model!([1.0, 0.0, 0.0], taylor = 1, unroll = [12, 13, 14, 15, 16, 17, 18, 19, 20, 22, 24]);

const USAGE: &str = "usage: profile MODEL METHOD TOL [REPEATS] | profile tape MODEL | profile orders MODEL \
                     (MODEL: kepler, arenstorf, oss, lorenz; METHOD: taylor, taylor:ORDER, taylor-compact, dop853, dopri5)";

/// Solves `repeats` times from 0 to `t1`, prints the timing and, when
/// `reference` is given, the largest error at `t1`.
fn run<M: Model + Clone + Send + Sync + 'static>(
    model: &M,
    t1: f64,
    reference: Option<&[f64]>,
    opts: &Options,
    repeats: usize,
) -> Result<(), String> {
    let mut last = None;
    let start = Instant::now();
    for _ in 0..repeats {
        last = Some(model.simulate(0.0, t1, opts).map_err(|e| e.to_string())?);
    }
    let sol = last.ok_or("REPEATS must be at least 1")?;
    let per = start.elapsed().as_secs_f64() / repeats as f64;
    let steps = sol.stats().steps;
    println!("{per:.3e} s per solve, {steps} steps, {:.3e} s per step", per / steps as f64);
    if let Some(reference) = reference {
        let error =
            sol.final_state().iter().zip(reference).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        println!("error at t1 {error:.2e}");
    }
    Ok(())
}

fn dump_tape<M: Model>(model: &M) {
    if let Some((ops, outs)) = model.taylor_tape() {
        for (i, op) in ops.iter().enumerate() {
            println!("u{i} = {op:?}");
        }
        println!("outputs {outs:?}");
    }
}

/// The order `Method::Taylor` picks at each tolerance if all were
/// unrolled, next to Jorba & Zou's.
fn print_orders<M: Model>(model: &M) {
    use daegen::runtime::taylor_order::{jorba_zou_order, order_to_unroll};
    for k in 3..=16 {
        let tol = 10f64.powi(-k);
        let best = order_to_unroll(model, tol).unwrap_or(0);
        println!("tol {tol:.0e}: order {best} (Jorba & Zou {})", jorba_zou_order(tol));
    }
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize| args.get(i).map(String::as_str).ok_or(USAGE);
    if arg(0)? == "tape" {
        match arg(1)? {
            "kepler" => dump_tape(&Kepler::default()),
            "arenstorf" => dump_tape(&Arenstorf::default()),
            "oss" => dump_tape(&OuterSolarSystem::default()),
            "lorenz" => dump_tape(&Lorenz::default()),
            _ => return Err(USAGE.into()),
        }
        return Ok(());
    }
    if arg(0)? == "orders" {
        match arg(1)? {
            "kepler" => print_orders(&Kepler::default()),
            "arenstorf" => print_orders(&Arenstorf::default()),
            "oss" => print_orders(&OuterSolarSystem::default()),
            "lorenz" => print_orders(&Lorenz::default()),
            _ => return Err(USAGE.into()),
        }
        return Ok(());
    }
    let tol: f64 = arg(2)?.parse().map_err(|_| USAGE)?;
    let repeats: usize = match args.get(3) {
        Some(r) => r.parse().map_err(|_| USAGE)?,
        None => 1000,
    };
    let opts = Options::new().rtol(tol).atol(tol).dense_output(false);
    let opts = match arg(1)? {
        "taylor" => opts.method(Method::Taylor),
        "taylor-compact" => opts.method(Method::Taylor).taylor_compact(true),
        m if m.starts_with("taylor:") => {
            let order = m["taylor:".len()..].parse().map_err(|_| USAGE)?;
            opts.method(Method::Taylor).taylor_order(order)
        }
        "dop853" => opts.method(Method::Dop853),
        "dopri5" => opts.method(Method::Dopri5),
        _ => return Err(USAGE.into()),
    };
    match arg(0)? {
        "kepler" => {
            let t1 = 20.0 * std::f64::consts::PI;
            let exact = kepler_exact(t1);
            run(&Kepler::default(), t1, Some(&exact), &opts, repeats)
        }
        "arenstorf" => run(&Arenstorf::default(), ARENSTORF_T, Some(&ARENSTORF_Y0), &opts, repeats),
        "oss" => run(&OuterSolarSystem::default(), 20000.0, None, &opts, repeats),
        "lorenz" => run(&Lorenz::default(), 20.0, Some(&LORENZ_AT_20), &opts, repeats),
        _ => Err(USAGE.into()),
    }
}
