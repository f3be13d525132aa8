//! Another solver run on the same problem. Peers see a registered model
//! through [`PeerProblem`]: its size, initial state, end time, and the
//! generated right-hand side and (dense) Jacobian, so every registered ODE
//! reaches every peer with no code per model, and both sides evaluate the
//! same `f`.

use crate::{Record, Settings};

/// A registered problem as a peer sees it.
pub struct PeerProblem<'a> {
    /// The model's name.
    pub name: &'a str,
    /// Its name in `shared/peers/peer.py`, if it has one.
    pub peer: Option<&'a str>,
    /// The initial state.
    pub y0: Vec<f64>,
    /// The end time (runs start at 0).
    pub t_end: f64,
    /// The relative tolerances of the sweep.
    pub tolerances: Vec<f64>,
    /// atol = this × rtol.
    pub atol_factor: f64,
    /// The sweep has an implicit method (the problem is stiff): implicit
    /// peers apply.
    pub stiff: bool,
    /// The sweep has an explicit method: explicit peers apply.
    pub nonstiff: bool,
    /// The reference at `t_end`.
    pub reference: &'a [f64],
    /// `f(t, y)`; NaN where the model's evaluation fails.
    pub rhs: &'a VectorFunction<'a>,
    /// `∂f/∂y`, dense, row-major.
    pub jacobian: &'a VectorFunction<'a>,
}

/// A function of `(t, y)` writing into its third argument.
pub type VectorFunction<'a> = dyn Fn(f64, &[f64], &mut [f64]) + Sync + 'a;

/// A peer solver.
pub trait Peer {
    /// `ode_solvers DOP853`, `heyoka`, …
    fn name(&self) -> String;
    /// Whether it runs on this problem (an explicit peer on a stiff
    /// problem, a Python peer without the problem in peer.py: no).
    fn applies(&self, problem: &PeerProblem) -> bool;
    /// One run at relative tolerance `tol`: `Err` says why the peer is
    /// missing (not installed, …), which the report shows; a run that fails
    /// is a record with an infinite error.
    fn run(&self, problem: &PeerProblem, tol: f64, settings: &Settings) -> Result<Record, String>;
    /// Whether its runs are timed in this process, so that they alternate
    /// with ours (see [`Settings::rounds`]); a peer in another process,
    /// which starts up for every run, runs once per tolerance.
    fn in_process(&self) -> bool {
        true
    }
    /// The peer's own set-up time for the problem (heyoka's JIT build), if
    /// it has one.
    fn setup_seconds(&self, _problem: &PeerProblem) -> Option<f64> {
        None
    }
}
