//! Ensembles: one model run many times, each member with its own
//! parameters (and, if asked, its own initial state), on every core.
//!
//! Members are independent runs, spread over a rayon thread pool; each
//! member's answer is exactly the one a lone run of it gives, so the
//! results do not depend on the number of threads. A member that fails
//! keeps its `Err` (with its partial solution) in its place; the others
//! run on. For ensembles too large to keep every solution, [`Ensemble::map`]
//! reduces each member as soon as it ends, [`Ensemble::fold`] folds them
//! in member order, and [`Ensemble::final_states`] (or
//! [`Ensemble::final_values`], any names) keeps one row each.
//! [`Ensemble::shard`] cuts the members into contiguous blocks, one per
//! machine, whose [`FinalStates`] merge back into the unsharded answer.
//!
//! Like DifferentialEquations.jl's `EnsembleProblem` (a `prob_func` per
//! member) and heyoka's `ensemble_propagate_until`.

mod batch;
mod final_states;

pub use batch::Batch;
pub use final_states::{FinalState, FinalStates, Shard};

use crate::error::Error;
use crate::options::Options;
use crate::run::Simulate;
use crate::solution::Solution;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::ops::Range;

/// How many members [`Ensemble::fold`] keeps reduced at a time before it
/// folds them in order: enough to keep every thread busy, few enough
/// that a million members need no more memory than this many.
const FOLD_CHUNK: usize = 4096;

/// A model's initial state per member, as [`Ensemble::initial_states`]
/// gives it.
type InitialStateOf<'a> = Box<dyn Fn(usize) -> Vec<f64> + Send + Sync + 'a>;

/// `n` runs of a model: `Ensemble::new(n, |i| model_for_member(i))`.
///
/// ```
/// # use daegen_runtime::{Ensemble, Options};
/// # fn demo<M: daegen_runtime::Simulate + Default>(set: impl Fn(&mut M, usize) + Sync) {
/// let ensemble = Ensemble::new(1000, |i| {
///     let mut model = M::default();
///     set(&mut model, i);
///     model
/// })
/// .threads(2);
/// let finals = ensemble.final_states(0.0, 10.0, &Options::new().tolerance(1e-10));
/// # }
/// ```
pub struct Ensemble<'a, M, F> {
    model_of: F,
    initial_state_of: Option<InitialStateOf<'a>>,
    members: Range<usize>,
    threads: Option<usize>,
    progress: bool,
    _model: std::marker::PhantomData<fn() -> M>,
}

impl<'a, M, F> Ensemble<'a, M, F>
where
    M: Simulate,
    F: Fn(usize) -> M + Sync,
{
    /// Members `0..n`, member `i` the model `model_of(i)` (its parameters
    /// set for that member) from the model's own initial state.
    pub fn new(n: usize, model_of: F) -> Self {
        Ensemble {
            model_of,
            initial_state_of: None,
            members: 0..n,
            threads: None,
            progress: false,
            _model: std::marker::PhantomData,
        }
    }

    /// Starts member `i` from `initial_state(i)` (ordered as
    /// [`crate::ModelInfo::states`]) instead of the model's initial state;
    /// a DAE's state is made consistent as a lone run's is.
    pub fn initial_states(
        mut self,
        initial_state: impl Fn(usize) -> Vec<f64> + Send + Sync + 'a,
    ) -> Self {
        self.initial_state_of = Some(Box::new(initial_state));
        self
    }

    /// Runs on `k` threads (default, and `k = 0`: one per core).
    pub fn threads(mut self, k: usize) -> Self {
        self.threads = (k > 0).then_some(k);
        self
    }

    /// Draws one progress bar on stderr for the ensemble (members done of
    /// all); the members' own bars ([`Options::progress`]) stay off.
    pub fn progress(mut self, show: bool) -> Self {
        self.progress = show;
        self
    }

    /// Keeps only the members of shard `shard` (the `i`-th of `n`
    /// contiguous blocks, as [`Shard::members`] cuts them): one machine's
    /// part of an ensemble spread over `n`. A shard of a shard cuts the
    /// shard's members.
    pub fn shard(mut self, shard: Shard) -> Self {
        let block = shard.members(self.members.len());
        let start = self.members.start;
        self.members = start + block.start..start + block.end;
        self
    }

    /// The members this ensemble runs (all of them, or its shard's).
    pub fn members(&self) -> Range<usize> {
        self.members.clone()
    }

    /// Runs every member from `t0` to `t1` with `options`: their results
    /// in member order (the first is member `members().start`).
    pub fn run(&self, t0: f64, t1: f64, options: &Options) -> Vec<Result<Solution, Error>> {
        self.map(t0, t1, options, |_, result| result)
    }

    /// Runs every member and hands its result to `reduce` as soon as it
    /// ends, keeping only what `reduce` returns: `(member, result)` in,
    /// the reductions out, in member order.
    pub fn map<T: Send>(
        &self,
        t0: f64,
        t1: f64,
        options: &Options,
        reduce: impl Fn(usize, Result<Solution, Error>) -> T + Sync,
    ) -> Vec<T> {
        let bar = self.progress.then(|| progress_bar(self.members.len()));
        let pool = self.pool();
        let reduced = self.map_members(&pool, self.members.clone(), t0, t1, options, &reduce, &bar);
        if let Some(bar) = bar {
            bar.finish();
        }
        reduced
    }

    /// Folds every member's result, reduced by `reduce`, into `init` in
    /// member order, `fold(accumulator, member, reduced)`, whatever the
    /// thread count; at most a few thousand reductions are held at once.
    pub fn fold<A, T: Send>(
        &self,
        t0: f64,
        t1: f64,
        options: &Options,
        reduce: impl Fn(usize, Result<Solution, Error>) -> T + Sync,
        init: A,
        mut fold: impl FnMut(A, usize, T) -> A,
    ) -> A {
        let bar = self.progress.then(|| progress_bar(self.members.len()));
        let pool = self.pool();
        let mut accumulator = init;
        let mut start = self.members.start;
        while start < self.members.end {
            let end = (start + FOLD_CHUNK).min(self.members.end);
            let reduced = self.map_members(&pool, start..end, t0, t1, options, &reduce, &bar);
            for (i, value) in (start..end).zip(reduced) {
                accumulator = fold(accumulator, i, value);
            }
            start = end;
        }
        if let Some(bar) = bar {
            bar.finish();
        }
        accumulator
    }

    /// Every member's state at the end of its run (the steps between are
    /// not kept: a member stores one state), or its error.
    pub fn final_states(&self, t0: f64, t1: f64, options: &Options) -> FinalStates {
        let options = final_state_options(options, t1);
        let names = M::INFO.states.iter().map(|s| s.to_string()).collect();
        let rows = self.map(t0, t1, &options, |member, result| FinalState {
            member,
            state: match result {
                Ok(solution) => Ok(solution.final_state().to_vec()),
                Err(e) => Err(e.to_string()),
            },
        });
        FinalStates { names, rows }
    }

    /// Every member's values of `names` (states, algebraic variables or
    /// outputs) at the end of its run, as [`Ensemble::final_states`] keeps
    /// the states; `Err` before any run for a name the model does not have.
    pub fn final_values(
        &self,
        t0: f64,
        t1: f64,
        options: &Options,
        names: &[&str],
    ) -> Result<FinalStates, Error> {
        let info = &M::INFO;
        let known: Vec<&'static str> =
            info.states.iter().chain(info.outputs).chain(info.algebraics).copied().collect();
        if let Some(name) = names.iter().find(|n| !known.contains(n)) {
            return Err(Error::UnknownName { name: name.to_string(), known });
        }
        let options = final_state_options(options, t1);
        let rows = self.map(t0, t1, &options, |member, result| FinalState {
            member,
            state: result
                .and_then(|solution| names.iter().map(|n| solution.last(n)).collect())
                .map_err(|e| e.to_string()),
        });
        Ok(FinalStates { names: names.iter().map(|n| n.to_string()).collect(), rows })
    }

    /// The members `members`, each reduced as it ends, in member order.
    #[allow(clippy::too_many_arguments)]
    fn map_members<T: Send>(
        &self,
        pool: &Pool,
        members: Range<usize>,
        t0: f64,
        t1: f64,
        options: &Options,
        reduce: &(impl Fn(usize, Result<Solution, Error>) -> T + Sync),
        bar: &Option<ProgressBar>,
    ) -> Vec<T> {
        let options = options.progress(false);
        let one = |i: usize| {
            let result = self.run_member(i, t0, t1, &options);
            if let Some(bar) = bar {
                bar.inc(1);
            }
            reduce(i, result)
        };
        match pool.run(|| members.clone().into_par_iter().map(one).collect()) {
            Ok(reduced) => reduced,
            // No pool, no runs: each member says why.
            Err(message) => members
                .map(|i| reduce(i, Err(Error::InvalidOptions { message: message.clone() })))
                .collect(),
        }
    }

    fn run_member(&self, i: usize, t0: f64, t1: f64, options: &Options) -> Result<Solution, Error> {
        let model = (self.model_of)(i);
        match &self.initial_state_of {
            Some(initial) => model.simulate_from(t0, &initial(i), t1, options),
            None => model.simulate(t0, t1, options),
        }
    }

    /// The ensemble's threads: rayon's global pool (one thread per core)
    /// by default, else a pool of its own, built once a run.
    fn pool(&self) -> Pool {
        match self.threads {
            None => Pool::Global,
            Some(k) => match rayon::ThreadPoolBuilder::new().num_threads(k).build() {
                Ok(pool) => Pool::Own(pool),
                Err(e) => Pool::Failed(format!("the ensemble could not start {k} threads: {e}")),
            },
        }
    }
}

/// Where an ensemble's members run.
enum Pool {
    Global,
    Own(rayon::ThreadPool),
    /// No threads could be started: the reason, for every member.
    Failed(String),
}

impl Pool {
    /// `f` on this pool's threads.
    fn run<R: Send>(&self, f: impl FnOnce() -> R + Send) -> Result<R, String> {
        match self {
            Pool::Global => Ok(f()),
            Pool::Own(pool) => Ok(pool.install(f)),
            Pool::Failed(message) => Err(message.clone()),
        }
    }
}

/// `options` for a run whose end alone is kept: no steps stored.
/// `output_times` is refused beside `keep_every` and without dense output,
/// which keep little anyway.
fn final_state_options(options: &Options, t1: f64) -> Options {
    if options.output_times.is_none() && options.keep_every <= 1 && options.dense_output {
        options.output_times(vec![t1])
    } else {
        options.clone()
    }
}

/// A bar of `n` members on stderr.
fn progress_bar(n: usize) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(n as u64), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{bar:30} {pos}/{len} members, {per_sec}, {eta} left")
    {
        bar.set_style(style);
    }
    bar
}
