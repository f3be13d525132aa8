//! The Taylor methods' code: what a model gives them (`analysis`: which
//! of the following it has, or why not), the economic scheme's
//! derivatives (`economic`), the adaptive method's AD tape (`tape`), and its unrolled
//! jets (`unrolled`, the pass manager over `folding`, `factoring`,
//! `layout`, `lanes`, `groups` and `sharing`).

pub mod analysis;
pub mod economic;
pub mod factoring;
pub mod folding;
pub mod groups;
pub mod jet_layout;
pub mod sharing;
pub mod tape;
pub mod unrolled;
pub mod vector_rows;
