//! Monte Carlo over an uncertain throw: ten thousand projectiles with
//! quadratic air drag, each with its own drag coefficient, launch speed and
//! angle, run as an ensemble on every core, or as one shard of it on one
//! machine of many, with a merge step that puts the shards back together.
//!
//! Member i draws its drag c, speed and angle from fixed pseudo-random
//! sequences (the same members on every machine) around c = 0.005 1/m,
//! 50 m/s and 0.7 rad; each run stops where the projectile lands (a
//! terminal event). The distribution of the range is printed.
//!
//! Run:
//!
//! ```text
//! cargo run --release --example ensemble                     # every member, every core
//! cargo run --release --example ensemble -- --shard 0/4 --out shard0.csv
//! cargo run --release --example ensemble -- merge --out all.csv shard0.csv shard1.csv shard2.csv shard3.csv
//! ```
//!
//! Options: `--members N` (10000), `--threads K` (every core),
//! `--method dopri5|dop853` (dopri5), `--tolerance TOL` (1e-8),
//! `--shard i/n`, `--out FILE` (the final states as CSV). The guide's
//! chapter on ensembles spreads the shards with a Slurm array job or a
//! Kubernetes indexed Job.

use daegen::prelude::*;
use daegen::{Ensemble, FinalStates, Shard};
use std::time::Instant;

/// A point mass thrown from 1.5 m, slowed by air drag ∝ speed²
/// (c = ρ C_d A / 2m), until it lands.
#[dae_model]
fn projectile() {
    /// Drag over mass (1/m).
    let c = param(0.005);
    /// Launch speed (m/s).
    let speed = param(50.0);
    /// Launch angle above the horizontal (rad).
    let angle = param(0.7);
    let g = param(9.81);
    let x = state(0.0);
    let y = state(1.5);
    let u = state(speed * cos(angle));
    let v = state(speed * sin(angle));
    let w = sqrt(u * u + v * v);
    der(x) == u;
    der(y) == v;
    der(u) == -c * w * u;
    der(v) == -g - c * w * v;
    /// It lands.
    let landing = event(y).falling().terminal();
}

/// u in [0, 1) from SplitMix64 of `k` (Steele, Lea and Flood 2014), the
/// same on every machine.
fn uniform(k: u64) -> f64 {
    let mut z = k.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// Member i's throw: drag ±40 %, speed ±2 m/s, angle ±0.05 rad.
fn throw(i: usize) -> Projectile {
    let draw = |k: u64| 2.0 * uniform(3 * i as u64 + k) - 1.0;
    Projectile {
        c: 0.005 * (1.0 + 0.4 * draw(0)),
        speed: 50.0 + 2.0 * draw(1),
        angle: 0.7 + 0.05 * draw(2),
        ..Projectile::default()
    }
}

/// What the command line asked for.
struct Request {
    members: usize,
    threads: usize,
    method: Method,
    tolerance: f64,
    shard: Option<Shard>,
    out: Option<String>,
    merge: Vec<String>,
}

fn parse(args: &[String]) -> Result<Request, String> {
    let mut request = Request {
        members: 10_000,
        threads: 0,
        method: Method::Dopri5,
        tolerance: 1e-8,
        shard: None,
        out: None,
        merge: Vec::new(),
    };
    let mut merging = false;
    let mut k = 0;
    while k < args.len() {
        let value = || args.get(k + 1).cloned().ok_or(format!("{} needs a value", args[k]));
        match args[k].as_str() {
            "merge" if k == 0 => merging = true,
            "--members" => {
                request.members = value()?.parse().map_err(|e| format!("--members: {e}"))?
            }
            "--threads" => {
                request.threads = value()?.parse().map_err(|e| format!("--threads: {e}"))?
            }
            "--tolerance" => {
                request.tolerance = value()?.parse().map_err(|e| format!("--tolerance: {e}"))?
            }
            "--method" => {
                request.method = match value()?.as_str() {
                    "dopri5" => Method::Dopri5,
                    "dop853" => Method::Dop853,
                    other => return Err(format!("--method: `{other}`; write dopri5 or dop853")),
                }
            }
            "--shard" => request.shard = Some(Shard::parse(&value()?).map_err(|e| e.to_string())?),
            "--out" => request.out = Some(value()?),
            file if merging && !file.starts_with("--") => {
                request.merge.push(file.to_string());
                k += 1;
                continue;
            }
            other => return Err(format!("unknown argument `{other}`")),
        }
        k += if k == 0 && merging { 1 } else { 2 };
    }
    Ok(request)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Err(e) = parse(&args).map_err(|e| e.into()).and_then(|request| run(&request)) {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run(request: &Request) -> Result<(), Box<dyn std::error::Error>> {
    if !request.merge.is_empty() {
        let parts: Result<Vec<_>, _> = request.merge.iter().map(FinalStates::read_csv).collect();
        let merged = FinalStates::merge(parts?, request.members)?;
        println!("merged {} shards: {} members", request.merge.len(), merged.rows.len());
        report(&merged);
        if let Some(out) = &request.out {
            merged.write_csv(out)?;
            println!("wrote {out}");
        }
        return Ok(());
    }
    let mut ensemble =
        Ensemble::new(request.members, throw).threads(request.threads).progress(true);
    if let Some(shard) = request.shard {
        ensemble = ensemble.shard(shard);
    }
    let members = ensemble.members();
    println!(
        "throws {}..{} of {}, drag, speed and angle uncertain, {:?} at tol {:e}",
        members.start, members.end, request.members, request.method, request.tolerance
    );
    let options = Options::new().method(request.method).tolerance(request.tolerance);
    let started = Instant::now();
    // Every throw lands before t = 20 s; the landing event ends the run.
    let finals = ensemble.final_states(0.0, 20.0, &options);
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "{} members in {seconds:.2} s: {:.0} members/s",
        finals.rows.len(),
        finals.rows.len() as f64 / seconds
    );
    report(&finals);
    if let Some(out) = &request.out {
        finals.write_csv(out)?;
        println!("wrote {out}");
    }
    Ok(())
}

/// The members that failed, and the distribution of the range.
fn report(finals: &FinalStates) {
    for (member, message) in finals.errors() {
        println!("member {member} failed: {message}");
    }
    let landed: Vec<&Vec<f64>> = finals.rows.iter().filter_map(|r| r.state.as_ref().ok()).collect();
    // Each run ends at its landing: y = 0 there, to the event's accuracy.
    let highest = landed.iter().map(|y| y[1].abs()).fold(0.0, f64::max);
    let mut range: Vec<f64> = landed.iter().map(|y| y[0]).collect();
    range.sort_by(f64::total_cmp);
    let n = range.len();
    if n == 0 {
        return;
    }
    let mean = range.iter().sum::<f64>() / n as f64;
    let sd = (range.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
    let at = |q: f64| range[((n - 1) as f64 * q).round() as usize];
    println!("{n} throws landed (|y| at landing ≤ {highest:.1e} m)");
    println!(
        "range: mean {mean:.2} m, sd {sd:.2} m; 5 % {:.2} m, median {:.2} m, 95 % {:.2} m",
        at(0.05),
        at(0.5),
        at(0.95)
    );
}
