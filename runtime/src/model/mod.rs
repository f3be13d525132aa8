//! What a generated model gives the integrators: the contract between
//! `#[dae_model]` and the runtime, by capability.

mod capability;

pub use capability::{Availability, Jacobian, MassMatrix};

use crate::info::{ConstraintInfo, EvalError, ModelInfo, ProjectionLevel};

/// Whether `M` integrates a mass matrix other than the identity (diagonal
/// or general), which only RADAU5 does.
pub(crate) fn has_mass_matrix<M: Model>() -> bool {
    !M::MASS.is_identity()
}

/// `M`'s mass matrix, dense and row-major (`n × n`), or empty for `M = I`.
pub(crate) fn dense_mass_matrix<M: Model>(model: &M) -> Vec<f64> {
    let n = M::STATES;
    match M::MASS {
        MassMatrix::Identity => Vec::new(),
        MassMatrix::Diagonal(diagonal) => {
            let mut dense = vec![0.0; n * n];
            for (i, &m) in diagonal.iter().enumerate().take(n) {
                dense[i * n + i] = m;
            }
            dense
        }
        MassMatrix::Pattern(pattern) => {
            let mut values = vec![0.0; pattern.len()];
            model.mass_values(&mut values);
            let mut dense = vec![0.0; n * n];
            for (&(r, c), v) in pattern.iter().zip(values) {
                dense[r * n + c] = v;
            }
            dense
        }
    }
}

/// A state vector of compile-time length: `[f64; N]`. Integrators keep
/// their working vectors in it, so loops over a state unroll and need no
/// bounds checks.
pub trait StateVector: Copy + AsRef<[f64]> + AsMut<[f64]> + Send + Sync + 'static {
    /// The zero vector.
    fn zeros() -> Self;
}

impl<const N: usize> StateVector for [f64; N] {
    fn zeros() -> Self {
        [0.0; N]
    }
}

/// A model compiled by `#[dae_model]`: `y' = f(t, y)` (or `M y' = f(t, y)`)
/// with `y` the states after reduction to first order.
///
/// The items come in groups, one per capability: the core every model has
/// (its size, names, start, right-hand side and outputs), then the
/// Jacobian, the mass form, constraints, events, Taylor series, lanes and
/// sensitivities. What a model lacks is said once, by the group's
/// descriptor: [`Model::JACOBIAN`] ([`Jacobian::Differenced`]),
/// [`Model::MASS`] ([`MassMatrix::Identity`]), [`Model::TAYLOR_TAPE`] and
/// [`Model::EVENT_RATES`] ([`Availability::Unavailable`] with the reason),
/// an empty list (no constraints, no events, no unrolled orders), a count
/// (`LANES = 1`, `SENSITIVITY_COLUMNS = 0`, `TAYLOR_ORDER = 0`), or `None`
/// from a method that hands over data it may not have. The runtime calls
/// a group's methods only where its descriptor offers them, so every
/// default body below is never run by it; a hand-written model implements
/// the core and whichever groups it has.
///
/// Generated code implements every group it has; a method nobody calls is
/// removed from the final binary.
pub trait Model {
    // ----- Core -----

    /// Number of first-order states.
    const STATES: usize;
    /// `[f64; STATES]`.
    type State: StateVector;
    /// Differentiation index found at compile time (0 for an ODE).
    const INDEX: usize;
    /// Names and documentation.
    const INFO: ModelInfo;

    /// Writes the initial state (values may depend on the parameters).
    fn initial_state(&self, y: &mut [f64]);

    /// Writes `dy = f(t, y)`. `y` and `dy` have [`Model::STATES`] entries.
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), EvalError>;

    /// Where the macro combined the model's equations by dividing by an
    /// expression of its parameters (a circuit's capacitance, say), the
    /// first such divisor these parameters make zero or not finite, as
    /// "the coefficient of `der(y1)` in `…`"; `None` when all hold. A run
    /// checks it before its first step.
    fn degenerate_parameters(&self) -> Option<&'static str> {
        None
    }

    /// The value of parameter `index` of [`ModelInfo::parameters`] (NaN
    /// past the last), which a run checks before its first step.
    fn parameter(&self, index: usize) -> f64 {
        let _ = index;
        0.0
    }

    /// Sets parameter `index` of [`ModelInfo::parameters`] to `value`
    /// (nothing past the last): what a tool that knows the model only by
    /// its names (an FMI importer) sets it by.
    fn set_parameter(&mut self, index: usize, value: f64) {
        let _ = (index, value);
    }

    /// Sets input `index` of [`ModelInfo::inputs`] (nothing past the last).
    fn set_input(&mut self, index: usize, input: crate::Input) {
        let _ = (index, input);
    }

    /// A description of the model for people: its doc comment, then its
    /// states, parameters (with this instance's values), algebraic
    /// variables, outputs and events, each with its doc comment; every
    /// name a [`crate::Solution`] answers to is listed.
    fn describe(&self) -> String {
        crate::describe::describe(&Self::INFO, Some(&|k| self.parameter(k)))
    }

    /// The output number `index` at `(t, y)`: the outputs of
    /// [`ModelInfo::outputs`], then the algebraic variables of
    /// [`ModelInfo::algebraics`]. NaN where the model cannot be evaluated
    /// (a singular block), which cannot happen at a point the run accepted;
    /// NaN by default, for a hand-written model without outputs.
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        let _ = (index, t, y);
        f64::NAN
    }

    // ----- Jacobian -----

    /// Whether ∂f/∂y and ∂f/∂t are generated, and where ∂f/∂y is
    /// non-zero.
    const JACOBIAN: Jacobian = Jacobian::Differenced;

    /// Writes the non-zero entries of `∂f/∂y` in the order of the
    /// [`Model::JACOBIAN`] pattern; called only where it is symbolic.
    fn jacobian(&self, t: f64, y: &[f64], values: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, y, values);
        Err(EvalError::JacobianUnavailable)
    }

    /// Writes `∂f/∂t`; called only where [`Model::JACOBIAN`] has it.
    fn time_derivative(&self, t: f64, y: &[f64], dfdt: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, y, dfdt);
        Err(EvalError::JacobianUnavailable)
    }

    // ----- Mass form -----

    /// The mass matrix `M` of `M y' = f(t, y)`.
    const MASS: MassMatrix = MassMatrix::Identity;

    /// Writes the entries of a [`MassMatrix::Pattern`], in its order.
    fn mass_values(&self, values: &mut [f64]) {
        let _ = values;
    }

    /// Components that are index-2 variables of a mass-matrix model (their
    /// error is measured relative to the step, as in `radau5.f`).
    const INDEX2_COMPONENTS: &'static [usize] = &[];

    /// Integrates the model's mass-matrix form (generated for DAEs whose
    /// differential equations solve symbolically) from the consistent
    /// state `y0` with RADAU5; `None` when the model has none.
    fn simulate_mass_form(
        &self,
        t0: f64,
        y0: &[f64],
        t1: f64,
        options: &crate::Options,
    ) -> Option<Result<crate::Solution, crate::Error>> {
        let _ = (t0, y0, t1, options);
        None
    }

    // ----- Constraints -----

    /// Constraints and hidden constraints the solution must satisfy
    /// (empty for an ODE): the runtime projects onto them after each step.
    const CONSTRAINTS: &'static [ConstraintInfo] = &[];

    /// [`Model::CONSTRAINTS`] by level, each with the states it corrects.
    const PROJECTION: &'static [ProjectionLevel] = &[];

    /// States whose initial values consistent initialization keeps
    /// (`state(x0).fixed()`); the others are guesses.
    const FIXED_STATES: &'static [usize] = &[];

    /// Second-order coordinates that no constraint involves (a body free
    /// to slide along a cylindrical joint's axis): each is a degree of
    /// freedom beyond those the constraints leave of the coordinates they
    /// involve.
    const UNCONSTRAINED_COORDINATES: usize = 0;

    /// Writes the residual of every constraint in [`Model::CONSTRAINTS`].
    fn constraints(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let _ = (t, y, out);
    }

    /// Writes the Jacobian of the rows of projection level `level` with
    /// respect to its states, dense and row-major (`rows × slots`).
    fn constraint_jacobian(&self, level: usize, t: f64, y: &[f64], out: &mut [f64]) {
        let _ = (level, t, y, out);
    }

    // ----- Initialization -----

    /// Sets each relation on model variables (`if v < -ve { .. }`, `min`,
    /// `max`, `sign`), held in a discrete boolean between events, from its
    /// value at `(t, y)`: the run calls it at its start.
    fn start_relations(&self, t: f64, y: &mut [f64]) {
        let _ = (t, y);
    }

    /// The states the initial equations (`initial(lhs == rhs)`) decide,
    /// solved for before the first step; every other state keeps its
    /// start.
    const INITIAL_FREE: &'static [usize] = &[];

    /// Each initial equation as written.
    const INITIAL_EQUATIONS: &'static [&'static str] = &[];

    /// Writes each initial equation's residual `lhs − rhs` at `(t, y)`.
    fn initial_residuals(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let _ = (t, y, out);
    }

    /// Writes the initial residuals' Jacobian with respect to the states
    /// of [`Model::INITIAL_FREE`], dense and row-major.
    fn initial_jacobian(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let _ = (t, y, out);
    }

    // ----- Events -----

    /// Writes the value of every event function (see [`ModelInfo::events`])
    /// at `(t, y)` into `g`.
    fn events(&self, t: f64, y: &[f64], g: &mut [f64]) {
        let _ = (t, y, g);
    }

    /// Whether [`Model::event_rates`] is generated (not where the mass
    /// matrix is solved at run time); without the rates, an event function
    /// that crosses zero and back within one step goes unseen.
    const EVENT_RATES: Availability =
        Availability::Unavailable("the rates of its event functions are not generated");

    /// Writes the time derivative of every event function along the
    /// solution, `dg/dt = ∂g/∂t + ∇g·f`, at `(t, y)` into `dg`; called
    /// only where [`Model::EVENT_RATES`] is available.
    fn event_rates(&self, t: f64, y: &[f64], dg: &mut [f64]) {
        let _ = (t, y, dg);
    }

    /// Clock `index` of [`ModelInfo::clocks`]: its period and its first
    /// instant, `(h, t0)` of `every(h).offset(t0)`, with this instance's
    /// parameters.
    fn clock(&self, index: usize) -> (f64, f64) {
        let _ = index;
        (f64::INFINITY, 0.0)
    }

    /// Applies the actions of `trigger` at time `t`: event `trigger` of
    /// [`ModelInfo::events`], or clock `trigger − events` of
    /// [`ModelInfo::clocks`]. `pre` holds the state just before the
    /// instant (what `pre(x)` reads); `y` the state as the actions before
    /// left it, which each action updates in place, in the order written.
    fn act(&self, trigger: usize, t: f64, pre: &[f64], y: &mut [f64]) {
        let _ = (trigger, t, pre, y);
    }

    /// The breakpoints of this instance's inputs ([`ModelInfo::inputs`]):
    /// the times where a table's interpolation has a kink or a jump in a
    /// derivative, and the instants where the model's own expressions
    /// switch in the time alone (`heaviside(t − t0)`, a step source): a
    /// run steps to each exactly and restarts there.
    fn input_breakpoints(&self) -> Vec<f64> {
        Vec::new()
    }

    // ----- Taylor series -----

    /// Highest order of [`Model::taylor_derivatives`] (0: none generated).
    const TAYLOR_ORDER: usize = 0;

    /// Writes y', y'', …, y⁽ᵒʳᵈᵉʳ⁾ at (t, y) into `out` (order blocks of
    /// STATES values), from the derivatives the macro derived symbolically
    /// (the economic Taylor scheme, course notes §1.3.1); called only for
    /// an order up to [`Model::TAYLOR_ORDER`].
    fn taylor_derivatives(
        &self,
        t: f64,
        y: &[f64],
        order: usize,
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        let _ = (t, y, out);
        Err(EvalError::TaylorUnavailable { order })
    }

    /// Whether [`Model::taylor_tape`] hands over the model's tape, and if
    /// not, why (found at compile time): `Method::Taylor` refuses the run
    /// with the reason.
    const TAYLOR_TAPE: Availability = Availability::Unavailable("it has no Taylor tape");

    /// The right-hand side as a tape of elementary operations and the
    /// operand of each f_i, for the adaptive Taylor method (generated for
    /// every explicit ODE with a smooth right-hand side, see
    /// [`Model::TAYLOR_TAPE`]).
    #[allow(clippy::type_complexity)]
    fn taylor_tape(
        &self,
    ) -> Option<(Vec<crate::taylor_tape::TapeOp>, Vec<crate::taylor_tape::Operand>)> {
        None
    }

    /// Orders of the adaptive Taylor method emitted as straight-line code
    /// (`#[dae_model(unroll = [..])]`); empty: the tape is interpreted.
    const TAYLOR_UNROLLED: &'static [usize] = &[];

    /// The length of the buffer [`Model::taylor_jet_unrolled`] needs for
    /// `order`: STATES·(order+1), or more for a large jet, which keeps all
    /// its intermediate coefficients there after the states'.
    fn taylor_jet_len(&self, order: usize) -> usize {
        Self::STATES * (order + 1)
    }

    /// Whether [`Model::taylor_jet_unrolled`] writes `order`'s coefficients
    /// order by order, state i's coefficient k at `out[k·STATES + i]`,
    /// instead of state by state. Large jets do: the state update and the
    /// step size rule then run over contiguous vectors of states.
    fn taylor_jet_by_coefficient(&self, order: usize) -> bool {
        let _ = order;
        false
    }

    /// The normalised Taylor coefficients of the solution through (t, y)
    /// up to `order`, by the straight-line recurrences emitted for that
    /// order: state i's coefficient k at `out[i·(order+1) + k]`, or at
    /// `out[k·STATES + i]` when [`Model::taylor_jet_by_coefficient`] says
    /// so (what lies beyond is the jet's own). `false` (and nothing
    /// written) when `order` is not in [`Model::TAYLOR_UNROLLED`] or `out`
    /// is shorter than [`Model::taylor_jet_len`].
    fn taylor_jet_unrolled(&self, t: f64, y: &[f64], order: usize, out: &mut [f64]) -> bool {
        let _ = (t, y, order, out);
        false
    }

    // ----- Lanes -----

    /// Members stepped together: a batch model (`#[dae_model(batch = L)]`)
    /// holds `LANES` members' states, component `i` of lane `l` at
    /// `i·LANES + l`, and the step-size control measures each lane alone;
    /// 1 for every other model.
    const LANES: usize = 1;

    /// A batch model's members' tapes, lane by lane (see [`Model::LANES`]):
    /// the adaptive Taylor method runs them as one tape on lanes. `None`
    /// for every other model, and for a batch whose members have no tape.
    fn taylor_member_tapes(&self) -> Option<Vec<crate::taylor_tape::Tape>> {
        None
    }

    // ----- Sensitivities -----

    /// For a model made by `with_sensitivities()`: how many sensitivity
    /// columns follow the base model's states (its `STATES / (1 + columns)`
    /// of them); its Jacobian is then block lower triangular with the base
    /// Jacobian on the diagonal, and the implicit methods factor that block
    /// alone. 0 for every other model.
    const SENSITIVITY_COLUMNS: usize = 0;

    /// For a model with sensitivity columns
    /// ([`Model::SENSITIVITY_COLUMNS`]): writes the derivatives of the
    /// model's own states alone, the first `STATES / (1 +
    /// SENSITIVITY_COLUMNS)`, into `dy` (that long), reading those states
    /// of `y` (all [`Model::STATES`]): what a staggered corrector iterates
    /// on before the columns. `None` where it is not generated.
    fn own_rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Option<Result<(), EvalError>> {
        let _ = (t, y, dy);
        None
    }
}
