//! Joint coordinates for a planar scene (course notes §4.2.2):
//! relative joint coordinates along a spanning tree grown from the ground
//! through revolute, prismatic and fixed joints (a welded body adds no
//! coordinate), each body's pose an expression of
//! them, Lagrange's equations `d/dt ∂T/∂q̇ − ∂T/∂q = Q − Φ_qᵀ λ` derived
//! symbolically, and the joints off the tree (cut joints, closing the
//! loops) kept as constraints with their multipliers. Initial body
//! velocities become initial joint rates. The user's body
//! coordinates (`crank.x`, …) become expressions, so outputs and the cut
//! constraints read them unchanged.

use super::Scene;
use crate::front::lower::Lower;
use crate::mechanics::names::rotate;
use crate::mechanics::{retain_unlisted, Frame, JointRecord};
use crate::{FxHashMap, Graph, Id, SymbolId, VectorField};
use proc_macro2::TokenStream;
use quote::ToTokens;

impl Lower<'_, Scene> {
    /// Replaces the global coordinates of a scene by joint coordinates and
    /// writes Lagrange's equations: the spanning tree, the bodies placed
    /// along it, their motion, the tree joints replaced by coordinates,
    /// everything rewritten in them, and one equation per coordinate.
    pub(crate) fn recursive_equations(&mut self, item: &syn::ItemFn) {
        let origin = item.sig.ident.to_token_stream();
        let records = self.scene.records.clone();
        let tree = match spanning_tree(&records, self.scene.bodies.len()) {
            Ok(tree) => tree,
            Err(i) => {
                let name = self.scene.bodies[i].name.clone();
                return self.cx.error_at(&origin, format!("joint coordinates need every body on a tree of revolute, prismatic and fixed joints from the ground, and `{name}` is not: join it, or write `#[dae_model(scene = global)]` for body coordinates"));
            }
        };
        let rates = self.body_rates();
        let Some(placement) = self.place_bodies(&tree, &records, &rates, &origin) else {
            return;
        };
        let Some((field, replace, velocity)) = self.body_motion(&placement, &origin) else {
            return;
        };
        self.body_coordinates(&placement.pose, &velocity, &origin);
        let cut_joints: Vec<usize> =
            (0..records.len()).filter(|r| !tree.iter().any(|t| t.0 == *r)).collect();
        self.planar_joint_coordinates(&cut_joints, &origin);
        let Some(drop_rows) = self.tree_joints_to_coordinates(&tree, &records, &placement, &origin)
        else {
            return;
        };
        let Some((loads, cut)) = self.rewrite_in_joint_coordinates(&replace, &drop_rows, &origin)
        else {
            return;
        };
        let mut field = field;
        self.lagrange_equations(&placement, &velocity, &mut field, &loads, &cut, &origin);
        self.scene.summary.push_str(&format!(
            " Recursive formulation: {} joint coordinates on the spanning tree, {} cut-joint constraint rows.",
            placement.coordinates.len(),
            cut.len()
        ));
    }

    /// Initial body velocities become initial joint rates: a revolute
    /// joint's is the relative angular velocity, a prismatic joint's the
    /// relative speed of its points along its axis (a body without
    /// velocities starts at rest). Linear velocities that disagree with
    /// these are not used. Takes the bodies' `init`s out of the model.
    fn body_rates(&mut self) -> FxHashMap<SymbolId, Id> {
        let mut rates: FxHashMap<SymbolId, Id> = FxHashMap::default();
        let mut kept_inits = Vec::with_capacity(self.inits.len());
        for init in std::mem::take(&mut self.inits) {
            let of = self.scene.bodies.iter().find_map(|b| {
                [b.x, b.y, b.theta].into_iter().find(|&s| {
                    matches!(self.g.symbol(init.target).kind, crate::SymbolKind::Derivative { of, order: 1 } if of == s)
                })
            });
            match of {
                Some(s) => {
                    rates.insert(s, init.value);
                }
                None => kept_inits.push(init),
            }
        }
        self.inits = kept_inits;
        rates
    }

    /// The rate a body coordinate started with (0 if none was given).
    fn body_rate(&mut self, rates: &FxHashMap<SymbolId, Id>, s: SymbolId) -> Id {
        rates.get(&s).copied().unwrap_or_else(|| self.g.zero())
    }

    /// The initial value of a state.
    pub(crate) fn state_initial_value(&self, s: SymbolId) -> Option<Id> {
        self.states.iter().find(|d| d.symbol == s).map(|d| d.init)
    }

    /// Poses [x, y, θ] of the bodies in joint coordinates, joint by joint
    /// along the tree, with each joint's coordinate, initial value and rate.
    fn place_bodies(
        &mut self,
        tree: &[TreeEdge],
        records: &[JointRecord],
        rates: &FxHashMap<SymbolId, Id>,
        origin: &TokenStream,
    ) -> Option<Placement> {
        let n = self.scene.bodies.len();
        let mut placement = Placement {
            pose: vec![None; n],
            start: vec![None; n],
            coordinates: Vec::new(),
            joint_rates: Vec::new(),
        };
        for &edge in tree {
            self.place_child(edge, &records[edge.0], rates, &mut placement, origin)?;
        }
        Some(placement)
    }

    /// Places the child of one tree joint from its parent: welded, turned
    /// by a revolute joint's angle, or slid along a prismatic joint's axis.
    fn place_child(
        &mut self,
        (_, parent, child, child_is_b): TreeEdge,
        rec: &JointRecord,
        rates: &FxHashMap<SymbolId, Id>,
        placement: &mut Placement,
        origin: &TokenStream,
    ) -> Option<()> {
        let zero = self.g.zero();
        let Placement { pose, start, coordinates, joint_rates } = placement;
        let (p_parent, p_child) =
            if child_is_b { (rec.local_a, rec.local_b) } else { (rec.local_b, rec.local_a) };
        let body = self.scene.bodies[child].clone();
        let (parent_pose, parent_start) = match parent {
            Frame::Ground => ([zero; 3], [zero; 3]),
            Frame::Body(p) => match (pose[p], start[p]) {
                (Some(a), Some(b)) => (a, b),
                _ => return None,
            },
        };
        let (Some(cx0), Some(cy0), Some(ct0)) = (
            self.state_initial_value(body.x),
            self.state_initial_value(body.y),
            self.state_initial_value(body.theta),
        ) else {
            return None;
        };
        if rec.kind == "fixed" {
            // Welded: the child moves with the parent and adds no
            // coordinate, no state and no equation.
            let welded = (|| -> crate::Result<[Id; 3]> {
                let g = &mut self.g;
                let relative0 = g.sub(ct0, parent_start[2])?;
                let theta = g.add(parent_pose[2], relative0)?;
                let arm = rotate(g, parent_pose[2], p_parent)?;
                let back = rotate(g, theta, p_child)?;
                let x = g.add(parent_pose[0], arm[0])?;
                let y = g.add(parent_pose[1], arm[1])?;
                Ok([g.sub(x, back[0])?, g.sub(y, back[1])?, theta])
            })();
            match welded {
                Ok(p) => {
                    pose[child] = Some(p);
                    start[child] = Some([cx0, cy0, ct0]);
                }
                Err(err) => {
                    self.cx.error_at(origin, err);
                    return None;
                }
            }
            return Some(());
        }
        let name = format!("{}.q", rec.name);
        let geometry = JointGeometry {
            rec,
            child_is_b,
            p_parent,
            p_child,
            parent_pose,
            parent_start,
            child_start: [cx0, cy0, ct0],
        };
        let built = joint_pose(&mut self.g, &geometry, &name);
        let (q_node, child_pose, child_start, q0) = match built {
            Ok(v) => v,
            Err(err) => {
                self.cx.error_at(origin, err);
                return None;
            }
        };
        let child_velocity = [
            self.body_rate(rates, body.x),
            self.body_rate(rates, body.y),
            self.body_rate(rates, body.theta),
        ];
        let parent_velocity = match parent {
            Frame::Ground => [zero; 3],
            Frame::Body(p) => {
                let b = self.scene.bodies[p].clone();
                [
                    self.body_rate(rates, b.x),
                    self.body_rate(rates, b.y),
                    self.body_rate(rates, b.theta),
                ]
            }
        };
        let rate = joint_rate(&mut self.g, &geometry, child_velocity, parent_velocity);
        match rate {
            Ok(r) => joint_rates.push(r),
            Err(err) => {
                self.cx.error_at(origin, err);
                return None;
            }
        }
        let q = self.g.as_symbol(q_node)?;
        pose[child] = Some(child_pose);
        start[child] = Some(child_start);
        coordinates.push((q, q0, name));
        Some(())
    }

    /// The bodies' velocities in joint coordinates, and the substitution of
    /// every body coordinate and its derivatives by the poses'.
    #[allow(clippy::type_complexity)]
    fn body_motion(
        &mut self,
        placement: &Placement,
        origin: &TokenStream,
    ) -> Option<(VectorField, FxHashMap<SymbolId, Id>, Vec<[Id; 3]>)> {
        let (n, zero) = (self.scene.bodies.len(), self.g.zero());
        let (pose, coordinates) = (&placement.pose, &placement.coordinates);
        // Substitution: body coordinates and their derivatives.
        let mut field = VectorField::new();
        for &(q, _, _) in coordinates {
            let (Ok(d1), Ok(d2)) = (self.g.derivative(q, 1), self.g.derivative(q, 2)) else {
                return None;
            };
            let s1 = self.g.as_symbol(d1)?;
            field.set(q, d1);
            field.set(s1, d2);
        }
        let mut replace: FxHashMap<SymbolId, Id> = FxHashMap::default();
        let mut velocity: Vec<[Id; 3]> = Vec::with_capacity(n);
        for (b, body) in self.scene.bodies.clone().iter().enumerate() {
            let p = pose[b]?;
            let mut v = [zero; 3];
            for (k, s) in [body.x, body.y, body.theta].into_iter().enumerate() {
                let derived = (|| -> crate::Result<(Id, Id, Id, Id)> {
                    let g = &mut self.g;
                    let d1 = g.total_derivative(p[k], &mut field)?;
                    let d2 = g.total_derivative(d1, &mut field)?;
                    Ok((d1, d2, g.derivative(s, 1)?, g.derivative(s, 2)?))
                })();
                let Ok((d1, d2, s1, s2)) = derived else {
                    self.cx.error_at(origin, "the body poses could not be differentiated");
                    return None;
                };
                replace.insert(s, p[k]);
                if let Some(s1) = self.g.as_symbol(s1) {
                    replace.insert(s1, d1);
                }
                if let Some(s2) = self.g.as_symbol(s2) {
                    replace.insert(s2, d2);
                }
                v[k] = d1;
            }
            velocity.push(v);
        }
        Some((field, replace, velocity))
    }

    /// Out: the tree joints' constraints and multipliers and the body
    /// states; in: the joint coordinates with their initial values and
    /// rates. Returns the constraint rows left out.
    fn tree_joints_to_coordinates(
        &mut self,
        tree: &[TreeEdge],
        records: &[JointRecord],
        placement: &Placement,
        origin: &TokenStream,
    ) -> Option<std::collections::HashSet<usize>> {
        let (coordinates, joint_rates) = (&placement.coordinates, &placement.joint_rates);
        let mut drop_equations = std::collections::HashSet::new();
        let mut drop_algebraics = std::collections::HashSet::new();
        let mut drop_rows = std::collections::HashSet::new();
        for &(r, ..) in tree {
            drop_equations.extend(records[r].equations.clone());
            drop_algebraics.extend(records[r].algebraics.clone());
            drop_rows.extend(records[r].rows.clone());
        }
        let body_symbols: Vec<SymbolId> =
            self.scene.bodies.iter().flat_map(|b| [b.x, b.y, b.theta]).collect();
        retain_unlisted(&mut self.equations, &drop_equations);
        retain_unlisted(&mut self.algebraics, &drop_algebraics);
        self.states.retain(|s| !body_symbols.contains(&s.symbol));
        for ((q, q0, name), &rate) in coordinates.iter().zip(joint_rates) {
            let kind = records
                .iter()
                .find(|r| format!("{}.q", r.name) == *name)
                .map_or("revolute", |r| r.kind);
            self.states.push(crate::front::ir::StateDecl {
                name: name.clone(),
                symbol: *q,
                init: *q0,
                origin: origin.clone(),
                fixed: false,
                doc: crate::mechanics::names::planar_joint_doc(kind).to_string(),
                avoid: false,
                prefer: false,
            });
            if self.g.as_number(rate).is_some_and(|v| v.is_zero()) {
                continue;
            }
            self.init_rate(*q, rate, origin)?;
        }
        Some(drop_rows)
    }

    /// Everything that read the body coordinates reads the poses: the
    /// equations, outputs, events, invariants, loads and the cut joints'
    /// rows (returned with their multipliers).
    #[allow(clippy::type_complexity)]
    fn rewrite_in_joint_coordinates(
        &mut self,
        replace: &FxHashMap<SymbolId, Id>,
        drop_rows: &std::collections::HashSet<usize>,
        origin: &TokenStream,
    ) -> Option<(Vec<(usize, Id, Id, Id)>, Vec<(Id, Id)>)> {
        let mut ok = true;
        let mut sub = |g: &mut crate::Graph, id: Id| -> Id {
            match g.substitute(id, replace) {
                Ok(v) => v,
                Err(_) => {
                    ok = false;
                    id
                }
            }
        };
        for eq in &mut self.equations {
            eq.lhs = sub(&mut self.g, eq.lhs);
            eq.rhs = sub(&mut self.g, eq.rhs);
        }
        for o in &mut self.outputs {
            o.value = sub(&mut self.g, o.value);
        }
        for ev in &mut self.events {
            ev.value = sub(&mut self.g, ev.value);
        }
        for inv in &mut self.invariants {
            inv.value = sub(&mut self.g, inv.value);
        }
        let loads: Vec<(usize, Id, Id, Id)> = self
            .scene
            .loads
            .iter()
            .map(|&(b, fx, fy, tau)| {
                (b, sub(&mut self.g, fx), sub(&mut self.g, fy), sub(&mut self.g, tau))
            })
            .collect();
        let cut: Vec<(Id, Id)> = self
            .scene
            .rows
            .iter()
            .enumerate()
            .filter(|(i, _)| !drop_rows.contains(i))
            .map(|(_, &(row, l))| (sub(&mut self.g, row), l))
            .collect();
        if !ok {
            self.cx.error_at(origin, "the scene could not be rewritten in joint coordinates");
            return None;
        }
        Some((loads, cut))
    }

    /// Lagrange's equations, one per joint coordinate:
    /// d/dt ∂T/∂q̇ − ∂T/∂q = Q − Φ_qᵀ λ.
    fn lagrange_equations(
        &mut self,
        placement: &Placement,
        velocity: &[[Id; 3]],
        field: &mut VectorField,
        loads: &[(usize, Id, Id, Id)],
        cut: &[(Id, Id)],
        origin: &TokenStream,
    ) {
        let (pose, coordinates) = (&placement.pose, &placement.coordinates);
        let zero = self.g.zero();
        let bodies = self.scene.bodies.clone();
        let gravity = self.scene.gravity;
        for &(q, _, _) in coordinates {
            let equation = (|| -> crate::Result<Vec<(Id, Id)>> {
                let g = &mut self.g;
                let mut kinetic = Vec::new();
                for (b, body) in bodies.iter().enumerate() {
                    let v = velocity[b];
                    let (vx2, vy2, w2) =
                        (g.mul(v[0], v[0])?, g.mul(v[1], v[1])?, g.mul(v[2], v[2])?);
                    let s = g.add(vx2, vy2)?;
                    let translation = g.mul(body.mass, s)?;
                    let rotation = g.mul(body.inertia, w2)?;
                    kinetic.push(translation);
                    kinetic.push(rotation);
                }
                let twice_t = g.sum(&kinetic)?;
                let half = g.rational(1, 2)?;
                let t = g.mul(half, twice_t)?;
                let rate = g.derivative(q, 1)?;
                let rate = g
                    .as_symbol(rate)
                    .ok_or_else(|| crate::Error::Unsupported { message: "a joint rate".into() })?;
                let momentum = g.partial(t, rate)?;
                let d_momentum = g.total_derivative(momentum, field)?;
                let dt_dq = g.partial(t, q)?;
                let lhs = g.sub(d_momentum, dt_dq)?;
                // Generalised forces: Σ F·∂c/∂q + τ ∂θ/∂q, gravity included.
                let mut forces = Vec::new();
                for (b, body) in bodies.iter().enumerate() {
                    let p = pose[b].unwrap_or([zero; 3]);
                    let (dx, dy, dth) =
                        (g.partial(p[0], q)?, g.partial(p[1], q)?, g.partial(p[2], q)?);
                    if let Some((gx, gy)) = gravity {
                        let (wx, wy) = (g.mul(body.mass, gx)?, g.mul(body.mass, gy)?);
                        forces.push(g.mul(wx, dx)?);
                        forces.push(g.mul(wy, dy)?);
                    }
                    for &(on, fx, fy, tau) in loads {
                        if on == b {
                            forces.push(g.mul(fx, dx)?);
                            forces.push(g.mul(fy, dy)?);
                            forces.push(g.mul(tau, dth)?);
                        }
                    }
                }
                super::push_constraint_forces(g, cut, q, &mut forces)?;
                Ok(vec![(lhs, g.sum(&forces)?)])
            })();
            // One error is enough: the next coordinates would fail alike.
            let failed = equation.is_err();
            self.push_equations_of_motion(equation, origin);
            if failed {
                return;
            }
        }
    }
}

/// A joint of the spanning tree: its record, the parent frame, the child
/// body, and whether the child is the joint's second frame.
type TreeEdge = (usize, Frame, usize, bool);

/// The bodies placed along the tree.
struct Placement {
    /// Each body's [x, y, θ] in joint coordinates.
    pose: Vec<Option<[Id; 3]>>,
    /// Each body's initial [x, y, θ].
    start: Vec<Option<[Id; 3]>>,
    /// Each joint coordinate, its initial value and its name.
    coordinates: Vec<(SymbolId, Id, String)>,
    /// Each joint coordinate's initial rate.
    joint_rates: Vec<Id>,
}

/// The spanning tree grown from the ground, in the order the joints place
/// the bodies (`Err`: a body it does not reach).
fn spanning_tree(records: &[JointRecord], n: usize) -> Result<Vec<TreeEdge>, usize> {
    let mut placed = vec![false; n];
    let mut tree: Vec<(usize, Frame, usize, bool)> = Vec::new();
    loop {
        let mut changed = false;
        for (r, rec) in records.iter().enumerate() {
            if rec.kind == "distance" || tree.iter().any(|t| t.0 == r) {
                continue;
            }
            let is_placed = |f: Frame| match f {
                Frame::Ground => true,
                Frame::Body(i) => placed[i],
            };
            match (is_placed(rec.a), is_placed(rec.b), rec.b, rec.a) {
                (true, false, Frame::Body(child), _) => {
                    tree.push((r, rec.a, child, true));
                    placed[child] = true;
                    changed = true;
                }
                (false, true, _, Frame::Body(child)) if rec.kind == "revolute" => {
                    tree.push((r, rec.b, child, false));
                    placed[child] = true;
                    changed = true;
                }
                _ => {}
            }
        }
        if !changed {
            break;
        }
    }
    match placed.iter().position(|p| !p) {
        Some(i) => Err(i),
        None => Ok(tree),
    }
}

/// One tree joint as its child sees it: the joint's points in the parent
/// and the child, and where both started.
struct JointGeometry<'a> {
    rec: &'a JointRecord,
    child_is_b: bool,
    p_parent: [Id; 2],
    p_child: [Id; 2],
    parent_pose: [Id; 3],
    parent_start: [Id; 3],
    child_start: [Id; 3],
}

/// The joint's coordinate `name`, the child's pose in it, the child's
/// initial pose, and the coordinate's initial value.
fn joint_pose(
    g: &mut Graph,
    j: &JointGeometry,
    name: &str,
) -> crate::Result<(Id, [Id; 3], [Id; 3], Id)> {
    let (rec, child_is_b, p_parent, p_child) = (j.rec, j.child_is_b, j.p_parent, j.p_child);
    let (parent_pose, parent_start) = (j.parent_pose, j.parent_start);
    let [cx0, cy0, ct0] = j.child_start;
    let zero = g.zero();
    let q_node = g.state(name)?;
    let relative0 = g.sub(ct0, parent_start[2])?;
    if rec.kind == "revolute" {
        // θ_child = θ_parent + q; the child hangs from the joint.
        // q is always θ_b − θ_a, as in body coordinates:
        // for a joint the tree reaches from b, the child is a.
        let theta = if child_is_b {
            g.add(parent_pose[2], q_node)?
        } else {
            g.sub(parent_pose[2], q_node)?
        };
        let relative0 = if child_is_b { relative0 } else { g.neg(relative0)? };
        let arm = rotate(g, parent_pose[2], p_parent)?;
        let jx = g.add(parent_pose[0], arm[0])?;
        let jy = g.add(parent_pose[1], arm[1])?;
        let back = rotate(g, theta, p_child)?;
        let x = g.sub(jx, back[0])?;
        let y = g.sub(jy, back[1])?;
        Ok((q_node, [x, y, theta], [cx0, cy0, ct0], relative0))
    } else {
        // The child slides along the parent's axis at a constant
        // relative angle; q is the slide from the parent's point.
        let axis = rec.axis.unwrap_or([zero, zero]);
        let a2 = {
            let (xx, yy) = (g.mul(axis[0], axis[0])?, g.mul(axis[1], axis[1])?);
            let s = g.add(xx, yy)?;
            g.sqrt(s)?
        };
        let unit = [g.div(axis[0], a2)?, g.div(axis[1], a2)?];
        let theta = g.add(parent_pose[2], relative0)?;
        let arm = rotate(g, parent_pose[2], p_parent)?;
        let dir = rotate(g, parent_pose[2], unit)?;
        let jx = g.add(parent_pose[0], arm[0])?;
        let jy = g.add(parent_pose[1], arm[1])?;
        let (sx, sy) = (g.mul(q_node, dir[0])?, g.mul(q_node, dir[1])?);
        let px = g.add(jx, sx)?;
        let py = g.add(jy, sy)?;
        let back = rotate(g, theta, p_child)?;
        let x = g.sub(px, back[0])?;
        let y = g.sub(py, back[1])?;
        // s0: the child's point from the parent's, along the axis, at the start.
        let arm0 = rotate(g, parent_start[2], p_parent)?;
        let j0x = g.add(parent_start[0], arm0[0])?;
        let j0y = g.add(parent_start[1], arm0[1])?;
        let tip0 = rotate(g, ct0, p_child)?;
        let b0x = g.add(cx0, tip0[0])?;
        let b0y = g.add(cy0, tip0[1])?;
        let d0x = g.sub(b0x, j0x)?;
        let d0y = g.sub(b0y, j0y)?;
        let dir0 = rotate(g, parent_start[2], unit)?;
        let s1 = g.mul(d0x, dir0[0])?;
        let s2 = g.mul(d0y, dir0[1])?;
        let s0 = g.add(s1, s2)?;
        Ok((q_node, [x, y, theta], [cx0, cy0, ct0], s0))
    }
}

/// The joint coordinate's initial rate from the bodies' initial velocities.
fn joint_rate(
    g: &mut Graph,
    j: &JointGeometry,
    child_velocity: [Id; 3],
    parent_velocity: [Id; 3],
) -> crate::Result<Id> {
    let (rec, child_is_b, p_parent, p_child) = (j.rec, j.child_is_b, j.p_parent, j.p_child);
    let (parent_start, child_start) = (j.parent_start, j.child_start);
    let zero = g.zero();
    if rec.kind == "revolute" {
        let (b, a) = if child_is_b {
            (child_velocity[2], parent_velocity[2])
        } else {
            (parent_velocity[2], child_velocity[2])
        };
        return g.sub(b, a);
    }
    // v + ω k × (R(θ) p) of each joint point, along the axis.
    let point_velocity =
        |g: &mut crate::Graph, v: [Id; 3], angle: Id, p: [Id; 2]| -> crate::Result<[Id; 2]> {
            let [rx, ry] = rotate(g, angle, p)?;
            let wy = g.mul(v[2], ry)?;
            let wx = g.mul(v[2], rx)?;
            Ok([g.sub(v[0], wy)?, g.add(v[1], wx)?])
        };
    let vb = point_velocity(g, child_velocity, child_start[2], p_child)?;
    let vj = point_velocity(g, parent_velocity, parent_start[2], p_parent)?;
    let axis = rec.axis.unwrap_or([zero, zero]);
    let dir = rotate(g, parent_start[2], axis)?;
    let (xx, yy) = (g.mul(axis[0], axis[0])?, g.mul(axis[1], axis[1])?);
    let len2 = g.add(xx, yy)?;
    let len = g.sqrt(len2)?;
    let dx = g.sub(vb[0], vj[0])?;
    let dy = g.sub(vb[1], vj[1])?;
    let p1 = g.mul(dx, dir[0])?;
    let p2 = g.mul(dy, dir[1])?;
    let along = g.add(p1, p2)?;
    g.div(along, len)
}
