//! The relative motion each spatial joint allows in joint coordinates: the
//! rotation and offset of its second body from its first as expressions
//! of its coordinates, the axes of its motion subspace, and the new
//! states with their initial values and rates, read from the bodies'
//! start. A joint's coordinates count from the start (angles from 0,
//! slides from the initial offset), so the relative attitude at the
//! start, C0 = R_a0ᵀ R_b0, is part of every joint's rotation.

use super::algebra::{
    add3, axis_angle, conjugate, cross3, dot3, exact_where_rounded, mat_mul, mat_t_vec, mat_vec,
    quaternion_product, rodrigues, rotation, scale3, sub3, unit3, Mat3, Vec3,
};
use super::names::spatial_joint_doc;
use super::unsupported;
use super::Scene;
use super::{Frame, SpatialJointRecord};
use crate::front::lower::Lower;
use crate::{Graph, Id, SymbolId};

/// Where a body started: centre of mass, unit quaternion, velocity of the
/// centre and angular velocity (body axes).
#[derive(Clone, Copy)]
pub(super) struct Start {
    pub centre: Vec3,
    pub quaternion: [Id; 4],
    pub velocity: Vec3,
    pub rates: Vec3,
}

/// A joint axis, before the child is placed.
#[derive(Clone, Copy)]
pub(super) enum Axis {
    /// A turn about the unit axis given in a's (`in_b: false`) or b's axes,
    /// through b's joint point; the line is fixed in b when `fixed_in_b`.
    Turn { axis: Vec3, in_b: bool, fixed_in_b: bool },
    /// A slide along the unit axis in a's axes (fixed in a).
    Slide { axis: Vec3 },
}

/// One column of the motion subspace: the axis, its generalised speed u
/// and the speed's derivative u̇.
#[derive(Clone, Copy)]
pub(super) struct Column {
    pub axis: Axis,
    pub speed: Id,
    pub acceleration: Id,
}

/// A new state: its name, symbol, initial value, documentation and, for a
/// second-order coordinate, its initial rate.
pub(super) struct NewState {
    pub name: String,
    pub symbol: SymbolId,
    pub init: Id,
    pub doc: String,
    pub rate: Option<Id>,
}

/// What a tree joint contributes: the relative rotation of b from a, as a
/// quaternion and as a matrix, b's joint point from a's in a's axes, the
/// axes, new states, and a relative quaternion's kinematics.
pub(super) struct Motion {
    pub quaternion: [Id; 4],
    pub rot: Mat3,
    pub offset: Vec3,
    /// The relative rotation at the start, C0 = R_a0ᵀ R_b0.
    pub start_rot: Mat3,
    pub columns: Vec<Column>,
    pub states: Vec<NewState>,
    /// A spherical joint's quaternion and rates (q' = ½ q ⊗ ω).
    pub attitude: Option<([SymbolId; 4], [SymbolId; 3])>,
}

impl Lower<'_, Scene> {
    /// The relative motion a tree joint allows, its coordinates, their
    /// initial values and rates.
    pub(super) fn joint_motion(
        &mut self,
        rec: &SpatialJointRecord,
        start: &[Start],
    ) -> crate::Result<Motion> {
        let g = &mut self.g;
        let (zero, one) = (g.zero(), g.one());
        let identity = [one, zero, zero, zero];
        let at_start = |f: Frame, g: &mut Graph| -> crate::Result<(Start, Mat3)> {
            match f {
                Frame::Ground => Ok((
                    Start {
                        centre: [zero; 3],
                        quaternion: identity,
                        velocity: [zero; 3],
                        rates: [zero; 3],
                    },
                    [one, zero, zero, zero, one, zero, zero, zero, one],
                )),
                Frame::Body(b) => Ok((start[b], rotation(g, start[b].quaternion)?)),
            }
        };
        let (sa, ra0) = at_start(rec.a, g)?;
        let (sb, rb0) = at_start(rec.b, g)?;
        // The relative attitude at the start, C0 = R_a0ᵀ R_b0.
        let qa0 = conjugate(g, sa.quaternion)?;
        let qc0 = quaternion_product(g, qa0, sb.quaternion)?;
        let qc0 = exact_where_rounded(g, qc0)?;
        let c0 = rotation(g, qc0)?;
        let c0 = exact_where_rounded(g, c0)?;
        // The joint points at the start, the relative angular velocity
        // (world) and the relative velocity of b's point (world).
        let arm_a = mat_vec(g, &ra0, rec.local_a)?;
        let xa0 = add3(g, sa.centre, arm_a)?;
        let arm_b = mat_vec(g, &rb0, rec.local_b)?;
        let xb0 = add3(g, sb.centre, arm_b)?;
        let wa = mat_vec(g, &ra0, sa.rates)?;
        let wb = mat_vec(g, &rb0, sb.rates)?;
        let w_rel = sub3(g, wb, wa)?;
        let point_velocity = |g: &mut Graph, s: &Start, w: Vec3, x: Vec3| -> crate::Result<Vec3> {
            let lever = sub3(g, x, s.centre)?;
            let turn = cross3(g, w, lever)?;
            add3(g, s.velocity, turn)
        };
        let vb = point_velocity(g, &sb, wb, xb0)?;
        let va = point_velocity(g, &sa, wa, xb0)?;
        let v_rel = sub3(g, vb, va)?;
        let gap0 = sub3(g, xb0, xa0)?;
        let gap0_in_a = mat_t_vec(g, &ra0, gap0)?;
        let name = rec.name.clone();
        let mut states = Vec::new();
        // A second-order coordinate: its state, speed and acceleration.
        let mut coordinate = |g: &mut Graph,
                              suffix: &str,
                              init: Id,
                              rate: Id,
                              doc: &str|
         -> crate::Result<(Id, Id, Id)> {
            let full = format!("{name}.{suffix}");
            let node = g.state(&full)?;
            let symbol = g.as_symbol(node).ok_or_else(|| unsupported("a joint coordinate"))?;
            states.push(NewState {
                name: full,
                symbol,
                init,
                doc: doc.to_string(),
                rate: Some(rate),
            });
            Ok((node, g.derivative(symbol, 1)?, g.derivative(symbol, 2)?))
        };
        let along = |g: &mut Graph, v: Vec3, u_in_a: Vec3| -> crate::Result<Id> {
            let u = mat_vec(g, &ra0, u_in_a)?;
            dot3(g, v, u)
        };
        let axis = match rec.axis {
            Some(u) => unit3(g, u)?,
            None => [zero; 3],
        };
        // The relative rotation R_u(angle)·C0 about the joint's axis in a,
        // as a quaternion and a matrix, and the column of that turn.
        let turned = |g: &mut Graph, angle: Id| -> crate::Result<([Id; 4], Mat3)> {
            let turn = axis_angle(g, axis, angle)?;
            let matrix = rodrigues(g, axis, angle)?;
            Ok((quaternion_product(g, turn, qc0)?, mat_mul(g, &matrix, &c0)?))
        };
        let turn_column = |(_, speed, acceleration): (Id, Id, Id)| Column {
            axis: Axis::Turn { axis, in_b: false, fixed_in_b: true },
            speed,
            acceleration,
        };
        let mut columns = Vec::new();
        let mut attitude = None;
        let (quaternion, rot, offset) = match rec.kind {
            "revolute" => {
                let rate = along(g, w_rel, axis)?;
                let q = coordinate(g, "q", zero, rate, spatial_joint_doc(rec.kind, "q"))?;
                columns.push(turn_column(q));
                let (quaternion, rot) = turned(g, q.0)?;
                (quaternion, rot, [zero; 3])
            }
            "prismatic" => {
                let s0 = dot3(g, gap0_in_a, axis)?;
                let rate = along(g, v_rel, axis)?;
                let doc = spatial_joint_doc(rec.kind, "q");
                let (q, speed, acceleration) = coordinate(g, "q", s0, rate, doc)?;
                columns.push(Column { axis: Axis::Slide { axis }, speed, acceleration });
                (qc0, c0, scale3(g, q, axis)?)
            }
            "cylindrical" => {
                let s0 = dot3(g, gap0_in_a, axis)?;
                let rate = along(g, v_rel, axis)?;
                let doc = spatial_joint_doc(rec.kind, "q");
                let (q, speed, acceleration) = coordinate(g, "q", s0, rate, doc)?;
                columns.push(Column { axis: Axis::Slide { axis }, speed, acceleration });
                let rate = along(g, w_rel, axis)?;
                let angle =
                    coordinate(g, "angle", zero, rate, spatial_joint_doc(rec.kind, "angle"))?;
                columns.push(turn_column(angle));
                let (quaternion, rot) = turned(g, angle.0)?;
                (quaternion, rot, scale3(g, q, axis)?)
            }
            "universal" => {
                let ub = match rec.cross_axis {
                    Some(u) => unit3(g, u)?,
                    None => [zero; 3],
                };
                let rate = along(g, w_rel, axis)?;
                let doc = spatial_joint_doc(rec.kind, "q1");
                let (q1, speed, acceleration) = coordinate(g, "q1", zero, rate, doc)?;
                columns.push(Column {
                    axis: Axis::Turn { axis, in_b: false, fixed_in_b: false },
                    speed,
                    acceleration,
                });
                let ub_world = mat_vec(g, &rb0, ub)?;
                let rate = dot3(g, w_rel, ub_world)?;
                let doc = spatial_joint_doc(rec.kind, "q2");
                let (q2, speed, acceleration) = coordinate(g, "q2", zero, rate, doc)?;
                columns.push(Column {
                    axis: Axis::Turn { axis: ub, in_b: true, fixed_in_b: true },
                    speed,
                    acceleration,
                });
                let first = axis_angle(g, axis, q1)?;
                let second = axis_angle(g, ub, q2)?;
                let q = quaternion_product(g, first, qc0)?;
                let q = quaternion_product(g, q, second)?;
                let r1 = rodrigues(g, axis, q1)?;
                let r2 = rodrigues(g, ub, q2)?;
                let r = mat_mul(g, &r1, &c0)?;
                (q, mat_mul(g, &r, &r2)?, [zero; 3])
            }
            "planar" => {
                let values = rec.axis_values.unwrap_or([0.0, 0.0, 1.0]);
                let [n1, n2] = super::spatial_joint_rows::normals(g, axis, values)?;
                let (e1, e2) = (unit3(g, n1)?, unit3(g, n2)?);
                let mut offset = [zero; 3];
                for (e, suffix) in [(e1, "u"), (e2, "v")] {
                    let s0 = dot3(g, gap0_in_a, e)?;
                    let rate = along(g, v_rel, e)?;
                    let doc = spatial_joint_doc(rec.kind, suffix);
                    let (q, speed, acceleration) = coordinate(g, suffix, s0, rate, doc)?;
                    columns.push(Column { axis: Axis::Slide { axis: e }, speed, acceleration });
                    let step = scale3(g, q, e)?;
                    offset = add3(g, offset, step)?;
                }
                let rate = along(g, w_rel, axis)?;
                let angle =
                    coordinate(g, "angle", zero, rate, spatial_joint_doc(rec.kind, "angle"))?;
                columns.push(turn_column(angle));
                let (quaternion, rot) = turned(g, angle.0)?;
                (quaternion, rot, offset)
            }
            "spherical" => {
                let mut q = [zero; 4];
                let mut qs = Vec::with_capacity(4);
                for (k, c) in ["q0", "q1", "q2", "q3"].iter().enumerate() {
                    let full = format!("{name}.{c}");
                    q[k] = g.state(&full)?;
                    let symbol = g.as_symbol(q[k]).ok_or_else(|| unsupported("a quaternion"))?;
                    qs.push(symbol);
                    let init = if k == 0 { one } else { zero };
                    let doc = spatial_joint_doc(rec.kind, c).to_string();
                    states.push(NewState { name: full, symbol, init, doc, rate: None });
                }
                let w_in_b = mat_t_vec(g, &rb0, w_rel)?;
                let mut ws = Vec::with_capacity(3);
                for (k, c) in ["wx", "wy", "wz"].iter().enumerate() {
                    let full = format!("{name}.{c}");
                    let node = g.state(&full)?;
                    let symbol = g.as_symbol(node).ok_or_else(|| unsupported("a joint rate"))?;
                    ws.push(symbol);
                    let doc = spatial_joint_doc(rec.kind, c).to_string();
                    states.push(NewState { name: full, symbol, init: w_in_b[k], doc, rate: None });
                    let mut e = [zero; 3];
                    e[k] = one;
                    columns.push(Column {
                        axis: Axis::Turn { axis: e, in_b: true, fixed_in_b: true },
                        speed: node,
                        acceleration: g.derivative(symbol, 1)?,
                    });
                }
                attitude = Some(([qs[0], qs[1], qs[2], qs[3]], [ws[0], ws[1], ws[2]]));
                let relative = rotation(g, q)?;
                (quaternion_product(g, qc0, q)?, mat_mul(g, &c0, &relative)?, [zero; 3])
            }
            // Welded: no coordinate.
            _ => (qc0, c0, [zero; 3]),
        };
        Ok(Motion { quaternion, rot, offset, start_rot: c0, columns, states, attitude })
    }
}
