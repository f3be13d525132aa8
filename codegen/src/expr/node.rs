//! The vocabulary of the expression DAG: ids, symbols, functions and nodes.

use crate::expr::number::Number;
use std::fmt;

/// A node of the [`crate::Graph`]: an index into its arena. Children always have
/// smaller ids than their parents, so ascending id order is a topological order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Id(pub(crate) u32);

impl Id {
    /// The arena index.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for Id {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "%{}", self.0)
    }
}

/// A symbol of the [`crate::Graph`]: an index into its symbol table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SymbolId(pub(crate) u32);

impl SymbolId {
    /// The symbol-table index.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What a symbol stands for in a model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SymbolKind {
    /// A differential variable.
    State,
    /// An algebraic variable of a DAE.
    Algebraic,
    /// A runtime parameter (constant during a run).
    Parameter,
    /// The independent variable.
    Time,
    /// A signal the caller supplies at run time (`input(u0)`), a function
    /// of the time that the analyses treat as known, like the time; with
    /// `rate_of`, the rate of that input.
    Input {
        /// For the rate of an input, the input.
        rate_of: Option<SymbolId>,
    },
    /// The `order`-th time derivative of another symbol (`der(x)`, `der(der(x))`),
    /// used by implicit forms and the economic Taylor scheme.
    Derivative {
        /// The differentiated symbol (never itself a derivative).
        of: SymbolId,
        /// 1 for `der(x)`, 2 for `der(der(x))`, ...
        order: u32,
    },
    /// A named intermediate standing for its definition; differentiation and
    /// evaluation see through it, emission gives it its own `let`.
    Intermediate {
        /// The expression the name stands for.
        definition: Id,
    },
}

/// A symbol's name and kind.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symbol {
    /// The name used in `Display`, in emitted code and in error messages.
    pub name: String,
    /// What it stands for.
    pub kind: SymbolKind,
}

/// Elementary functions of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Func {
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
    /// Tangent.
    Tan,
    /// Arcsine.
    Asin,
    /// Arccosine.
    Acos,
    /// Arctangent.
    Atan,
    /// Hyperbolic sine.
    Sinh,
    /// Hyperbolic cosine.
    Cosh,
    /// Hyperbolic tangent.
    Tanh,
    /// Exponential.
    Exp,
    /// Natural logarithm.
    Ln,
    /// Absolute value (not smooth at 0).
    Abs,
    /// Sign: -1, 0 or 1 (not continuous at 0); the derivative of `abs`.
    Sign,
}

impl Func {
    /// Every function, for parsers and tests.
    pub const ALL: [Func; 13] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Sinh,
        Func::Cosh,
        Func::Tanh,
        Func::Exp,
        Func::Ln,
        Func::Abs,
        Func::Sign,
    ];

    /// The name in the text syntax (`ln`, not Rust's method name).
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
            Func::Sign => "sign",
        }
    }

    /// `false` for functions whose derivative is not continuous everywhere
    /// in their domain; methods that need smoothness refuse them.
    pub fn is_smooth(self) -> bool {
        !matches!(self, Func::Abs | Func::Sign)
    }

    /// The value in `f64`, with the semantics of the emitted code.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sinh => x.sinh(),
            Func::Cosh => x.cosh(),
            Func::Tanh => x.tanh(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Abs => x.abs(),
            Func::Sign => sign(x),
        }
    }
}

/// -1, 0 or 1 (unlike `f64::signum`, which gives 1 at 0).
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// One node of the DAG. Only [`crate::Graph`]'s smart constructors make them,
/// so every node is in canonical form:
///
/// - `Add` has at least two terms sorted by id, at most one of them a
///   number, none of them an `Add`, and no two that differ only by a numeric
///   coefficient (like terms are collected).
/// - `Mul` has at least two factors sorted by id, at most one of them a
///   number (not 0 or 1), none of them a `Mul`, and no two with the same base
///   (powers are merged). Negation is `-1 * x`, division is `x * y^-1`.
/// - `Pow` never has exponent 0 or 1, and has two numbers only for an
///   irrational root of a rational (`2^(1/2)` stays exact).
/// - `Call` and `Atan2` never have only numeric arguments.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant.
    Number(Number),
    /// A symbol (state, parameter, time, ...).
    Symbol(SymbolId),
    /// A sum of terms.
    Add(Box<[Id]>),
    /// A product of factors.
    Mul(Box<[Id]>),
    /// `[base, exponent]`; numeric exponents are exact rationals where possible.
    Pow([Id; 2]),
    /// An elementary function of one argument.
    Call(Func, Id),
    /// `[y, x]` of `atan2(y, x)`.
    Atan2([Id; 2]),
}

impl Node {
    /// The operands in order (an intermediate symbol's definition is not an
    /// operand here; see [`crate::Graph::operands`]).
    pub fn children(&self) -> &[Id] {
        match self {
            Node::Number(_) | Node::Symbol(_) => &[],
            Node::Add(c) | Node::Mul(c) => c,
            Node::Pow(pair) | Node::Atan2(pair) => pair,
            Node::Call(_, a) => std::slice::from_ref(a),
        }
    }
}
