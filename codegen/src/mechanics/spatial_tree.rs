//! The spanning tree of a spatial scene in joint coordinates: its edges
//! and its bodies placed by them, what the rewrite builds and the
//! joint-space dynamics reads.

use super::algebra::{Mat3, Vec3};
use super::Frame;
use crate::Id;

/// A joint of the spanning tree (`joint: None`, a free joint from the
/// ground), the parent frame, the child body, and whether the child is
/// the joint's second frame.
#[derive(Clone, Copy)]
pub(super) struct Edge {
    pub joint: Option<usize>,
    pub parent: Frame,
    pub child: usize,
    pub child_is_b: bool,
}

/// A placed body: quaternion, rotation (body to world) and centre of mass,
/// as expressions of the joint coordinates.
#[derive(Clone, Copy)]
pub(super) struct Placed {
    pub quaternion: [Id; 4],
    pub rot: Mat3,
    pub centre: Vec3,
}
