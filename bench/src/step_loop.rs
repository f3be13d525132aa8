//! The explicit pairs' step loop (`--loop`): what a step costs beyond its
//! right-hand-side evaluations, on problems whose right-hand side is cheap
//! (Lorenz, 3 states; Arenstorf, 4), for DOPRI5 and DOP853 with each
//! feature of a run added in turn: the least loop (no stiffness test, no
//! dense output, only the last step kept), Hairer's stiffness test, every
//! step stored, the dense output (which makes the options a user gets by
//! default), and an event watched (one that never fires).
//!
//! Measured by `loop-subject` (bench/loop-subject: the cases of
//! `loop-subject/src/cases.rs` as a binary of their own, built for AVX2 at most
//! so that valgrind can run it): time, the median of repeated runs on this
//! shared machine, and instructions, `valgrind --tool=callgrind`,
//! repeatable to the instruction, from the difference of three runs and
//! one. Per step, the loop's own share is the step's cost less
//! (evaluations per step × one evaluation's cost). Heap allocations per
//! step are counted by the subject's allocator. The same cases run
//! `ode_solvers`' pairs on the same generated right-hand side (`ode_solvers`
//! rows), and the floor of a step is its evaluations one after another,
//! each at `y + h k` of the one before (`chained`): what no loop can beat
//! where the right-hand side's latency sets the pace. A second table times
//! ours against `ode_solvers` in alternation at three tolerances. A third
//! sets the Taylor method's step, in cycles, against the arithmetic of
//! its recurrences counted in the generated code. Writes
//! `results/step_loop.md`.

use super::*;

/// The cases, as `loop-subject/src/cases.rs` names them.
const CASES: [&str; 6] =
    ["least", "stiffness test", "every step kept", "dense output", "event", "ode_solvers"];

/// The problems.
const PROBLEMS: [&str; 2] = ["lorenz", "arenstorf"];

/// `loop-subject`, built on first use.
fn subject() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("loop-subject");
    let built = Command::new("cargo")
        .args(["build", "--release", "--quiet"])
        .current_dir(&dir)
        .status()
        .ok()?;
    built.success().then(|| dir.join("target/release/loop-subject"))
}

/// What the subject prints for `args`, as numbers.
fn subject_numbers(subject: &Path, args: &[&str]) -> Option<Vec<f64>> {
    let out = Command::new(subject).args(args).output().ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    text.split_whitespace().map(|w| w.parse().ok()).collect()
}

/// Instructions callgrind counts for the subject's `count args`, or `None`
/// without valgrind.
fn instructions(subject: &Path, args: &[&str]) -> Option<f64> {
    let out = std::env::temp_dir().join(format!("daegen-loop-{}.callgrind", std::process::id()));
    let status = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg(format!("--callgrind-out-file={}", out.display()))
        .arg(subject)
        .arg("count")
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .ok()?;
    if !status.success() {
        return None;
    }
    let text = std::fs::read_to_string(&out).ok()?;
    let _ = std::fs::remove_file(&out);
    text.lines().find_map(|l| l.strip_prefix("totals:")).and_then(|v| v.trim().parse().ok())
}

/// Instructions per `per` from the difference between `big` and `small`
/// repetitions of `args` (the last argument, the repetitions, appended).
fn instructions_per(
    subject: &Path,
    args: &[&str],
    (small, big): (usize, usize),
    per: f64,
) -> Option<f64> {
    let with = |reps: usize| {
        let reps = reps.to_string();
        let mut all: Vec<&str> = args.to_vec();
        all.push(&reps);
        instructions(subject, &all)
    };
    Some((with(big)? - with(small)?) / ((big - small) as f64 * per))
}

/// Writes results/step_loop.md.
pub fn step_loop_section() -> String {
    let tol = "1e-6";
    let mut text = format!(
        "# The explicit pairs' step loop\n\nMachine: {}. Written by `cd bench && cargo run --release -- --loop` (bench/src/step_loop.rs, measured by bench/loop-subject). At rtol = atol = {tol}, each feature added to the ones above it: `least` (no stiffness test, no dense output, only the last step kept), `stiffness test` (Hairer's), `every step kept`, `dense output` (with the two above, `Options::new()`'s own), `event` (one watched that never fires; Lorenz only); `ode_solvers`: that crate's pair (0.6, Hairer's controllers, every step kept, its stiffness test every 1000 steps) on the same generated right-hand side. The `chained` row is one evaluation after another, each at `y + h k` of the one before: a stage's latency, and evaluations per step times it is the floor of a step. Per step: its time and instructions (callgrind), and the loop's own share, the step's less (evaluations per step × one evaluation); heap allocations per step from the difference of a run and one twice as long.\n\n",
        machine()
    );
    let Some(subject) = subject() else {
        text.push_str("bench/loop-subject did not build.\n");
        return text;
    };
    text.push_str("| problem | method | case | steps | evals/step | ns/step | loop ns/step | instr/step | loop instr/step | allocs/step |\n|---|---|---|---|---|---|---|---|---|---|\n");
    let show = |v: Option<f64>| v.map_or("–".to_string(), |v| format!("{v:.0}"));
    for problem in PROBLEMS {
        let rhs_ns = subject_numbers(&subject, &["time", problem, "rhs"])
            .and_then(|v| v.first().copied())
            .unwrap_or(f64::NAN);
        let rhs_instr =
            instructions_per(&subject, &[problem, "rhs", "-", "-"], (100_000, 300_000), 1.0);
        let chained_ns = subject_numbers(&subject, &["time", problem, "chain"])
            .and_then(|v| v.first().copied())
            .unwrap_or(f64::NAN);
        text.push_str(&format!(
            "| {problem} | one evaluation | | | | {rhs_ns:.1} | | {} | | |\n| {problem} | one evaluation, chained | | | | {chained_ns:.1} | | | | |\n",
            show(rhs_instr)
        ));
        for method in ["Dopri5", "Dop853"] {
            for case in CASES {
                if case == "event" && problem != "lorenz" {
                    continue;
                }
                let Some(v) = subject_numbers(&subject, &["time", problem, method, case, tol])
                else {
                    continue;
                };
                let [steps, evals_per_step, per_step, allocations] = v[..] else { continue };
                let loop_ns = per_step - evals_per_step * rhs_ns;
                let instr =
                    instructions_per(&subject, &[problem, method, case, tol], (1, 3), steps);
                let loop_instr = instr.zip(rhs_instr).map(|(i, r)| i - evals_per_step * r);
                text.push_str(&format!(
                    "| {problem} | {method} | {case} | {steps} | {evals_per_step:.2} | {per_step:.1} | {loop_ns:.1} | {} | {} | {allocations:.3} |\n",
                    show(instr),
                    show(loop_instr),
                ));
            }
        }
    }
    text.push_str(&versus_table(&subject));
    text
}

/// Ours (every step kept, as the work-precision sweep runs) against
/// `ode_solvers` in alternation, at three tolerances.
fn versus_table(subject: &Path) -> String {
    let mut text = String::from("\n## Against ode_solvers, in alternation\n\nEach row: 301 rounds of one run of ours (every step kept, the stiffness test on) and one of `ode_solvers`' (as above), medians per step; the floor is evaluations per step × the chained evaluation above; ratio = ours / ode_solvers' run time.\n\n| problem | method | tol | steps ours / ode_solvers | ns/step ours | ode_solvers | floor | ratio |\n|---|---|---|---|---|---|---|---|\n");
    for problem in PROBLEMS {
        let chained = subject_numbers(subject, &["time", problem, "chain"])
            .and_then(|v| v.first().copied())
            .unwrap_or(f64::NAN);
        for method in ["Dopri5", "Dop853"] {
            for tol in ["1e-3", "1e-6", "1e-9"] {
                let Some(v) = subject_numbers(subject, &["versus", problem, method, tol]) else {
                    continue;
                };
                let [ours_steps, peer_steps, ours, peer, ratio] = v[..] else { continue };
                let evals =
                    subject_numbers(subject, &["time", problem, method, "every step kept", tol])
                        .and_then(|v| v.get(1).copied())
                        .unwrap_or(f64::NAN);
                text.push_str(&format!(
                    "| {problem} | {method} | {tol} | {ours_steps} / {peer_steps} | {ours:.1} | {peer:.1} | {:.1} | {ratio:.2}× |\n",
                    evals * chained
                ));
            }
        }
    }
    text
}

/// This machine's clock, in cycles per nanosecond, from a chain of
/// dependent floating-point multiplications (four cycles each on Intel's
/// cores since Skylake; additions take two on the newest, so they would
/// not do), timed as the median of 31.
fn cycles_per_ns() -> f64 {
    const PRODUCTS: usize = 20_000_000;
    let mut times: Vec<f64> = (0..31)
        .map(|_| {
            // Slightly above 1: the chain grows by e^0.2 at most.
            let factor = std::hint::black_box(1.0 + 1e-8);
            let start = Instant::now();
            let mut x = std::hint::black_box(1.0f64);
            for _ in 0..PRODUCTS {
                x *= factor;
            }
            std::hint::black_box(x);
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    4.0 * PRODUCTS as f64 / (times[15] * 1e9)
}

/// One Taylor row: at `tol`, the order the method picks, the operations
/// of a step (the unrolled jet counted in the generated code, the state
/// update per state), and a step's time and cycles.
fn taylor_row<M: Benchmark>(tol: f64, cycles_per_ns: f64) -> Option<String> {
    let model = M::default();
    let order = daegen::runtime::taylor_order::order_to_unroll(&model, tol)?;
    let code = daegen_workprecision::expansion_cost(M::SOURCE, M::ATTRIBUTES, 1).ok()?.code;
    let jet = daegen_workprecision::taylor_jet_operations(&code, order)? as f64;
    let update =
        M::STATES as f64 * daegen::runtime::taylor::update_operations_per_state(order) as f64;
    let options = Options::new().method(Method::Taylor).tolerance(tol).dense_output(false);
    let t1 = M::bench().t_end;
    let settings = Settings { min_repeats: 21, ..Settings::default() };
    let (seconds, solution) =
        daegen_workprecision::median_time(&settings, || model.simulate(0.0, t1, &options));
    let stats = solution.ok()?.stats();
    let ns = seconds * 1e9 / stats.steps as f64;
    let cycles = ns * cycles_per_ns;
    Some(format!(
        "| {} | {tol:.0e} | {order}{} | {jet:.0} | {update:.0} | {:.0} | {ns:.0} | {cycles:.0} | {:.2} |\n",
        M::NAME,
        if stats.taylor_unrolled { "" } else { " (tape)" },
        jet + update,
        cycles / (jet + update),
    ))
}

/// The Taylor method's cost per step against the arithmetic of its
/// recurrences.
pub fn taylor_section() -> String {
    let clock = cycles_per_ns();
    let mut text = format!(
        "\n## The Taylor step against its arithmetic\n\nPer step at the order `Method::Taylor` picks: the jet's floating-point operations counted in the generated code (a multiply-add one, loops by their trips; `daegen_workprecision::taylor_jet_operations`), the state update's (Horner's sums, the compensated addition, the three norms), and the step's measured time (median of at least 21 solves, every step kept, no dense output) in cycles at this machine's clock, {clock:.2} GHz, measured by a chain of dependent multiplications (4 cycles each). A core of this kind retires two scalar multiply-adds a cycle, so below 0.5 cycles an operation the jet ran some of its operations as vectors (rows that repeat one computation are written side by side as lane pairs, as Kepler's and Arenstorf's x and y are); above 1.5 the step does something besides its arithmetic.\n\n| problem | tol | order | jet operations | update operations | operations per step | ns per step | cycles per step | cycles / operations |\n|---|---|---|---|---|---|---|---|---|\n"
    );
    for tol in [1e-9, 1e-12, 1e-15] {
        for row in [
            taylor_row::<crate::Kepler>(tol, clock),
            taylor_row::<crate::Arenstorf>(tol, clock),
            taylor_row::<crate::Lorenz>(tol, clock),
            taylor_row::<crate::OuterSolarSystem>(tol, clock),
        ]
        .into_iter()
        .flatten()
        {
            text.push_str(&row);
        }
    }
    text
}
