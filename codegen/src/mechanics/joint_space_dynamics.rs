//! Joint-space dynamics of a spatial tree (Featherstone, *Rigid Body
//! Dynamics Algorithms*, 2008): the bodies' spatial velocities and the
//! motion subspace with its rates, V_i = V_parent + Σ S_k u_k and
//! Ṡ_k = V_F × S_k for an axis fixed in body F; the mass matrix by the
//! composite-rigid-body algorithm (§6.2), M_kl = S_kᵀ I^c_i S_l; the bias
//! forces by recursive Newton–Euler with u̇ = 0 (§5.3),
//! f_i = I_i a_i + v_i ×* I_i v_i − f_ext, C_k = S_kᵀ F_i; and the cut
//! joints' reactions −(∂Φ̇/∂u)ᵀ λ.

use super::algebra::{add3, cross3, mat_vec, scale3, Mat3};
use super::spatial_joint_motion::{Axis, Column};
use super::spatial_tree::{parents_and_order, speeds, Edge, Placed, Speeds};
use super::spatial_vectors::{
    add, add_inertia, apply, body_inertia, cross_force, cross_motion, dot, negate, scale, sub,
    Spatial,
};
use super::tree_factorization::solve_along_tree;
use super::unsupported;
use super::Scene;
use super::{Frame, SpatialJointRecord};
use crate::front::lower::Lower;
use crate::{Graph, Id, VectorField};

/// A column of the motion subspace in world axes: S, Ṡ, u and u̇.
#[derive(Clone, Copy)]
pub(super) struct Subspace {
    pub s: Spatial,
    pub rate: Spatial,
    pub speed: Id,
    pub acceleration: Id,
}

/// The tree's velocities and subspaces, and the field that differentiates
/// along them.
pub(super) struct Dynamics {
    pub field: VectorField,
    pub velocity: Vec<Spatial>,
    pub subspace: Vec<Vec<Subspace>>,
}

impl Lower<'_, Scene> {
    /// Velocities V_i = V_parent + Σ S_k u_k and the motion subspace in
    /// world axes, with the axes' rates Ṡ_k = V_F × S_k.
    pub(super) fn tree_dynamics(
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

    /// The equations of motion, one per joint speed: the mass matrix by the
    /// composite-rigid-body algorithm, the bias forces (gyroscopic and
    /// Coriolis terms, gravity, loads) by recursive Newton–Euler with
    /// u̇ = 0, and the cut joints' reactions.
    pub(super) fn crba_rnea(
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
        let (parent, order) = parents_and_order(tree, n);
        // Each body's inertia about the origin, world axes.
        let mut inertia = Vec::with_capacity(n);
        for (b, body) in bodies.iter().enumerate() {
            inertia.push(body_inertia(
                g,
                body.mass,
                &body.inertia,
                &placed[b].rot,
                placed[b].centre,
            )?);
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
            for load in loads.iter().filter(|l| l.body == b) {
                let turned = mat_vec(g, &placed[b].rot, load.body_force)?;
                let force = add3(g, load.world_force, turned)?;
                external.push((force, mat_vec(g, &placed[b].rot, load.torque)?));
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
        let Speeds { index, first, previous } = speeds(&order, &parent, |b| subspace[b].len());
        let m = index.len();
        let mut mass = vec![vec![zero; m]; m];
        for &i in &order {
            // F = I^c_i S_k once; M_kl = S_lᵀ F for l on the path to the root.
            for (k, row) in subspace[i].iter().enumerate() {
                let f = apply(g, &composite[i], row.s)?;
                let mut j = Some(i);
                while let Some(jb) = j {
                    for (l, col) in subspace[jb].iter().enumerate() {
                        let entry = dot(g, col.s, f)?;
                        mass[first[i] + k][first[jb] + l] = entry;
                        mass[first[jb] + l][first[i] + k] = entry;
                    }
                    j = parent[jb];
                }
            }
        }
        // Reactions of the cut joints through the speeds: ∂Φ̇/∂u.
        let mut rates = Vec::with_capacity(cut_rows.len());
        for &(row, lambda) in cut_rows {
            rates.push((g.total_derivative(row, field)?, lambda));
        }
        let mut forces = Vec::with_capacity(m);
        for &(b, c) in &index {
            let col = subspace[b][c];
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
            forces.push(g.sum(&rhs)?);
        }
        // A tree: the accelerations explicit, through the tree's
        // factorisation. Cut joints add their multipliers, and the KKT
        // system is left to the run-time solve.
        if rates.is_empty() {
            let accelerations = solve_along_tree(g, &mass, &previous, &forces)?;
            return Ok(index
                .iter()
                .zip(accelerations)
                .map(|(&(b, c), a)| (subspace[b][c].acceleration, a))
                .collect());
        }
        let mut equations = Vec::with_capacity(m);
        for (k, &force) in forces.iter().enumerate() {
            let mut lhs = Vec::with_capacity(m);
            for (l, &(bl, cl)) in index.iter().enumerate() {
                if g.as_number(mass[k][l]).is_some_and(|v| v.is_zero()) {
                    continue;
                }
                lhs.push(g.mul(mass[k][l], subspace[bl][cl].acceleration)?);
            }
            equations.push((g.sum(&lhs)?, force));
        }
        Ok(equations)
    }
}
