//! Planar multibody scenes in body coordinates (course notes
//! §4.2.2): each body is free, `(x, y, θ)` of its centre of mass, and each
//! joint is a set of constraints on those coordinates with its reaction as
//! algebraic variables. At the end of the model the macro writes each
//! body's Newton–Euler equations `M q'' = f − Φ_qᵀ λ`, with Φ_q the
//! symbolic partial derivatives of the joints' constraints; the DAE
//! pipeline does the rest (index 3, the KKT system, projection).
//!
//! ```text
//! let ground = ground();
//! let crank = body(m, j, [x0, y0, theta0]);      // optional 4th: [vx, vy, omega]
//! let pin = revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
//! distance(crank, a, slider, b, l);               // a massless rod
//! prismatic(ground, p, slider, q, vec3(1.0, 0.0, 0.0));
//! gravity(vec3(0.0, -g, 0.0));
//! force(body, point, f);  torque(body, tau);
//! spring(a, pa, b, pb, k, rest_length, damping);  // along the line of the points
//! let p = position(crank, point);                 // world position of a body point
//! ```

use super::names::{point, rotate};
use super::Scene;
use super::{Body, Frame, JointRecord, FORCE_USAGE};
use crate::front::lower::Binding;
use crate::front::lower::Lower;
use crate::{Id, SymbolId};
use quote::ToTokens;
use syn::Expr;

impl Lower<'_, Scene> {
    /// `let b = body(m, j, [x, y, θ])` or `let g = ground()`.
    pub(crate) fn scene_declaration(
        &mut self,
        ident: &syn::Ident,
        kind: &str,
        call: &syn::ExprCall,
        local: &syn::Local,
    ) {
        if kind == "ground" {
            if !self.arity(call, "ground", 0) {
                return;
            }
            self.scene.ground = true;
            return self.bind(ident, Binding::Ground);
        }
        if self.scene.is_spatial() {
            self.bind(ident, Binding::BrokenBody);
            return self.cx.error_at(local, "a scene is planar (`body`) or spatial (`spatial_body`), not both: declare every body with `body(m, j, [x, y, theta])`");
        }
        if !(3..=4).contains(&call.args.len()) {
            return self.cx.error_at(call, "`body` takes a mass, an inertia about the centre of mass, the initial `[x, y, theta]` and optionally the initial `[vx, vy, omega]`");
        }
        let (Some(mass), Some(inertia)) = (self.value(&call.args[0]), self.value(&call.args[1]))
        else {
            return;
        };
        let triple = |this: &mut Self, e: &Expr| -> Option<Vec<Id>> {
            match e {
                Expr::Array(a) if a.elems.len() == 3 => {
                    a.elems.iter().map(|v| this.initial_value(v)).collect()
                }
                other => {
                    this.cx.error_at(other, "write three values: `[x, y, theta]`");
                    None
                }
            }
        };
        let Some(position) = triple(self, &call.args[2]) else {
            return;
        };
        let velocity = match call.args.get(3) {
            Some(v) => match triple(self, v) {
                Some(v) => Some(v),
                None => return,
            },
            None => None,
        };
        let name = ident.to_string();
        let origin = local.to_token_stream();
        let mut symbols = Vec::with_capacity(3);
        for (k, coordinate) in ["x", "y", "theta"].iter().enumerate() {
            let state = format!("{name}.{coordinate}");
            let doc = crate::mechanics::names::body_coordinate_doc(coordinate);
            let Some(symbol) = self.declare_state(state, position[k], ident, &origin, doc) else {
                return;
            };
            if let Some(v) = &velocity {
                if self.init_rate(symbol, v[k], &origin).is_none() {
                    return;
                }
            }
            symbols.push(symbol);
        }
        if self.scene.first_body.is_none() {
            self.scene.first_body = Some(origin);
        }
        self.scene.bodies.push(Body {
            name: name.clone(),
            x: symbols[0],
            y: symbols[1],
            theta: symbols[2],
            mass,
            inertia,
        });
        self.bind(ident, Binding::Body(self.scene.bodies.len() - 1));
    }

    pub(crate) fn frame(&mut self, e: &Expr) -> Option<Frame> {
        let name = match e {
            Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
            _ => None,
        };
        let Some(name) = name else {
            self.cx.error_at(e, "name a body or the ground here");
            return None;
        };
        match self.lookup(&name).cloned() {
            Some(Binding::Body(b)) => Some(Frame::Body(b)),
            Some(Binding::Ground) => Some(Frame::Ground),
            Some(Binding::BrokenBody | Binding::Broken) => None,
            Some(other) => {
                let what = other.describe();
                let declaration = if self.scene.is_spatial() {
                    "spatial_body(m, inertia, [x, y, z], [q0, q1, q2, q3])"
                } else {
                    "body(m, j, [x, y, theta])"
                };
                self.cx.error_at(e, format!("`{name}` is {what}, not a body: declare it with `let {name} = {declaration};`"));
                None
            }
            None => {
                self.unknown_name(e, &name);
                None
            }
        }
    }

    /// A body-fixed point given in body coordinates, as (x, y) in the world.
    fn world_point(&mut self, frame: Frame, p: &Expr, at: &Expr) -> Option<[Id; 2]> {
        let t = self.tensor(p)?;
        if (t.rows, t.cols) != (3, 1) {
            self.cx.error_at(
                p,
                format!(
                    "a point is a 3-vector in body coordinates (z ignored in the plane), not a {}",
                    t.shape()
                ),
            );
            return None;
        }
        let (px, py) = (t.data[0], t.data[1]);
        match frame {
            Frame::Ground => Some([px, py]),
            Frame::Body(b) => {
                let body = &self.scene.bodies[b];
                let pose = [body.x, body.y, body.theta].map(|s| self.g.symbol_node(s));
                let r = point(&mut self.g, pose, [px, py]);
                self.graph_result_pair(r, at)
            }
        }
    }

    /// `crank.theta`, `top.q0`: a coordinate of a body, as a value.
    pub(crate) fn body_coordinate(&mut self, f: &syn::ExprField, e: &Expr) -> Option<Id> {
        let base = match &*f.base {
            Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
            _ => None,
        };
        let body = match base.as_deref().map(|n| self.lookup(n).cloned()) {
            Some(Some(Binding::Body(b))) => b,
            _ => {
                self.cx.error_at(e, "fields are not part of the model language, except the coordinates of a body (`crank.theta`)");
                return None;
            }
        };
        let member = match &f.member {
            syn::Member::Named(i) => i.to_string(),
            syn::Member::Unnamed(i) => i.index.to_string(),
        };
        let (names, symbols): (&[&str], Vec<SymbolId>) = if self.scene.spatial.is_empty() {
            let b = &self.scene.bodies[body];
            (&["x", "y", "theta"], vec![b.x, b.y, b.theta])
        } else {
            let b = &self.scene.spatial[body];
            let mut s = b.position.to_vec();
            s.extend(b.quaternion);
            s.extend(b.rates);
            (&["x", "y", "z", "q0", "q1", "q2", "q3", "wx", "wy", "wz"], s)
        };
        match names.iter().position(|n| *n == member) {
            Some(k) => Some(self.g.symbol_node(symbols[k])),
            None => {
                let list = names.join("`, `");
                self.cx.error_at(
                    &f.member,
                    format!("a body's coordinates are `{list}`, not `{member}`"),
                );
                None
            }
        }
    }

    fn graph_result_pair(&mut self, r: crate::Result<[Id; 2]>, at: &Expr) -> Option<[Id; 2]> {
        match r {
            Ok(v) => Some(v),
            Err(e) => {
                self.cx.error_at(at, e);
                None
            }
        }
    }

    /// `position(body, p)`: the world position of a body point, a 3-vector.
    pub(crate) fn position(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<[Id; 2]> {
        if c.args.len() != 2 {
            self.cx.error_at(c, "`position` takes a body and a point in its coordinates: `position(crank, vec3(0.5, 0.0, 0.0))`");
            return None;
        }
        let frame = self.frame(&c.args[0])?;
        self.world_point(frame, &c.args[1], e)
    }

    fn angle(&mut self, frame: Frame) -> Id {
        match frame {
            Frame::Ground => self.g.zero(),
            Frame::Body(b) => self.g.symbol_node(self.scene.bodies[b].theta),
        }
    }

    /// A joint statement; `name` names its reactions (`name[0]`, ...).
    pub(crate) fn joint(
        &mut self,
        kind: &str,
        name: Option<&syn::Ident>,
        c: &syn::ExprCall,
        e: &Expr,
    ) {
        if self.scene.is_spatial() {
            return self.spatial_joint(kind, name, c, e);
        }
        if matches!(kind, "spherical" | "universal" | "cylindrical" | "planar") {
            return self.cx.error_at(c, format!("a planar scene has no {kind} joint (its bodies move in one plane, turning about its normal): use `revolute` or `prismatic`, or declare the bodies with `spatial_body`"));
        }
        let extra = match kind {
            "distance" => Some("length"),
            "prismatic" => Some("axis_in_a"),
            _ => None,
        };
        let Some((a, b)) = self.joint_frames(kind, c, extra) else {
            return;
        };
        let (Some(pa), Some(pb)) =
            (self.world_point(a, &c.args[1], e), self.world_point(b, &c.args[3], e))
        else {
            return;
        };
        let initial = |this: &Self, f: Frame| match f {
            Frame::Ground => None,
            Frame::Body(k) => {
                this.states.iter().find(|s| s.symbol == this.scene.bodies[k].theta).map(|s| s.init)
            }
        };
        let rows: crate::Result<Vec<Id>> = match kind {
            "revolute" => (0..2).map(|k| self.g.sub(pa[k], pb[k])).collect(),
            "fixed" => {
                // Welded: the points coincide and the relative angle keeps
                // its initial value.
                let (ta, tb) = (self.angle(a), self.angle(b));
                let (ia, ib) = (initial(self, a), initial(self, b));
                (|| {
                    let g = &mut self.g;
                    let zero = g.zero();
                    let relative = g.sub(tb, ta)?;
                    let start = g.sub(ib.unwrap_or(zero), ia.unwrap_or(zero))?;
                    Ok(vec![g.sub(pa[0], pb[0])?, g.sub(pa[1], pb[1])?, g.sub(relative, start)?])
                })()
            }
            "distance" => {
                let Some(l) = self.value(&c.args[4]) else {
                    return;
                };
                (|| {
                    let g = &mut self.g;
                    let dx = g.sub(pb[0], pa[0])?;
                    let dy = g.sub(pb[1], pa[1])?;
                    let dx2 = g.mul(dx, dx)?;
                    let dy2 = g.mul(dy, dy)?;
                    let l2 = g.mul(l, l)?;
                    let s = g.add(dx2, dy2)?;
                    Ok(vec![g.sub(s, l2)?])
                })()
            }
            _ => {
                // B's point stays on the line through A's point along A's
                // axis, and the relative angle keeps its initial value.
                let Some(axis) = self.tensor(&c.args[4]) else {
                    return;
                };
                if (axis.rows, axis.cols) != (3, 1) {
                    return self
                        .cx
                        .error_at(&c.args[4], "the axis is a 3-vector in A's coordinates");
                }
                let (ta, tb) = (self.angle(a), self.angle(b));
                let (ia, ib) = (initial(self, a), initial(self, b));
                (|| {
                    let g = &mut self.g;
                    // The axis in the world: R(θa) (ax, ay).
                    let [wx, wy] = rotate(g, ta, [axis.data[0], axis.data[1]])?;
                    let dx = g.sub(pb[0], pa[0])?;
                    let dy = g.sub(pb[1], pa[1])?;
                    let cross1 = g.mul(dx, wy)?;
                    let cross2 = g.mul(dy, wx)?;
                    let along = g.sub(cross1, cross2)?;
                    let zero = g.zero();
                    let relative = g.sub(tb, ta)?;
                    let start = g.sub(ib.unwrap_or(zero), ia.unwrap_or(zero))?;
                    Ok(vec![along, g.sub(relative, start)?])
                })()
            }
        };
        let rows = match rows {
            Ok(r) => r,
            Err(err) => return self.cx.error_at(e, err),
        };
        let local = |this: &mut Self, arg: &Expr| -> Option<[Id; 2]> {
            let t = this.tensor(arg)?;
            Some([t.data[0], t.data[1]])
        };
        let (Some(local_a), Some(local_b)) = (local(self, &c.args[1]), local(self, &c.args[3]))
        else {
            return;
        };
        let axis = if kind == "prismatic" { local(self, &c.args[4]) } else { None };
        let Some((equations, algebraics, rows)) = self.add_joint_rows(kind, name, rows, e) else {
            return;
        };
        let kind = match kind {
            "revolute" => "revolute",
            "distance" => "distance",
            "fixed" => "fixed",
            _ => "prismatic",
        };
        let name = self.scene.joint_rows.last().map(|j| j.0.clone()).unwrap_or_default();
        self.scene.records.push(JointRecord {
            kind,
            name,
            a,
            b,
            local_a,
            local_b,
            axis,
            equations,
            algebraics,
            rows,
        });
    }

    /// Checks a joint's arguments `(a, point_in_a, b, point_in_b[, extra])`
    /// and resolves its two frames, which must differ (a joint from a frame
    /// to itself constrains nothing).
    pub(crate) fn joint_frames(
        &mut self,
        kind: &str,
        c: &syn::ExprCall,
        extra: Option<&str>,
    ) -> Option<(Frame, Frame)> {
        let arity = if extra.is_some() { 5 } else { 4 };
        if c.args.len() != arity {
            let tail = extra.map_or(String::new(), |e| format!(", {e}"));
            self.cx.error_at(
                c,
                format!("`{kind}` takes {arity} arguments: `{kind}(a, point_in_a, b, point_in_b{tail})`"),
            );
            return None;
        }
        let (a, b) = (self.frame(&c.args[0]), self.frame(&c.args[2]));
        let (a, b) = (a?, b?);
        if a == b {
            let name = c.args[0].to_token_stream().to_string();
            self.cx.error_at(c, format!("this joint joins `{name}` to itself: name two different bodies (or a body and the ground)"));
            return None;
        }
        Some((a, b))
    }

    /// A joint's constraint rows, each with its reaction `name[k]` as an
    /// algebraic variable; returns the ranges of equations, algebraic
    /// variables and scene rows it added.
    pub(crate) fn add_joint_rows(
        &mut self,
        kind: &str,
        name: Option<&syn::Ident>,
        rows: Vec<Id>,
        e: &Expr,
    ) -> Option<(std::ops::Range<usize>, std::ops::Range<usize>, std::ops::Range<usize>)> {
        let (equations_start, algebraics_start, rows_start) =
            (self.equations.len(), self.algebraics.len(), self.scene.rows.len());
        self.scene.joints += 1;
        let base = match name {
            Some(n) => n.to_string(),
            None => format!("{kind}{}", self.scene.joints),
        };
        let zero = self.g.zero();
        let mut multipliers = Vec::with_capacity(rows.len());
        for (k, &row) in rows.iter().enumerate() {
            let lambda_name = format!("{base}[{k}]");
            let doc = format!(
                "multiplier of row {k} of the joint's constraints Φ (its reaction is −Φ_qᵀλ)"
            );
            let origin = e.to_token_stream();
            let lambda = self.declare_algebraic(lambda_name, zero, e, &origin, doc)?;
            self.equations.push(crate::front::ir::Equation {
                lhs: row,
                rhs: zero,
                origin: e.to_token_stream(),
                is_constraint: true,
                mode: Vec::new(),
            });
            self.scene.rows.push((row, lambda));
            multipliers.push(lambda);
        }
        if let Some(n) = name {
            let t = crate::front::tensor::Tensor::from_vector(multipliers);
            self.bind(n, Binding::Tensor(t));
        }
        self.scene.joint_rows.push((base, rows_start..self.scene.rows.len(), e.to_token_stream()));
        Some((
            equations_start..self.equations.len(),
            algebraics_start..self.algebraics.len(),
            rows_start..self.scene.rows.len(),
        ))
    }

    /// The body a `force` or `torque` (the call's name) acts on: checks the
    /// number of arguments (`usage` says what they are) and that the first
    /// names a body.
    pub(crate) fn loaded_body(
        &mut self,
        c: &syn::ExprCall,
        arity: usize,
        usage: &str,
    ) -> Option<usize> {
        let kind = c.func.to_token_stream().to_string();
        if c.args.len() != arity {
            self.cx.error_at(c, format!("`{kind}` takes {usage}"));
            return None;
        }
        match self.frame(&c.args[0])? {
            Frame::Body(b) => Some(b),
            Frame::Ground => {
                self.cx.error_at(&c.args[0], format!("a {kind} acts on a body, not on the ground"));
                None
            }
        }
    }

    /// `spring(a, pa, b, pb, k, l0, c)`: its two frames and stiffness, rest
    /// length and damping (the points are read by the caller, in the plane
    /// or in space).
    pub(crate) fn spring_arguments(
        &mut self,
        c: &syn::ExprCall,
    ) -> Option<(Frame, Frame, [Id; 3])> {
        if c.args.len() != 7 {
            self.cx.error_at(c, "`spring` takes `spring(a, point_in_a, b, point_in_b, stiffness, rest_length, damping)`");
            return None;
        }
        let (a, b) = (self.frame(&c.args[0]), self.frame(&c.args[2]));
        let values = [4, 5, 6].map(|i| self.value(&c.args[i]));
        let (a, b) = (a?, b?);
        let [k, l0, damping] = values;
        Some((a, b, [k?, l0?, damping?]))
    }

    /// `gravity(g)`, `force(body, point, f)`, `torque(body, tau)`.
    pub(crate) fn load(&mut self, kind: &str, c: &syn::ExprCall, e: &Expr) {
        if self.scene.is_spatial() {
            return self.spatial_load(kind, c, e);
        }
        let zero = self.g.zero();
        match kind {
            "gravity" => {
                if c.args.len() != 1 {
                    return self.cx.error_at(c, "`gravity` takes the acceleration of gravity as a 3-vector: `gravity(vec3(0.0, -g, 0.0))`");
                }
                let Some(t) = self.tensor(&c.args[0]) else {
                    return;
                };
                if (t.rows, t.cols) != (3, 1) {
                    return self.cx.error_at(&c.args[0], "gravity is a 3-vector");
                }
                self.scene.gravity = Some((t.data[0], t.data[1]));
            }
            "force" => {
                let Some(b) = self.loaded_body(c, 3, FORCE_USAGE) else {
                    return;
                };
                let Some(f) = self.tensor(&c.args[2]) else {
                    return;
                };
                if (f.rows, f.cols) != (3, 1) {
                    return self.cx.error_at(&c.args[2], "a force is a 3-vector in world axes");
                }
                let Some(p) = self.world_point(Frame::Body(b), &c.args[1], e) else {
                    return;
                };
                // Its moment about the centre of mass: (P − c) × f.
                self.apply(b, p, f.data[0], f.data[1], e);
            }
            "spring" => self.spring(c, e),
            _ => {
                let Some(b) =
                    self.loaded_body(c, 2, "a body and the torque about its centre of mass")
                else {
                    return;
                };
                let Some(tau) = self.value(&c.args[1]) else {
                    return;
                };
                self.scene.loads.push((b, zero, zero, tau));
            }
        }
    }

    /// The kind of the named planar joint `name` a flange drives.
    pub(crate) fn joint_axis(&self, name: &str) -> Option<&'static str> {
        if self.scene.is_spatial() {
            return self.spatial_joint_axis(name);
        }
        let record = self.scene.records.iter().find(|r| r.name == name)?;
        matches!(record.kind, "revolute" | "prismatic").then_some(record.kind)
    }

    /// `joint.flange`: the joint's relative angle `θ_b − θ_a` (a revolute)
    /// or the displacement of b's joint point from a's along the axis (a
    /// prismatic), and `flow` acting across it: a torque on b and −torque
    /// on a, or a force along the axis at b's joint point and its reaction.
    pub(crate) fn joint_flange(&mut self, name: &str, flow: Id, at: &Expr) -> Option<Id> {
        if self.scene.is_spatial() {
            return self.spatial_joint_flange(name, flow, at);
        }
        let record = self.scene.records.iter().find(|r| r.name == name)?.clone();
        let angle = |this: &mut Self, f: Frame| match f {
            Frame::Ground => this.g.zero(),
            Frame::Body(b) => this.g.symbol_node(this.scene.bodies[b].theta),
        };
        let zero = self.g.zero();
        if record.kind == "revolute" {
            let (ta, tb) = (angle(self, record.a), angle(self, record.b));
            let relative = self.g.sub(tb, ta);
            let relative = self.graph_result(relative, at)?;
            if let Frame::Body(b) = record.b {
                self.scene.loads.push((b, zero, zero, flow));
            }
            if let Frame::Body(a) = record.a {
                let reaction = self.g.neg(flow);
                let reaction = self.graph_result(reaction, at)?;
                self.scene.loads.push((a, zero, zero, reaction));
            }
            return Some(relative);
        }
        // Prismatic: the axis in a's frame, turned into the world.
        let axis = record.axis?;
        let world = |this: &mut Self, f: Frame, p: [Id; 2]| -> Option<[Id; 2]> {
            match f {
                Frame::Ground => Some(p),
                Frame::Body(b) => {
                    let body = &this.scene.bodies[b];
                    let pose = [body.x, body.y, body.theta].map(|s| this.g.symbol_node(s));
                    let r = point(&mut this.g, pose, p);
                    this.graph_result_pair(r, at)
                }
            }
        };
        let (pa, pb) =
            (world(self, record.a, record.local_a)?, world(self, record.b, record.local_b)?);
        let ta = angle(self, record.a);
        let u = rotate(&mut self.g, ta, axis);
        let u = self.graph_result_pair(u, at)?;
        let s = (|| {
            let g = &mut self.g;
            let dx = g.sub(pb[0], pa[0])?;
            let dy = g.sub(pb[1], pa[1])?;
            let along_x = g.mul(dx, u[0])?;
            let along_y = g.mul(dy, u[1])?;
            let along = g.add(along_x, along_y)?;
            let norm = {
                let xx = g.mul(u[0], u[0])?;
                let yy = g.mul(u[1], u[1])?;
                let n2 = g.add(xx, yy)?;
                g.sqrt(n2)?
            };
            let fx = g.mul(flow, u[0])?;
            let fy = g.mul(flow, u[1])?;
            let (fx, fy) = (g.div(fx, norm)?, g.div(fy, norm)?);
            Ok((g.div(along, norm)?, fx, fy))
        })();
        let (s, fx, fy) = self.graph_result_triple(s, at)?;
        if let Frame::Body(b) = record.b {
            self.apply(b, pb, fx, fy, at);
        }
        if let Frame::Body(a) = record.a {
            let (rx, ry) = (self.g.neg(fx), self.g.neg(fy));
            let (rx, ry) = (self.graph_result(rx, at)?, self.graph_result(ry, at)?);
            self.apply(a, pb, rx, ry, at);
        }
        Some(s)
    }

    fn graph_result_triple(
        &mut self,
        r: crate::Result<(Id, Id, Id)>,
        at: &Expr,
    ) -> Option<(Id, Id, Id)> {
        match r {
            Ok(v) => Some(v),
            Err(e) => {
                self.cx.error_at(at, e);
                None
            }
        }
    }

    /// A world force `(fx, fy)` at the world point `p` of body `b`: the force
    /// and its moment `(p − c) × f` about the centre of mass.
    fn apply(&mut self, b: usize, p: [Id; 2], fx: Id, fy: Id, e: &Expr) {
        let body = self.scene.bodies[b].clone();
        let moment = (|| {
            let g = &mut self.g;
            let (x, y) = (g.symbol_node(body.x), g.symbol_node(body.y));
            let rx = g.sub(p[0], x)?;
            let ry = g.sub(p[1], y)?;
            let m1 = g.mul(rx, fy)?;
            let m2 = g.mul(ry, fx)?;
            g.sub(m1, m2)
        })();
        if let Some(moment) = self.graph_result(moment, e) {
            self.scene.loads.push((b, fx, fy, moment));
        }
    }

    /// `spring(a, pa, b, pb, k, l0, c)`: a spring–damper between two points,
    /// tension `k (d − l0) + c ḋ` along the line from one to the other.
    fn spring(&mut self, c: &syn::ExprCall, e: &Expr) {
        let Some((a, b, [k, l0, damping])) = self.spring_arguments(c) else {
            return;
        };
        let (Some(pa), Some(pb)) =
            (self.world_point(a, &c.args[1], e), self.world_point(b, &c.args[3], e))
        else {
            return;
        };
        // ḋ along the motion: each coordinate's derivative is its der().
        let mut field = crate::VectorField::new();
        for body in self.scene.bodies.clone() {
            for s in [body.x, body.y, body.theta] {
                if let Ok(d) = self.g.derivative(s, 1) {
                    field.set(s, d);
                }
            }
        }
        let forces = (|| -> crate::Result<[Id; 4]> {
            let g = &mut self.g;
            let dx = g.sub(pb[0], pa[0])?;
            let dy = g.sub(pb[1], pa[1])?;
            let dx2 = g.mul(dx, dx)?;
            let dy2 = g.mul(dy, dy)?;
            let d2 = g.add(dx2, dy2)?;
            let (d, tension) = super::spring_tension(g, d2, [k, damping, l0], &mut field)?;
            // On A towards B, on B towards A.
            let ux = g.div(dx, d)?;
            let uy = g.div(dy, d)?;
            let fx = g.mul(tension, ux)?;
            let fy = g.mul(tension, uy)?;
            Ok([fx, fy, g.neg(fx)?, g.neg(fy)?])
        })();
        let forces = match forces {
            Ok(f) => f,
            Err(err) => return self.cx.error_at(e, err),
        };
        for (frame, p, fx, fy) in [(a, pa, forces[0], forces[1]), (b, pb, forces[2], forces[3])] {
            if let Frame::Body(i) = frame {
                self.apply(i, p, fx, fy, e);
            }
        }
    }

    /// The Newton–Euler equations of every body, `M q'' = f − Φ_qᵀ λ`.
    pub(crate) fn scene_equations(&mut self, item: &syn::ItemFn) {
        if self.scene.bodies.is_empty() && self.scene.spatial.is_empty() {
            return;
        }
        let at = self.scene.first_body.clone().unwrap_or_else(|| item.sig.ident.to_token_stream());
        if !self.scene.ground {
            return self.cx.error_at(at, "a scene needs a ground, the world frame its joints and loads refer to: add `let ground = ground();` and attach a body to it with a joint (a scene whose bodies float declares it too)");
        }
        let spatial = !self.scene.spatial.is_empty();
        let n = self.scene.bodies.len() + self.scene.spatial.len();
        let m = self.scene.rows.len();
        let coordinates = if spatial { 6 * n } else { 3 * n };
        // DOF = n − rank Φ_q at the start (eq. 4.23); Grübler's count when
        // Φ_q cannot be evaluated there.
        let mobility = self.mobility();
        let (rank, how) = match &mobility {
            Some(mob) => (mob.rank, "rank Φ_q at the initial configuration"),
            None => (m, "Grübler's count"),
        };
        let dof = coordinates as i64 - rank as i64;
        if dof <= 0 {
            return self.cx.error_at(at, format!("this scene cannot move: {n} bodies have {coordinates} coordinates and the joints constrain {rank} of them ({how}, {m} rows), {dof} degrees of freedom; it is a structure, not a mechanism: remove a joint"));
        }
        if let Some(&row) = mobility.as_ref().and_then(|mob| mob.redundant.first()) {
            if let Some((name, _, origin)) = self.joint_of_row(row) {
                let rows: Vec<String> = mobility
                    .iter()
                    .flat_map(|mob| &mob.redundant)
                    .filter_map(|&r| self.joint_of_row(r))
                    .filter(|(n, _, _)| *n == name)
                    .map(|(_, k, _)| k.to_string())
                    .collect();
                let which = match rows.as_slice() {
                    [one] => format!("its row {one} follows"),
                    [init @ .., last] => format!("its rows {} and {last} follow", init.join(", ")),
                    [] => String::new(),
                };
                let remedy = if spatial {
                    "remove it, or use a joint that constrains less (`spherical` for `revolute`, `distance` for `spherical`)"
                } else {
                    "remove it, or use a joint that constrains less (`distance` for `revolute`)"
                };
                return self.cx.error_at(origin, format!("joint `{name}` is redundant at the initial configuration: {which} from the joints declared before it (rank Φ_q = {rank} for {m} rows), so the reactions are undetermined; {remedy}"));
            }
        }
        let loops = self.scene.joints as i64 - n as i64;
        self.scene.summary = format!(
            "{} scene ({} formulation): {n} bodies, {} joints with {m} constraint rows, {} independent loop(s) (joints − bodies), {dof} degrees of freedom ({coordinates} coordinates − {how} {rank}).",
            if spatial { "Spatial" } else { "Planar" },
            if self.scene.recursive { "recursive" } else { "global" },
            self.scene.joints,
            loops.max(0)
        );
        if spatial && self.scene.recursive {
            return self.spatial_recursive_equations(item);
        }
        if spatial {
            let origin = item.sig.ident.to_token_stream();
            return self.spatial_equations(&origin);
        }
        if self.scene.recursive {
            return self.recursive_equations(item);
        }
        let bodies = self.scene.bodies.clone();
        let rows = self.scene.rows.clone();
        let loads = self.scene.loads.clone();
        let gravity = self.scene.gravity;
        let origin = item.sig.ident.to_token_stream();
        for (b, body) in bodies.iter().enumerate() {
            for (k, coordinate) in [body.x, body.y, body.theta].into_iter().enumerate() {
                let equation = (|| -> crate::Result<Vec<(Id, Id)>> {
                    let g = &mut self.g;
                    let inertia = if k < 2 { body.mass } else { body.inertia };
                    let acceleration = g.derivative(coordinate, 2)?;
                    let lhs = g.mul(inertia, acceleration)?;
                    let mut terms = Vec::new();
                    if let (Some((gx, gy)), true) = (gravity, k < 2) {
                        terms.push(g.mul(body.mass, if k == 0 { gx } else { gy })?);
                    }
                    for &(on, fx, fy, tau) in &loads {
                        if on == b {
                            terms.push([fx, fy, tau][k]);
                        }
                    }
                    super::push_constraint_forces(g, &rows, coordinate, &mut terms)?;
                    Ok(vec![(lhs, g.sum(&terms)?)])
                })();
                self.push_equations_of_motion(equation, &origin);
            }
        }
        let every: Vec<usize> = (0..self.scene.records.len()).collect();
        self.planar_joint_coordinates(&every, &origin);
    }
}
