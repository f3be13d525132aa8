//! The integration methods, one module per method (Hairer's explicit pairs
//! share `adaptive`, the Taylor methods `taylor`), and `auto`, which
//! switches between them.

pub(crate) mod adaptive;
pub(crate) mod auto;
pub(crate) mod backward_euler;
pub mod dop853;
pub mod dopri5;
pub mod explicit_rk;
pub mod implicit_tableau;
pub(crate) mod radau5;
pub(crate) mod stiffness;
pub mod taylor;
