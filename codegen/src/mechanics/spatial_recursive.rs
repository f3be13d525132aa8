//! Joint coordinates for a spatial scene: joint coordinates along a
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
//! prismatic joint's slide `j.q` as in body coordinates; a
//! cylindrical joint's `j.q` and `j.angle`; a universal joint's turns
//! `j.q1` (about the axis in a) and `j.q2` (about the axis in b); a planar
//! joint's slides `j.u`, `j.v` and turn `j.angle`; a spherical joint's
//! relative quaternion `j.q0`…`j.q3` with the relative angular velocity in
//! the child's axes `j.wx`, `j.wy`, `j.wz`. A body that no tree joint
//! reaches hangs from the ground by a free joint: it keeps its own
//! coordinates (centre of mass, quaternion, body rates). The bodies'
//! coordinates become outputs of the joint coordinates, so a solution
//! answers to the same names in both formulations.
//!
//! This module grows the tree, places the bodies, rewrites the model in
//! joint coordinates and checks the start; `spatial_joint_motion` says what
//! each joint allows, `joint_space_dynamics` writes the equations, over the
//! arithmetic of `spatial_vectors` and `algebra`.

use super::algebra::{
    add3, conjugate, cross3, mat_mul, mat_t_vec, mat_vec, quaternion_product, quaternion_rates,
    rotation, sub3, transpose, Vec3,
};
use super::body_frame_dynamics::{body_frames, Relative};
use super::joint_space_dynamics::Dynamics;
use super::spatial_joint_motion::{Axis, Column, Motion, NewState, Start};
use super::spatial_tree::{Edge, Placed};
use super::spatial_vectors::Spatial;
use super::unsupported;
use super::Scene;
use super::{retain_unlisted, Frame, SpatialJointRecord};
use crate::front::lower::Lower;
use crate::{FxHashMap, Graph, Id, SymbolId, VectorField};
use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::Expr;

/// Joints that can carry the tree; `distance` is always cut.
const TREE_JOINTS: [&str; 7] =
    ["revolute", "prismatic", "spherical", "fixed", "universal", "cylindrical", "planar"];

/// A child body positioned more than this far from where its tree joint
/// places it (relative to the scene's size, 1 m at least) is a mistake.
const PLACEMENT_TOLERANCE: f64 = 1e-9;

impl Lower<'_, Scene> {
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
        let mut relative: Vec<Option<Relative>> = vec![None; n];
        let mut states: Vec<NewState> = Vec::new();
        let mut attitudes = Vec::new();
        for edge in &tree {
            let Some(r) = edge.joint else {
                let (body, axes) = self.free_joint(edge.child)?;
                placed[edge.child] = Some(body);
                columns[edge.child] = axes;
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
            let parent = frame_pose(edge.parent, &mut self.g)?;
            let child = place_child(&mut self.g, edge, rec, &motion, &parent)?;
            placed[edge.child] = Some(child);
            relative[edge.child] = Some(Relative {
                kind: rec.kind,
                rot: motion.rot,
                start_rot: motion.start_rot,
                offset: motion.offset,
            });
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
        self.declare_joint_states(&states, origin)?;
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
        // In body frames where every joint allows it.
        let frames = body_frames(
            &mut self.g,
            &tree,
            &records,
            &relative,
            &placed,
            &columns,
            !cut.is_empty(),
        )?;
        let body_rates: Option<Vec<Vec3>> =
            frames.as_ref().map(|f| f.velocity.iter().map(|v| v.top).collect());
        // Everything written in body coordinates is rewritten in joint ones.
        let mut replace =
            self.body_substitution(&placed, &velocity, body_rates.as_deref(), &free, &mut field)?;
        self.prismatic_flange_substitution(&states, &mut replace, &mut field)?;
        let cut_rows = self.rewrite_spatial(&replace, &records, &cut)?;
        self.spatial_body_outputs(&placed, &velocity, &free, origin)?;
        // Equations of motion.
        let equations = match &frames {
            Some(frames) => frames.equations_of_motion(
                &mut self.g,
                &tree,
                &self.scene.spatial.clone(),
                &placed,
                &self.scene.spatial_loads.clone(),
                self.scene.gravity_vector,
            )?,
            None => self.crba_rnea(&tree, &placed, &subspace, &cut_rows, &mut field)?,
        };
        self.push_equations_of_motion(Ok(equations), origin);
        self.quaternion_kinematics(&attitudes, &free, origin)?;
        self.apply_joint_inits(&states);
        let coordinates = subspace.iter().map(Vec::len).sum::<usize>();
        self.scene.summary.push_str(&format!(
            " Recursive formulation: {coordinates} joint speeds on the spanning tree ({} free bodies), mass matrix by the composite-rigid-body algorithm, bias forces by recursive Newton–Euler, {}, {} cut-joint constraint rows.",
            free.iter().filter(|f| **f).count(),
            match frames.is_some() {
                true => "in body frames, accelerations through the tree's factorisation",
                false => "in world axes",
            },
            cut_rows.len()
        ));
        Ok(())
    }

    /// A prismatic joint's flange displacement (see `spatial_joint_flange`):
    /// the joint's coordinate `name.q` on the tree, the displacement
    /// rewritten in joint coordinates for a joint that closes a loop; with
    /// its rates.
    fn prismatic_flange_substitution(
        &mut self,
        states: &[NewState],
        replace: &mut FxHashMap<SymbolId, Id>,
        field: &mut VectorField,
    ) -> crate::Result<()> {
        for (name, placeholder, value) in std::mem::take(&mut self.scene.prismatic_flanges) {
            let g = &mut self.g;
            let coordinate = format!("{name}.q");
            let targets: [Id; 3] = match states.iter().find(|s| s.name == coordinate) {
                Some(s) => [
                    g.symbol_node(s.symbol),
                    g.derivative(s.symbol, 1)?,
                    g.derivative(s.symbol, 2)?,
                ],
                None => {
                    let x = g.substitute(value, replace)?;
                    let v = g.total_derivative(x, field)?;
                    let a = g.total_derivative(v, field)?;
                    [x, v, a]
                }
            };
            replace.insert(placeholder, targets[0]);
            for (order, target) in [(1, targets[1]), (2, targets[2])] {
                let d = g.derivative(placeholder, order)?;
                let symbol = g.as_symbol(d).ok_or_else(|| unsupported("a flange's rate"))?;
                replace.insert(symbol, target);
            }
        }
        Ok(())
    }

    /// `init(j.q, ..)` and `init(der(j.q), ..)`: the joint coordinates'
    /// starts, taken after the bodies' poses were checked against the
    /// joints at zero (the poses are the coordinates' zero).
    fn apply_joint_inits(&mut self, states: &[NewState]) {
        for init in std::mem::take(&mut self.scene.joint_inits) {
            let Some(state) = states.iter().find(|s| s.name == init.name) else {
                let joint = init.name.split('.').next().unwrap_or("");
                let own: Vec<&str> = states
                    .iter()
                    .filter(|s| s.name.split('.').next() == Some(joint))
                    .map(|s| s.name.as_str())
                    .collect();
                let message = if own.is_empty() {
                    format!("joint `{joint}` has no coordinates of its own: it closes a loop (a constraint) or holds nothing")
                } else {
                    format!(
                        "`{}` is not a coordinate of joint `{joint}`; it has {}",
                        init.name,
                        own.join(", ")
                    )
                };
                self.cx.error_at(&init.origin, message);
                continue;
            };
            if init.order == 0 {
                if let Some(decl) = self.states.iter_mut().find(|d| d.symbol == state.symbol) {
                    decl.init = init.value;
                }
                continue;
            }
            if state.rate.is_none() {
                self.cx.error_at(
                    &init.origin,
                    format!(
                        "`{}` is not a second-order coordinate: set its start with `init({}, ..)`",
                        init.name, init.name
                    ),
                );
                continue;
            }
            let rate = self.g.derivative(state.symbol, 1).ok().and_then(|d| self.g.as_symbol(d));
            self.inits.retain(|i| Some(i.target) != rate);
            if self.init_rate(state.symbol, init.value, &init.origin).is_none() {
                self.cx.error_at(&init.origin, "its rate cannot be set");
            }
        }
    }

    /// `init(j.q, value)`, `init(der(j.q), value)` on a joint (see
    /// [`crate::front::lower::SceneLanguage::joint_init`]).
    pub(crate) fn joint_init(&mut self, target: &Expr, value: &Expr, whole: &Expr) -> bool {
        let (field, order) = match target {
            Expr::Field(f) => (f, 0),
            Expr::Call(c)
                if c.args.len() == 1
                    && matches!(&*c.func, Expr::Path(p) if p.path.is_ident("der")) =>
            {
                match &c.args[0] {
                    Expr::Field(f) => (f, 1),
                    _ => return false,
                }
            }
            _ => return false,
        };
        let (Expr::Path(base), syn::Member::Named(member)) = (&*field.base, &field.member) else {
            return false;
        };
        let Some(joint) = base.path.get_ident().map(|i| i.to_string()) else { return false };
        let spatial = self.scene.spatial_records.iter().any(|r| r.name == joint);
        let planar = self.scene.records.iter().any(|r| r.name == joint);
        if !spatial && !planar {
            return false;
        }
        if !self.scene.recursive || planar {
            self.cx.error_at(target, format!("`{joint}.{member}` is not a state here: a joint's coordinates are states in a spatial scene under `#[dae_model(scene = recursive)]`; here the bodies start where they are declared"));
            return true;
        }
        let Some(value) = self.initial_value(value) else { return true };
        self.scene.joint_inits.push(crate::mechanics::JointInit {
            name: format!("{joint}.{member}"),
            order,
            value,
            origin: whole.to_token_stream(),
        });
        true
    }

    /// q' = ½ q ⊗ ω for each spherical joint's quaternion (|q| = 1 kept
    /// by projection) and each free body's.
    fn quaternion_kinematics(
        &mut self,
        attitudes: &[([SymbolId; 4], [SymbolId; 3])],
        free: &[bool],
        origin: &TokenStream,
    ) -> crate::Result<()> {
        let mut kinematics = Vec::new();
        for (q, w) in attitudes {
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
        Ok(())
    }

    /// A body on a free joint: its own coordinates, and six axes, three
    /// slides along the world axes (its centre's velocity) and three turns
    /// about its body axes through its centre (its body rates).
    #[allow(clippy::type_complexity)]
    fn free_joint(
        &mut self,
        b: usize,
    ) -> crate::Result<(Placed, Vec<(Column, Frame, Frame, bool)>)> {
        let mut axes = Vec::with_capacity(6);
        let body = self.scene.spatial[b].clone();
        let g = &mut self.g;
        let quaternion = body.quaternion.map(|s| g.symbol_node(s));
        let rot = rotation(g, quaternion)?;
        let centre = body.position.map(|s| g.symbol_node(s));
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
            axes.push((slide, Frame::Ground, Frame::Body(b), true));
        }
        for k in 0..3 {
            let mut e = [zero; 3];
            e[k] = one;
            let turn = Column {
                axis: Axis::Turn { axis: e, in_b: true, fixed_in_b: true },
                speed: g.symbol_node(body.rates[k]),
                acceleration: g.derivative(body.rates[k], 1)?,
            };
            axes.push((turn, Frame::Ground, Frame::Body(b), true));
        }
        Ok((Placed { quaternion, rot, centre }, axes))
    }

    /// The joint coordinates as states, with their initial rates.
    fn declare_joint_states(
        &mut self,
        states: &[NewState],
        origin: &TokenStream,
    ) -> crate::Result<()> {
        for s in states {
            self.states.push(crate::front::ir::StateDecl {
                name: s.name.clone(),
                symbol: s.symbol,
                init: s.init,
                origin: origin.clone(),
                fixed: false,
                doc: s.doc.clone(),
                avoid: false,
                prefer: false,
            });
        }
        for s in states {
            if let Some(rate) = s.rate {
                if !self.g.as_number(rate).is_some_and(|v| v.is_zero()) {
                    self.init_rate(s.symbol, rate, origin)
                        .ok_or_else(|| unsupported("a joint rate"))?;
                }
            }
        }
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
            let init = |this: &Self, s: SymbolId| this.state_initial_value(s).unwrap_or(zero);
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
            // Its coordinates, now states, with their rates.
            let names = super::names::SPATIAL_JOINT_COORDINATES.iter();
            for suffix in names.filter(|(k, _)| *k == rec.kind).flat_map(|(_, s)| s.iter()) {
                drop_outputs.insert(format!("{}.{suffix}", rec.name));
                drop_outputs.insert(format!("der({}.{suffix})", rec.name));
            }
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
        let values = self.start_values();
        let value =
            |g: &Graph, id: Id| g.eval(&[id], &|s| values.get(&s).copied().unwrap_or(f64::NAN))[0];
        for (b, p) in placed.iter().enumerate() {
            if free[b] {
                continue;
            }
            let mut worst: f64 = 0.0;
            let mut scale: f64 = 1.0;
            for k in 0..3 {
                let got = value(&self.g, p.centre[k]);
                let want = value(&self.g, start[b].centre[k]);
                worst = worst.max((got - want).abs());
                scale = scale.max(want.abs());
            }
            if worst <= PLACEMENT_TOLERANCE * scale {
                continue;
            }
            let (joint, at) = self.tree_joint_of(b, tree, records)?;
            let body = self.body_name(b);
            let worst = if worst >= 1e-4 {
                format!("{worst:.4}").trim_end_matches('0').to_string()
            } else {
                format!("{worst:.1e}")
            };
            return Some((at, format!("`{body}` starts {worst} m from where joint `{joint}` places it: in joint coordinates a body's start follows from its joint, so give `{body}` an initial position that satisfies `{joint}`")));
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
                let v = self.g.eval(&[rate], &|s| values.get(&s).copied().unwrap_or(f64::NAN))[0];
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
            let (vc, w) = centre_and_body_rates(g, p, v).ok()?;
            let got: Vec<f64> = vc.iter().chain(&w).map(|&x| value(g, x)).collect();
            let want: Vec<f64> =
                start[b].velocity.iter().chain(&start[b].rates).map(|&x| value(g, x)).collect();
            let worst = got.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            let scale = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            if worst <= PLACEMENT_TOLERANCE * scale {
                continue;
            }
            let (joint, at) = self.tree_joint_of(b, tree, records)?;
            let body = self.body_name(b);
            let show = |x: &[f64]| {
                let parts: Vec<String> =
                    x.iter().map(|v| format!("{}", (v * 1e6).round() / 1e6)).collect();
                format!("[{}], [{}]", parts[..3].join(", "), parts[3..].join(", "))
            };
            return Some((at, format!("`{body}` starts moving at {} (velocity, body rates) but joint `{joint}` moves it at {}: in joint coordinates a body's motion follows from its joints' rates, so give `{body}` a velocity and body rates that satisfy `{joint}`", show(&want), show(&got))));
        }
        None
    }

    /// The tree joint that places body `b`: its name and statement.
    fn tree_joint_of(
        &self,
        b: usize,
        tree: &[Edge],
        records: &[SpatialJointRecord],
    ) -> Option<(String, TokenStream)> {
        let joint = tree.iter().find(|e| e.child == b).and_then(|e| e.joint)?;
        let joint = records[joint].name.clone();
        let at = self.scene.joint_rows.iter().find(|j| j.0 == joint)?.2.clone();
        Some((joint, at))
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

    /// The body coordinates and their rates in joint coordinates (free
    /// bodies keep theirs); second derivatives only where something reads
    /// them.
    fn body_substitution(
        &mut self,
        placed: &[Placed],
        velocity: &[Spatial],
        body_rates: Option<&[Vec3]>,
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
                self.scene.spatial_loads.iter().flat_map(|l| l.entries().collect::<Vec<_>>()),
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
            let (vc, w_body) = centre_and_body_rates(g, &p, v)?;
            // The body frames' rates where they were computed: the same
            // values, without turning the world's through the chain.
            let w_body = body_rates.map_or(w_body, |r| r[b]);
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
        for load in &mut self.scene.spatial_loads {
            for x in load.entries_mut() {
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
            let (vc, w_body) = centre_and_body_rates(g, p, v)?;
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
                    declared: false,
                });
            }
        }
        Ok(())
    }
}

/// The child of a tree joint placed from its parent: Q_b = Q_a ⊗ Q_rel and
/// b's joint point is a's moved by the offset (in a's axes), or the
/// inverse where the child is the joint's first frame.
fn place_child(
    g: &mut Graph,
    edge: &Edge,
    rec: &SpatialJointRecord,
    motion: &Motion,
    parent: &Placed,
) -> crate::Result<Placed> {
    if edge.child_is_b {
        let quaternion = quaternion_product(g, parent.quaternion, motion.quaternion)?;
        let rot = mat_mul(g, &parent.rot, &motion.rot)?;
        let arm = add3(g, rec.local_a, motion.offset)?;
        let arm = mat_vec(g, &parent.rot, arm)?;
        let point = add3(g, parent.centre, arm)?;
        let back = mat_vec(g, &rot, rec.local_b)?;
        Ok(Placed { quaternion, rot, centre: sub3(g, point, back)? })
    } else {
        let inverse = conjugate(g, motion.quaternion)?;
        let quaternion = quaternion_product(g, parent.quaternion, inverse)?;
        let rot = mat_mul(g, &parent.rot, &transpose(&motion.rot))?;
        let arm = mat_vec(g, &parent.rot, rec.local_b)?;
        let point = add3(g, parent.centre, arm)?;
        let back = add3(g, rec.local_a, motion.offset)?;
        let back = mat_vec(g, &rot, back)?;
        Ok(Placed { quaternion, rot, centre: sub3(g, point, back)? })
    }
}

/// A body's centre velocity v_O + ω × c and its angular velocity in body
/// axes Rᵀ ω, from its spatial velocity (ω; v_O).
fn centre_and_body_rates(g: &mut Graph, p: &Placed, v: Spatial) -> crate::Result<(Vec3, Vec3)> {
    let turn = cross3(g, v.top, p.centre)?;
    Ok((add3(g, v.bottom, turn)?, mat_t_vec(g, &p.rot, v.top)?))
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
