//! The front end: the attribute's arguments, the model function lowered
//! (with the `components` it instantiates flattened into it)
//! into the model IR (`ir`, by `lower/`, with `vectors` expanding vector
//! and matrix expressions into `tensor` values), diagnostics collected
//! with the user's tokens (`ctxt`, `names`, `warnings`). Scenes enter
//! through `lower::SceneLanguage`; the front end names no scene type.

pub mod attributes;
pub mod components;
pub mod ctxt;
pub mod ir;
pub mod lower;
pub mod names;
pub mod tensor;
pub mod vectors;
pub mod warnings;
