//! Spatial multibody scenes in body coordinates (course notes §4.2,
//! with quaternion attitudes, §4.1.3): each body is free, the position of
//! its centre of mass `r`, a unit quaternion `q` and its angular velocity
//! `ω` in body axes; each joint is a set of constraints on `(r, q)` with its
//! reaction as algebraic variables. At the end of the model the macro writes
//!
//! ```text
//! m r'' = m g + F − Φ_rᵀ λ
//! q'    = ½ q ⊗ (0, ω)                         (|q| = 1 projected onto)
//! J ω' = τ − ω × J ω − Lᵀ Φ_qᵀ λ,   L = ∂q/∂π = ½ [−q_vᵀ; q0 I + [q_v]×]
//! ```
//!
//! where π is the virtual rotation in body axes, so `Lᵀ Φ_qᵀ λ` is the
//! constraint torque in body axes. Joints (`x` a point, `u` an axis, both
//! in the coordinates of the body named before them):
//!
//! ```text
//! let top = spatial_body(m, vec3(a, a, c), [x, y, z], [q0, q1, q2, q3]);  // optional [v], [ω]
//! spherical(a, pa, b, pb);          // 3 rows: the points coincide
//! revolute(a, pa, b, pb, u);        // 5 rows: and u stays along its initial direction in b
//! prismatic(a, pa, b, pb, u);       // 5 rows: pb on the line (pa, u), relative attitude kept
//! fixed(a, pa, b, pb);              // 6 rows: welded in the initial relative attitude
//! distance(a, pa, b, pb, l);        // 1 row: a massless rod with ball joints
//! universal(a, pa, b, pb, ua, ub);  // 4 rows: the points coincide, ua (in a) ⟂ ub (in b)
//! cylindrical(a, pa, b, pb, u);     // 4 rows: pb on the line (pa, u), u kept in b: slides and turns
//! planar(a, pa, b, pb, n);          // 3 rows: pb in the plane (pa, n), n kept in b
//! ```
//!
//! The universal (Cardan) joint is a spherical joint whose two cross axes,
//! one fixed in each body, stay perpendicular; the cylindrical one a
//! revolute joint free to slide along its axis; the planar one keeps b on
//! a plane of a, turning about its normal (Haug, *Computer-Aided
//! Kinematics and Dynamics of Mechanical Systems*, 1989, §9.2: the
//! universal joint as spherical + dot-1, the cylindrical as two dot-1 and
//! two dot-2 constraints).

use super::algebra::{
    add3, cross3, dot3, mat_t_vec, mat_vec, quaternion_rates, rotation, scale3, sub3, Mat3, Vec3,
};
use super::spatial_joint_rows::{JointGeometry, Pose};
use super::Scene;
use super::{SpatialBody, SpatialLoad};
use crate::front::lower::Binding;
use crate::front::lower::Lower;
use crate::{Graph, Id, SymbolId};
use quote::ToTokens;
use syn::Expr;

/// The frame of three points in natural coordinates (course notes §4.1.5,
/// in space): origin P1, x axis along P1P2, z axis normal to the plane of
/// the three points, y = z × x. Columns of the rotation matrix.
pub(crate) fn natural_frame(g: &mut Graph, p1: Vec3, p2: Vec3, p3: Vec3) -> crate::Result<Mat3> {
    let unit = |g: &mut Graph, v: Vec3| -> crate::Result<Vec3> {
        let n2 = dot3(g, v, v)?;
        let n = g.sqrt(n2)?;
        Ok([g.div(v[0], n)?, g.div(v[1], n)?, g.div(v[2], n)?])
    };
    let a = sub3(g, p2, p1)?;
    let b = sub3(g, p3, p1)?;
    let i = unit(g, a)?;
    let normal = cross3(g, a, b)?;
    let k = unit(g, normal)?;
    let j = cross3(g, k, i)?;
    Ok([i[0], j[0], k[0], i[1], j[1], k[1], i[2], j[2], k[2]])
}

/// Spatial joints and their number of rows.
pub(crate) const SPATIAL_JOINTS: [(&str, usize); 8] = [
    ("spherical", 3),
    ("revolute", 5),
    ("prismatic", 5),
    ("fixed", 6),
    ("distance", 1),
    ("universal", 4),
    ("cylindrical", 4),
    ("planar", 3),
];

impl Lower<'_, Scene> {
    /// `let b = spatial_body(m, inertia, [x, y, z], [q0, q1, q2, q3])`, with
    /// optional initial `[vx, vy, vz]` and `[ωx, ωy, ωz]` (body axes).
    pub(crate) fn spatial_declaration(
        &mut self,
        ident: &syn::Ident,
        call: &syn::ExprCall,
        local: &syn::Local,
    ) {
        // Until it is declared, later statements see a body whose
        // declaration failed, and stay quiet about it.
        self.scene.spatial_declared = true;
        self.bind(ident, Binding::BrokenBody);
        if !self.scene.bodies.is_empty() {
            return self.cx.error_at(local, "a scene is planar (`body`) or spatial (`spatial_body`), not both: declare every body with `spatial_body(m, inertia, [x, y, z], [q0, q1, q2, q3])`");
        }
        if !(4..=6).contains(&call.args.len()) {
            return self.cx.error_at(call, "`spatial_body` takes a mass, the inertia about the centre of mass in body axes (`vec3` of principal moments or a `mat3`), the initial `[x, y, z]` and `[q0, q1, q2, q3]`, and optionally the initial `[vx, vy, vz]` and body rates `[wx, wy, wz]`");
        }
        let Some(mass) = self.value(&call.args[0]) else {
            return;
        };
        let Some(j) = self.tensor(&call.args[1]) else {
            return;
        };
        let zero = self.g.zero();
        let inertia: Mat3 = match (j.rows, j.cols) {
            (3, 1) => [j.data[0], zero, zero, zero, j.data[1], zero, zero, zero, j.data[2]],
            (3, 3) => std::array::from_fn(|k| j.data[k]),
            _ => {
                return self.cx.error_at(&call.args[1], format!("the inertia is a `vec3` of principal moments or a `mat3` in body axes, not a {}", j.shape()));
            }
        };
        let array = |this: &mut Self, e: &Expr, n: usize, what: &str| -> Option<Vec<Id>> {
            match e {
                Expr::Array(a) if a.elems.len() == n => {
                    a.elems.iter().map(|v| this.initial_value(v)).collect()
                }
                other => {
                    this.cx.error_at(other, format!("write {n} values: `{what}`"));
                    None
                }
            }
        };
        let Some(position) = array(self, &call.args[2], 3, "[x, y, z]") else {
            return;
        };
        let Some(attitude) = array(self, &call.args[3], 4, "[q0, q1, q2, q3]") else {
            return;
        };
        let velocity = match call.args.get(4) {
            Some(v) => match array(self, v, 3, "[vx, vy, vz]") {
                Some(v) => v,
                None => return,
            },
            None => vec![zero; 3],
        };
        let rates = match call.args.get(5) {
            Some(v) => match array(self, v, 3, "[wx, wy, wz]") {
                Some(v) => v,
                None => return,
            },
            None => vec![zero; 3],
        };
        let name = ident.to_string();
        let origin = local.to_token_stream();
        let declare = |this: &mut Self, coordinate: &str, init: Id| -> Option<SymbolId> {
            let doc = crate::mechanics::names::body_coordinate_doc(coordinate);
            this.declare_state(format!("{name}.{coordinate}"), init, ident, &origin, doc)
        };
        let mut symbols = Vec::with_capacity(10);
        for (k, c) in ["x", "y", "z"].iter().enumerate() {
            symbols.push(declare(self, c, position[k]));
        }
        for (k, c) in ["q0", "q1", "q2", "q3"].iter().enumerate() {
            symbols.push(declare(self, c, attitude[k]));
        }
        for (k, c) in ["wx", "wy", "wz"].iter().enumerate() {
            symbols.push(declare(self, c, rates[k]));
        }
        let Some(symbols) = symbols.into_iter().collect::<Option<Vec<SymbolId>>>() else {
            return;
        };
        if call.args.len() > 4 {
            for k in 0..3 {
                if self.init_rate(symbols[k], velocity[k], &origin).is_none() {
                    return;
                }
            }
        }
        // |q|² − 1, kept at zero by projection (course notes §4.1.3).
        let norm = (|| {
            let g = &mut self.g;
            let mut terms = Vec::with_capacity(5);
            for &s in &symbols[3..7] {
                let q = g.symbol_node(s);
                terms.push(g.mul(q, q)?);
            }
            terms.push(g.int(-1));
            g.sum(&terms)
        })();
        match norm {
            Ok(value) => self
                .invariants
                .push(crate::front::ir::UserInvariant { value, origin: origin.clone() }),
            Err(e) => return self.cx.error_at(ident, e),
        }
        if self.scene.first_body.is_none() {
            self.scene.first_body = Some(origin);
        }
        self.scene.spatial.push(SpatialBody {
            position: [symbols[0], symbols[1], symbols[2]],
            quaternion: [symbols[3], symbols[4], symbols[5], symbols[6]],
            rates: [symbols[7], symbols[8], symbols[9]],
            mass,
            inertia,
        });
        self.rebind(ident, Binding::Body(self.scene.spatial.len() - 1));
    }

    /// `orientation(body)`: R(q), body axes to world axes.
    pub(crate) fn orientation(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<Mat3> {
        if c.args.len() != 1 {
            self.cx.error_at(c, "`orientation` takes a spatial body: `orientation(top)`");
            return None;
        }
        let frame = self.frame(&c.args[0])?;
        match self.pose(frame) {
            Ok(pose) => Some(pose.rot),
            Err(err) => {
                self.cx.error_at(e, err);
                None
            }
        }
    }

    /// The pose of a frame, with its initial attitude for joints that keep it.
    fn pose(&mut self, frame: crate::mechanics::Frame) -> crate::Result<Pose> {
        let g = &mut self.g;
        let (zero, one) = (g.zero(), g.one());
        let identity = [one, zero, zero, zero, one, zero, zero, zero, one];
        match frame {
            crate::mechanics::Frame::Ground => {
                Ok(Pose { r: [zero; 3], rot: identity, rot0: identity })
            }
            crate::mechanics::Frame::Body(b) => {
                let body = self.scene.spatial[b].clone();
                let q = body.quaternion.map(|s| self.g.symbol_node(s));
                let q0 = body
                    .quaternion
                    .map(|s| self.states.iter().find(|d| d.symbol == s).map_or(zero, |d| d.init));
                let g = &mut self.g;
                Ok(Pose {
                    r: body.position.map(|s| g.symbol_node(s)),
                    rot: rotation(g, q)?,
                    rot0: rotation(g, q0)?,
                })
            }
        }
    }

    /// A frame's attitude quaternion now and at the start, and its
    /// angular velocity in its own axes (the ground's: identity, zero).
    fn attitude(&mut self, frame: crate::mechanics::Frame) -> ([Id; 4], [Id; 4], Vec3) {
        let (zero, one) = (self.g.zero(), self.g.one());
        match frame {
            crate::mechanics::Frame::Ground => {
                ([one, zero, zero, zero], [one, zero, zero, zero], [zero; 3])
            }
            crate::mechanics::Frame::Body(b) => {
                let body = self.scene.spatial[b].clone();
                let start = |s: SymbolId| {
                    self.states.iter().find(|d| d.symbol == s).map_or(zero, |d| d.init)
                };
                let q0 = body.quaternion.map(start);
                (
                    body.quaternion.map(|s| self.g.symbol_node(s)),
                    q0,
                    body.rates.map(|s| self.g.symbol_node(s)),
                )
            }
        }
    }

    /// A 3-vector argument.
    fn vec3_arg(&mut self, e: &Expr, what: &str) -> Option<Vec3> {
        let t = self.tensor(e)?;
        if (t.rows, t.cols) != (3, 1) {
            self.cx.error_at(e, format!("{what} is a 3-vector, not a {}", t.shape()));
            return None;
        }
        Some([t.data[0], t.data[1], t.data[2]])
    }

    /// The points in body coordinates of a joint's or a spring's call
    /// `(a, sa, b, sb, ..)`, both checked (each error reported).
    fn attachment_points(&mut self, c: &syn::ExprCall) -> Option<[Vec3; 2]> {
        let what = "a point in body coordinates";
        let (sa, sb) = (self.vec3_arg(&c.args[1], what), self.vec3_arg(&c.args[3], what));
        Some([sa?, sb?])
    }

    /// The poses of frames `a` and `b` and the vector from `a`'s point
    /// `sa` to `b`'s point `sb`, in the world.
    fn attachment_gap(
        &mut self,
        [a, b]: [crate::mechanics::Frame; 2],
        [sa, sb]: [Vec3; 2],
    ) -> crate::Result<(Pose, Pose, Vec3)> {
        let pa = self.pose(a)?;
        let pb = self.pose(b)?;
        let g = &mut self.g;
        let xa = Self::place(g, &pa, sa)?;
        let xb = Self::place(g, &pb, sb)?;
        Ok((pa, pb, sub3(g, xb, xa)?))
    }

    /// `position(body, p)` in a spatial scene: `r + R(q) p`.
    pub(crate) fn spatial_position(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<Vec3> {
        let frame = self.frame(&c.args[0])?;
        let p = self.vec3_arg(&c.args[1], "a point in body coordinates")?;
        let r = self.pose(frame).and_then(|pose| Self::place(&mut self.g, &pose, p));
        match r {
            Ok(v) => Some(v),
            Err(err) => {
                self.cx.error_at(e, err);
                None
            }
        }
    }

    fn place(g: &mut Graph, pose: &Pose, p: Vec3) -> crate::Result<Vec3> {
        let turned = mat_vec(g, &pose.rot, p)?;
        add3(g, pose.r, turned)
    }

    /// A joint of a spatial scene: its constraint rows.
    pub(crate) fn spatial_joint(
        &mut self,
        kind: &str,
        name: Option<&syn::Ident>,
        c: &syn::ExprCall,
        e: &Expr,
    ) {
        let Some(&(kind, _)) = SPATIAL_JOINTS.iter().find(|(k, _)| *k == kind) else {
            return self.cx.error_at(c, format!("`{kind}` is not a spatial joint: use `spherical`, `revolute`, `prismatic`, `fixed`, `distance`, `universal`, `cylindrical` or `planar`"));
        };
        let extra = match kind {
            "distance" => Some("length"),
            "revolute" | "prismatic" | "cylindrical" => Some("axis_in_a"),
            "planar" => Some("normal_in_a"),
            _ => None,
        };
        let (a, b) = if kind == "universal" {
            if c.args.len() != 6 {
                return self.cx.error_at(c, "`universal` takes 6 arguments: `universal(a, point_in_a, b, point_in_b, axis_in_a, axis_in_b)`, the two cross axes perpendicular at the start");
            }
            let mut four = c.clone();
            four.args = c.args.iter().take(4).cloned().collect();
            match self.joint_frames(kind, &four, None) {
                Some(frames) => frames,
                None => return,
            }
        } else {
            match self.joint_frames(kind, c, extra) {
                Some(frames) => frames,
                None => return,
            }
        };
        let Some([sa, sb]) = self.attachment_points(c) else {
            return;
        };
        let extra = match kind {
            "distance" => match self.value(&c.args[4]) {
                Some(l) => Some([l, l, l]),
                None => return,
            },
            "revolute" | "prismatic" | "cylindrical" | "universal" => {
                match self.vec3_arg(&c.args[4], "the axis") {
                    Some(u) => Some(u),
                    None => return,
                }
            }
            "planar" => match self.vec3_arg(&c.args[4], "the plane's normal") {
                Some(n) => Some(n),
                None => return,
            },
            _ => None,
        };
        let cross_axis = match kind {
            "universal" => match self.vec3_arg(&c.args[5], "the axis in b") {
                Some(u) => Some(u),
                None => return,
            },
            _ => None,
        };
        let axis_values = extra.map(|u| u.map(|x| self.numeric(x)));
        let attitudes = [self.attitude(a), self.attitude(b)];
        // The rows, and the joint's coordinates as expressions of the
        // bodies' (named as joint coordinates name them).
        let rows = self.attachment_gap([a, b], [sa, sb]).and_then(|(pa, pb, gap)| {
            let joint = JointGeometry { pa, pb, gap, extra, cross_axis, axis_values, attitudes };
            super::spatial_joint_rows::rows_and_coordinates(&mut self.g, kind, &joint)
        });
        match rows {
            Ok((rows, coordinates)) => {
                // A Cardan joint's cross axes are perpendicular: other axes
                // are a mistake the dot-1 row would repair by turning a body.
                if kind == "universal" {
                    let cosine = self.numeric(rows[3]);
                    if cosine.abs() > 1e-9 {
                        return self.cx.error_at(c, format!("the two axes of `universal` must be perpendicular at the start, as a Cardan joint's cross axes are: axis_in_a and axis_in_b have the dot product {cosine} in world axes"));
                    }
                }
                let Some((equations, algebraics, rows)) = self.add_joint_rows(kind, name, rows, e)
                else {
                    return;
                };
                let name = self.scene.joint_rows.last().map(|j| j.0.clone()).unwrap_or_default();
                self.scene.spatial_records.push(super::SpatialJointRecord {
                    kind,
                    name,
                    a,
                    b,
                    local_a: sa,
                    local_b: sb,
                    axis: extra,
                    axis_values,
                    cross_axis,
                    equations,
                    algebraics,
                    rows,
                });
                if let Some((joint, ..)) = self.scene.joint_rows.last() {
                    let joint = joint.clone();
                    self.spatial_joint_coordinates(&joint, kind, [a, b], &coordinates, e);
                }
            }
            Err(err) => self.cx.error_at(e, err),
        }
    }

    /// `gravity`, `force`, `torque`, `spring` in a spatial scene; forces and
    /// torques in world axes, points in body coordinates.
    pub(crate) fn spatial_load(&mut self, kind: &str, c: &syn::ExprCall, e: &Expr) {
        use crate::mechanics::Frame;
        match kind {
            "gravity" => {
                if c.args.len() != 1 {
                    return self.cx.error_at(c, "`gravity` takes the acceleration of gravity as a 3-vector: `gravity(vec3(0.0, 0.0, -g))`");
                }
                if let Some(v) = self.vec3_arg(&c.args[0], "gravity") {
                    self.scene.gravity_vector = Some(v);
                }
            }
            "force" => {
                let Some(b) = self.loaded_body(c, 3, crate::mechanics::FORCE_USAGE) else {
                    return;
                };
                let (Some(s), Some(f)) = (
                    self.vec3_arg(&c.args[1], "a point in body coordinates"),
                    self.vec3_arg(&c.args[2], "a force"),
                ) else {
                    return;
                };
                // Its moment about the centre of mass in body axes: s × Rᵀ f.
                let r = (|| {
                    let pose = self.pose(Frame::Body(b))?;
                    let g = &mut self.g;
                    let local = mat_t_vec(g, &pose.rot, f)?;
                    cross3(g, s, local)
                })();
                match r {
                    Ok(tau) => {
                        let load = SpatialLoad::world(&mut self.g, b, f, tau);
                        self.scene.spatial_loads.push(load);
                    }
                    Err(err) => self.cx.error_at(e, err),
                }
            }
            "torque" => {
                let Some(b) =
                    self.loaded_body(c, 2, "a body and the torque in world axes (a 3-vector)")
                else {
                    return;
                };
                let Some(tau) = self.vec3_arg(&c.args[1], "a torque") else {
                    return;
                };
                let r = (|| {
                    let pose = self.pose(Frame::Body(b))?;
                    mat_t_vec(&mut self.g, &pose.rot, tau)
                })();
                let zero = self.g.zero();
                match r {
                    Ok(local) => {
                        let load = SpatialLoad::world(&mut self.g, b, [zero; 3], local);
                        self.scene.spatial_loads.push(load);
                    }
                    Err(err) => self.cx.error_at(e, err),
                }
            }
            _ => self.spatial_spring(c, e),
        }
    }

    /// The kind of the named spatial joint `name` a flange drives.
    pub(crate) fn spatial_joint_axis(&self, name: &str) -> Option<&'static str> {
        let record = self.scene.spatial_records.iter().find(|r| r.name == name)?;
        matches!(record.kind, "revolute" | "prismatic").then_some(record.kind)
    }

    /// `joint.flange` of a spatial joint, and `flow` across it: a torque
    /// about a revolute's axis (on b, its reaction on a), or a force along
    /// a prismatic's axis at b's joint point. A revolute's angle has no
    /// coordinate in body coordinates: it is the state `joint.angle`,
    /// integrating the relative angular velocity about the axis from 0
    /// (in joint coordinates, tied to the joint's own).
    pub(crate) fn spatial_joint_flange(&mut self, name: &str, flow: Id, at: &Expr) -> Option<Id> {
        use crate::mechanics::Frame;
        let record = self.scene.spatial_records.iter().find(|r| r.name == name)?.clone();
        let axis = record.axis?;
        // The axis about which a revolute lets b turn keeps its direction
        // in either body's axes: u_a as written, u_b = R_b0ᵀ R_a0 u_a from
        // the initial poses. The relative rate about it, u_b·ω_b − u_a·ω_a
        // (ω in body axes), is then linear in the rates with constant
        // coefficients, so a rotor tied to the joint keeps no state of its
        // own.
        let rate_along = |this: &mut Self, frame: Frame, axis: Vec3| -> crate::Result<Id> {
            match frame {
                Frame::Ground => Ok(this.g.zero()),
                Frame::Body(b) => {
                    let rates = this.scene.spatial[b].rates.map(|s| this.g.symbol_node(s));
                    dot3(&mut this.g, axis, rates)
                }
            }
        };
        let built = (|| -> crate::Result<(Vec3, Pose, Id, Pose, Id, [Vec3; 2])> {
            let pa = self.pose(record.a)?;
            let pb = self.pose(record.b)?;
            let g = &mut self.g;
            let norm2 = dot3(g, axis, axis)?;
            let norm = g.sqrt(norm2)?;
            let one = g.one();
            let inverse = g.div(one, norm)?;
            let unit_a = scale3(g, inverse, axis)?;
            let u = mat_vec(g, &pa.rot, unit_a)?;
            let u0 = mat_vec(g, &pa.rot0, unit_a)?;
            let unit_b = mat_t_vec(g, &pb.rot0, u0)?;
            let wa = rate_along(self, record.a, unit_a)?;
            let wb = rate_along(self, record.b, unit_b)?;
            Ok((u, pa, wa, pb, wb, [unit_a, unit_b]))
        })();
        let (u, pa, wa, pb, wb, [unit_a, unit_b]) = match built {
            Ok(v) => v,
            Err(e) => {
                self.cx.error_at(at, e);
                return None;
            }
        };
        let zero = self.g.zero();
        let result = (|| -> crate::Result<Id> {
            if record.kind == "revolute" {
                // The torque about the axis, in each body's own axes: the
                // axis keeps its direction in both.
                let on_b = scale3(&mut self.g, flow, unit_b)?;
                let minus = self.g.neg(flow)?;
                let on_a = scale3(&mut self.g, minus, unit_a)?;
                for (frame, torque) in [(record.b, on_b), (record.a, on_a)] {
                    if let Frame::Body(b) = frame {
                        let load = SpatialLoad::world(&mut self.g, b, [zero; 3], torque);
                        self.scene.spatial_loads.push(load);
                    }
                }
                return self.g.sub(wb, wa);
            }
            // Prismatic: the force along the axis at b's joint point, in
            // each body's own axes (the bodies keep their relative
            // attitude): on b, f u_b with moment p_b × f u_b about its
            // centre; on a, −f u_a at the same point, p_a + s u_a, whose
            // moment is p_a × (−f u_a).
            let point = |this: &mut Self, pose: &Pose, p: Vec3| -> crate::Result<Vec3> {
                let turned = mat_vec(&mut this.g, &pose.rot, p)?;
                add3(&mut this.g, pose.r, turned)
            };
            let (xa, xb) = (point(self, &pa, record.local_a)?, point(self, &pb, record.local_b)?);
            let offset = sub3(&mut self.g, xb, xa)?;
            let g = &mut self.g;
            for (frame, arm, axis, sign) in
                [(record.b, record.local_b, unit_b, 1), (record.a, record.local_a, unit_a, -1)]
            {
                let Frame::Body(body) = frame else { continue };
                let k = g.int(sign);
                let signed = g.mul(k, flow)?;
                let body_force = scale3(g, signed, axis)?;
                let torque = cross3(g, arm, body_force)?;
                self.scene.spatial_loads.push(SpatialLoad {
                    body,
                    world_force: [zero; 3],
                    body_force,
                    torque,
                });
            }
            dot3(&mut self.g, u, offset)
        })();
        let value = match result {
            Ok(v) => v,
            Err(e) => {
                self.cx.error_at(at, e);
                return None;
            }
        };
        if record.kind == "prismatic" {
            if !self.scene.recursive {
                return Some(value);
            }
            // In joint coordinates the displacement is the joint's own
            // coordinate: a symbol stands for it until the formulation
            // puts `name.q` in its place (the expression in the bodies'
            // coordinates would not simplify to it, and a part's state tied
            // to it would stay apart).
            let placeholder = self.g.state(&format!("{name}.flange_s")).ok();
            let Some(symbol) = placeholder.and_then(|n| self.g.as_symbol(n)) else {
                self.cx.error_at(at, "the flange's displacement cannot be made");
                return None;
            };
            self.scene.prismatic_flanges.push((name.to_string(), symbol, value));
            return placeholder;
        }
        // The revolute's angle, integrated from zero.
        let origin = at.to_token_stream();
        let state_name = format!("{name}.angle");
        let ident = syn::Ident::new("angle", proc_macro2::Span::call_site());
        let doc = "angle of the joint's flange, the relative rotation about its axis from the start (rad)";
        let symbol = self.declare_state(state_name, zero, &ident, &origin, doc)?;
        if let Some(state) = self.states.iter_mut().find(|s| s.symbol == symbol) {
            state.avoid = true;
        }
        let d = self.g.derivative(symbol, 1).ok()?;
        self.equations.push(crate::front::ir::Equation {
            lhs: d,
            rhs: value,
            origin,
            is_constraint: false,
            mode: Vec::new(),
        });
        Some(self.g.symbol_node(symbol))
    }

    /// `spring(a, pa, b, pb, k, l0, c)` between two points of a spatial scene.
    fn spatial_spring(&mut self, c: &syn::ExprCall, e: &Expr) {
        use crate::mechanics::Frame;
        let Some((a, b, [k, l0, damping])) = self.spring_arguments(c) else {
            return;
        };
        let Some([sa, sb]) = self.attachment_points(c) else {
            return;
        };
        let mut field = self.spatial_field();
        let r = (|| -> crate::Result<(Vec3, Vec3, Vec3)> {
            let (pa, pb, gap) = self.attachment_gap([a, b], [sa, sb])?;
            let g = &mut self.g;
            let d2 = dot3(g, gap, gap)?;
            let (d, tension) = super::spring_tension(g, d2, [k, damping, l0], &mut field)?;
            let over = g.div(tension, d)?;
            // On a towards b; on b the opposite.
            let f = scale3(g, over, gap)?;
            let on_a = mat_t_vec(g, &pa.rot, f)?;
            let on_b = mat_t_vec(g, &pb.rot, f)?;
            Ok((f, cross3(g, sa, on_a)?, cross3(g, sb, on_b)?))
        })();
        let (f, tau_a, tau_b) = match r {
            Ok(v) => v,
            Err(err) => return self.cx.error_at(e, err),
        };
        if let Frame::Body(i) = a {
            let load = SpatialLoad::world(&mut self.g, i, f, tau_a);
            self.scene.spatial_loads.push(load);
        }
        if let Frame::Body(i) = b {
            let minus = (|| {
                let g = &mut self.g;
                Ok::<_, crate::Error>((
                    [g.neg(f[0])?, g.neg(f[1])?, g.neg(f[2])?],
                    [g.neg(tau_b[0])?, g.neg(tau_b[1])?, g.neg(tau_b[2])?],
                ))
            })();
            match minus {
                Ok((f, tau)) => {
                    let load = SpatialLoad::world(&mut self.g, i, f, tau);
                    self.scene.spatial_loads.push(load);
                }
                Err(err) => self.cx.error_at(e, err),
            }
        }
    }

    /// The motion as a vector field on the coordinates: `r' = v`, `q' = ½ q ⊗ ω`.
    fn spatial_field(&mut self) -> crate::VectorField {
        let mut field = crate::VectorField::new();
        for body in self.scene.spatial.clone() {
            for s in body.position {
                if let Ok(d) = self.g.derivative(s, 1) {
                    field.set(s, d);
                }
            }
            let q = body.quaternion.map(|s| self.g.symbol_node(s));
            let w = body.rates.map(|s| self.g.symbol_node(s));
            if let Ok(rates) = quaternion_rates(&mut self.g, q, w) {
                for (s, d) in body.quaternion.into_iter().zip(rates) {
                    field.set(s, d);
                }
            }
        }
        field
    }

    /// The numerical columns of Φ_q for one spatial body at a point: three
    /// translations, then three rotations about the body axes (Φ_q L).
    pub(crate) fn spatial_jacobian_columns(
        &mut self,
        b: usize,
        row: Id,
        value: &dyn Fn(&Graph, Id) -> f64,
    ) -> crate::Result<[f64; 6]> {
        let body = self.scene.spatial[b].clone();
        let mut out = [0.0; 6];
        for k in 0..3 {
            let d = self.g.partial(row, body.position[k])?;
            out[k] = value(&self.g, d);
        }
        let mut dq = [0.0; 4];
        for k in 0..4 {
            let d = self.g.partial(row, body.quaternion[k])?;
            dq[k] = value(&self.g, d);
        }
        let q = body.quaternion.map(|s| {
            let n = self.g.symbol_node(s);
            value(&self.g, n)
        });
        let l = rotation_map(q);
        for k in 0..3 {
            out[3 + k] = (0..4).map(|i| dq[i] * l[i][k]).sum();
        }
        Ok(out)
    }

    /// The equations of motion of every spatial body.
    pub(crate) fn spatial_equations(&mut self, origin: &proc_macro2::TokenStream) {
        let bodies = self.scene.spatial.clone();
        let rows = self.scene.rows.clone();
        let loads = self.scene.spatial_loads.clone();
        let gravity = self.scene.gravity_vector;
        let r = (|| -> crate::Result<Vec<(Id, Id)>> {
            let mut equations = Vec::with_capacity(13 * bodies.len());
            for (b, body) in bodies.iter().enumerate() {
                let g = &mut self.g;
                // Translation: m r'' = m g + F − Φ_rᵀ λ.
                for k in 0..3 {
                    let acceleration = g.derivative(body.position[k], 2)?;
                    let lhs = g.mul(body.mass, acceleration)?;
                    let mut terms = Vec::new();
                    if let Some(gv) = gravity {
                        terms.push(g.mul(body.mass, gv[k])?);
                    }
                    for load in loads.iter().filter(|l| l.body == b) {
                        terms.push(load.world_force[k]);
                    }
                    for load in loads.iter().filter(|l| l.body == b) {
                        if load
                            .body_force
                            .iter()
                            .any(|&x| g.as_number(x).is_none_or(|v| !v.is_zero()))
                        {
                            let q = body.quaternion.map(|s| g.symbol_node(s));
                            let rot = rotation(g, q)?;
                            let world = mat_vec(g, &rot, load.body_force)?;
                            terms.push(world[k]);
                        }
                    }
                    super::push_constraint_forces(g, &rows, body.position[k], &mut terms)?;
                    equations.push((lhs, g.sum(&terms)?));
                }
                // Attitude: q' = ½ q ⊗ (0, ω).
                let q = body.quaternion.map(|s| g.symbol_node(s));
                let w = body.rates.map(|s| g.symbol_node(s));
                let rates = quaternion_rates(g, q, w)?;
                for k in 0..4 {
                    equations.push((g.derivative(body.quaternion[k], 1)?, rates[k]));
                }
                // Rotation: J ω' = τ − ω × J ω − Lᵀ Φ_qᵀ λ.
                let mut dw = [w[0]; 3];
                for k in 0..3 {
                    dw[k] = g.derivative(body.rates[k], 1)?;
                }
                let lhs = mat_vec(g, &body.inertia, dw)?;
                let jw = mat_vec(g, &body.inertia, w)?;
                let gyroscopic = cross3(g, w, jw)?;
                let half = g.rational(1, 2)?;
                // Columns of L = ½ [−q_vᵀ; q0 I + [q_v]×]: L[i][k].
                let l = |g: &mut Graph, i: usize, k: usize| -> crate::Result<Id> {
                    let entry = match i {
                        0 => g.neg(q[1 + k])?,
                        _ if i - 1 == k => q[0],
                        _ => {
                            // [q_v]× row i−1, column k.
                            let (r, c) = (i - 1, k);
                            let m = 3 - r - c;
                            if (r + 1) % 3 == c {
                                g.neg(q[1 + m])?
                            } else {
                                q[1 + m]
                            }
                        }
                    };
                    g.mul(half, entry)
                };
                for k in 0..3 {
                    let mut terms = vec![g.neg(gyroscopic[k])?];
                    for load in loads.iter().filter(|l| l.body == b) {
                        terms.push(load.torque[k]);
                    }
                    for &(row, lambda) in &rows {
                        let mut generalized = Vec::with_capacity(4);
                        for i in 0..4 {
                            let d = g.partial(row, body.quaternion[i])?;
                            if g.as_number(d).is_some_and(|v| v.is_zero()) {
                                continue;
                            }
                            let lik = l(g, i, k)?;
                            generalized.push(g.mul(d, lik)?);
                        }
                        if generalized.is_empty() {
                            continue;
                        }
                        let s = g.sum(&generalized)?;
                        let t = g.mul(s, lambda)?;
                        terms.push(g.neg(t)?);
                    }
                    equations.push((lhs[k], g.sum(&terms)?));
                }
            }
            Ok(equations)
        })();
        self.push_equations_of_motion(r, origin);
    }
}

/// L = ∂q/∂π = ½ [−q_vᵀ; q0 I + [q_v]×] at a numerical quaternion, 4 × 3.
fn rotation_map(q: [f64; 4]) -> [[f64; 3]; 4] {
    let [q0, q1, q2, q3] = q;
    [
        [-0.5 * q1, -0.5 * q2, -0.5 * q3],
        [0.5 * q0, -0.5 * q3, 0.5 * q2],
        [0.5 * q3, 0.5 * q0, -0.5 * q1],
        [-0.5 * q2, 0.5 * q1, 0.5 * q0],
    ]
}
