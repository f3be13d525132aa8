//! The runner: registered models in, one [`Problem`] per model out, with a
//! progress line while it runs and the CSV, SVG and markdown written at the
//! end.

use crate::sweep::{plan, reference_values, run_planned};
use crate::{
    expansion_cost, median, summary_markdown, to_csv, work_precision_svg, ExpansionCost, Peer,
    PeerProblem, Record, Settings,
};
use daegen::runtime::bench::Benchmark;
use daegen::Method;
use std::io::Write;
use std::path::Path;

/// The results of one registered model.
#[derive(Clone, Debug, Default)]
pub struct Problem {
    /// The model's name.
    pub name: String,
    /// Where the reference comes from.
    pub reference_source: String,
    /// Every run, ours and the peers'.
    pub records: Vec<Record>,
    /// Peers that could not run, and why.
    pub missing: Vec<(String, String)>,
    /// Macro expansion time and generated size.
    pub expansion: Option<ExpansionCost>,
    /// rustc's time on the generated code (release), when measured.
    pub rustc_seconds: Option<f64>,
    /// Peers' set-up times (heyoka's JIT build).
    pub setup: Vec<(String, f64)>,
}

/// A run's record from its last round, and its times in every round.
#[derive(Default)]
struct Timed {
    last: Option<Record>,
    times: Vec<f64>,
}

impl Timed {
    fn add(&mut self, record: Record) {
        self.times.push(record.seconds);
        self.last = Some(record);
    }

    /// The record with the median of its rounds' times.
    fn record(self) -> Option<Record> {
        let mut record = self.last?;
        record.seconds = median(self.times);
        Some(record)
    }
}

/// Sweeps registered models and their peers.
pub struct Runner {
    settings: Settings,
    peers: Vec<Box<dyn Peer>>,
    problems: Vec<Problem>,
    /// Print a progress line on stderr.
    pub progress: bool,
}

impl Runner {
    /// A runner with no peers.
    pub fn new(settings: Settings) -> Runner {
        Runner { settings, peers: Vec::new(), problems: Vec::new(), progress: true }
    }

    /// Adds a peer; it runs on every problem it applies to.
    pub fn peer(mut self, peer: impl Peer + 'static) -> Runner {
        self.peers.push(Box::new(peer));
        self
    }

    /// The problems run so far.
    pub fn problems(&self) -> &[Problem] {
        &self.problems
    }

    /// Mutable access, to attach measurements made outside (rustc times).
    pub fn problems_mut(&mut self) -> &mut [Problem] {
        &mut self.problems
    }

    fn say(&self, line: &str) {
        if self.progress {
            eprint!("\r\x1b[2K{line}");
            let _ = std::io::stderr().flush();
        }
    }

    /// Sweeps `M`'s methods and every peer that applies, in
    /// [`Settings::rounds`] rounds: in each, every tolerance's runs side by
    /// side.
    pub fn run<M: Benchmark>(&mut self) -> &Problem {
        let bench = M::bench();
        let mut problem = Problem {
            name: M::NAME.to_string(),
            reference_source: if bench.source.is_empty() {
                "the given values".into()
            } else {
                bench.source.to_string()
            },
            ..Problem::default()
        };
        if let daegen::runtime::bench::Reference::Run { method, tol } = &bench.reference {
            problem.reference_source = format!("a {method:?} run at tolerance {tol:e}");
        }
        self.say(&format!("{}: expanding", M::NAME));
        match expansion_cost(M::SOURCE, M::ATTRIBUTES, 5) {
            Ok(cost) => problem.expansion = Some(cost),
            Err(e) => problem.missing.push(("expansion".into(), e)),
        }
        self.say(&format!("{}: reference", M::NAME));
        let reference = match reference_values::<M>(&bench) {
            Ok(r) => r,
            Err(e) => {
                problem.missing.push(("reference".into(), e));
                let i = self.problems.len();
                self.problems.push(problem);
                return &self.problems[i];
            }
        };
        let settings = self.settings.clone();
        let progress = self.progress;
        let say = |line: &str| {
            if progress {
                eprint!("\r\x1b[2K{line}");
                let _ = std::io::stderr().flush();
            }
        };
        let model = M::default();
        let plan = plan::<M>(&settings);
        // Peers see the generated f and its Jacobian (ODEs only).
        let n = M::STATES;
        let rhs = |t: f64, y: &[f64], dy: &mut [f64]| {
            if model.rhs(t, y, dy).is_err() {
                dy.iter_mut().for_each(|v| *v = f64::NAN);
            }
        };
        let jacobian = |t: f64, y: &[f64], j: &mut [f64]| {
            let mut values = vec![0.0; M::JACOBIAN.pattern().len()];
            j.iter_mut().for_each(|v| *v = 0.0);
            if model.jacobian(t, y, &mut values).is_err() {
                j.iter_mut().for_each(|v| *v = f64::NAN);
                return;
            }
            for (&(r, c), v) in M::JACOBIAN.pattern().iter().zip(values) {
                j[r * n + c] = v;
            }
        };
        let mut y0 = vec![0.0; n];
        model.initial_state(&mut y0);
        let explicit =
            |m: &Method| !matches!(m, Method::Radau5 | Method::Rodas5P | Method::BackwardEuler);
        let peer_problem = PeerProblem {
            name: M::NAME,
            peer: bench.peer,
            y0,
            t_end: bench.t_end,
            tolerances: bench
                .tolerances
                .iter()
                .copied()
                .filter(|&t| t >= settings.tightest)
                .collect(),
            atol_factor: bench.atol_factor,
            stiff: bench.methods.iter().any(|m| !explicit(m)),
            nonstiff: bench.methods.iter().any(explicit),
            reference: &reference,
            rhs: &rhs,
            jacobian: &jacobian,
        };
        let peers: Vec<&dyn Peer> = if M::INDEX == 0 && M::INFO.algebraics.is_empty() {
            self.peers.iter().map(|p| p.as_ref()).filter(|p| p.applies(&peer_problem)).collect()
        } else {
            Vec::new()
        };
        for peer in &peers {
            if let Some(t) = peer.setup_seconds(&peer_problem) {
                problem.setup.push((peer.name(), t));
            }
        }
        // Each tolerance (or step) once, in the order the runs first reach it.
        let mut keys: Vec<f64> = Vec::new();
        for tol in plan.iter().map(|r| r.tol).chain(peer_problem.tolerances.iter().copied()) {
            if !keys.contains(&tol) {
                keys.push(tol);
            }
        }
        let round = settings.one_round();
        let mut ours: Vec<Timed> = plan.iter().map(|_| Timed::default()).collect();
        let mut theirs: Vec<Vec<Timed>> =
            peers.iter().map(|_| keys.iter().map(|_| Timed::default()).collect()).collect();
        let mut failed: Vec<Option<String>> = peers.iter().map(|_| None).collect();
        for r in 0..settings.rounds.max(1) {
            for (k, &tol) in keys.iter().enumerate() {
                // Ours first in odd rounds, last in even ones: what runs
                // first after another solver's (caches, clock) is not
                // always the same side.
                for side in [r % 2, 1 - r % 2] {
                    if side == 0 {
                        for (run, timed) in
                            plan.iter().zip(&mut ours).filter(|(run, _)| run.tol == tol)
                        {
                            say(&format!("{} {} {tol:.0e}, round {}", M::NAME, run.method, r + 1));
                            timed.add(run_planned(&model, run, &round, &reference));
                        }
                        continue;
                    }
                    if !peer_problem.tolerances.contains(&tol) {
                        continue;
                    }
                    for (j, peer) in peers.iter().enumerate() {
                        if failed[j].is_some() || (r > 0 && !peer.in_process()) {
                            continue;
                        }
                        say(&format!("{} {} {tol:.0e}, round {}", M::NAME, peer.name(), r + 1));
                        // A peer out of process times its own repeats, all of them.
                        let its = if peer.in_process() { &round } else { &settings };
                        match peer.run(&peer_problem, tol, its) {
                            Ok(record) => theirs[j][k].add(record),
                            Err(why) => failed[j] = Some(why),
                        }
                    }
                }
            }
        }
        problem.records = ours.into_iter().filter_map(Timed::record).collect();
        for (j, peer) in peers.iter().enumerate() {
            let runs = std::mem::take(&mut theirs[j]);
            problem.records.extend(runs.into_iter().filter_map(Timed::record));
            if let Some(why) = failed[j].take() {
                problem.missing.push((peer.name(), why));
            }
        }
        self.say("");
        let i = self.problems.len();
        self.problems.push(problem);
        &self.problems[i]
    }

    /// Writes `results.csv`, one `<problem>.svg` per problem and
    /// `summary.md` into `dir`.
    pub fn write(&self, dir: &Path) -> std::io::Result<()> {
        std::fs::create_dir_all(dir)?;
        let all: Vec<Record> =
            self.problems.iter().flat_map(|p| p.records.iter().cloned()).collect();
        std::fs::write(dir.join("results.csv"), to_csv(&all))?;
        for p in &self.problems {
            if let Ok(svg) = work_precision_svg(&p.name, &p.records) {
                std::fs::write(dir.join(format!("{}.svg", p.name)), svg)?;
            }
        }
        std::fs::write(dir.join("summary.md"), summary_markdown(&self.problems))
    }
}
