//! Ten thousand Kepler orbits with random eccentricities, run as an
//! ensemble on every core, or as one shard of it on one machine of many,
//! with a merge step that puts the shards back together.
//!
//! Each member is an orbit of semi-major axis 1 started at its pericentre,
//! with its eccentricity drawn from [0, 0.9) (a fixed pseudo-random
//! sequence: the same members on every machine). Each run ends at t = 20π
//! (ten orbits); its energy error against the exact −1/2 is printed.
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
//! `--method taylor|dop853` (taylor), `--tolerance TOL` (1e-12),
//! `--shard i/n`, `--out FILE` (the final states as CSV). The guide's
//! chapter on ensembles spreads the shards with a Slurm array job or a
//! Kubernetes indexed Job.

use daegen::prelude::*;
use daegen::{Ensemble, FinalStates, Shard};
use std::f64::consts::PI;
use std::time::Instant;

/// The two-body problem in the plane, in units where the period is 2π,
/// started at the pericentre of an orbit of eccentricity e.
#[dae_model(taylor = 1)]
fn kepler() {
    /// Eccentricity.
    let e = param(0.5);
    let q1 = state(1.0 - e);
    let q2 = state(0.0);
    let p1 = state(0.0);
    let p2 = state(sqrt((1.0 + e) / (1.0 - e)));
    let r3 = (q1 * q1 + q2 * q2).powf(-1.5);
    der(q1) == p1;
    der(q2) == p2;
    der(p1) == -q1 * r3;
    der(p2) == -q2 * r3;
}

/// Member i's eccentricity in [0, 0.9): SplitMix64 of i (Steele, Lea and
/// Flood 2014), the same on every machine.
fn eccentricity(i: usize) -> f64 {
    let mut z = (i as u64).wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    0.9 * (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The energy ½|p|² − 1/|q| of a final state.
fn energy(y: &[f64]) -> f64 {
    0.5 * (y[2] * y[2] + y[3] * y[3]) - (y[0] * y[0] + y[1] * y[1]).powf(-0.5)
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
        method: Method::Taylor,
        tolerance: 1e-12,
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
                    "taylor" => Method::Taylor,
                    "dop853" => Method::Dop853,
                    other => return Err(format!("--method: `{other}`; write taylor or dop853")),
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
    let mut ensemble = Ensemble::new(request.members, |i| Kepler { e: eccentricity(i) })
        .threads(request.threads)
        .progress(true);
    if let Some(shard) = request.shard {
        ensemble = ensemble.shard(shard);
    }
    let members = ensemble.members();
    println!(
        "Kepler orbits {}..{} of {}, e in [0, 0.9), t = 20π, {:?} at tol {:e}",
        members.start, members.end, request.members, request.method, request.tolerance
    );
    let options = Options::new().method(request.method).tolerance(request.tolerance);
    let started = Instant::now();
    let finals = ensemble.final_states(0.0, 20.0 * PI, &options);
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

/// The members that failed, and the largest and median energy errors.
fn report(finals: &FinalStates) {
    let mut errors: Vec<f64> = finals
        .rows
        .iter()
        .filter_map(|r| r.state.as_ref().ok())
        .map(|y| (energy(y) + 0.5).abs())
        .collect();
    errors.sort_by(f64::total_cmp);
    for (member, message) in finals.errors() {
        println!("member {member} failed: {message}");
    }
    if let (Some(median), Some(max)) = (errors.get(errors.len() / 2), errors.last()) {
        println!("energy error |E + 1/2|: median {median:.1e}, largest {max:.1e}");
    }
}
