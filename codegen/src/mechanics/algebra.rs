//! Three-vectors, 3 × 3 matrices and quaternions whose entries are
//! expression nodes: the arithmetic that the spatial formulations write
//! their kinematics in.

use crate::{Graph, Id};

/// A 3 × 3 matrix, row-major.
pub(crate) type Mat3 = [Id; 9];
/// A 3-vector.
pub(crate) type Vec3 = [Id; 3];

/// a + b.
pub(crate) fn add3(g: &mut Graph, a: Vec3, b: Vec3) -> crate::Result<Vec3> {
    Ok([g.add(a[0], b[0])?, g.add(a[1], b[1])?, g.add(a[2], b[2])?])
}

/// a − b.
pub(crate) fn sub3(g: &mut Graph, a: Vec3, b: Vec3) -> crate::Result<Vec3> {
    Ok([g.sub(a[0], b[0])?, g.sub(a[1], b[1])?, g.sub(a[2], b[2])?])
}

/// s·a.
pub(crate) fn scale3(g: &mut Graph, s: Id, a: Vec3) -> crate::Result<Vec3> {
    Ok([g.mul(s, a[0])?, g.mul(s, a[1])?, g.mul(s, a[2])?])
}

/// a · b.
pub(crate) fn dot3(g: &mut Graph, a: Vec3, b: Vec3) -> crate::Result<Id> {
    let t = [g.mul(a[0], b[0])?, g.mul(a[1], b[1])?, g.mul(a[2], b[2])?];
    g.sum(&t)
}

/// a × b.
pub(crate) fn cross3(g: &mut Graph, a: Vec3, b: Vec3) -> crate::Result<Vec3> {
    let mut c = [a[0]; 3];
    for k in 0..3 {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let p = g.mul(a[i], b[j])?;
        let m = g.mul(a[j], b[i])?;
        c[k] = g.sub(p, m)?;
    }
    Ok(c)
}

/// m·v.
pub(crate) fn mat_vec(g: &mut Graph, m: &Mat3, v: Vec3) -> crate::Result<Vec3> {
    let mut r = v;
    for (i, out) in r.iter_mut().enumerate() {
        *out = dot3(g, [m[3 * i], m[3 * i + 1], m[3 * i + 2]], v)?;
    }
    Ok(r)
}

/// mᵀ·v.
pub(crate) fn mat_t_vec(g: &mut Graph, m: &Mat3, v: Vec3) -> crate::Result<Vec3> {
    let mut r = v;
    for (i, out) in r.iter_mut().enumerate() {
        *out = dot3(g, [m[i], m[3 + i], m[6 + i]], v)?;
    }
    Ok(r)
}

/// R(q) of eq. 4.19 (body to world) for a unit quaternion.
pub(crate) fn rotation(g: &mut Graph, q: [Id; 4]) -> crate::Result<Mat3> {
    let [q0, q1, q2, q3] = q;
    let mut entry = |terms: [(Id, Id, i64); 2], constant: i64| -> crate::Result<Id> {
        let mut parts = Vec::with_capacity(3);
        for (x, y, sign) in terms {
            let p = g.mul(x, y)?;
            let k = g.int(2 * sign);
            parts.push(g.mul(k, p)?);
        }
        parts.push(g.int(constant));
        g.sum(&parts)
    };
    Ok([
        entry([(q0, q0, 1), (q1, q1, 1)], -1)?,
        entry([(q1, q2, 1), (q0, q3, -1)], 0)?,
        entry([(q0, q2, 1), (q1, q3, 1)], 0)?,
        entry([(q0, q3, 1), (q1, q2, 1)], 0)?,
        entry([(q0, q0, 1), (q2, q2, 1)], -1)?,
        entry([(q2, q3, 1), (q0, q1, -1)], 0)?,
        entry([(q1, q3, 1), (q0, q2, -1)], 0)?,
        entry([(q0, q1, 1), (q2, q3, 1)], 0)?,
        entry([(q1, q1, -1), (q2, q2, -1)], 1)?,
    ])
}

/// `q' = ½ q ⊗ (0, ω)`: `(−½ q_v·ω, ½ (q0 ω + q_v × ω))`.
pub(crate) fn quaternion_rates(g: &mut Graph, q: [Id; 4], w: Vec3) -> crate::Result<[Id; 4]> {
    let half = g.rational(1, 2)?;
    let qv = [q[1], q[2], q[3]];
    let d = dot3(g, qv, w)?;
    let d = g.mul(half, d)?;
    let q0w = scale3(g, q[0], w)?;
    let c = cross3(g, qv, w)?;
    let v = add3(g, q0w, c)?;
    let v = scale3(g, half, v)?;
    Ok([g.neg(d)?, v[0], v[1], v[2]])
}

/// The Hamilton product a ⊗ b (scalar part first).
pub(crate) fn quaternion_product(g: &mut Graph, a: [Id; 4], b: [Id; 4]) -> crate::Result<[Id; 4]> {
    let (av, bv) = ([a[1], a[2], a[3]], [b[1], b[2], b[3]]);
    let d = dot3(g, av, bv)?;
    let ab = g.mul(a[0], b[0])?;
    let scalar = g.sub(ab, d)?;
    let t1 = scale3(g, a[0], bv)?;
    let t2 = scale3(g, b[0], av)?;
    let c = cross3(g, av, bv)?;
    let v = add3(g, t1, t2)?;
    let v = add3(g, v, c)?;
    Ok([scalar, v[0], v[1], v[2]])
}

/// The conjugate (the inverse of a unit quaternion).
pub(crate) fn conjugate(g: &mut Graph, q: [Id; 4]) -> crate::Result<[Id; 4]> {
    Ok([q[0], g.neg(q[1])?, g.neg(q[2])?, g.neg(q[3])?])
}

/// The rotation by `angle` about the unit axis `u`: (cos(θ/2), sin(θ/2) u).
pub(crate) fn axis_angle(g: &mut Graph, u: Vec3, angle: Id) -> crate::Result<[Id; 4]> {
    let half = g.rational(1, 2)?;
    let h = g.mul(half, angle)?;
    let (c, s) = (g.call(crate::Func::Cos, h)?, g.call(crate::Func::Sin, h)?);
    Ok([c, g.mul(s, u[0])?, g.mul(s, u[1])?, g.mul(s, u[2])?])
}

/// u / |u|.
pub(crate) fn unit3(g: &mut Graph, u: Vec3) -> crate::Result<Vec3> {
    let length = dot3(g, u, u)?;
    let length = g.sqrt(length)?;
    Ok([g.div(u[0], length)?, g.div(u[1], length)?, g.div(u[2], length)?])
}

/// The product a·b of two matrices.
pub(crate) fn mat_mul(g: &mut Graph, a: &Mat3, b: &Mat3) -> crate::Result<Mat3> {
    let mut c = *a;
    for i in 0..3 {
        for j in 0..3 {
            let row = [a[3 * i], a[3 * i + 1], a[3 * i + 2]];
            c[3 * i + j] = dot3(g, row, [b[j], b[3 + j], b[6 + j]])?;
        }
    }
    Ok(c)
}

/// mᵀ.
pub(crate) fn transpose(m: &Mat3) -> Mat3 {
    [m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]]
}

/// Rotation by `angle` about the unit axis `u` (Rodrigues):
/// cos θ 1 + sin θ [u]× + (1 − cos θ) u uᵀ.
pub(crate) fn rodrigues(g: &mut Graph, u: Vec3, angle: Id) -> crate::Result<Mat3> {
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

/// Constant entries within 1e-14 of 0 or ±1 made exact: a rotation
/// composed of quarter turns carries the rounding of cos(π/2) (6e-17),
/// which would otherwise multiply through every product along the tree and
/// hide its zeros. Entries that are not numbers are left alone.
pub(crate) fn exact_where_rounded<const N: usize>(
    g: &mut Graph,
    xs: [Id; N],
) -> crate::Result<[Id; N]> {
    let mut out = xs;
    for x in &mut out {
        let Some(v) = g.as_number(*x).map(|n| n.to_f64()) else { continue };
        if v.abs() < 1e-14 {
            *x = g.zero();
        } else if (v.abs() - 1.0).abs() < 1e-14 {
            *x = g.int(if v > 0.0 { 1 } else { -1 });
        }
    }
    Ok(out)
}
