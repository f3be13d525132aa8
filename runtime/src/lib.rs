//! `daegen-runtime`: what generated models run on. Today it holds the Taylor
//! step shared by the economic Taylor scheme and the high-order Taylor
//! method; integrators, Newton solvers, projection, dense output, events and
//! errors land here as the front end grows.

pub mod taylor_series;
