//! The typed descriptors of [`super::Model`]'s capability groups: each
//! says in one value what a model offers, so no two items can disagree.

/// How the implicit methods get a model's ∂f/∂y and ∂f/∂t.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Jacobian {
    /// Neither is generated (a hand-written model, a batch, a model whose
    /// f is not explicit): the implicit methods difference
    /// [`super::Model::rhs`] with `radau5.f`'s increments.
    Differenced,
    /// [`super::Model::jacobian`] writes the structurally non-zero entries
    /// of ∂f/∂y at `pattern`, `(row, column)`, in its order (an empty
    /// pattern: f does not depend on y).
    Symbolic {
        /// The non-zero entries, in the order `jacobian` writes them.
        pattern: &'static [(usize, usize)],
        /// Whether [`super::Model::time_derivative`] writes ∂f/∂t; where
        /// it does not, ∂f/∂t is differenced.
        time_derivative: bool,
    },
}

impl Jacobian {
    /// The non-zero entries of a symbolic Jacobian; empty where it is
    /// differenced.
    pub const fn pattern(&self) -> &'static [(usize, usize)] {
        match self {
            Jacobian::Differenced => &[],
            Jacobian::Symbolic { pattern, .. } => pattern,
        }
    }

    /// Whether ∂f/∂y is generated.
    pub const fn is_symbolic(&self) -> bool {
        matches!(self, Jacobian::Symbolic { .. })
    }

    /// Whether ∂f/∂t is generated.
    pub const fn has_time_derivative(&self) -> bool {
        matches!(self, Jacobian::Symbolic { time_derivative: true, .. })
    }
}

/// The mass matrix `M` of `M y' = f(t, y)`, constant during a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MassMatrix {
    /// `M = I`: an explicit ODE, which every method integrates.
    Identity,
    /// A diagonal `M`: 1 for a differential component, 0 for an algebraic
    /// one (the Gear–Gupta–Leimkuhler form of a mechanism, a semi-explicit
    /// index-1 DAE). Only RADAU5 and RODAS5P integrate it.
    Diagonal(&'static [f64]),
    /// A general `M` with non-zero entries at these `(row, column)`, whose
    /// values [`super::Model::mass_values`] writes in this order (they may
    /// depend on the parameters): a circuit's capacitances between nodes,
    /// as written. Only RADAU5 and RODAS5P integrate it, as Hairer's
    /// RADAU5 does.
    Pattern(&'static [(usize, usize)]),
}

impl MassMatrix {
    /// Whether `M = I`.
    pub const fn is_identity(&self) -> bool {
        matches!(self, MassMatrix::Identity)
    }

    /// The diagonal of a [`MassMatrix::Diagonal`]; empty otherwise.
    pub const fn diagonal(&self) -> &'static [f64] {
        match self {
            MassMatrix::Diagonal(diagonal) => diagonal,
            _ => &[],
        }
    }

    /// The non-zero entries of a [`MassMatrix::Pattern`]; empty otherwise.
    pub const fn pattern(&self) -> &'static [(usize, usize)] {
        match self {
            MassMatrix::Pattern(pattern) => pattern,
            _ => &[],
        }
    }

    /// Whether component `i` is algebraic on a diagonal `M` (its entry is
    /// 0); a general `M` does not say it per component.
    pub fn is_algebraic(&self, i: usize) -> bool {
        matches!(self, MassMatrix::Diagonal(d) if d.get(i) == Some(&0.0))
    }
}

/// Whether a model has a capability the macro generates where it can, and
/// if it cannot, why (which a method that needs it gives as its refusal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Availability {
    /// Generated.
    Available,
    /// Not generated, for this reason.
    Unavailable(&'static str),
}

impl Availability {
    /// Whether it is generated.
    pub const fn is_available(&self) -> bool {
        matches!(self, Availability::Available)
    }

    /// The reason it is not generated; `None` where it is.
    pub const fn reason(&self) -> Option<&'static str> {
        match self {
            Availability::Available => None,
            Availability::Unavailable(reason) => Some(reason),
        }
    }
}
