//! Errors of the symbolic engine. Each names the expression or symbol involved.

use std::fmt;

/// What went wrong while building, parsing or transforming expressions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// Folding constants would give NaN or an infinity, e.g. `ln(0)` or `1/0`.
    NotFinite {
        /// The offending constant expression in the text syntax.
        expression: String,
        /// Why it has no finite value.
        reason: &'static str,
    },
    /// A name is already used for a symbol of another kind.
    NameTaken {
        /// The name.
        name: String,
    },
    /// The model asks for something its form does not allow.
    Unsupported {
        /// What and why.
        message: String,
    },
    /// A non-smooth function where the Taylor methods need a smooth
    /// right-hand side.
    NotSmooth {
        /// The call node, to find where the user wrote it.
        node: crate::Id,
        /// The function's name in the model language.
        function: &'static str,
    },
    /// The text syntax could not be read.
    Parse {
        /// Byte offset of the problem in the input.
        position: usize,
        /// What was expected or found.
        message: String,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NotFinite { expression, reason } => {
                write!(f, "`{expression}` has no finite value: {reason}")
            }
            Error::NameTaken { name } => {
                write!(f, "the name `{name}` is already used by another symbol")
            }
            Error::Parse { position, message } => write!(f, "at byte {position}: {message}"),
            Error::Unsupported { message } => f.write_str(message),
            Error::NotSmooth { function, .. } => {
                // A model writes `sign` only as a step, `heaviside`.
                let function = if *function == "sign" { "heaviside" } else { function };
                write!(
                f,
                "`{function}` is not smooth and the Taylor methods need a smooth right-hand side: \
                 remove `taylor = ...` from `#[dae_model]`, or write the model without `{function}`"
                )
            }
        }
    }
}

impl std::error::Error for Error {}

/// Results of the symbolic engine.
pub type Result<T> = std::result::Result<T, Error>;
