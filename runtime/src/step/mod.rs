//! What every method does around a step: step-size control, events on the
//! step's continuous extension, projection onto the constraints, and
//! finite-difference Jacobians.

pub mod control;
pub(crate) mod events;
pub(crate) mod jacobian;
pub(crate) mod projection;
