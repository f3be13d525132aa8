//! Joint-space dynamics of a spatial tree in each body's own frame (its
//! centre of mass and axes), as robotics libraries compute it
//! (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, §5.3 and §6.2):
//! a joint's motion subspace is then constant, a body's inertia is the
//! constant one it was given, gravity is the ground's acceleration
//! (a_0 = −g) rather than a force on every body, and the transforms
//! between neighbours involve one joint only. In world axes every body's
//! inertia and axis must be turned through the whole chain above it,
//! which costs a robot arm two to three times the arithmetic.
//!
//! Used for trees whose joints keep their axes in the child's frame
//! (revolute, prismatic, cylindrical, spherical, a free body at the root)
//! and no cut joints; `joint_space_dynamics` writes the others in world
//! axes.

use super::algebra::{add3, cross3, mat_mul, mat_t_vec, mat_vec, scale3, transpose, Mat3, Vec3};
use super::spatial_joint_motion::{Axis, Column};
use super::spatial_tree::{parents_and_order, speeds, Edge, Placed, Speeds};
use super::spatial_vectors::{add, cross_force, cross_motion, dot, scale, sub, Spatial};
use super::tree_factorization::solve_along_tree;
use super::{Frame, SpatialJointRecord};
use crate::{Graph, Id};

/// How a tree joint moves its child relative to its parent, from the
/// joint's motion: its kind, the relative rotation R_rel (child axes to
/// parent axes), the rotation at the start C0, and the offset along it.
#[derive(Clone, Copy)]
pub(super) struct Relative {
    pub kind: &'static str,
    pub rot: Mat3,
    pub start_rot: Mat3,
    pub offset: Vec3,
}

/// The tree in body frames: per body the transform from its parent's
/// frame (E, parent axes to the body's, and r, the body's centre in the
/// parent's frame), its columns S in its own frame with their speeds and
/// accelerations, the apparent rate Σ S̊ u, and its velocity.
pub(super) struct BodyFrames {
    rotation: Vec<Mat3>,
    translation: Vec<Vec3>,
    columns: Vec<Vec<(Spatial, Column)>>,
    apparent: Vec<Spatial>,
    /// Each body's spatial velocity in its own frame: (ω; v_c), body axes.
    pub velocity: Vec<Spatial>,
}

/// `x` kept whole where it is a sum: a named intermediate. The
/// simplifier spreads a sum scaled by a number into the sum it enters
/// (so that terms can cancel), and a velocity that enters every inertia
/// product would be spread into each of them.
fn shared(g: &mut Graph, x: Id) -> crate::Result<Id> {
    match g.node(x) {
        crate::Node::Add(_) => g.intermediate(&format!("__shared{}", x.0), x),
        _ => Ok(x),
    }
}

/// [`shared`] for each entry of a spatial vector.
fn shared_spatial(g: &mut Graph, v: Spatial) -> crate::Result<Spatial> {
    let mut out = v;
    for x in out.top.iter_mut().chain(out.bottom.iter_mut()) {
        *x = shared(g, *x)?;
    }
    Ok(out)
}

/// E v for a motion vector given about the parent's origin: the body's
/// view of it, (E ω; E (v − r × ω)).
fn motion_to_child(g: &mut Graph, e: &Mat3, r: Vec3, m: Spatial) -> crate::Result<Spatial> {
    let rw = cross3(g, r, m.top)?;
    let v = super::algebra::sub3(g, m.bottom, rw)?;
    Ok(Spatial { top: mat_vec(g, e, m.top)?, bottom: mat_vec(g, e, v)? })
}

/// Xᵀ f for a force vector in the body's frame: the same force about the
/// parent's origin, parent axes, (Eᵀ n + r × Eᵀ f; Eᵀ f).
fn force_to_parent(g: &mut Graph, e: &Mat3, r: Vec3, f: Spatial) -> crate::Result<Spatial> {
    let n = mat_t_vec(g, e, f.top)?;
    let f = mat_t_vec(g, e, f.bottom)?;
    let moment = cross3(g, r, f)?;
    Ok(Spatial { top: add3(g, n, moment)?, bottom: f })
}

/// A rigid inertia about a frame's origin in its axes: the rotational
/// inertia J_O, the first moment h = m c and the mass.
#[derive(Clone, Copy)]
struct Rigid {
    j: Mat3,
    h: Vec3,
    mass: Id,
}

/// I (ω; v) = (J_O ω + h × v; m v − h × ω).
fn apply(g: &mut Graph, i: &Rigid, m: Spatial) -> crate::Result<Spatial> {
    let jw = mat_vec(g, &i.j, m.top)?;
    let hv = cross3(g, i.h, m.bottom)?;
    let mv = scale3(g, i.mass, m.bottom)?;
    let hw = cross3(g, i.h, m.top)?;
    Ok(Spatial { top: add3(g, jw, hv)?, bottom: super::algebra::sub3(g, mv, hw)? })
}

/// [a]× [b]×, the product of two cross-product matrices: b aᵀ − (a·b) 1.
fn cross_cross(g: &mut Graph, a: Vec3, b: Vec3) -> crate::Result<Mat3> {
    let ab = super::algebra::dot3(g, a, b)?;
    let mut m = [ab; 9];
    for i in 0..3 {
        for k in 0..3 {
            let p = g.mul(b[i], a[k])?;
            m[3 * i + k] = if i == k { g.sub(p, ab)? } else { p };
        }
    }
    Ok(m)
}

/// The inertia `i`, given in a child's frame, in its parent's frame
/// (Featherstone eq. 2.63): turned by Eᵀ, then moved by r,
/// J' = J̃ − [h̃]×[r]× − [r]×[h̃]× − m [r]×[r]×, h' = h̃ + m r.
fn inertia_to_parent(g: &mut Graph, e: &Mat3, r: Vec3, i: &Rigid) -> crate::Result<Rigid> {
    let je = mat_mul(g, &i.j, e)?;
    let turned = mat_mul(g, &transpose(e), &je)?;
    let h = mat_t_vec(g, e, i.h)?;
    let hr = cross_cross(g, h, r)?;
    let rh = cross_cross(g, r, h)?;
    let rr = cross_cross(g, r, r)?;
    let mut j = turned;
    for i_ in 0..3 {
        for k in i_..3 {
            let at = 3 * i_ + k;
            let mrr = g.mul(i.mass, rr[at])?;
            let shift = g.sum(&[hr[at], rh[at], mrr])?;
            let entry = g.sub(turned[at], shift)?;
            j[at] = entry;
            j[3 * k + i_] = entry;
        }
    }
    let mr = scale3(g, i.mass, r)?;
    Ok(Rigid { j, h: add3(g, h, mr)?, mass: i.mass })
}

/// The tree in body frames, or `None` where some joint's axis moves in
/// its child's frame (universal, planar), a joint's child is its first
/// frame, or a cut joint closes a loop: those keep the world-axes form.
pub(super) fn body_frames(
    g: &mut Graph,
    tree: &[Edge],
    records: &[SpatialJointRecord],
    relative: &[Option<Relative>],
    placed: &[Placed],
    columns: &[Vec<(Column, Frame, Frame, bool)>],
    has_cuts: bool,
) -> crate::Result<Option<BodyFrames>> {
    let n = placed.len();
    let zero = g.zero();
    let still = Spatial { top: [zero; 3], bottom: [zero; 3] };
    if has_cuts {
        return Ok(None);
    }
    let identity = {
        let one = g.one();
        [one, zero, zero, zero, one, zero, zero, zero, one]
    };
    let mut frames = BodyFrames {
        rotation: vec![identity; n],
        translation: vec![[zero; 3]; n],
        columns: vec![Vec::new(); n],
        apparent: vec![still; n],
        velocity: vec![still; n],
    };
    for edge in tree {
        let b = edge.child;
        let parent_velocity = match edge.parent {
            Frame::Ground => still,
            Frame::Body(p) => frames.velocity[p],
        };
        let Some(r) = edge.joint else {
            // A free body from the ground: its centre's velocity in world
            // axes and its body rates. S = (0; Rᵀ e_k) and (e_k; 0), and
            // the slides' axes turn with the body: S̊ u = (0; −ω × v).
            if edge.parent != Frame::Ground {
                return Ok(None);
            }
            let rot = placed[b].rot;
            frames.rotation[b] = transpose(&rot);
            frames.translation[b] = placed[b].centre;
            for (k, &(column, ..)) in columns[b].iter().enumerate() {
                let mut e = [zero; 3];
                e[k % 3] = g.one();
                let s = match k < 3 {
                    true => Spatial { top: [zero; 3], bottom: mat_t_vec(g, &rot, e)? },
                    false => Spatial { top: e, bottom: [zero; 3] },
                };
                frames.columns[b].push((s, column));
            }
            let mut v = still;
            for &(s, column) in &frames.columns[b] {
                let step = scale(g, column.speed, s)?;
                v = add(g, v, step)?;
            }
            let turn = cross3(g, v.top, v.bottom)?;
            let minus = g.int(-1);
            frames.apparent[b] = Spatial { top: [zero; 3], bottom: scale3(g, minus, turn)? };
            frames.velocity[b] = shared_spatial(g, v)?;
            continue;
        };
        let (Some(rel), true) = (relative[b], edge.child_is_b) else { return Ok(None) };
        let rec = &records[r];
        // b's centre in the parent's frame: a's joint point, moved along
        // the joint, less b's joint point turned into a's axes.
        let arm = add3(g, rec.local_a, rel.offset)?;
        let back = mat_vec(g, &rel.rot, rec.local_b)?;
        let centre = super::algebra::sub3(g, arm, back)?;
        frames.rotation[b] = transpose(&rel.rot);
        frames.translation[b] = centre;
        for &(column, ..) in &columns[b] {
            let s = match (column.axis, rel.kind) {
                // An axis in a's axes that the joint turns about or slides
                // along: C0ᵀ u in b's.
                (Axis::Turn { axis, in_b: false, fixed_in_b: true }, _) => {
                    let d = mat_t_vec(g, &rel.start_rot, axis)?;
                    Spatial { top: d, bottom: cross3(g, rec.local_b, d)? }
                }
                (Axis::Turn { axis, in_b: true, fixed_in_b: true }, _) => {
                    Spatial { top: axis, bottom: cross3(g, rec.local_b, axis)? }
                }
                (Axis::Slide { axis }, "prismatic" | "cylindrical") => {
                    Spatial { top: [zero; 3], bottom: mat_t_vec(g, &rel.start_rot, axis)? }
                }
                _ => return Ok(None),
            };
            frames.columns[b].push((s, column));
        }
        let mut v = motion_to_child(g, &frames.rotation[b], centre, parent_velocity)?;
        for &(s, column) in &frames.columns[b] {
            let step = scale(g, column.speed, s)?;
            v = add(g, v, step)?;
        }
        frames.velocity[b] = shared_spatial(g, v)?;
    }
    Ok(Some(frames))
}

impl BodyFrames {
    /// The equations of motion, one per joint speed, `(u̇_k, its value)`:
    /// bias forces by recursive Newton–Euler with u̇ = 0 and gravity as the
    /// ground's acceleration, the mass matrix by the composite-rigid-body
    /// algorithm, both in body frames, solved along the tree.
    pub(super) fn equations_of_motion(
        &self,
        g: &mut Graph,
        tree: &[Edge],
        bodies: &[super::SpatialBody],
        placed: &[Placed],
        loads: &[super::SpatialLoad],
        gravity: Option<Vec3>,
    ) -> crate::Result<Vec<(Id, Id)>> {
        let n = bodies.len();
        let zero = g.zero();
        let still = Spatial { top: [zero; 3], bottom: [zero; 3] };
        let (parent, order) = parents_and_order(tree, n);
        let ground_acceleration = match gravity {
            Some(gv) => {
                let minus = g.int(-1);
                Spatial { top: [zero; 3], bottom: scale3(g, minus, gv)? }
            }
            None => still,
        };
        // Forward: bias accelerations; each body's force
        // f = I a + v ×* I v − f_ext about its centre.
        let mut acceleration = vec![still; n];
        let mut force = vec![still; n];
        for &b in &order {
            let from = match parent[b] {
                Some(p) => acceleration[p],
                None => ground_acceleration,
            };
            let (e, r) = (&self.rotation[b], self.translation[b]);
            let mut a = motion_to_child(g, e, r, from)?;
            a = add(g, a, self.apparent[b])?;
            let mut joint_velocity = still;
            for &(s, column) in &self.columns[b] {
                let step = scale(g, column.speed, s)?;
                joint_velocity = add(g, joint_velocity, step)?;
            }
            let v = self.velocity[b];
            let coriolis = cross_motion(g, v, joint_velocity)?;
            a = add(g, a, coriolis)?;
            let a = shared_spatial(g, a)?;
            acceleration[b] = a;
            let body = &bodies[b];
            let inertia = Rigid { j: body.inertia, h: [zero; 3], mass: body.mass };
            let ia = apply(g, &inertia, a)?;
            let iv = apply(g, &inertia, v)?;
            let gyro = cross_force(g, v, iv)?;
            let mut f = add(g, ia, gyro)?;
            for load in loads.iter().filter(|l| l.body == b) {
                // A world force at the centre: turned into the body's axes.
                let f_body = match load.world_force.iter().all(|&x| x == zero) {
                    true => load.body_force,
                    false => {
                        let turned = mat_t_vec(g, &placed[b].rot, load.world_force)?;
                        add3(g, turned, load.body_force)?
                    }
                };
                f = sub(g, f, Spatial { top: load.torque, bottom: f_body })?;
            }
            force[b] = f;
        }
        // Backward: each body's force and composite inertia, its children's
        // added, carried to its parent.
        let mut composite: Vec<Rigid> = bodies
            .iter()
            .map(|body| Rigid { j: body.inertia, h: [zero; 3], mass: body.mass })
            .collect();
        for &b in order.iter().rev() {
            force[b] = shared_spatial(g, force[b])?;
            if let Some(p) = parent[b] {
                let (e, r) = (&self.rotation[b], self.translation[b]);
                let f = force_to_parent(g, e, r, force[b])?;
                force[p] = add(g, force[p], f)?;
                let c = &composite[b];
                let mut j = c.j;
                for x in &mut j {
                    *x = shared(g, *x)?;
                }
                let h = [shared(g, c.h[0])?, shared(g, c.h[1])?, shared(g, c.h[2])?];
                composite[b] = Rigid { j, h, mass: c.mass };
                let moved = inertia_to_parent(g, e, r, &composite[b])?;
                let mut j = composite[p].j;
                for (k, x) in j.iter_mut().enumerate() {
                    *x = g.add(*x, moved.j[k])?;
                }
                composite[p] = Rigid {
                    j,
                    h: add3(g, composite[p].h, moved.h)?,
                    mass: g.add(composite[p].mass, moved.mass)?,
                };
            }
        }
        let Speeds { index, first, previous } = speeds(&order, &parent, |b| self.columns[b].len());
        let m = index.len();
        // M_kl = S_lᵀ I^c_i S_k, the force I^c_i S_k carried up the tree.
        let mut mass = vec![vec![zero; m]; m];
        for &i in &order {
            for (k, &(s, _)) in self.columns[i].iter().enumerate() {
                let f = apply(g, &composite[i], s)?;
                let mut f = shared_spatial(g, f)?;
                let mut j = i;
                loop {
                    for (l, &(sl, _)) in self.columns[j].iter().enumerate() {
                        let entry = dot(g, sl, f)?;
                        mass[first[i] + k][first[j] + l] = entry;
                        mass[first[j] + l][first[i] + k] = entry;
                    }
                    let Some(p) = parent[j] else { break };
                    f = force_to_parent(g, &self.rotation[j], self.translation[j], f)?;
                    f = shared_spatial(g, f)?;
                    j = p;
                }
            }
        }
        let mut forces = Vec::with_capacity(m);
        for &(b, c) in &index {
            let bias = dot(g, self.columns[b][c].0, force[b])?;
            forces.push(g.neg(bias)?);
        }
        let accelerations = solve_along_tree(g, &mass, &previous, &forces)?;
        Ok(index
            .iter()
            .zip(accelerations)
            .map(|(&(b, c), a)| (self.columns[b][c].1.acceleration, a))
            .collect())
    }
}
