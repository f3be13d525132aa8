//! The explicit pairs' step loop (`--loop`): what a step costs beyond its
//! right-hand-side evaluations, on problems whose right-hand side is cheap
//! (Lorenz, 3 states; Arenstorf, 4), for DOPRI5 and DOP853 with each
//! feature of a run added in turn: the least loop (no stiffness test, no
//! dense output, only the last step kept), Hairer's stiffness test, every
//! step stored, the dense output (which makes the options a user gets by
//! default), and an event watched (one that never fires).
//!
//! Measured by `loop-subject` (bench/loop-subject: the cases of
//! `step_loop_cases.rs` as a binary of their own, built for AVX2 at most
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
//! ours against `ode_solvers` in alternation at three tolerances. Writes
//! `results/step_loop.md`.

use super::*;

/// The cases, as `step_loop_cases.rs` names them.
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
