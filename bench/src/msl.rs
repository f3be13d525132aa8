//! `--msl`: the Modelica Standard Library's examples rewritten with
//! daegen's library (tests/models/msl.rs) against MAP-LIB's reference
//! results: each one's states, its run time, and the largest distance of
//! its compared signals from the reference, over the half-height of the
//! tube csv-compare checks (tests/support/tube.rs; within 1, inside).

// MSL's sources write π/2 to 16 digits; the models keep their numbers.
#![allow(clippy::approx_constant)]

use daegen::prelude::*;
use std::path::Path;
use std::time::Instant;

include!("../../tests/models/msl.rs");

#[path = "../../tests/support/tube.rs"]
mod tube;

/// The largest deviation of `example`'s run at `options` from its
/// reference, over the tube's half-height, and the rows outside the tube.
fn deviation(example: &MslExample, reference: &tube::Reference, options: &Options) -> (f64, usize) {
    let t1 = *reference.times.last().expect("rows");
    let sol = match (example.run)(t1, options) {
        Ok(sol) => sol,
        Err(_) => return (f64::INFINITY, reference.times.len()),
    };
    let (mut worst, mut outside): (f64, usize) = (0.0, 0);
    for &(msl, ours) in example.signals {
        let k = reference.signals.iter().position(|s| s == msl).expect("a compared signal");
        let value = |t: f64, before: bool| {
            let read = if before { sol.at_left(t, ours) } else { sol.at(t, ours) };
            read.unwrap_or(f64::NAN)
        };
        let comparison = tube::compare(reference, k, &value, 0.002);
        worst = worst.max(comparison.worst);
        outside += comparison.outside;
    }
    (worst, outside)
}

/// The median of five runs after one to warm up, in milliseconds.
fn run_time(example: &MslExample, t1: f64, options: &Options) -> f64 {
    let _ = (example.run)(t1, options);
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let start = Instant::now();
            let _ = (example.run)(t1, options);
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[2]
}

/// The doc comment's first paragraph on one line, for a table cell.
fn cell(doc: &str) -> String {
    let text =
        doc.split("\n\n").next().unwrap_or("").split_whitespace().collect::<Vec<_>>().join(" ");
    text.replace('|', "\\|")
}

/// The `--msl` report.
pub fn msl_section() -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/msl");
    let mut out = String::from("# MSL's examples against MAP-LIB's references\n\n");
    out.push_str(&format!("Machine: {}.\n\n", crate::machine()));
    out.push_str(
        "Each example of the Modelica Standard Library 4.0.0 rewritten with daegen's library \
         (`tests/models/msl.rs`), run from 0 to the reference's end, and compared \
         at the reference's rows with MAP-LIB's result (Dymola 2020x, DASSL, tolerance 1e-6; \
         `tests/msl/`) by csv-compare's tube (relative size 0.002 of the signal's range and of \
         the time span). Deviation: the largest distance from the reference over all compared \
         signals and rows, in units of the tube's half-height (inside below 1 without the \
         tube's width in time, which lets a jump a little early or late pass), for the default \
         method (`Method::Auto`) at rtol 1e-6, atol 1e-8, as Dymola's run, and for RADAU5 at \
         rtol 1e-8, atol 1e-10, as the test command checks every example (inside the tube). \
         Run time: the median of five runs of the first. States: the continuous ones.\n\n",
    );
    out.push_str(
        "| example | states | run (ms) | deviation (rows outside), Auto at 1e-6 | deviation (rows outside), RADAU5 at 1e-8 | the rewrite |\n\
         |---|---|---|---|---|---|\n",
    );
    let loose = Options::new().rtol(1e-6).atol(1e-8);
    let tight = Options::new().method(Method::Radau5).rtol(1e-8).atol(1e-10);
    for example in msl_examples() {
        let reference = tube::reference_in(&dir, example.name);
        let t1 = *reference.times.last().expect("rows");
        let (loose_worst, loose_outside) = deviation(&example, &reference, &loose);
        let (tight_worst, tight_outside) = deviation(&example, &reference, &tight);
        out.push_str(&format!(
            "| {} | {} | {:.2} | {:.4} ({}) | {:.4} ({}) | {} |\n",
            example.name,
            example.states,
            run_time(&example, t1, &loose),
            loose_worst,
            loose_outside,
            tight_worst,
            tight_outside,
            cell(example.doc),
        ));
    }
    out
}
