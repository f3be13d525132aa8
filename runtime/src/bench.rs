//! What a work-precision benchmark needs to know about a model, declared
//! with the model: `#[dae_model(bench = Bench::until(t1).exact(f))]` makes
//! the model implement [`Benchmark`], and a runner (the `daegen-workprecision`
//! crate) sweeps its methods and tolerances, measures error against the
//! reference, time and work, and runs the peers on the same problem. Adding a
//! model to the benchmarks is that attribute and one line in the runner's
//! list; nothing is written by hand per model.

use crate::{Method, Model};

/// Where the error of a run is measured against, at the end time.
#[derive(Clone, Debug)]
pub enum Reference {
    /// Values at the end: an exact solution or a published reference.
    Values(Vec<f64>),
    /// A documented high-accuracy run of another method (rtol = atol =
    /// `tol`), when neither exists.
    Run {
        /// The method of the reference run.
        method: Method,
        /// Its tolerance.
        tol: f64,
    },
}

/// A benchmark problem: the model with its end time, reference, methods and
/// tolerances. Built with [`Bench::until`] and its setters.
#[derive(Clone, Debug)]
pub struct Bench {
    /// The end time (runs start at 0).
    pub t_end: f64,
    /// What errors are measured against.
    pub reference: Reference,
    /// The methods swept (adaptive ones over `tolerances`, fixed-step ones
    /// over `steps`).
    pub methods: Vec<Method>,
    /// Relative tolerances, loosest first.
    pub tolerances: Vec<f64>,
    /// The absolute tolerance is this times the relative one.
    pub atol_factor: f64,
    /// Step counts over `[0, t_end]` for fixed-step methods.
    pub steps: Vec<usize>,
    /// The problem's name in `shared/peers/peer.py`, if it has one.
    pub peer: Option<&'static str>,
    /// A line saying where the reference comes from.
    pub source: &'static str,
}

impl Bench {
    /// A problem integrated over `[0, t_end]`, by default with DOPRI5 and
    /// DOP853 at tolerances 1e-3 … 1e-14 against a DOP853 run at 1e-14.
    pub fn until(t_end: f64) -> Bench {
        Bench {
            t_end,
            reference: Reference::Run { method: Method::Dop853, tol: 1e-14 },
            methods: vec![Method::Dopri5, Method::Dop853],
            tolerances: (3..=14).map(|k| 10f64.powi(-k)).collect(),
            atol_factor: 1.0,
            steps: vec![100, 200, 400, 800, 1600],
            peer: None,
            source: "",
        }
    }

    /// Errors against exact or published values at `t_end`.
    pub fn reference(mut self, values: impl AsRef<[f64]>, source: &'static str) -> Bench {
        self.reference = Reference::Values(values.as_ref().to_vec());
        self.source = source;
        self
    }

    /// Errors against the exact solution `f(t_end)`.
    pub fn exact<V: AsRef<[f64]>>(mut self, f: impl Fn(f64) -> V) -> Bench {
        self.reference = Reference::Values(f(self.t_end).as_ref().to_vec());
        self.source = "exact solution";
        self
    }

    /// Errors against a run of `method` at tolerance `tol` (documented in
    /// the report as such).
    pub fn reference_run(mut self, method: Method, tol: f64) -> Bench {
        self.reference = Reference::Run { method, tol };
        self.source = "high-accuracy run of another method";
        self
    }

    /// The methods to sweep.
    pub fn methods(mut self, methods: impl IntoIterator<Item = Method>) -> Bench {
        self.methods = methods.into_iter().collect();
        self
    }

    /// Relative tolerances `10^-from … 10^-to`.
    pub fn tolerances(mut self, from: i32, to: i32) -> Bench {
        self.tolerances = (from..=to).map(|k| 10f64.powi(-k)).collect();
        self
    }

    /// atol = `factor` × rtol (Robertson: 1e-6).
    pub fn atol_factor(mut self, factor: f64) -> Bench {
        self.atol_factor = factor;
        self
    }

    /// Step counts for fixed-step methods.
    pub fn steps(mut self, steps: impl IntoIterator<Item = usize>) -> Bench {
        self.steps = steps.into_iter().collect();
        self
    }

    /// The same problem in `shared/peers/peer.py` (SciPy and heyoka).
    pub fn peer(mut self, name: &'static str) -> Bench {
        self.peer = Some(name);
        self
    }
}

/// A model registered for the work-precision benchmarks; implemented by
/// `#[dae_model(bench = ...)]`.
pub trait Benchmark: Model + Default + Clone + Send + Sync + 'static {
    /// The model function's name (`kepler`).
    const NAME: &'static str;
    /// The model function as written, for timing its expansion.
    const SOURCE: &'static str;
    /// The `#[dae_model(...)]` arguments other than `bench`.
    const ATTRIBUTES: &'static str;
    /// The problem.
    fn bench() -> Bench;
}
