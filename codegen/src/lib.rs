//! `daegen-codegen`: daegen's symbolic engine, a plain library that the
//! `#[dae_model]` macro calls and that tests use directly.
//!
//! The pipeline, one pass per module:
//!
//! 1. [`Graph`] (`graph.rs`, `build.rs`): a hash-consed DAG of canonical
//!    nodes with exact rational constants; smart constructors simplify
//!    without changing values.
//! 2. Differentiation (`diff.rs`, `jacobian.rs`): partial and total time
//!    derivatives in forward mode over the DAG, sparse Jacobians.
//! 3. Scheduling (`schedule.rs`): common-subexpression elimination across all
//!    outputs into a straight-line [`Program`].
//! 4. Emission (`emit.rs`): the program as Rust tokens.
//!
//! ```
//! use daegen_codegen::{Graph, emit_program};
//! use proc_macro2::Literal;
//! use quote::quote;
//!
//! let mut g = Graph::new();
//! let x = g.time("x")?;
//! let y = g.state("y")?;
//! let f = g.parse("x*y + x")?;                 // y' = x y + x (course notes, Example 1.4)
//! let ys = g.as_symbol(y).unwrap();
//! let dfdy = g.partial(f, ys)?;
//! assert_eq!(g.show(dfdy).to_string(), "x");
//! let program = g.schedule(&[f, dfdy]);
//! let code = emit_program(&g, &program, &|s| if s == ys { quote!(y) } else { quote!(x) },
//!     &|i, v| { let i = Literal::usize_unsuffixed(i); quote!(out[#i] = #v;) });
//! assert_eq!(code.to_string(), "out [0] = x + x * y ; out [1] = x ;");
//! # let _ = x;
//! # Ok::<(), daegen_codegen::Error>(())
//! ```

// The symbolic kernels index several arrays by one position (y, f, scale, …):
// an index loop says so more plainly than zipped iterators.
#![allow(clippy::needless_range_loop)]

mod build;
mod diff;
mod display;
mod economic_taylor;
mod emit;
mod error;
mod eval;
mod graph;
mod jacobian;
pub mod model;
mod node;
mod number;
mod parse;
mod rational;
mod schedule;
mod substitute;

pub use diff::VectorField;
pub use display::Show;
pub use economic_taylor::economic_taylor_derivatives;
pub use emit::{emit_program, token_count};
pub use error::{Error, Result};
pub use graph::FxHashMap;
pub use graph::Graph;
pub use jacobian::SparseJacobian;
pub use model::expand_dae_model;
pub use node::{sign, Func, Id, Node, Symbol, SymbolId, SymbolKind};
pub use number::{pow_f64, Number};
pub use rational::Rational;
pub use schedule::{Program, Temp, MAX_INLINE_DEPTH};
