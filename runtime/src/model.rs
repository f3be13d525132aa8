//! What a generated model gives the integrators: the contract between
//! `#[dae_model]` and the runtime.

use crate::info::{ConstraintInfo, EvalError, ModelInfo, ProjectionLevel};

/// Whether `M` integrates a mass matrix other than the identity (diagonal
/// or general), which only RADAU5 does.
pub(crate) fn has_mass_matrix<M: Model>() -> bool {
    !M::MASS.is_empty() || !M::MASS_PATTERN.is_empty()
}

/// `M`'s mass matrix, dense and row-major (`n × n`), or empty for `M = I`.
pub(crate) fn dense_mass_matrix<M: Model>(model: &M) -> Vec<f64> {
    let n = M::STATES;
    if !M::MASS_PATTERN.is_empty() {
        let mut values = vec![0.0; M::MASS_PATTERN.len()];
        model.mass_values(&mut values);
        let mut dense = vec![0.0; n * n];
        for (&(r, c), v) in M::MASS_PATTERN.iter().zip(values) {
            dense[r * n + c] = v;
        }
        dense
    } else if M::MASS.len() == n {
        let mut dense = vec![0.0; n * n];
        for (i, &m) in M::MASS.iter().enumerate() {
            dense[i * n + i] = m;
        }
        dense
    } else {
        Vec::new()
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

/// A model compiled by `#[dae_model]`: `y' = f(t, y)` with `y` the states
/// after reduction to first order.
///
/// Generated code implements every method; integrators call only what they
/// need, and a method nobody calls is removed from the final binary.
pub trait Model {
    /// Number of first-order states.
    const STATES: usize;
    /// `[f64; STATES]`.
    type State: StateVector;
    /// Differentiation index found at compile time (0 for an ODE).
    const INDEX: usize;
    /// Names and documentation.
    const INFO: ModelInfo;
    /// `(row, column)` of the structurally non-zero entries of `∂f/∂y`, in
    /// the order [`Model::jacobian`] writes them. A hand-written model
    /// without a Jacobian leaves it empty.
    const JACOBIAN_PATTERN: &'static [(usize, usize)] = &[];
    /// For a model made by `with_sensitivities()`: how many sensitivity
    /// columns follow the base model's states (its `STATES / (1 + columns)`
    /// of them); its Jacobian is then block lower triangular with the base
    /// Jacobian on the diagonal, and the implicit methods factor that block
    /// alone. 0 for every other model.
    const SENSITIVITY_COLUMNS: usize = 0;

    /// Writes the initial state (values may depend on the parameters).
    fn initial_state(&self, y: &mut [f64]);

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

    /// A description of the model for people: its doc comment, then its
    /// states, parameters (with this instance's values), algebraic
    /// variables, outputs and events, each with its doc comment; every
    /// name a [`crate::Solution`] answers to is listed.
    fn describe(&self) -> String {
        crate::describe::describe(&Self::INFO, Some(&|k| self.parameter(k)))
    }

    /// Writes `dy = f(t, y)`. `y` and `dy` have [`Model::STATES`] entries.
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), EvalError>;

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

    /// Writes the non-zero entries of `∂f/∂y` in the order of
    /// [`Model::JACOBIAN_PATTERN`]. Without it (the default, for a
    /// hand-written model) the implicit methods difference [`Model::rhs`].
    fn jacobian(&self, t: f64, y: &[f64], values: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, y, values);
        Err(EvalError::JacobianUnavailable)
    }

    /// Writes `∂f/∂t`; like [`Model::jacobian`], differenced where missing.
    fn time_derivative(&self, t: f64, y: &[f64], dfdt: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, y, dfdt);
        Err(EvalError::JacobianUnavailable)
    }

    /// Members stepped together: a batch model (`#[dae_model(batch = L)]`)
    /// holds `LANES` members' states, component `i` of lane `l` at
    /// `i·LANES + l`, and the step-size control measures each lane alone;
    /// 1 for every other model.
    const LANES: usize = 1;

    /// Highest order of [`Model::taylor_derivatives`] (0: none generated).
    const TAYLOR_ORDER: usize = 0;

    /// Writes y', y'', …, y⁽ᵒʳᵈᵉʳ⁾ at (t, y) into `out` (order blocks of
    /// STATES values), from the derivatives the macro derived symbolically
    /// (the economic Taylor scheme, course notes §1.3.1).
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

    /// Why [`Model::taylor_tape`] is `None`, found at compile time (empty
    /// where the model has its tape): `Method::Taylor` refuses the run with
    /// it.
    const TAYLOR_UNAVAILABLE: &'static str = "";

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
    /// so (what lies beyond is the jet's own). `false` (and nothing written) when `order`
    /// is not in [`Model::TAYLOR_UNROLLED`] or `out` is shorter than
    /// [`Model::taylor_jet_len`].
    fn taylor_jet_unrolled(&self, t: f64, y: &[f64], order: usize, out: &mut [f64]) -> bool {
        let _ = (t, y, order, out);
        false
    }

    /// The right-hand side as a tape of elementary operations and the
    /// operand of each f_i, for the adaptive Taylor method (generated for
    /// every explicit ODE with a smooth right-hand side; `None` otherwise,
    /// see [`Model::TAYLOR_UNAVAILABLE`]).
    #[allow(clippy::type_complexity)]
    fn taylor_tape(
        &self,
    ) -> Option<(Vec<crate::taylor_tape::TapeOp>, Vec<crate::taylor_tape::Operand>)> {
        None
    }

    /// A batch model's members' tapes, lane by lane (see [`Model::LANES`]):
    /// the adaptive Taylor method runs them as one tape on lanes. `None`
    /// for every other model, and for a batch whose members have no tape.
    fn taylor_member_tapes(&self) -> Option<Vec<crate::taylor_tape::Tape>> {
        None
    }

    /// Writes the value of every event function (see [`ModelInfo::events`])
    /// at `(t, y)` into `g`.
    fn events(&self, t: f64, y: &[f64], g: &mut [f64]) {
        let _ = (t, y, g);
    }

    /// Writes the time derivative of every event function along the
    /// solution, `dg/dt = ∂g/∂t + ∇g·f`, at `(t, y)` into `dg`; `false` if
    /// the model does not have them (its mass matrix is solved at run time).
    fn event_rates(&self, t: f64, y: &[f64], dg: &mut [f64]) -> bool {
        let _ = (t, y, dg);
        false
    }

    /// Constraints and hidden constraints the solution must satisfy
    /// (empty for an ODE): the runtime projects onto them after each step.
    const CONSTRAINTS: &'static [ConstraintInfo] = &[];

    /// The diagonal of a singular mass matrix `M` in `M y' = f(t, y)`: 1 for
    /// a differential component, 0 for an algebraic one; empty for `M = I`.
    /// Only RADAU5 integrates such a model (the Gear–Gupta–Leimkuhler form
    /// of a mechanism, a semi-explicit index-1 DAE).
    const MASS: &'static [f64] = &[];

    /// The non-zero entries `(row, column)` of a general mass matrix `M` in
    /// `M y' = f(t, y)`, constant during a run (it may depend on the
    /// parameters): a circuit's capacitances between nodes, as written.
    /// Empty for `M = I` or the diagonal [`Model::MASS`]. Only RADAU5
    /// integrates such a model, as Hairer's RADAU5 does.
    const MASS_PATTERN: &'static [(usize, usize)] = &[];

    /// Writes the entries of [`Model::MASS_PATTERN`], in its order.
    fn mass_values(&self, values: &mut [f64]) {
        let _ = values;
    }

    /// Components that are index-2 variables of a mass-matrix model (their
    /// error is measured relative to the step, as in `radau5.f`).
    const INDEX2_COMPONENTS: &'static [usize] = &[];

    /// States whose initial values consistent initialization keeps
    /// (`state(x0).fixed()`); the others are guesses.
    const FIXED_STATES: &'static [usize] = &[];

    /// [`Model::CONSTRAINTS`] by level, each with the states it corrects.
    const PROJECTION: &'static [ProjectionLevel] = &[];

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

    /// The output number `index` at `(t, y)`: the outputs of
    /// [`ModelInfo::outputs`], then the algebraic variables of
    /// [`ModelInfo::algebraics`]. NaN where the model cannot be evaluated
    /// (a singular block), which cannot happen at a point the run accepted;
    /// NaN by default, for a hand-written model without outputs.
    fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        let _ = (index, t, y);
        f64::NAN
    }

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
}
