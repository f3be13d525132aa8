//! The names a scene answers to beyond its states, so a solution reads the
//! same names in either formulation: where the bodies' coordinates are the
//! states (body coordinates), each revolute and prismatic joint's
//! coordinate `joint.q` (and in the plane its rate `der(joint.q)`) as an
//! output; where joint coordinates are the states (the recursive
//! formulation), each body's `body.x`, `body.y`, `body.theta` and their
//! rates `der(body.x)`, … as outputs, and the coordinates of the joints
//! off the tree too.
//!
//! A planar revolute joint's coordinate is the angle of its second body
//! relative to its first, `θ_b − θ_a`; a prismatic joint's is the slide of
//! b's point from a's along the axis, in metres. A spatial revolute joint's
//! is the rotation of b relative to a about the axis since the start (0
//! there), a spatial prismatic joint's the slide along the axis.

use super::Scene;
use crate::front::ir::Output;
use crate::front::lower::Lower;
use crate::mechanics::Frame;
use crate::{Id, SymbolId};
use proc_macro2::TokenStream;

impl Lower<'_, Scene> {
    /// `joint.q` and `der(joint.q)` of the revolute and prismatic joints
    /// among `joints` (indices into the scene's records), in the body
    /// coordinates (which joint coordinates then rewrite).
    pub(crate) fn planar_joint_coordinates(&mut self, joints: &[usize], origin: &TokenStream) {
        let records: Vec<_> = joints
            .iter()
            .map(|&r| &self.scene.records[r])
            .filter(|r| matches!(r.kind, "revolute" | "prismatic"))
            .map(|r| (r.kind, r.name.clone(), r.a, r.b, r.local_a, r.local_b, r.axis))
            .collect();
        let coordinates: Vec<SymbolId> =
            self.scene.bodies.iter().flat_map(|b| [b.x, b.y, b.theta]).collect();
        for (kind, name, a, b, local_a, local_b, axis) in records {
            let built = (|| -> crate::Result<(Id, Id, &'static str)> {
                let [xa, ya, ta] = self.frame_pose(a);
                let [xb, yb, tb] = self.frame_pose(b);
                let g = &mut self.g;
                let doc = planar_joint_doc(kind);
                let q = if kind == "revolute" {
                    g.sub(tb, ta)?
                } else {
                    let pa = point(g, [xa, ya, ta], local_a)?;
                    let pb = point(g, [xb, yb, tb], local_b)?;
                    let zero = g.zero();
                    let axis = axis.unwrap_or([zero, zero]);
                    let w = rotate(g, ta, axis)?;
                    let (dx, dy) = (g.sub(pb[0], pa[0])?, g.sub(pb[1], pa[1])?);
                    let (p1, p2) = (g.mul(dx, w[0])?, g.mul(dy, w[1])?);
                    let along = g.add(p1, p2)?;
                    let (a1, a2) = (g.mul(axis[0], axis[0])?, g.mul(axis[1], axis[1])?);
                    let length = g.add(a1, a2)?;
                    let length = g.sqrt(length)?;
                    g.div(along, length)?
                };
                Ok((q, rate_through(g, q, &coordinates)?, doc))
            })();
            match built {
                Ok((q, rate, doc)) => {
                    self.push_output(format!("{name}.q"), q, doc, origin);
                    let doc = format!("rate of `{name}.q`");
                    self.push_output(format!("der({name}.q)"), rate, &doc, origin);
                }
                Err(e) => return self.cx.error_at(origin, e),
            }
        }
    }

    /// `body.x`, `body.y`, `body.theta` and their rates, from the poses and
    /// velocities of joint coordinates (expressions of the joint
    /// coordinates and their rates).
    pub(crate) fn body_coordinates(
        &mut self,
        pose: &[Option<[Id; 3]>],
        velocity: &[[Id; 3]],
        origin: &TokenStream,
    ) {
        let names: Vec<String> = self.scene.bodies.iter().map(|b| b.name.clone()).collect();
        for (b, name) in names.iter().enumerate() {
            let Some(p) = pose[b] else { continue };
            for (k, coordinate) in ["x", "y", "theta"].iter().enumerate() {
                let doc = body_coordinate_doc(coordinate);
                self.push_output(format!("{name}.{coordinate}"), p[k], doc, origin);
                let doc = format!("rate of `{name}.{coordinate}`");
                self.push_output(format!("der({name}.{coordinate})"), velocity[b][k], &doc, origin);
            }
        }
    }

    /// A spatial joint's coordinates in body coordinates, named as joint
    /// coordinates name them (`hinge.q`, `cross.q1`, `ball.q0`, …), each
    /// with its rate `der(hinge.q)` by the chain rule through the bodies'
    /// positions and attitudes, but a spherical joint's, whose relative
    /// quaternion and rates are first-order.
    pub(crate) fn spatial_joint_coordinates(
        &mut self,
        name: &str,
        kind: &str,
        frames: [Frame; 2],
        coordinates: &[(&'static str, Id)],
        origin: &impl quote::ToTokens,
    ) {
        let origin = origin.to_token_stream();
        let mut symbols: Vec<SymbolId> = Vec::new();
        for frame in frames {
            if let Frame::Body(b) = frame {
                let body = &self.scene.spatial[b];
                symbols.extend(body.position);
                symbols.extend(body.quaternion);
            }
        }
        for &(suffix, value) in coordinates {
            let doc = spatial_joint_doc(kind, suffix);
            self.push_output(format!("{name}.{suffix}"), value, doc, &origin);
            if kind == "spherical" {
                continue;
            }
            match rate_through(&mut self.g, value, &symbols) {
                Ok(rate) => {
                    let doc = format!("rate of `{name}.{suffix}`");
                    self.push_output(format!("der({name}.{suffix})"), rate, &doc, &origin);
                }
                Err(e) => return self.cx.error_at(&origin, e),
            }
        }
    }

    /// `[x, y, θ]` of a frame: the body's coordinates, or zeros for the ground.
    fn frame_pose(&mut self, frame: Frame) -> [Id; 3] {
        match frame {
            Frame::Ground => [self.g.zero(); 3],
            Frame::Body(k) => {
                let b = &self.scene.bodies[k];
                let (x, y, t) = (b.x, b.y, b.theta);
                [self.g.symbol_node(x), self.g.symbol_node(y), self.g.symbol_node(t)]
            }
        }
    }

    fn push_output(&mut self, name: String, value: Id, doc: &str, origin: &TokenStream) {
        let (doc, origin) = (doc.to_string(), origin.clone());
        self.outputs.push(Output { name, value, doc, origin, declared: false });
    }
}

/// What a body's coordinate is, planar or spatial.
pub(crate) fn body_coordinate_doc(coordinate: &str) -> &'static str {
    match coordinate {
        "x" | "y" | "z" => "centre of mass, world axes (m)",
        "theta" => "angle of the body (rad)",
        "q0" | "q1" | "q2" | "q3" => "attitude quaternion, body to world (q0 = cos(θ/2))",
        _ => "angular velocity, body axes (rad/s)",
    }
}

/// The rate of `value`, a function of the coordinates `through`, by the
/// chain rule: Σ ∂value/∂s · der(s).
fn rate_through(g: &mut crate::Graph, value: Id, through: &[SymbolId]) -> crate::Result<Id> {
    let mut terms = Vec::new();
    for &s in through {
        let d = g.partial(value, s)?;
        if g.as_number(d).is_some_and(|v| v.is_zero()) {
            continue;
        }
        let rate = g.derivative(s, 1)?;
        terms.push(g.mul(d, rate)?);
    }
    g.sum(&terms)
}

/// The coordinates of each kind of spatial joint, by name, as the states
/// in joint coordinates and the outputs in body coordinates both call
/// them.
pub(crate) const SPATIAL_JOINT_COORDINATES: [(&str, &[&str]); 6] = [
    ("revolute", &["q"]),
    ("prismatic", &["q"]),
    ("cylindrical", &["q", "angle"]),
    ("universal", &["q1", "q2"]),
    ("planar", &["u", "v", "angle"]),
    ("spherical", &["q0", "q1", "q2", "q3", "wx", "wy", "wz"]),
];

/// What coordinate `suffix` of a spatial joint of `kind` is.
pub(crate) fn spatial_joint_doc(kind: &str, suffix: &str) -> &'static str {
    match (kind, suffix) {
        ("revolute", _) | (_, "angle") => {
            "rotation of the second body relative to the first about the axis since the start (rad)"
        }
        ("universal", "q1") => "rotation about the axis in the first body since the start (rad)",
        ("universal", "q2") => "rotation about the axis in the second body since the start (rad)",
        ("planar", "u") => "slide of the second body's point from the first's along n × e_k, e_k the axis of the first body least aligned with the normal n, normalised (m)",
        ("planar", "v") => "slide of the second body's point from the first's along n × u, normalised (m)",
        ("spherical", "wx" | "wy" | "wz") => "angular velocity of the second body relative to the first, second body's axes (rad/s)",
        ("spherical", _) => "relative attitude quaternion since the start, second body's axes (q0 = cos(θ/2))",
        _ => "slide of the second body's point from the first's along the axis (m)",
    }
}

/// What a planar joint's coordinate is.
pub(crate) fn planar_joint_doc(kind: &str) -> &'static str {
    if kind == "revolute" {
        "angle of the second body relative to the first (rad)"
    } else {
        "slide of the second body's point from the first's along the axis (m)"
    }
}

/// `R(angle) p` in the plane.
pub(crate) fn rotate(g: &mut crate::Graph, angle: Id, p: [Id; 2]) -> crate::Result<[Id; 2]> {
    let (c, s) = (g.call(crate::Func::Cos, angle)?, g.call(crate::Func::Sin, angle)?);
    let (a1, a2) = (g.mul(c, p[0])?, g.mul(s, p[1])?);
    let (b1, b2) = (g.mul(s, p[0])?, g.mul(c, p[1])?);
    Ok([g.sub(a1, a2)?, g.add(b1, b2)?])
}

/// The world position of the point `local` of a body at `pose`.
pub(crate) fn point(g: &mut crate::Graph, pose: [Id; 3], local: [Id; 2]) -> crate::Result<[Id; 2]> {
    let arm = rotate(g, pose[2], local)?;
    Ok([g.add(pose[0], arm[0])?, g.add(pose[1], arm[1])?])
}
