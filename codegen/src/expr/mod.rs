//! Expressions: a hash-consed DAG of canonical nodes with exact rational
//! constants (`node`, `number`, `rational`, `graph`), constructors that
//! simplify without changing values (`build`), forward-mode
//! differentiation (`diff`, `jacobian`), substitution, evaluation, a
//! parser and a printer for tests.

pub mod build;
pub mod diff;
pub mod display;
pub mod eval;
pub mod graph;
pub mod jacobian;
pub mod node;
pub mod number;
pub mod parse;
pub mod rational;
pub mod substitute;
