//! The runner's machinery on a tiny sweep: one model, two tolerances, one
//! stand-in peer. Checks the CSV, the SVG and the summary are well formed
//! and that errors fall with the tolerance. No timing assertions.

use daegen::prelude::*;
use daegen_workprecision::{
    parse_csv, to_csv, work_precision_svg, Peer, PeerProblem, Record, Runner, Settings,
};

/// x'' = −x from (1, 0): x = cos t, x' = −sin t.
#[dae_model(bench = Bench::until(3.0)
    .exact(|t: f64| [t.cos(), -t.sin()])
    .methods([Dop853])
    .tolerances(4, 8)
    .peer("none"))]
fn oscillator() {
    let x = state(1.0);
    let v = state(0.0);
    der(x) == v;
    der(v) == -x;
}

/// A stand-in peer: forward Euler with h = tol, through the generated f;
/// it notes the tolerances it is asked for, in order.
#[derive(Default)]
struct EulerPeer {
    asked: std::sync::Arc<std::sync::Mutex<Vec<f64>>>,
}

/// A stand-in peer in another process: it runs once per tolerance.
struct OutOfProcess {
    asked: std::sync::Arc<std::sync::Mutex<Vec<f64>>>,
}

impl Peer for OutOfProcess {
    fn name(&self) -> String {
        "out of process".into()
    }
    fn applies(&self, _: &PeerProblem) -> bool {
        true
    }
    fn in_process(&self) -> bool {
        false
    }
    fn run(&self, p: &PeerProblem, tol: f64, s: &Settings) -> Result<Record, String> {
        self.asked.lock().map_err(|e| e.to_string())?.push(tol);
        EulerPeer::default().run(p, tol, s).map(|r| Record { method: self.name(), ..r })
    }
}

impl Peer for EulerPeer {
    fn name(&self) -> String {
        "test Euler".into()
    }
    fn applies(&self, problem: &PeerProblem) -> bool {
        problem.nonstiff
    }
    fn run(&self, p: &PeerProblem, tol: f64, _: &Settings) -> Result<Record, String> {
        self.asked.lock().map_err(|e| e.to_string())?.push(tol);
        let start = std::time::Instant::now();
        let n = (p.t_end / tol).ceil() as usize;
        let h = p.t_end / n as f64;
        let mut y = p.y0.clone();
        let mut dy = vec![0.0; y.len()];
        for k in 0..n {
            (p.rhs)(k as f64 * h, &y, &mut dy);
            for (yi, di) in y.iter_mut().zip(&dy) {
                *yi += h * di;
            }
        }
        Ok(Record {
            problem: p.name.to_string(),
            method: self.name(),
            tol,
            error: daegen_workprecision::mixed_error(&y, p.reference),
            seconds: start.elapsed().as_secs_f64().max(1e-9),
            steps: n,
            rejected: 0,
            rhs_evals: n,
            jacobian_evals: 0,
        })
    }
}

/// A peer that is not installed.
struct AbsentPeer;

impl Peer for AbsentPeer {
    fn name(&self) -> String {
        "absent".into()
    }
    fn applies(&self, _: &PeerProblem) -> bool {
        true
    }
    fn run(&self, _: &PeerProblem, _: f64, _: &Settings) -> Result<Record, String> {
        Err("not installed".into())
    }
}

#[test]
fn a_tiny_sweep_writes_well_formed_csv_svg_and_summary() {
    let bench = <Oscillator as daegen::runtime::bench::Benchmark>::bench();
    assert_eq!(bench.tolerances.len(), 5);
    let settings = Settings {
        min_repeats: 1,
        max_repeats: 2,
        budget: std::time::Duration::ZERO,
        // Two tolerances: 1e-4 and 1e-5.
        tightest: 1e-5,
        rounds: 2,
    };
    let euler = EulerPeer::default();
    let asked = euler.asked.clone();
    let once = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let out_of_process = OutOfProcess { asked: once.clone() };
    let mut runner = Runner::new(settings).peer(euler).peer(AbsentPeer).peer(out_of_process);
    runner.progress = false;
    let problem = runner.run::<Oscillator>().clone();
    let ours: Vec<&Record> =
        problem.records.iter().filter(|r| r.method == "daegen DOP853").collect();
    assert_eq!(ours.len(), 2);
    assert!(ours[1].error < ours[0].error, "{ours:?}");
    assert!(ours.iter().all(|r| r.steps > 0 && r.rhs_evals > r.steps));
    let euler: Vec<&Record> = problem.records.iter().filter(|r| r.method == "test Euler").collect();
    assert_eq!(euler.len(), 2);
    // Euler's error is O(h): ten times smaller h, about ten times smaller error.
    let drop = euler[0].error / euler[1].error;
    assert!((5.0..20.0).contains(&drop), "Euler error ratio {drop}");
    assert_eq!(problem.missing, vec![("absent".to_string(), "not installed".to_string())]);
    // In each of the two rounds every tolerance in turn, alongside ours; one
    // record per tolerance. A peer in another process runs once.
    let asked = asked.lock().map(|a| a.clone()).unwrap_or_default();
    assert_eq!(asked, [1e-4, 1e-5, 1e-4, 1e-5]);
    let once = once.lock().map(|a| a.clone()).unwrap_or_default();
    assert_eq!(once, [1e-4, 1e-5]);
    assert_eq!(problem.records.iter().filter(|r| r.method == "out of process").count(), 2);
    let expansion = problem.expansion.as_ref().expect("the model expands");
    assert!(expansion.bytes > 100 && expansion.code.contains("fn rhs"));

    // CSV: a header, one line per run, and it reads back to the same records.
    let csv = to_csv(&problem.records);
    assert_eq!(csv.lines().count(), 1 + problem.records.len());
    assert_eq!(parse_csv(&csv).unwrap(), problem.records);
    assert!(parse_csv("problem,method\nx").is_err());

    // SVG: one document with a line per method and the legend.
    let svg = work_precision_svg("oscillator", &problem.records).unwrap();
    assert!(svg.trim_start().starts_with("<svg"), "{:.80}", svg);
    assert!(svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<svg").count(), 1);
    assert!(svg.matches("<polyline").count() >= 2, "one line per method");
    assert!(svg.contains("daegen DOP853") && svg.contains("test Euler"));
    assert!(work_precision_svg("empty", &[]).is_err());

    // The files, and the summary's ratio cell and missing peer.
    let dir = std::env::temp_dir().join(format!("daegen-wp-{}", std::process::id()));
    runner.write(&dir).unwrap();
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(summary.contains("### oscillator"));
    assert!(summary.contains("| daegen DOP853 |"));
    assert!(summary.contains("absent: missing (not installed)"));
    assert!(dir.join("oscillator.svg").exists());
    let written = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert_eq!(parse_csv(&written).unwrap().len(), problem.records.len());
    let _ = std::fs::remove_dir_all(&dir);
}
