//! What a model says about itself at compile time: the names and docs of
//! its values ([`ModelInfo`], [`EventInfo`]), its constraints
//! ([`ConstraintInfo`], [`ProjectionLevel`]), and why it could not be
//! evaluated at a point ([`EvalError`]).

/// Why a model could not be evaluated at a point.
#[derive(Clone, Debug, PartialEq)]
pub enum EvalError {
    /// A block of the mass matrix `E(t, y)` in `E y' = g` is singular here.
    SingularMassMatrix {
        /// The derivatives of the block, by name.
        unknowns: Vec<&'static str>,
    },
    /// The model has no analytic Jacobian (its mass matrix is solved at run time).
    JacobianUnavailable,
    /// Newton's method on the model's nonlinear algebraic equations failed:
    /// ∂g/∂z singular (`singular`: the equations do not determine the
    /// variables there, the DAE is not of index 1 at this point), or no
    /// convergence from the last solution nor from the guesses.
    NonlinearAlgebraic {
        /// The equations, as written.
        equations: Vec<&'static str>,
        /// The variables they determine.
        unknowns: Vec<&'static str>,
        /// Whether ∂g/∂z was singular.
        singular: bool,
    },
    /// The model has no Taylor derivatives of this order: expand it with
    /// `#[dae_model(taylor = p)]`, p ≥ the order asked for.
    TaylorUnavailable {
        /// The order asked for.
        order: usize,
    },
}

impl std::fmt::Display for EvalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EvalError::SingularMassMatrix { unknowns } => write!(
                f,
                "the equations do not determine {} here (their coefficient matrix is singular at this point): the model passes through a singular configuration, or its equations are dependent there",
                unknowns.join(", ")
            ),
            EvalError::NonlinearAlgebraic {
                equations,
                unknowns,
                singular: true,
            } => write!(
                f,
                "the equations `{}` do not determine `{}` here: their Jacobian in {} is singular, so the DAE is not of index 1 at this point (a turning point of the algebraic equations, or variables the equations do not fix)",
                equations.join("`, `"),
                unknowns.join("`, `"),
                unknowns.join(", ")
            ),
            EvalError::NonlinearAlgebraic {
                equations, unknowns, ..
            } => write!(
                f,
                "Newton's method on `{}` did not converge for `{}`, neither from the last solution nor from the guesses given with algebraic(..): the equations may have no solution near there, or the guesses are too far",
                equations.join("`, `"),
                unknowns.join("`, `")
            ),
            EvalError::JacobianUnavailable => write!(
                f,
                "the model has no analytic Jacobian (its mass matrix is solved at run time)"
            ),
            EvalError::TaylorUnavailable { order } => write!(
                f,
                "Taylor derivatives of order {order} were not generated; expand the model with #[dae_model(taylor = {order})] or higher"
            ),
        }
    }
}

/// Which zero crossings of an event function fire the event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventDirection {
    /// Every crossing.
    Any,
    /// From negative to positive (`event(g).rising()`).
    Rising,
    /// From positive to negative (`event(g).falling()`).
    Falling,
}

/// An event declared with `let name = event(g)`: the run notes the times
/// where `g(t, y)` crosses zero, applies the event's actions there
/// (`.reinit(..)`), and stops at the first if it is terminal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EventInfo {
    /// The `let` name.
    pub name: &'static str,
    /// Which crossings count.
    pub direction: EventDirection,
    /// The run stops at the first crossing.
    pub terminal: bool,
    /// The states and discrete values its actions set, in order (empty:
    /// the event only marks the time).
    pub resets: &'static [&'static str],
    /// The event's doc comment.
    pub doc: &'static str,
}

/// A clock declared with `let name = every(h).offset(t0).reinit(..)`: its
/// actions at the instants `t0 + k·h`, which every method steps to
/// exactly ([`crate::Model::clock`] gives `h` and `t0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClockInfo {
    /// The `let` name.
    pub name: &'static str,
    /// The states and discrete values its actions set, in order.
    pub resets: &'static [&'static str],
    /// The clock's doc comment.
    pub doc: &'static str,
}

/// How a model's equations are solved for their unknowns (the highest
/// derivatives and the algebraic variables) at each evaluation, as the
/// sorting at compile time found it: aliases removed, then the equations
/// in causal order, one at a time where one equation determines one
/// unknown, in blocks where several determine several together.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StructureInfo {
    /// Equations removed with one of their variables as aliases (`a ==
    /// b`, `a == -b`, `a + b == 0`, `a == c`): the variable reads its
    /// alias's value.
    pub aliases: usize,
    /// Equations solved one at a time, symbolically, each for its unknown
    /// from what the equations before it determined.
    pub one_at_a_time: usize,
    /// The blocks of equations solved together, in causal order.
    pub blocks: &'static [BlockInfo],
}

impl StructureInfo {
    /// The structure of a model written by hand: nothing known.
    pub const NONE: StructureInfo = StructureInfo { aliases: 0, one_at_a_time: 0, blocks: &[] };
}

/// Equations that determine their unknowns together.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockInfo {
    /// Its equations, as many as its unknowns (before tearing).
    pub size: usize,
    /// How it is solved.
    pub solution: BlockSolution,
}

/// How a block of equations is solved at each evaluation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockSolution {
    /// Linear in its unknowns and solved symbolically at compile time.
    Symbolic,
    /// Linear, solved by an LU factorization at run time of `lu` unknowns
    /// (the others eliminated symbolically around it: accelerations with a
    /// constant mass matrix, around a mechanism's multipliers).
    Linear {
        /// The unknowns of the run-time factorization.
        lu: usize,
    },
    /// Nonlinear, solved by Newton's method on `tearing` variables, the
    /// others computed from them equation by equation.
    Newton {
        /// The variables Newton iterates on.
        tearing: usize,
    },
    /// Nonlinear in algebraic variables that do not close into a block:
    /// left to the Newton iteration of the mass-matrix form (RADAU5).
    MassMatrix,
}

/// Names and documentation of a model, known at compile time.
#[derive(Clone, Copy, Debug)]
pub struct ModelInfo {
    /// The generated type's name.
    pub name: &'static str,
    /// The model's doc comment.
    pub doc: &'static str,
    /// States in solution order: declared states, then (for each state of
    /// order k ≥ 2) its derivatives `der(x)` … `der^(k-1)(x)` right after it.
    pub states: &'static [&'static str],
    /// Each state's doc comment (for `der(x)`, what it is the rate of; for
    /// a scene's coordinates, what they are).
    pub state_docs: &'static [&'static str],
    /// Parameters in declaration order.
    pub parameters: &'static [&'static str],
    /// Each parameter's doc comment.
    pub parameter_docs: &'static [&'static str],
    /// Named outputs (`let e = output(...)`).
    pub outputs: &'static [&'static str],
    /// Each output's doc comment.
    pub output_docs: &'static [&'static str],
    /// The outputs the model declares at its own level, the model's
    /// outputs to the world (an FMU's); the rest of [`ModelInfo::outputs`]
    /// are values read by name: its parts' outputs, variables the
    /// structure eliminated, a scene's coordinates, inputs.
    pub declared_outputs: &'static [&'static str],
    /// Number of equations the user wrote (after unrolling loops).
    pub equations: usize,
    /// Events (`let e = event(g)`), in declaration order.
    pub events: &'static [EventInfo],
    /// Clocks (`let tick = every(h)`), in declaration order.
    pub clocks: &'static [ClockInfo],
    /// The states that are discrete values (`discrete(v0)`): constant
    /// between events, set only by actions.
    pub discrete: &'static [&'static str],
    /// Inputs (`let u = input(u0)`): signals the caller supplies, each a
    /// field of type [`crate::Input`], read by name like outputs.
    pub inputs: &'static [&'static str],
    /// Algebraic variables (`let z = algebraic(guess)`), computed from the
    /// states at each point; read them by name like outputs.
    pub algebraics: &'static [&'static str],
    /// Each algebraic variable's doc comment.
    pub algebraic_docs: &'static [&'static str],
    /// How the equations are solved for their unknowns.
    pub structure: StructureInfo,
    /// The instances of components the model was built from, parents
    /// first: the hierarchy its names follow (`motor.emf.i`).
    pub components: &'static [ComponentInfo],
}

/// One instance of a component in a model built from parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ComponentInfo {
    /// Its path: `motor.emf`.
    pub path: &'static str,
    /// The part it instantiates: `emf`, or the user's `parts::dc_motor`.
    pub part: &'static str,
}

impl ModelInfo {
    /// The names of a model written by hand rather than by the macro: its
    /// states, no docs, parameters, outputs, events or structure. Set what
    /// else it has with struct update syntax:
    /// `ModelInfo { state_docs: &["charge"], ..ModelInfo::bare("Rc", &["q"], 1) }`.
    pub const fn bare(
        name: &'static str,
        states: &'static [&'static str],
        equations: usize,
    ) -> ModelInfo {
        ModelInfo {
            name,
            doc: "",
            states,
            state_docs: &[],
            parameters: &[],
            parameter_docs: &[],
            outputs: &[],
            output_docs: &[],
            declared_outputs: &[],
            equations,
            events: &[],
            clocks: &[],
            discrete: &[],
            inputs: &[],
            algebraics: &[],
            algebraic_docs: &[],
            structure: StructureInfo::NONE,
            components: &[],
        }
    }
}

/// A constraint, or a derivative of one, that the integrated index-1 form
/// no longer enforces and that the runtime projects onto after each step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConstraintInfo {
    /// The user's equation, as written.
    pub equation: &'static str,
    /// How often it was differentiated (0: the constraint itself; 1: the
    /// velocity level of a position constraint).
    pub level: usize,
}

/// The invariants of one differentiation level and the states a projection
/// onto them corrects (positions for level 0, velocities for level 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProjectionLevel {
    /// Indices into [`crate::Model::CONSTRAINTS`].
    pub rows: &'static [usize],
    /// Indices of the corrected states, ascending.
    pub slots: &'static [usize],
}

impl ModelInfo {
    /// Whether a run of the model has instants where something acts or
    /// changes: an event with actions, a clock, an input (a table's
    /// breakpoints).
    pub fn is_hybrid(&self) -> bool {
        !self.clocks.is_empty()
            || !self.inputs.is_empty()
            || self.events.iter().any(|e| !e.resets.is_empty())
    }
}
