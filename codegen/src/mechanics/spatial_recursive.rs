//! The recursive formulation of a spatial scene: joint coordinates along a
//! spanning tree grown from the ground, the joint-space mass matrix by the
//! composite-rigid-body algorithm and the bias forces by recursive
//! Newton–Euler (Featherstone, *Rigid Body Dynamics Algorithms*, 2008,
//! §6.2 and §5.3), both written symbolically so that common-subexpression
//! elimination shares them, and the joints off the tree (closing loops)
//! kept as constraints with their multipliers:
//!
//! ```text
//! M(q) u̇ + C(q, u) = −(∂Φ̇/∂u)ᵀ λ,    M_kl = S_kᵀ I^c_i S_l,    C_k = S_kᵀ F_i
//! ```
//!
//! Spatial vectors are in world axes about the world origin (Featherstone's
//! absolute coordinates), so a joint's motion subspace S is the axis's
//! Plücker vector and needs no transforms; an axis fixed in body F changes
//! as Ṡ = V_F × S. Coordinates: a revolute joint's turn `j.q` and a
//! prismatic joint's slide `j.q` as in the global formulation; a
//! cylindrical joint's `j.q` and `j.angle`; a universal joint's turns
//! `j.q1` (about the axis in a) and `j.q2` (about the axis in b); a planar
//! joint's slides `j.u`, `j.v` and turn `j.angle`; a spherical joint's
//! relative quaternion `j.q0`…`j.q3` with the relative angular velocity in
//! the child's axes `j.wx`, `j.wy`, `j.wz`. A body that no tree joint
//! reaches hangs from the ground by a free joint: it keeps its own
//! coordinates (centre of mass, quaternion, body rates). The bodies'
//! coordinates become outputs of the joint coordinates, so a solution
//! answers to the same names in both formulations.

use super::algebra::{
    add3, axis_angle, conjugate, cross3, dot3, mat_mul, mat_t_vec, mat_vec, quaternion_product,
    quaternion_rates, rotation, scale3, sub3, unit3, Mat3, Vec3,
};
use super::{Frame, SpatialJointRecord};
use crate::front::lower::Lower;
use crate::{FxHashMap, Graph, Id, SymbolId, VectorField};
use proc_macro2::TokenStream;
use quote::ToTokens;

/// Joints that can carry the tree; `distance` is always cut.
const TREE_JOINTS: [&str; 7] =
    ["revolute", "prismatic", "spherical", "fixed", "universal", "cylindrical", "planar"];

/// A child body positioned more than this far from where its tree joint
/// places it (relative to the scene's size, 1 m at least) is a mistake.
const PLACEMENT_TOLERANCE: f64 = 1e-9;

/// A spatial motion vector (ω; v_O) or force vector (n_O; f), world axes,
/// about the world origin.
#[derive(Clone, Copy)]
struct Spatial {
    top: Vec3,
    bottom: Vec3,
}

/// The spatial inertia of a body (or a composite) about the world origin:
/// [[I_O, [h]×], [[h]×ᵀ, m 1]] with h = m c.
#[derive(Clone, Copy)]
struct Inertia {
    about_origin: Mat3,
    h: Vec3,
    mass: Id,
}

/// A joint of the spanning tree (`joint: None`, a free joint from the
/// ground), the parent frame, the child body, and whether the child is
/// the joint's second frame.
#[derive(Clone, Copy)]
struct Edge {
    joint: Option<usize>,
    parent: Frame,
    child: usize,
    child_is_b: bool,
}

/// Where a body started: centre of mass, unit quaternion, velocity of the
/// centre and angular velocity (body axes).
#[derive(Clone, Copy)]
struct Start {
    centre: Vec3,
    quaternion: [Id; 4],
    velocity: Vec3,
    rates: Vec3,
}

/// A placed body: quaternion, rotation (body to world) and centre of mass,
/// as expressions of the joint coordinates.
#[derive(Clone, Copy)]
struct Placed {
    quaternion: [Id; 4],
    rot: Mat3,
    centre: Vec3,
}

/// A joint axis, before the child is placed.
#[derive(Clone, Copy)]
enum Axis {
    /// A turn about the unit axis given in a's (`in_b: false`) or b's axes,
    /// through b's joint point; the line is fixed in b when `fixed_in_b`.
    Turn { axis: Vec3, in_b: bool, fixed_in_b: bool },
    /// A slide along the unit axis in a's axes (fixed in a).
    Slide { axis: Vec3 },
}

/// One column of the motion subspace: the axis, its generalised speed u
/// and the speed's derivative u̇.
#[derive(Clone, Copy)]
struct Column {
    axis: Axis,
    speed: Id,
    acceleration: Id,
}

/// A new state: its name, symbol, initial value, documentation and, for a
/// second-order coordinate, its initial rate.
struct NewState {
    name: String,
    symbol: SymbolId,
    init: Id,
    doc: String,
    rate: Option<Id>,
}

/// What a tree joint contributes: the relative rotation of b from a, as a
/// quaternion and as a matrix, b's joint point from a's in a's axes, the
/// axes, new states, and a relative quaternion's kinematics.
struct Motion {
    quaternion: [Id; 4],
    rot: Mat3,
    offset: Vec3,
    columns: Vec<Column>,
    states: Vec<NewState>,
    /// A spherical joint's quaternion and rates (q' = ½ q ⊗ ω).
    attitude: Option<([SymbolId; 4], [SymbolId; 3])>,
}

impl Lower<'_> {
    /// Replaces a spatial scene's body coordinates by joint coordinates and
    /// writes its equations of motion by CRBA and RNEA.
    pub(crate) fn spatial_recursive_equations(&mut self, item: &syn::ItemFn) {
        let origin = item.sig.ident.to_token_stream();
        if let Err(e) = self.spatial_recursive(&origin) {
            self.cx.error_at(&origin, e);
        }
    }

    fn spatial_recursive(&mut self, origin: &TokenStream) -> crate::Result<()> {
        let records = self.scene.spatial_records.clone();
        let n = self.scene.spatial.len();
        let tree = spatial_tree(&records, n);
        let free: Vec<bool> =
            (0..n).map(|b| tree.iter().any(|e| e.joint.is_none() && e.child == b)).collect();
        let start = self.spatial_start(&free)?;
        // Kinematics along the tree.
        let mut placed: Vec<Option<Placed>> = vec![None; n];
        let mut columns: Vec<Vec<(Column, Frame, Frame, bool)>> = vec![Vec::new(); n];
        let mut states: Vec<NewState> = Vec::new();
        let mut attitudes = Vec::new();
        for edge in &tree {
            let Some(r) = edge.joint else {
                let body = self.scene.spatial[edge.child].clone();
                let g = &mut self.g;
                let quaternion = body.quaternion.map(|s| g.symbol_node(s));
                let rot = rotation(g, quaternion)?;
                let centre = body.position.map(|s| g.symbol_node(s));
                placed[edge.child] = Some(Placed { quaternion, rot, centre });
                let (zero, one) = (g.zero(), g.one());
                for k in 0..3 {
                    let mut e = [zero; 3];
                    e[k] = one;
                    let slide = Column {
                        axis: Axis::Slide { axis: e },
                        speed: g.derivative(body.position[k], 1)?,
                        acceleration: g.derivative(body.position[k], 2)?,
                    };
                    // A slide along a world axis: the ground is its frame.
                    columns[edge.child].push((slide, Frame::Ground, Frame::Body(edge.child), true));
                }
                for k in 0..3 {
                    let mut e = [zero; 3];
                    e[k] = one;
                    let turn = Column {
                        axis: Axis::Turn { axis: e, in_b: true, fixed_in_b: true },
                        speed: g.symbol_node(body.rates[k]),
                        acceleration: g.derivative(body.rates[k], 1)?,
                    };
                    columns[edge.child].push((turn, Frame::Ground, Frame::Body(edge.child), true));
                }
                continue;
            };
            let rec = &records[r];
            let motion = self.joint_motion(rec, &start)?;
            let frame_pose = |f: Frame, g: &mut Graph| -> crate::Result<Placed> {
                match f {
                    Frame::Ground => {
                        let (zero, one) = (g.zero(), g.one());
                        Ok(Placed {
                            quaternion: [one, zero, zero, zero],
                            rot: [one, zero, zero, zero, one, zero, zero, zero, one],
                            centre: [zero; 3],
                        })
                    }
                    Frame::Body(b) => placed[b].ok_or_else(|| unsupported("an unplaced body")),
                }
            };
            let g = &mut self.g;
            let parent = frame_pose(edge.parent, g)?;
            let child = if edge.child_is_b {
                // Q_b = Q_a ⊗ Q_rel, and b's point is a's moved by the offset.
                let quaternion = quaternion_product(g, parent.quaternion, motion.quaternion)?;
                let rot = mat_mul(g, &parent.rot, &motion.rot)?;
                let arm = add3(g, rec.local_a, motion.offset)?;
                let arm = mat_vec(g, &parent.rot, arm)?;
                let point = add3(g, parent.centre, arm)?;
                let back = mat_vec(g, &rot, rec.local_b)?;
                Placed { quaternion, rot, centre: sub3(g, point, back)? }
            } else {
                let inverse = conjugate(g, motion.quaternion)?;
                let quaternion = quaternion_product(g, parent.quaternion, inverse)?;
                let transposed = transpose(&motion.rot);
                let rot = mat_mul(g, &parent.rot, &transposed)?;
                let arm = mat_vec(g, &parent.rot, rec.local_b)?;
                let point = add3(g, parent.centre, arm)?;
                let back = add3(g, rec.local_a, motion.offset)?;
                let back = mat_vec(g, &rot, back)?;
                Placed { quaternion, rot, centre: sub3(g, point, back)? }
            };
            placed[edge.child] = Some(child);
            for column in motion.columns {
                columns[edge.child].push((column, rec.a, rec.b, edge.child_is_b));
            }
            states.extend(motion.states);
            if let Some(a) = motion.attitude {
                attitudes.push(a);
            }
        }
        let placed: Vec<Placed> =
            placed.into_iter().collect::<Option<_>>().ok_or_else(|| unsupported("a body"))?;
        // The states: out go the bodies' (except free ones) and the tree
        // joints' rows; in come the joint coordinates.
        let cut: Vec<usize> =
            (0..records.len()).filter(|&r| !tree.iter().any(|e| e.joint == Some(r))).collect();
        self.tree_joints_out(&records, &cut, &free);
        for s in &states {
            self.states.push(crate::front::ir::StateDecl {
                name: s.name.clone(),
                symbol: s.symbol,
                init: s.init,
                origin: origin.clone(),
                fixed: false,
                doc: s.doc.clone(),
            });
        }
        for s in &states {
            if let Some(rate) = s.rate {
                if !self.g.as_number(rate).is_some_and(|v| v.is_zero()) {
                    self.init_rate(s.symbol, rate, origin)
                        .ok_or_else(|| unsupported("a joint rate"))?;
                }
            }
        }
        if let Some((at, message)) = self.misplaced(&placed, &start, &free, &tree, &records) {
            self.cx.error_at(&at, message);
            return Ok(());
        }
        let field = self.joint_field(&states, &attitudes, &free)?;
        // Velocities, bias accelerations and the motion subspace in world axes.
        let dynamics = self.tree_dynamics(&tree, &placed, &columns, &records, field)?;
        let Dynamics { mut field, velocity, subspace } = dynamics;
        if let Some((at, message)) =
            self.moving_wrongly(&placed, &velocity, &start, &states, &free, &tree, &records)
        {
            self.cx.error_at(&at, message);
            return Ok(());
        }
        // Everything written in body coordinates is rewritten in joint ones.
        let replace = self.body_substitution(&placed, &velocity, &free, &mut field)?;
        let cut_rows = self.rewrite_spatial(&replace, &records, &cut)?;
        self.spatial_body_outputs(&placed, &velocity, &free, origin)?;
        // Equations of motion.
        let equations = self.crba_rnea(&tree, &placed, &subspace, &cut_rows, &mut field)?;
        self.push_equations_of_motion(Ok(equations), origin);
        let mut kinematics = Vec::new();
        for (q, w) in &attitudes {
            let g = &mut self.g;
            let qn = q.map(|s| g.symbol_node(s));
            let wn = w.map(|s| g.symbol_node(s));
            let rates = quaternion_rates(g, qn, wn)?;
            for k in 0..4 {
                kinematics.push((g.derivative(q[k], 1)?, rates[k]));
            }
            let mut terms: Vec<Id> = qn.iter().map(|&x| g.mul(x, x)).collect::<Result<_, _>>()?;
            terms.push(g.int(-1));
            let value = g.sum(&terms)?;
            self.invariants.push(crate::front::ir::UserInvariant { value, origin: origin.clone() });
        }
        for (b, body) in self.scene.spatial.clone().iter().enumerate() {
            if !free[b] {
                continue;
            }
            let g = &mut self.g;
            let qn = body.quaternion.map(|s| g.symbol_node(s));
            let wn = body.rates.map(|s| g.symbol_node(s));
            let rates = quaternion_rates(g, qn, wn)?;
            for k in 0..4 {
                kinematics.push((g.derivative(body.quaternion[k], 1)?, rates[k]));
            }
        }
        self.push_equations_of_motion(Ok(kinematics), origin);
        let coordinates = subspace.iter().map(Vec::len).sum::<usize>();
        self.scene.summary.push_str(&format!(
            " Recursive formulation: {coordinates} joint speeds on the spanning tree ({} free bodies), mass matrix by the composite-rigid-body algorithm, bias forces by recursive Newton–Euler, {} cut-joint constraint rows.",
            free.iter().filter(|f| **f).count(),
            cut_rows.len()
        ));
        Ok(())
    }

    /// Each body's start, its quaternion normalised; takes the initial
    /// velocities of the bodies that become expressions out of the model.
    fn spatial_start(&mut self, free: &[bool]) -> crate::Result<Vec<Start>> {
        let bodies = self.scene.spatial.clone();
        let mut velocity: FxHashMap<SymbolId, Id> = FxHashMap::default();
        let mut kept = Vec::with_capacity(self.inits.len());
        for init in std::mem::take(&mut self.inits) {
            let of = bodies.iter().enumerate().find_map(|(b, body)| {
                body.position.into_iter().find(|&s| {
                    matches!(self.g.symbol(init.target).kind, crate::SymbolKind::Derivative { of, order: 1 } if of == s)
                }).map(|s| (b, s))
            });
            match of {
                Some((b, s)) => {
                    velocity.insert(s, init.value);
                    if free[b] {
                        kept.push(init);
                    }
                }
                None => kept.push(init),
            }
        }
        self.inits = kept;
        let mut out = Vec::with_capacity(bodies.len());
        for body in &bodies {
            let zero = self.g.zero();
            let init = |this: &Self, s: SymbolId| this.state_init(s).unwrap_or(zero);
            let centre = body.position.map(|s| init(self, s));
            let q = body.quaternion.map(|s| init(self, s));
            let rates = body.rates.map(|s| init(self, s));
            let v = body.position.map(|s| velocity.get(&s).copied().unwrap_or(zero));
            let g = &mut self.g;
            let mut squares = Vec::with_capacity(4);
            for x in q {
                squares.push(g.mul(x, x)?);
            }
            let norm = g.sum(&squares)?;
            let norm = g.sqrt(norm)?;
            let quaternion =
                [g.div(q[0], norm)?, g.div(q[1], norm)?, g.div(q[2], norm)?, g.div(q[3], norm)?];
            out.push(Start { centre, quaternion, velocity: v, rates });
        }
        Ok(out)
    }

    /// A state's initial value.
    fn state_init(&self, s: SymbolId) -> Option<Id> {
        self.states.iter().find(|d| d.symbol == s).map(|d| d.init)
    }

    /// The relative motion a tree joint allows, its coordinates, their
    /// initial values and rates.
    fn joint_motion(&mut self, rec: &SpatialJointRecord, start: &[Start]) -> crate::Result<Motion> {
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
        let c0 = rotation(g, qc0)?;
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
        let turn_doc = "rotation of the second body relative to the first about the axis since the start (rad)";
        let slide_doc = "slide of the second body's point from the first's along the axis (m)";
        let axis = match rec.axis {
            Some(u) => unit3(g, u)?,
            None => [zero; 3],
        };
        let mut columns = Vec::new();
        let mut attitude = None;
        let (quaternion, rot, offset) = match rec.kind {
            "revolute" => {
                let rate = along(g, w_rel, axis)?;
                let (q, speed, acceleration) = coordinate(g, "q", zero, rate, turn_doc)?;
                columns.push(Column {
                    axis: Axis::Turn { axis, in_b: false, fixed_in_b: true },
                    speed,
                    acceleration,
                });
                let turn = axis_angle(g, axis, q)?;
                let turned = rodrigues(g, axis, q)?;
                (quaternion_product(g, turn, qc0)?, mat_mul(g, &turned, &c0)?, [zero; 3])
            }
            "prismatic" => {
                let s0 = dot3(g, gap0_in_a, axis)?;
                let rate = along(g, v_rel, axis)?;
                let (q, speed, acceleration) = coordinate(g, "q", s0, rate, slide_doc)?;
                columns.push(Column { axis: Axis::Slide { axis }, speed, acceleration });
                (qc0, c0, scale3(g, q, axis)?)
            }
            "cylindrical" => {
                let s0 = dot3(g, gap0_in_a, axis)?;
                let rate = along(g, v_rel, axis)?;
                let (q, speed, acceleration) = coordinate(g, "q", s0, rate, slide_doc)?;
                columns.push(Column { axis: Axis::Slide { axis }, speed, acceleration });
                let rate = along(g, w_rel, axis)?;
                let (angle, speed, acceleration) = coordinate(g, "angle", zero, rate, turn_doc)?;
                columns.push(Column {
                    axis: Axis::Turn { axis, in_b: false, fixed_in_b: true },
                    speed,
                    acceleration,
                });
                let turn = axis_angle(g, axis, angle)?;
                let turned = rodrigues(g, axis, angle)?;
                (quaternion_product(g, turn, qc0)?, mat_mul(g, &turned, &c0)?, scale3(g, q, axis)?)
            }
            "universal" => {
                let ub = match rec.cross_axis {
                    Some(u) => unit3(g, u)?,
                    None => [zero; 3],
                };
                let rate = along(g, w_rel, axis)?;
                let doc = "rotation about the axis in the first body since the start (rad)";
                let (q1, speed, acceleration) = coordinate(g, "q1", zero, rate, doc)?;
                columns.push(Column {
                    axis: Axis::Turn { axis, in_b: false, fixed_in_b: false },
                    speed,
                    acceleration,
                });
                let ub_world = mat_vec(g, &rb0, ub)?;
                let rate = dot3(g, w_rel, ub_world)?;
                let doc = "rotation about the axis in the second body since the start (rad)";
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
                let [n1, n2] = super::spatial::normals(g, axis, values)?;
                let (e1, e2) = (unit3(g, n1)?, unit3(g, n2)?);
                let mut offset = [zero; 3];
                for (e, suffix) in [(e1, "u"), (e2, "v")] {
                    let s0 = dot3(g, gap0_in_a, e)?;
                    let rate = along(g, v_rel, e)?;
                    let direction = if suffix == "u" {
                        "n × e_k, e_k the axis of the first body least aligned with the normal n"
                    } else {
                        "n × u"
                    };
                    let doc = format!("slide of the second body's point from the first's along {direction}, normalised (m)");
                    let (q, speed, acceleration) = coordinate(g, suffix, s0, rate, &doc)?;
                    columns.push(Column { axis: Axis::Slide { axis: e }, speed, acceleration });
                    let step = scale3(g, q, e)?;
                    offset = add3(g, offset, step)?;
                }
                let rate = along(g, w_rel, axis)?;
                let (angle, speed, acceleration) = coordinate(g, "angle", zero, rate, turn_doc)?;
                columns.push(Column {
                    axis: Axis::Turn { axis, in_b: false, fixed_in_b: true },
                    speed,
                    acceleration,
                });
                let turn = axis_angle(g, axis, angle)?;
                let turned = rodrigues(g, axis, angle)?;
                (quaternion_product(g, turn, qc0)?, mat_mul(g, &turned, &c0)?, offset)
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
                    let doc = "relative attitude quaternion since the start, second body's axes (q0 = cos(θ/2))";
                    states.push(NewState { name: full, symbol, init, doc: doc.into(), rate: None });
                }
                let w_in_b = mat_t_vec(g, &rb0, w_rel)?;
                let mut ws = Vec::with_capacity(3);
                for (k, c) in ["wx", "wy", "wz"].iter().enumerate() {
                    let full = format!("{name}.{c}");
                    let node = g.state(&full)?;
                    let symbol = g.as_symbol(node).ok_or_else(|| unsupported("a joint rate"))?;
                    ws.push(symbol);
                    let doc = "angular velocity of the second body relative to the first, second body's axes (rad/s)";
                    states.push(NewState {
                        name: full,
                        symbol,
                        init: w_in_b[k],
                        doc: doc.into(),
                        rate: None,
                    });
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
        Ok(Motion { quaternion, rot, offset, columns, states, attitude })
    }

    /// Out of the model: the non-free bodies' states and quaternion norms,
    /// the tree joints' rows, multipliers and coordinate outputs.
    fn tree_joints_out(&mut self, records: &[SpatialJointRecord], cut: &[usize], free: &[bool]) {
        let mut drop_equations = std::collections::HashSet::new();
        let mut drop_algebraics = std::collections::HashSet::new();
        let mut drop_outputs = std::collections::HashSet::new();
        for (r, rec) in records.iter().enumerate() {
            if cut.contains(&r) {
                continue;
            }
            drop_equations.extend(rec.equations.clone());
            drop_algebraics.extend(rec.algebraics.clone());
            drop_outputs.insert(format!("{}.q", rec.name));
            drop_outputs.insert(format!("{}.angle", rec.name));
        }
        let mut body_symbols = Vec::new();
        let mut norms = Vec::new();
        for (b, body) in self.scene.spatial.clone().iter().enumerate() {
            if free[b] {
                continue;
            }
            body_symbols.extend(body.position);
            body_symbols.extend(body.quaternion);
            body_symbols.extend(body.rates);
            // The same expression as the declaration's, hence the same node.
            let norm = (|| {
                let g = &mut self.g;
                let mut terms = Vec::with_capacity(5);
                for &s in &body.quaternion {
                    let q = g.symbol_node(s);
                    terms.push(g.mul(q, q)?);
                }
                terms.push(g.int(-1));
                g.sum(&terms)
            })();
            if let Ok(n) = norm {
                norms.push(n);
            }
        }
        retain_unlisted(&mut self.equations, &drop_equations);
        retain_unlisted(&mut self.algebraics, &drop_algebraics);
        self.states.retain(|s| !body_symbols.contains(&s.symbol));
        self.invariants.retain(|i| !norms.contains(&i.value));
        self.outputs.retain(|o| !drop_outputs.contains(&o.name));
    }

    /// A body that starts away from where its tree joint places it (checked
    /// at the defaults): the joint's statement and what to do.
    fn misplaced(
        &mut self,
        placed: &[Placed],
        start: &[Start],
        free: &[bool],
        tree: &[Edge],
        records: &[SpatialJointRecord],
    ) -> Option<(TokenStream, String)> {
        for (b, p) in placed.iter().enumerate() {
            if free[b] {
                continue;
            }
            let mut worst: f64 = 0.0;
            let mut scale: f64 = 1.0;
            for k in 0..3 {
                let got = self.numeric(p.centre[k]);
                let want = self.numeric(start[b].centre[k]);
                worst = worst.max((got - want).abs());
                scale = scale.max(want.abs());
            }
            if worst <= PLACEMENT_TOLERANCE * scale {
                continue;
            }
            let joint = tree.iter().find(|e| e.child == b).and_then(|e| e.joint)?;
            let joint = records[joint].name.clone();
            let at = self.scene.joint_rows.iter().find(|j| j.0 == joint)?.2.clone();
            let body = self.body_name(b);
            let worst = if worst >= 1e-4 {
                format!("{worst:.4}").trim_end_matches('0').to_string()
            } else {
                format!("{worst:.1e}")
            };
            return Some((at, format!("`{body}` starts {worst} m from where joint `{joint}` places it: in the recursive formulation a body's start follows from its joint, so give `{body}` an initial position that satisfies `{joint}`")));
        }
        None
    }

    /// A body whose given velocity or body rates differ from those its
    /// joints' initial rates give it (checked at the defaults): the joint's
    /// statement and what to do.
    #[allow(clippy::too_many_arguments)]
    fn moving_wrongly(
        &mut self,
        placed: &[Placed],
        velocity: &[Spatial],
        start: &[Start],
        states: &[NewState],
        free: &[bool],
        tree: &[Edge],
        records: &[SpatialJointRecord],
    ) -> Option<(TokenStream, String)> {
        let mut values = self.start_values();
        for s in states {
            if let Some(rate) = s.rate {
                let v = self.numeric(rate);
                let d = self.g.derivative(s.symbol, 1).ok()?;
                values.insert(self.g.as_symbol(d)?, v);
            }
        }
        let value =
            |g: &Graph, id: Id| g.eval(&[id], &|s| values.get(&s).copied().unwrap_or(f64::NAN))[0];
        for (b, p) in placed.iter().enumerate() {
            if free[b] {
                continue;
            }
            let v = velocity[b];
            let g = &mut self.g;
            let turn = cross3(g, v.top, p.centre).ok()?;
            let vc = add3(g, v.bottom, turn).ok()?;
            let w = mat_t_vec(g, &p.rot, v.top).ok()?;
            let got: Vec<f64> = vc.iter().chain(&w).map(|&x| value(g, x)).collect();
            let want: Vec<f64> =
                start[b].velocity.iter().chain(&start[b].rates).map(|&x| value(g, x)).collect();
            let worst = got.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            let scale = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            if worst <= PLACEMENT_TOLERANCE * scale {
                continue;
            }
            let joint = tree.iter().find(|e| e.child == b).and_then(|e| e.joint)?;
            let joint = records[joint].name.clone();
            let at = self.scene.joint_rows.iter().find(|j| j.0 == joint)?.2.clone();
            let body = self.body_name(b);
            let show = |x: &[f64]| {
                let parts: Vec<String> =
                    x.iter().map(|v| format!("{}", (v * 1e6).round() / 1e6)).collect();
                format!("[{}], [{}]", parts[..3].join(", "), parts[3..].join(", "))
            };
            return Some((at, format!("`{body}` starts moving at {} (velocity, body rates) but joint `{joint}` moves it at {}: in the recursive formulation a body's motion follows from its joints' rates, so give `{body}` a velocity and body rates that satisfy `{joint}`", show(&want), show(&got))));
        }
        None
    }

    /// The name a spatial body was declared with.
    fn body_name(&self, b: usize) -> String {
        let s = self.scene.spatial[b].position[0];
        let name = &self.g.symbol(s).name;
        name.strip_suffix(".x").unwrap_or(name).to_string()
    }

    /// The vector field of the joint coordinates: q' = u, u' = u̇, a
    /// quaternion's q' = ½ q ⊗ ω, and the free bodies' as in the global
    /// formulation.
    fn joint_field(
        &mut self,
        states: &[NewState],
        attitudes: &[([SymbolId; 4], [SymbolId; 3])],
        free: &[bool],
    ) -> crate::Result<VectorField> {
        let g = &mut self.g;
        let mut field = VectorField::new();
        let mut second_order = |g: &mut Graph, s: SymbolId| -> crate::Result<()> {
            let d1 = g.derivative(s, 1)?;
            let d2 = g.derivative(s, 2)?;
            let s1 = g.as_symbol(d1).ok_or_else(|| unsupported("a rate"))?;
            field.set(s, d1);
            field.set(s1, d2);
            Ok(())
        };
        for s in states.iter().filter(|s| s.rate.is_some()) {
            second_order(g, s.symbol)?;
        }
        let mut first_order: Vec<([SymbolId; 4], [SymbolId; 3])> = attitudes.to_vec();
        for (b, body) in self.scene.spatial.iter().enumerate() {
            if free[b] {
                for s in body.position {
                    second_order(g, s)?;
                }
                first_order.push((body.quaternion, body.rates));
            }
        }
        for (q, w) in first_order {
            let qn = q.map(|s| g.symbol_node(s));
            let wn = w.map(|s| g.symbol_node(s));
            let rates = quaternion_rates(g, qn, wn)?;
            for k in 0..4 {
                field.set(q[k], rates[k]);
            }
            for s in w {
                let d = g.derivative(s, 1)?;
                field.set(s, d);
            }
        }
        Ok(field)
    }

    /// Velocities V_i = V_parent + Σ S_k u_k and the motion subspace in
    /// world axes, with the axes' rates Ṡ_k = V_F × S_k.
    fn tree_dynamics(
        &mut self,
        tree: &[Edge],
        placed: &[Placed],
        columns: &[Vec<(Column, Frame, Frame, bool)>],
        records: &[SpatialJointRecord],
        field: VectorField,
    ) -> crate::Result<Dynamics> {
        let n = placed.len();
        let g = &mut self.g;
        let zero = g.zero();
        let still = Spatial { top: [zero; 3], bottom: [zero; 3] };
        let mut velocity = vec![still; n];
        let mut subspace: Vec<Vec<Subspace>> = vec![Vec::new(); n];
        for edge in tree {
            let b = edge.child;
            let parent_velocity = match edge.parent {
                Frame::Ground => still,
                Frame::Body(p) => velocity[p],
            };
            let mut v = parent_velocity;
            let mut built = Vec::new();
            for &(column, fa, fb, child_is_b) in &columns[b] {
                let pose = |f: Frame| match f {
                    Frame::Ground => None,
                    Frame::Body(i) => Some(placed[i]),
                };
                let (pa, pb) = (pose(fa), pose(fb));
                let rot_of = |p: Option<Placed>, g: &mut Graph| -> Mat3 {
                    p.map_or_else(
                        || {
                            let one = g.one();
                            [one, zero, zero, zero, one, zero, zero, zero, one]
                        },
                        |p| p.rot,
                    )
                };
                let (ra, rb) = (rot_of(pa, g), rot_of(pb, g));
                let (s, fixed_in) = match column.axis {
                    Axis::Slide { axis } => {
                        (Spatial { top: [zero; 3], bottom: mat_vec(g, &ra, axis)? }, fa)
                    }
                    Axis::Turn { axis, in_b, fixed_in_b } => {
                        let w = mat_vec(g, if in_b { &rb } else { &ra }, axis)?;
                        // Through b's joint point (a free body's centre).
                        let point = match edge.joint {
                            Some(r) => {
                                let pb = pb.ok_or_else(|| unsupported("a joint point"))?;
                                let arm = mat_vec(g, &pb.rot, records[r].local_b)?;
                                add3(g, pb.centre, arm)?
                            }
                            None => placed[b].centre,
                        };
                        let moment = cross3(g, point, w)?;
                        (Spatial { top: w, bottom: moment }, if fixed_in_b { fb } else { fa })
                    }
                };
                let s = if child_is_b { s } else { negate(g, s)? };
                let step = scale(g, column.speed, s)?;
                v = add(g, v, step)?;
                built.push((s, fixed_in, column));
            }
            velocity[b] = v;
            for (s, fixed_in, column) in built {
                let frame_velocity = match fixed_in {
                    Frame::Ground => still,
                    Frame::Body(i) if i == b => v,
                    Frame::Body(i) => velocity[i],
                };
                let rate = cross_motion(g, frame_velocity, s)?;
                subspace[b].push(Subspace {
                    s,
                    rate,
                    speed: column.speed,
                    acceleration: column.acceleration,
                });
            }
        }
        Ok(Dynamics { field, velocity, subspace })
    }

    /// The body coordinates and their rates in joint coordinates (free
    /// bodies keep theirs); second derivatives only where something reads
    /// them.
    fn body_substitution(
        &mut self,
        placed: &[Placed],
        velocity: &[Spatial],
        free: &[bool],
        field: &mut VectorField,
    ) -> crate::Result<FxHashMap<SymbolId, Id>> {
        let mut read: std::collections::HashSet<SymbolId> = std::collections::HashSet::new();
        {
            let mut roots: Vec<Id> = Vec::new();
            roots.extend(self.equations.iter().flat_map(|e| [e.lhs, e.rhs]));
            roots.extend(self.outputs.iter().map(|o| o.value));
            roots.extend(self.events.iter().map(|e| e.value));
            roots.extend(self.invariants.iter().map(|i| i.value));
            roots.extend(
                self.scene.spatial_loads.iter().flat_map(|(_, f, t)| f.iter().chain(t).copied()),
            );
            for r in roots {
                read.extend(self.g.free_symbols(r));
            }
        }
        let mut replace = FxHashMap::default();
        for (b, body) in self.scene.spatial.clone().iter().enumerate() {
            if free[b] {
                continue;
            }
            let p = placed[b];
            let g = &mut self.g;
            let v = velocity[b];
            // v_c = v_O + ω × c; ω in body axes = Rᵀ ω.
            let turn = cross3(g, v.top, p.centre)?;
            let vc = add3(g, v.bottom, turn)?;
            let w_body = mat_t_vec(g, &p.rot, v.top)?;
            for k in 0..3 {
                let s = body.position[k];
                replace.insert(s, p.centre[k]);
                let d1 = g.derivative(s, 1)?;
                let s1 = g.as_symbol(d1).ok_or_else(|| unsupported("a rate"))?;
                replace.insert(s1, vc[k]);
                let d2 = g.derivative(s, 2)?;
                let s2 = g.as_symbol(d2).ok_or_else(|| unsupported("an acceleration"))?;
                if read.contains(&s2) {
                    replace.insert(s2, g.total_derivative(vc[k], field)?);
                }
                let w = body.rates[k];
                replace.insert(w, w_body[k]);
                let dw = g.derivative(w, 1)?;
                let sw = g.as_symbol(dw).ok_or_else(|| unsupported("a rate"))?;
                if read.contains(&sw) {
                    replace.insert(sw, g.total_derivative(w_body[k], field)?);
                }
            }
            let rates = quaternion_rates(g, p.quaternion, w_body)?;
            for k in 0..4 {
                let s = body.quaternion[k];
                replace.insert(s, p.quaternion[k]);
                let d = g.derivative(s, 1)?;
                let sd = g.as_symbol(d).ok_or_else(|| unsupported("a rate"))?;
                replace.insert(sd, rates[k]);
            }
        }
        Ok(replace)
    }

    /// Rewrites everything that read body coordinates; returns the cut
    /// joints' rows with their multipliers.
    fn rewrite_spatial(
        &mut self,
        replace: &FxHashMap<SymbolId, Id>,
        records: &[SpatialJointRecord],
        cut: &[usize],
    ) -> crate::Result<Vec<(Id, Id)>> {
        let g = &mut self.g;
        for eq in &mut self.equations {
            eq.lhs = g.substitute(eq.lhs, replace)?;
            eq.rhs = g.substitute(eq.rhs, replace)?;
        }
        for o in &mut self.outputs {
            o.value = g.substitute(o.value, replace)?;
        }
        for ev in &mut self.events {
            ev.value = g.substitute(ev.value, replace)?;
        }
        for inv in &mut self.invariants {
            inv.value = g.substitute(inv.value, replace)?;
        }
        for (_, f, t) in &mut self.scene.spatial_loads {
            for x in f.iter_mut().chain(t.iter_mut()) {
                *x = g.substitute(*x, replace)?;
            }
        }
        let mut rows = Vec::new();
        for &r in cut {
            for k in records[r].rows.clone() {
                let (row, lambda) = self.scene.rows[k];
                rows.push((g.substitute(row, replace)?, lambda));
            }
        }
        Ok(rows)
    }

    /// `body.x` … `body.wz` and `der(body.x)` … of the bodies that became
    /// expressions.
    fn spatial_body_outputs(
        &mut self,
        placed: &[Placed],
        velocity: &[Spatial],
        free: &[bool],
        origin: &TokenStream,
    ) -> crate::Result<()> {
        for (b, p) in placed.iter().enumerate() {
            if free[b] {
                continue;
            }
            let name = self.body_name(b);
            let g = &mut self.g;
            let v = velocity[b];
            let turn = cross3(g, v.top, p.centre)?;
            let vc = add3(g, v.bottom, turn)?;
            let w_body = mat_t_vec(g, &p.rot, v.top)?;
            let mut outputs = Vec::new();
            for (k, c) in ["x", "y", "z"].iter().enumerate() {
                outputs.push((format!("{name}.{c}"), p.centre[k], c.to_string()));
            }
            for (k, c) in ["x", "y", "z"].iter().enumerate() {
                outputs.push((format!("der({name}.{c})"), vc[k], format!("rate:{c}")));
            }
            for (k, c) in ["q0", "q1", "q2", "q3"].iter().enumerate() {
                outputs.push((format!("{name}.{c}"), p.quaternion[k], c.to_string()));
            }
            for (k, c) in ["wx", "wy", "wz"].iter().enumerate() {
                outputs.push((format!("{name}.{c}"), w_body[k], c.to_string()));
            }
            for (output, value, doc) in outputs {
                let doc = match doc.strip_prefix("rate:") {
                    Some(c) => format!("rate of `{name}.{c}`"),
                    None => super::names::body_coordinate_doc(&doc).to_string(),
                };
                self.outputs.push(crate::front::ir::Output {
                    name: output,
                    value,
                    doc,
                    origin: origin.clone(),
                });
            }
        }
        Ok(())
    }

    /// The equations of motion, one per joint speed: the mass matrix by the
    /// composite-rigid-body algorithm, the bias forces (gyroscopic and
    /// Coriolis terms, gravity, loads) by recursive Newton–Euler with
    /// u̇ = 0, and the cut joints' reactions.
    fn crba_rnea(
        &mut self,
        tree: &[Edge],
        placed: &[Placed],
        subspace: &[Vec<Subspace>],
        cut_rows: &[(Id, Id)],
        field: &mut VectorField,
    ) -> crate::Result<Vec<(Id, Id)>> {
        let bodies = self.scene.spatial.clone();
        let loads = self.scene.spatial_loads.clone();
        let gravity = self.scene.gravity_vector;
        let n = bodies.len();
        let g = &mut self.g;
        let zero = g.zero();
        let still = Spatial { top: [zero; 3], bottom: [zero; 3] };
        let mut parent: Vec<Option<usize>> = vec![None; n];
        for e in tree {
            if let Frame::Body(p) = e.parent {
                parent[e.child] = Some(p);
            }
        }
        let order: Vec<usize> = tree.iter().map(|e| e.child).collect();
        // Each body's inertia about the origin, world axes.
        let mut inertia = Vec::with_capacity(n);
        for (b, body) in bodies.iter().enumerate() {
            inertia.push(body_inertia(g, body.mass, &body.inertia, &placed[b])?);
        }
        // Forward: velocities and bias accelerations.
        let mut velocity = vec![still; n];
        let mut bias = vec![still; n];
        for &b in &order {
            let (mut v, mut a) = match parent[b] {
                Some(p) => (velocity[p], bias[p]),
                None => (still, still),
            };
            for col in &subspace[b] {
                let sv = scale(g, col.speed, col.s)?;
                v = add(g, v, sv)?;
                let sa = scale(g, col.speed, col.rate)?;
                a = add(g, a, sa)?;
            }
            velocity[b] = v;
            bias[b] = a;
        }
        // Each body's force f = I a + v ×* I v − f_ext, accumulated towards the root.
        let mut force = vec![still; n];
        for &b in &order {
            let body = &bodies[b];
            let ia = apply(g, &inertia[b], bias[b])?;
            let iv = apply(g, &inertia[b], velocity[b])?;
            let gyro = cross_force(g, velocity[b], iv)?;
            let mut f = add(g, ia, gyro)?;
            let c = placed[b].centre;
            let mut external = Vec::new();
            if let Some(gv) = gravity {
                external.push((scale3(g, body.mass, gv)?, [zero; 3]));
            }
            for (on, fw, tau) in &loads {
                if *on == b {
                    external.push((*fw, mat_vec(g, &placed[b].rot, *tau)?));
                }
            }
            for (fw, torque) in external {
                let moment = cross3(g, c, fw)?;
                let moment = add3(g, moment, torque)?;
                let ext = Spatial { top: moment, bottom: fw };
                f = sub(g, f, ext)?;
            }
            force[b] = f;
        }
        let mut composite = inertia.clone();
        for &b in order.iter().rev() {
            if let Some(p) = parent[b] {
                force[p] = add(g, force[p], force[b])?;
                composite[p] = add_inertia(g, &composite[p], &composite[b])?;
            }
        }
        // Index every speed; M_kl = S_kᵀ I^c_i S_l for l on i's path to the root.
        let mut index = Vec::new();
        let mut first = vec![0; n];
        for &b in &order {
            first[b] = index.len();
            for k in 0..subspace[b].len() {
                index.push((b, k));
            }
        }
        let m = index.len();
        let mut mass = vec![vec![zero; m]; m];
        for &i in &order {
            let mut j = Some(i);
            while let Some(jb) = j {
                for (l, col) in subspace[jb].iter().enumerate() {
                    let f = apply(g, &composite[i], col.s)?;
                    for (k, row) in subspace[i].iter().enumerate() {
                        let entry = dot(g, row.s, f)?;
                        mass[first[i] + k][first[jb] + l] = entry;
                        mass[first[jb] + l][first[i] + k] = entry;
                    }
                }
                j = parent[jb];
            }
        }
        // Reactions of the cut joints through the speeds: ∂Φ̇/∂u.
        let mut rates = Vec::with_capacity(cut_rows.len());
        for &(row, lambda) in cut_rows {
            rates.push((g.total_derivative(row, field)?, lambda));
        }
        let mut equations = Vec::with_capacity(m);
        for (k, &(b, c)) in index.iter().enumerate() {
            let col = subspace[b][c];
            let mut lhs = Vec::with_capacity(m);
            for (l, &(bl, cl)) in index.iter().enumerate() {
                if g.as_number(mass[k][l]).is_some_and(|v| v.is_zero()) {
                    continue;
                }
                lhs.push(g.mul(mass[k][l], subspace[bl][cl].acceleration)?);
            }
            let bias_force = dot(g, col.s, force[b])?;
            let mut rhs = vec![g.neg(bias_force)?];
            let speed = g.as_symbol(col.speed).ok_or_else(|| unsupported("a joint speed"))?;
            for &(rate, lambda) in &rates {
                let d = g.partial(rate, speed)?;
                if g.as_number(d).is_some_and(|v| v.is_zero()) {
                    continue;
                }
                let t = g.mul(d, lambda)?;
                rhs.push(g.neg(t)?);
            }
            equations.push((g.sum(&lhs)?, g.sum(&rhs)?));
        }
        Ok(equations)
    }
}

/// A column of the motion subspace in world axes: S, Ṡ, u and u̇.
#[derive(Clone, Copy)]
struct Subspace {
    s: Spatial,
    rate: Spatial,
    speed: Id,
    acceleration: Id,
}

/// The tree's velocities and subspaces, and the field that differentiates
/// along them.
struct Dynamics {
    field: VectorField,
    velocity: Vec<Spatial>,
    subspace: Vec<Vec<Subspace>>,
}

/// The spanning tree: grown from the ground through tree joints in either
/// direction, declaration order first; a body it cannot reach hangs from
/// the ground by a free joint, and the tree grows on from it.
fn spatial_tree(records: &[SpatialJointRecord], n: usize) -> Vec<Edge> {
    let mut placed = vec![false; n];
    let mut tree: Vec<Edge> = Vec::new();
    loop {
        loop {
            let mut changed = false;
            for (r, rec) in records.iter().enumerate() {
                if !TREE_JOINTS.contains(&rec.kind) || tree.iter().any(|e| e.joint == Some(r)) {
                    continue;
                }
                let is_placed = |f: Frame| match f {
                    Frame::Ground => true,
                    Frame::Body(i) => placed[i],
                };
                let edge = match (is_placed(rec.a), is_placed(rec.b), rec.a, rec.b) {
                    (true, false, _, Frame::Body(child)) => {
                        Edge { joint: Some(r), parent: rec.a, child, child_is_b: true }
                    }
                    (false, true, Frame::Body(child), _) => {
                        Edge { joint: Some(r), parent: rec.b, child, child_is_b: false }
                    }
                    _ => continue,
                };
                placed[edge.child] = true;
                tree.push(edge);
                changed = true;
            }
            if !changed {
                break;
            }
        }
        match placed.iter().position(|p| !p) {
            Some(i) => {
                placed[i] = true;
                tree.push(Edge { joint: None, parent: Frame::Ground, child: i, child_is_b: true });
            }
            None => return tree,
        }
    }
}

fn unsupported(what: &str) -> crate::Error {
    crate::Error::Unsupported { message: what.to_string() }
}

/// Removes the items at the positions `dropped` lists.
fn retain_unlisted<T>(items: &mut Vec<T>, dropped: &std::collections::HashSet<usize>) {
    let mut i = 0;
    items.retain(|_| {
        i += 1;
        !dropped.contains(&(i - 1))
    });
}

fn transpose(m: &Mat3) -> Mat3 {
    [m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]]
}

/// Rotation by `angle` about the unit axis `u` (Rodrigues):
/// cos θ 1 + sin θ [u]× + (1 − cos θ) u uᵀ.
fn rodrigues(g: &mut Graph, u: Vec3, angle: Id) -> crate::Result<Mat3> {
    let (c, s) = (g.call(crate::Func::Cos, angle)?, g.call(crate::Func::Sin, angle)?);
    let one = g.one();
    let versine = g.sub(one, c)?;
    let mut r = [c; 9];
    for i in 0..3 {
        for j in 0..3 {
            let uu = g.mul(u[i], u[j])?;
            let mut terms = vec![g.mul(versine, uu)?];
            if i == j {
                terms.push(c);
            } else {
                // [u]×_ij = −ε_ijk u_k.
                let k = 3 - i - j;
                let t = g.mul(s, u[k])?;
                terms.push(if (i + 1) % 3 == j { g.neg(t)? } else { t });
            }
            r[3 * i + j] = g.sum(&terms)?;
        }
    }
    Ok(r)
}

fn add(g: &mut Graph, a: Spatial, b: Spatial) -> crate::Result<Spatial> {
    Ok(Spatial { top: add3(g, a.top, b.top)?, bottom: add3(g, a.bottom, b.bottom)? })
}

fn sub(g: &mut Graph, a: Spatial, b: Spatial) -> crate::Result<Spatial> {
    Ok(Spatial { top: sub3(g, a.top, b.top)?, bottom: sub3(g, a.bottom, b.bottom)? })
}

fn scale(g: &mut Graph, s: Id, a: Spatial) -> crate::Result<Spatial> {
    Ok(Spatial { top: scale3(g, s, a.top)?, bottom: scale3(g, s, a.bottom)? })
}

fn negate(g: &mut Graph, a: Spatial) -> crate::Result<Spatial> {
    let minus = g.int(-1);
    scale(g, minus, a)
}

/// A motion vector applied to a force vector (power): ω·n + v·f.
fn dot(g: &mut Graph, motion: Spatial, force: Spatial) -> crate::Result<Id> {
    let a = dot3(g, motion.top, force.top)?;
    let b = dot3(g, motion.bottom, force.bottom)?;
    g.add(a, b)
}

/// (ω; v) × (m; n) = (ω × m; ω × n + v × m), Featherstone eq. 2.31.
fn cross_motion(g: &mut Graph, a: Spatial, b: Spatial) -> crate::Result<Spatial> {
    let top = cross3(g, a.top, b.top)?;
    let wn = cross3(g, a.top, b.bottom)?;
    let vm = cross3(g, a.bottom, b.top)?;
    Ok(Spatial { top, bottom: add3(g, wn, vm)? })
}

/// (ω; v) ×* (n; f) = (ω × n + v × f; ω × f), Featherstone eq. 2.32.
fn cross_force(g: &mut Graph, a: Spatial, f: Spatial) -> crate::Result<Spatial> {
    let wn = cross3(g, a.top, f.top)?;
    let vf = cross3(g, a.bottom, f.bottom)?;
    Ok(Spatial { top: add3(g, wn, vf)?, bottom: cross3(g, a.top, f.bottom)? })
}

/// I (ω; v) = (I_O ω + h × v; m v − h × ω).
fn apply(g: &mut Graph, i: &Inertia, a: Spatial) -> crate::Result<Spatial> {
    let iw = mat_vec(g, &i.about_origin, a.top)?;
    let hv = cross3(g, i.h, a.bottom)?;
    let mv = scale3(g, i.mass, a.bottom)?;
    let hw = cross3(g, i.h, a.top)?;
    Ok(Spatial { top: add3(g, iw, hv)?, bottom: sub3(g, mv, hw)? })
}

fn add_inertia(g: &mut Graph, a: &Inertia, b: &Inertia) -> crate::Result<Inertia> {
    let mut about_origin = a.about_origin;
    for (k, x) in about_origin.iter_mut().enumerate() {
        *x = g.add(a.about_origin[k], b.about_origin[k])?;
    }
    Ok(Inertia { about_origin, h: add3(g, a.h, b.h)?, mass: g.add(a.mass, b.mass)? })
}

/// A body's spatial inertia about the origin: I_O = R J Rᵀ + m (|c|² 1 − c cᵀ).
fn body_inertia(g: &mut Graph, mass: Id, j: &Mat3, p: &Placed) -> crate::Result<Inertia> {
    let jr = mat_mul(g, j, &transpose(&p.rot))?;
    let world = mat_mul(g, &p.rot, &jr)?;
    let c = p.centre;
    let c2 = dot3(g, c, c)?;
    let mut about_origin = world;
    for i in 0..3 {
        for k in i..3 {
            let cc = g.mul(c[i], c[k])?;
            let shift = if i == k { g.sub(c2, cc)? } else { g.neg(cc)? };
            let shift = g.mul(mass, shift)?;
            let entry = g.add(world[3 * i + k], shift)?;
            about_origin[3 * i + k] = entry;
            about_origin[3 * k + i] = entry;
        }
    }
    Ok(Inertia { about_origin, h: scale3(g, mass, c)?, mass })
}
