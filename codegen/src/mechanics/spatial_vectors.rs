//! Featherstone's spatial vectors (*Rigid Body Dynamics Algorithms*,
//! 2008, ch. 2) with expression-node entries, in world axes about the
//! world origin: motion and force vectors, their cross products, and
//! rigid-body inertias.

use super::algebra::{add3, cross3, dot3, mat_mul, mat_vec, scale3, sub3, transpose, Mat3, Vec3};
use crate::{Graph, Id};

/// A spatial motion vector (ω; v_O) or force vector (n_O; f), world axes,
/// about the world origin.
#[derive(Clone, Copy)]
pub(super) struct Spatial {
    pub top: Vec3,
    pub bottom: Vec3,
}

/// The spatial inertia of a body (or a composite) about the world origin:
/// [[I_O, [h]×], [[h]×ᵀ, m 1]] with h = m c.
#[derive(Clone, Copy)]
pub(super) struct Inertia {
    pub about_origin: Mat3,
    pub h: Vec3,
    pub mass: Id,
}

/// a + b.
pub(super) fn add(g: &mut Graph, a: Spatial, b: Spatial) -> crate::Result<Spatial> {
    Ok(Spatial { top: add3(g, a.top, b.top)?, bottom: add3(g, a.bottom, b.bottom)? })
}

/// a − b.
pub(super) fn sub(g: &mut Graph, a: Spatial, b: Spatial) -> crate::Result<Spatial> {
    Ok(Spatial { top: sub3(g, a.top, b.top)?, bottom: sub3(g, a.bottom, b.bottom)? })
}

/// s·a.
pub(super) fn scale(g: &mut Graph, s: Id, a: Spatial) -> crate::Result<Spatial> {
    Ok(Spatial { top: scale3(g, s, a.top)?, bottom: scale3(g, s, a.bottom)? })
}

/// −a.
pub(super) fn negate(g: &mut Graph, a: Spatial) -> crate::Result<Spatial> {
    let minus = g.int(-1);
    scale(g, minus, a)
}

/// A motion vector applied to a force vector (power): ω·n + v·f.
pub(super) fn dot(g: &mut Graph, motion: Spatial, force: Spatial) -> crate::Result<Id> {
    let a = dot3(g, motion.top, force.top)?;
    let b = dot3(g, motion.bottom, force.bottom)?;
    g.add(a, b)
}

/// (ω; v) × (m; n) = (ω × m; ω × n + v × m), Featherstone eq. 2.31.
pub(super) fn cross_motion(g: &mut Graph, a: Spatial, b: Spatial) -> crate::Result<Spatial> {
    let top = cross3(g, a.top, b.top)?;
    let wn = cross3(g, a.top, b.bottom)?;
    let vm = cross3(g, a.bottom, b.top)?;
    Ok(Spatial { top, bottom: add3(g, wn, vm)? })
}

/// (ω; v) ×* (n; f) = (ω × n + v × f; ω × f), Featherstone eq. 2.32.
pub(super) fn cross_force(g: &mut Graph, a: Spatial, f: Spatial) -> crate::Result<Spatial> {
    let wn = cross3(g, a.top, f.top)?;
    let vf = cross3(g, a.bottom, f.bottom)?;
    Ok(Spatial { top: add3(g, wn, vf)?, bottom: cross3(g, a.top, f.bottom)? })
}

/// I (ω; v) = (I_O ω + h × v; m v − h × ω).
pub(super) fn apply(g: &mut Graph, i: &Inertia, a: Spatial) -> crate::Result<Spatial> {
    let iw = mat_vec(g, &i.about_origin, a.top)?;
    let hv = cross3(g, i.h, a.bottom)?;
    let mv = scale3(g, i.mass, a.bottom)?;
    let hw = cross3(g, i.h, a.top)?;
    Ok(Spatial { top: add3(g, iw, hv)?, bottom: sub3(g, mv, hw)? })
}

/// The inertia of two bodies moving as one.
pub(super) fn add_inertia(g: &mut Graph, a: &Inertia, b: &Inertia) -> crate::Result<Inertia> {
    let mut about_origin = a.about_origin;
    for (k, x) in about_origin.iter_mut().enumerate() {
        *x = g.add(a.about_origin[k], b.about_origin[k])?;
    }
    Ok(Inertia { about_origin, h: add3(g, a.h, b.h)?, mass: g.add(a.mass, b.mass)? })
}

/// A body's spatial inertia about the origin: I_O = R J Rᵀ + m (|c|² 1 − c cᵀ).
pub(super) fn body_inertia(
    g: &mut Graph,
    mass: Id,
    j: &Mat3,
    rot: &Mat3,
    c: Vec3,
) -> crate::Result<Inertia> {
    let jr = mat_mul(g, j, &transpose(rot))?;
    let world = mat_mul(g, rot, &jr)?;
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
