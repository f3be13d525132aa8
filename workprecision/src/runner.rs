//! The runner: registered models in, one [`Problem`] per model out, with a
//! progress line while it runs and the CSV, SVG and markdown written at the
//! end.

use crate::sweep::reference_values;
use crate::{
    expansion_cost, summary_markdown, sweep, to_csv, work_precision_svg, ExpansionCost, Peer,
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

    /// Sweeps `M`'s methods and every peer that applies.
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
        let mut say = |line: &str| {
            if progress {
                eprint!("\r\x1b[2K{line}");
                let _ = std::io::stderr().flush();
            }
        };
        problem.records = sweep::<M>(&settings, &reference, &mut say);
        // Peers see the generated f and its Jacobian (ODEs only).
        if M::INDEX == 0 && M::INFO.algebraics.is_empty() {
            let model = M::default();
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
            for peer in &self.peers {
                if !peer.applies(&peer_problem) {
                    continue;
                }
                let name = peer.name();
                if let Some(t) = peer.setup_seconds(&peer_problem) {
                    problem.setup.push((name.clone(), t));
                }
                for &tol in &peer_problem.tolerances {
                    say(&format!("{} {name} {tol:.0e}", M::NAME));
                    match peer.run(&peer_problem, tol, &settings) {
                        Ok(record) => problem.records.push(record),
                        Err(why) => {
                            problem.missing.push((name.clone(), why));
                            break;
                        }
                    }
                }
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
