//! From the model IR to a first-order system (`system`, which every pass
//! after reduction reads and which imports none of them): the states that
//! connections tie eliminated (`tied_states`), the structure
//! (`structure`: equations whose highest derivatives cancel combined by
//! `derivative_free`, the index reduced by `index_reduction` and
//! `linear_pencil`), aliases removed (`alias`), the equations matched to
//! their unknowns and sorted into blocks in causal order (`sorting`, over
//! `matching`), the blocks solved (`reduce`, `solve_unknowns`,
//! `newton_block`), forward sensitivities (`variational`), the
//! mass-matrix form (`mass_form`) and the constraints' projection levels
//! (`constraints`), as values that `emit` writes out.

pub mod actions;
pub mod alias;
pub mod constraints;
pub mod derivative_free;
pub mod hidden_ties;
pub mod index_reduction;
pub mod initialization;
pub mod inputs;
pub mod linear_form;
pub mod linear_pencil;
pub mod mass_form;
pub mod matching;
pub mod modes;
pub mod newton_block;
pub mod reduce;
pub mod solve_unknowns;
pub mod sorting;
pub mod structure;
pub mod system;
pub mod tied_states;
pub mod time_events;
pub mod variational;
