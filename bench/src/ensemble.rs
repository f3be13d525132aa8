//! Ensembles: throughput (members per second) of `daegen::Ensemble` on one
//! thread and on every core, against heyoka's `ensemble_propagate_until`
//! (scalar, and in its SIMD batch mode) on the same members through the
//! benchmark's own driver, `bench/peers/ensemble.py`.
//!
//! Kepler: 10⁴ orbits of semi-major axis 1 from their pericentres, the
//! eccentricity of member i 0.9·u_i with u_i from SplitMix64 of i (as
//! `examples/ensemble.rs` draws it), to t = 20π (ten orbits), by Taylor and
//! DOP853 at tol 1e-12. Robertson: 10³ runs with each rate constant scaled
//! by 1 + 0.2 (u − ½), to t = 10⁵, by RADAU5 at rtol 1e-8 (atol 1e-14);
//! heyoka has no stiff method. Times are the fastest of three runs.

use crate::*;
use daegen::Ensemble;

// Robertson's kinetics with its rate constants as parameters is the
// tests' `robertson_rates_model!` (main.rs).

/// u in [0, 1) from SplitMix64 of `i` (Steele, Lea and Flood 2014).
fn uniform(i: u64) -> f64 {
    let mut z = i.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The energy error |E + ½| of a Kepler final state (E = −½ for a = 1).
fn energy_error(y: &[f64]) -> f64 {
    (0.5 * (y[2] * y[2] + y[3] * y[3]) - (y[0] * y[0] + y[1] * y[1]).powf(-0.5) + 0.5).abs()
}

/// One ensemble timed on one thread and on every core.
struct Row {
    what: String,
    members: usize,
    one_thread: f64,
    all_threads: f64,
    /// Median and largest energy error (Kepler), or failures (Robertson).
    accuracy: String,
}

/// The fastest of three runs of `run`, and its last answer.
fn fastest<T>(mut run: impl FnMut() -> T) -> (f64, T) {
    let started = Instant::now();
    let mut answer = run();
    let mut best = started.elapsed().as_secs_f64();
    for _ in 0..2 {
        let started = Instant::now();
        answer = run();
        best = best.min(started.elapsed().as_secs_f64());
    }
    (best, answer)
}

fn kepler_row(method: Method, members: usize, cores: usize) -> Row {
    let opts = Options::new().method(method).tolerance(1e-12);
    let ensemble = |threads| {
        Ensemble::new(members, |i| Kepler { e: 0.9 * uniform(i as u64), ..Kepler::default() })
            .threads(threads)
    };
    let t1 = 20.0 * std::f64::consts::PI;
    let (one_thread, _) = fastest(|| ensemble(1).final_states(0.0, t1, &opts));
    let (all_threads, finals) = fastest(|| ensemble(cores).final_states(0.0, t1, &opts));
    let mut errors: Vec<f64> =
        finals.rows.iter().filter_map(|r| r.state.as_ref().ok()).map(|y| energy_error(y)).collect();
    errors.sort_by(f64::total_cmp);
    let failed = members - errors.len();
    Row {
        what: format!("Kepler, {method:?} at 1e-12"),
        members,
        one_thread,
        all_threads,
        accuracy: format!(
            "|E + ½|: median {:.1e}, largest {:.1e}{}",
            errors[errors.len() / 2],
            errors[errors.len() - 1],
            if failed > 0 { format!(", {failed} failed") } else { String::new() }
        ),
    }
}

fn robertson_row(members: usize, cores: usize) -> Row {
    let opts = Options::new().method(Method::Radau5).rtol(1e-8).atol(1e-14);
    let scaled =
        |i: usize, k: u64, base: f64| base * (1.0 + 0.2 * (uniform(3 * i as u64 + k) - 0.5));
    let ensemble = |threads| {
        Ensemble::new(members, move |i| RobertsonRates {
            k1: scaled(i, 0, 0.04),
            k2: scaled(i, 1, 3e7),
            k3: scaled(i, 2, 1e4),
        })
        .threads(threads)
    };
    let (one_thread, _) = fastest(|| ensemble(1).final_states(0.0, 1e5, &opts));
    let (all_threads, finals) = fastest(|| ensemble(cores).final_states(0.0, 1e5, &opts));
    // Mass is conserved: y1 + y2 + y3 = 1.
    let drift = finals
        .rows
        .iter()
        .filter_map(|r| r.state.as_ref().ok())
        .map(|y| (y[0] + y[1] + y[2] - 1.0).abs())
        .fold(0.0, f64::max);
    Row {
        what: "Robertson ±10 % rates, Radau5 at 1e-8".into(),
        members,
        one_thread,
        all_threads,
        accuracy: format!("|y1 + y2 + y3 − 1| ≤ {drift:.1e}, {} failed", finals.errors().count()),
    }
}

/// `method` at 1e-12 on `members` Kepler orbits with eccentricities
/// `e(i)`: scalar runs, batches of four and of eight on one thread, and
/// batches of eight on `cores` threads; for Taylor, the scalar runs also
/// with the straight-line jets `#[dae_model(unroll = [..])]` emits (the
/// batches interpret their tapes on lanes). (seconds, largest energy
/// error) of each.
fn batch_rows(
    method: Method,
    members: usize,
    e: &(dyn Fn(usize) -> f64 + Sync),
    cores: usize,
) -> Vec<(f64, f64)> {
    let opts = Options::new().method(method).tolerance(1e-12);
    let t1 = 20.0 * std::f64::consts::PI;
    let worst = |f: &daegen::FinalStates| {
        f.rows
            .iter()
            .filter_map(|r| r.state.as_ref().ok())
            .map(|y| energy_error(y))
            .fold(0.0, f64::max)
    };
    let (scalar, f1) = fastest(|| {
        Ensemble::new(members, |i| KeplerFour { e: e(i) }).threads(1).final_states(0.0, t1, &opts)
    });
    let (four, f4) = fastest(|| {
        Ensemble::new(members, |i| KeplerFour { e: e(i) })
            .threads(1)
            .final_states_batched::<KeplerFourBatch>(0.0, t1, &opts)
    });
    let (eight, f8) = fastest(|| {
        Ensemble::new(members, |i| KeplerEight { e: e(i) })
            .threads(1)
            .final_states_batched::<KeplerEightBatch>(0.0, t1, &opts)
    });
    let (both, fb) = fastest(|| {
        Ensemble::new(members, |i| KeplerEight { e: e(i) })
            .threads(cores)
            .final_states_batched::<KeplerEightBatch>(0.0, t1, &opts)
    });
    let mut rows =
        vec![(scalar, worst(&f1)), (four, worst(&f4)), (eight, worst(&f8)), (both, worst(&fb))];
    if method == Method::Taylor {
        let (unrolled, fu) = fastest(|| {
            Ensemble::new(members, |i| Kepler { e: e(i) }).threads(1).final_states(0.0, t1, &opts)
        });
        rows.push((unrolled, worst(&fu)));
    }
    rows
}

/// heyoka's ensemble through bench/peers/ensemble.py: (solve seconds,
/// median energy error, largest), or why not.
fn heyoka(members: usize, workers: usize, batch: usize) -> Result<(f64, f64, f64), String> {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/peers/ensemble.py");
    let out = Command::new("python3")
        .arg(script)
        .args(["--members", &members.to_string(), "--workers", &workers.to_string()])
        .args(["--batch", &batch.to_string(), "--tol", "1e-12"])
        .output()
        .map_err(|e| format!("python3 not found: {e}"))?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        return Err(format!("not run: {}", stderr.lines().last().unwrap_or("").trim()));
    }
    let json = String::from_utf8_lossy(&out.stdout);
    let field = |name: &str| -> Option<f64> {
        let at = json.find(&format!("\"{name}\": "))? + name.len() + 4;
        json[at..].split([',', '}']).next()?.trim().parse().ok()
    };
    match (field("solve_s"), field("median_energy_error"), field("max_energy_error")) {
        (Some(s), Some(m), Some(x)) => Ok((s, m, x)),
        _ => Err(format!("unreadable output: {json}")),
    }
}

/// Writes results/ensemble.md.
pub fn ensemble_section() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let kepler_members = 10_000;
    eprintln!("ensemble: Kepler, Taylor");
    let mut rows = vec![kepler_row(Method::Taylor, kepler_members, cores)];
    eprintln!("ensemble: Kepler, DOP853");
    rows.push(kepler_row(Method::Dop853, kepler_members, cores));
    eprintln!("ensemble: Robertson, Radau5");
    rows.push(robertson_row(1000, cores));
    let mut text = format!(
        "# Ensembles\n\nMachine: {}. Written by `cd bench && cargo run --release -- --ensemble` (bench/src/ensemble.rs). Throughput in members per second, the fastest of three runs; speed-up: one thread's time over {cores} threads'.\n\n| ensemble | members | 1 thread | {cores} threads | speed-up | accuracy |\n|---|---|---|---|---|---|\n",
        machine()
    );
    for r in &rows {
        text.push_str(&format!(
            "| {} | {} | {:.2} s ({:.0}/s) | {:.2} s ({:.0}/s) | {:.2}× | {} |\n",
            r.what,
            r.members,
            r.one_thread,
            r.members as f64 / r.one_thread,
            r.all_threads,
            r.members as f64 / r.all_threads,
            r.one_thread / r.all_threads,
            r.accuracy
        ));
    }
    text.push_str(&format!(
        "\n## Against heyoka\n\nThe same {kepler_members} Kepler members by heyoka's `ensemble_propagate_until` (Python, `algorithm=\"thread\"`, `max_workers` workers; its batch mode by `ensemble_propagate_until_batch` with `taylor_adaptive_batch`), tol 1e-12, through `bench/peers/ensemble.py`. Ratio: daegen's Taylor ensemble time over heyoka's at the same thread count (below 1: daegen faster).\n\n| heyoka | workers | time | members/s | \\|E + ½\\| median, largest | daegen Taylor / heyoka |\n|---|---|---|---|---|---|\n"
    ));
    let ours = [(1, rows[0].one_thread), (cores, rows[0].all_threads)];
    for batch in [1, 4, 8] {
        for &(workers, our_time) in &ours {
            eprintln!("ensemble: heyoka, batch {batch}, {workers} workers");
            let label = if batch == 1 { "scalar".to_string() } else { format!("batch of {batch}") };
            match heyoka(kepler_members, workers, batch) {
                Ok((seconds, median, max)) => text.push_str(&format!(
                    "| {label} | {workers} | {seconds:.2} s | {:.0} | {median:.1e}, {max:.1e} | {:.2} |\n",
                    kepler_members as f64 / seconds,
                    our_time / seconds
                )),
                Err(why) => text.push_str(&format!("| {label} | {workers} | {why} | | | |\n")),
            }
        }
    }
    text.push_str(&format!("\n## Batch lanes\n\n`#[dae_model(batch = L)]` steps L members together with one step size, each lane's error measured alone: DOP853 computes the right-hand side on `Lanes<L>` values (SIMD where the target has it), Taylor runs the members' tapes as one tape whose coefficients are lanes. Tol 1e-12 on one thread, 10⁴ Kepler orbits to t = 20π: members alike (e in [0.5, 0.51)) and members unlike (e in [0, 0.9)), where a batch takes the steps of its most eccentric member. Ratio: scalar time on one thread over batch time (above 1: the batch pays); the batch-of-8 column on {cores} threads adds every core. Taylor's scalar runs interpret the same tape; the last column is the scalar run with the straight-line jets `unroll` emits, against the batch of 8 on one thread.\n\n| method | members | scalar | batch of 4 | batch of 8 | batch of 8, {cores} threads | largest \\|E + ½\\| scalar, 4, 8 | scalar unrolled (batch of 8 over it) |\n|---|---|---|---|---|---|---|---|\n"));
    let alike = |i: usize| 0.5 + 0.01 * uniform(i as u64);
    let unlike = |i: usize| 0.9 * uniform(i as u64);
    let spreads: [(&str, &(dyn Fn(usize) -> f64 + Sync)); 2] =
        [("alike, e in [0.5, 0.51)", &alike), ("unlike, e in [0, 0.9)", &unlike)];
    for method in [Method::Dop853, Method::Taylor] {
        for (label, e) in spreads {
            eprintln!("ensemble: batch lanes, {method:?}, members {label}");
            let rows = batch_rows(method, kepler_members, e, cores);
            let [(s, es), (f, ef), (e8, ee), (b, _)] = [rows[0], rows[1], rows[2], rows[3]];
            let unrolled =
                rows.get(4).map_or("".to_string(), |&(u, _)| format!("{u:.2} s ({:.2}×)", u / e8));
            text.push_str(&format!(
                "| {method:?} | {label} | {s:.2} s | {f:.2} s ({:.2}×) | {e8:.2} s ({:.2}×) | {b:.2} s ({:.2}×) | {es:.1e}, {ef:.1e}, {ee:.1e} | {unrolled} |\n",
                s / f,
                s / e8,
                s / b
            ));
        }
    }
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/ensemble.md");
    if let Err(e) = std::fs::write(&path, &text) {
        eprintln!("cannot write {}: {e}", path.display());
    }
    print!("{text}");
}
