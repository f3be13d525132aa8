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

/// Each body's parent body (`None` under the ground) and the bodies in
/// the tree's order, parents first.
pub(super) fn parents_and_order(tree: &[Edge], n: usize) -> (Vec<Option<usize>>, Vec<usize>) {
    let mut parent: Vec<Option<usize>> = vec![None; n];
    for e in tree {
        if let Frame::Body(p) = e.parent {
            parent[e.child] = Some(p);
        }
    }
    (parent, tree.iter().map(|e| e.child).collect())
}

/// The joint speeds numbered along the tree, as its factorisation needs
/// them: each speed's (body, column), each body's first speed, and each
/// speed's predecessor on its path to the root (the body's previous
/// column, else its parent's last).
pub(super) struct Speeds {
    pub index: Vec<(usize, usize)>,
    pub first: Vec<usize>,
    pub previous: Vec<Option<usize>>,
}

/// [`Speeds`] of bodies in `order` with `columns(b)` speeds each.
pub(super) fn speeds(
    order: &[usize],
    parent: &[Option<usize>],
    columns: impl Fn(usize) -> usize,
) -> Speeds {
    let mut index = Vec::new();
    let mut first = vec![0; parent.len()];
    for &b in order {
        first[b] = index.len();
        index.extend((0..columns(b)).map(|k| (b, k)));
    }
    let previous = index
        .iter()
        .map(|&(b, c)| match (c, parent[b]) {
            (0, None) => None,
            (0, Some(p)) => Some(first[p] + columns(p) - 1),
            _ => Some(first[b] + c - 1),
        })
        .collect();
    Speeds { index, first, previous }
}
