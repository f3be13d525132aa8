//! The front end: the attribute's arguments, the model function lowered
//! into the model IR (`lower`, with `vectors` expanding vector and
//! matrix expressions into `tensor` values), diagnostics collected with the user's tokens (`ctxt`,
//! `names`, `warnings`).

pub mod attributes;
pub mod ctxt;
pub mod ir;
pub mod lower;
pub mod names;
pub mod tensor;
pub mod vectors;
pub mod warnings;
