//! A spatial joint in body coordinates: its constraint rows (course notes
//! §4.1, in space: a point kept on a point or a line, an axis kept normal
//! to two others, the relative attitude kept) and its coordinates as
//! expressions of the bodies' (the turn about an axis from the relative
//! attitude, the slides in a's axes, a universal joint's Cardan angles, a
//! spherical joint's relative quaternion and rates), named as joint
//! coordinates name them.

use super::algebra::{
    conjugate, cross3, dot3, exact_where_rounded, mat_t_vec, mat_vec, quaternion_product, sub3,
    Mat3, Vec3,
};
use crate::{Graph, Id};

/// Two vectors that span the plane normal to `u`: `u × e_k` for the axis
/// `e_k` least aligned with `u` (by its value at the defaults), then `u × n1`.
/// Polynomial in `u`, so exact for symbolic axes too.
pub(crate) fn normals(g: &mut Graph, u: Vec3, values: [f64; 3]) -> crate::Result<[Vec3; 2]> {
    let k = (0..3).min_by(|&i, &j| values[i].abs().total_cmp(&values[j].abs())).unwrap_or(0);
    let (zero, one) = (g.zero(), g.one());
    let mut e = [zero; 3];
    e[k] = one;
    let n1 = cross3(g, u, e)?;
    let n2 = cross3(g, u, n1)?;
    Ok([n1, n2])
}

/// What a joint needs of one of its two frames: where it is and how it is
/// turned, now and at the start.
#[derive(Clone, Copy)]
pub(super) struct Pose {
    pub(super) r: Vec3,
    pub(super) rot: Mat3,
    pub(super) rot0: Mat3,
}

/// A joint's coordinate in body coordinates: its name after the joint's
/// (`q`, `angle`, `q1`, …) and its value.
pub(super) type JointCoordinate = (&'static str, Id);

/// What a spatial joint's rows and coordinates are made of: its two
/// frames' poses, the gap from a's joint point to b's (world axes), its
/// axis or normal (or length) in a's axes with that axis's values at the
/// defaults, a universal joint's axis in b's axes, and each frame's
/// attitude (now, at the start) and body rates.
pub(super) struct JointGeometry {
    pub(super) pa: Pose,
    pub(super) pb: Pose,
    pub(super) gap: Vec3,
    pub(super) extra: Option<Vec3>,
    pub(super) cross_axis: Option<Vec3>,
    pub(super) axis_values: Option<[f64; 3]>,
    pub(super) attitudes: [([Id; 4], [Id; 4], Vec3); 2],
}

/// The constraint rows of a spatial joint of `kind`, and its coordinates
/// as expressions of the bodies' (named as joint coordinates name them).
pub(super) fn rows_and_coordinates(
    g: &mut Graph,
    kind: &str,
    joint: &JointGeometry,
) -> crate::Result<(Vec<Id>, Vec<JointCoordinate>)> {
    let JointGeometry { pa, pb, gap, extra, cross_axis, axis_values, attitudes } = *joint;
    let mut rows = Vec::with_capacity(6);
    // The relative attitude kept at its initial value: with
    // D = R_aᵀ R_b (R_a0ᵀ R_b0)ᵀ, which is I + [θ]× near it, the
    // rows are the three components of θ (twice).
    let relative = |g: &mut Graph| -> crate::Result<[Id; 9]> {
        let mut d = [pa.rot[0]; 9];
        let mut c0 = [pa.rot[0]; 9];
        for i in 0..3 {
            for j in 0..3 {
                let col = |m: &Mat3, k: usize| [m[k], m[3 + k], m[6 + k]];
                c0[3 * i + j] = dot3(g, col(&pa.rot0, i), col(&pb.rot0, j))?;
            }
        }
        // D = R_aᵀ R_b C0ᵀ: entry (i, j) = (R_a e_i) · (R_b C0ᵀ e_j).
        for j in 0..3 {
            let c0_row = [c0[3 * j], c0[3 * j + 1], c0[3 * j + 2]];
            let turned = mat_vec(g, &pb.rot, c0_row)?;
            for i in 0..3 {
                let col_a = [pa.rot[i], pa.rot[3 + i], pa.rot[6 + i]];
                d[3 * i + j] = dot3(g, col_a, turned)?;
            }
        }
        Ok(d)
    };
    let attitude = |g: &mut Graph| -> crate::Result<Vec<Id>> {
        let d = relative(g)?;
        Ok(vec![g.sub(d[7], d[5])?, g.sub(d[2], d[6])?, g.sub(d[3], d[1])?])
    };
    // |u| for a unit axis.
    let unit = |g: &mut Graph, u: Vec3| -> crate::Result<Vec3> {
        let length = dot3(g, u, u)?;
        let length = g.sqrt(length)?;
        Ok([g.div(u[0], length)?, g.div(u[1], length)?, g.div(u[2], length)?])
    };
    // u in b's axes at the start, then in the world now: it stays
    // normal to the two normals of u in a (the dot-2 rows of a
    // revolute or cylindrical joint, the normal of a planar one).
    let axis_kept = |g: &mut Graph, u: Vec3, rows: &mut Vec<Id>| -> crate::Result<()> {
        let u_world0 = mat_vec(g, &pa.rot0, u)?;
        let u_b = mat_t_vec(g, &pb.rot0, u_world0)?;
        let u_b_world = mat_vec(g, &pb.rot, u_b)?;
        for n in normals(g, u, axis_values.unwrap_or([1.0; 3]))? {
            let n_world = mat_vec(g, &pa.rot, n)?;
            rows.push(dot3(g, n_world, u_b_world)?);
        }
        Ok(())
    };
    // pb on the line through pa along u: the gap normal to u's normals.
    let on_line = |g: &mut Graph, u: Vec3, rows: &mut Vec<Id>| -> crate::Result<()> {
        for n in normals(g, u, axis_values.unwrap_or([1.0; 3]))? {
            let n_world = mat_vec(g, &pa.rot, n)?;
            rows.push(dot3(g, n_world, gap)?);
        }
        Ok(())
    };
    // The slide of pb from pa along the unit axis u (in a).
    let slide = |g: &mut Graph, u: Vec3| -> crate::Result<Id> {
        let u_hat = unit(g, u)?;
        let u_world = mat_vec(g, &pa.rot, u_hat)?;
        dot3(g, u_world, gap)
    };
    // The angle the relative attitude D = R_aᵀ R_b C0ᵀ has turned
    // about u: its axial vector is sin q · u, its trace 1 + 2 cos q.
    let turn = |g: &mut Graph, u: Vec3| -> crate::Result<Id> {
        let d = relative(g)?;
        let axial = [g.sub(d[7], d[5])?, g.sub(d[2], d[6])?, g.sub(d[3], d[1])?];
        let u_hat = unit(g, u)?;
        let twice_sin = dot3(g, u_hat, axial)?;
        let trace = g.sum(&[d[0], d[4], d[8]])?;
        let one = g.one();
        let twice_cos = g.sub(trace, one)?;
        g.atan2(twice_sin, twice_cos)
    };
    let mut coordinates = Vec::new();
    match kind {
        "universal" => {
            let (ua, ub) = (extra.unwrap_or([g.zero(); 3]), cross_axis.unwrap_or([g.zero(); 3]));
            rows.extend(gap);
            let ua_world = mat_vec(g, &pa.rot, ua)?;
            let ub_world = mat_vec(g, &pb.rot, ub)?;
            rows.push(dot3(g, ua_world, ub_world)?);
            // D = R_u(q1) R_v(q2), v = C0 u_b the second axis at
            // the start in a's axes: in the frame (u, v, u × v),
            // R_x(q1) R_y(q2), whose entries give both angles.
            let u = unit(g, ua)?;
            let ub_world0 = mat_vec(g, &pb.rot0, ub)?;
            let v = mat_t_vec(g, &pa.rot0, ub_world0)?;
            let v = unit(g, v)?;
            let w = cross3(g, u, v)?;
            let d = relative(g)?;
            let (dv, du, dw) = (mat_vec(g, &d, v)?, mat_vec(g, &d, u)?, mat_vec(g, &d, w)?);
            let (s1, c1) = (dot3(g, w, dv)?, dot3(g, v, dv)?);
            let (s2, c2) = (dot3(g, u, dw)?, dot3(g, u, du)?);
            coordinates.push(("q1", g.atan2(s1, c1)?));
            coordinates.push(("q2", g.atan2(s2, c2)?));
        }
        "cylindrical" => {
            let u = extra.unwrap_or([g.zero(); 3]);
            on_line(g, u, &mut rows)?;
            axis_kept(g, u, &mut rows)?;
            coordinates.push(("q", slide(g, u)?));
            coordinates.push(("angle", turn(g, u)?));
        }
        "planar" => {
            let n = extra.unwrap_or([g.zero(); 3]);
            let n_world = mat_vec(g, &pa.rot, n)?;
            rows.push(dot3(g, n_world, gap)?);
            axis_kept(g, n, &mut rows)?;
            // The slides along the plane's two unit directions,
            // in a's axes, as joint coordinates choose them.
            let [n1, n2] = normals(g, n, axis_values.unwrap_or([0.0, 0.0, 1.0]))?;
            let gap_in_a = mat_t_vec(g, &pa.rot, gap)?;
            let e1 = unit(g, n1)?;
            coordinates.push(("u", dot3(g, gap_in_a, e1)?));
            let e2 = unit(g, n2)?;
            coordinates.push(("v", dot3(g, gap_in_a, e2)?));
            coordinates.push(("angle", turn(g, n)?));
        }
        "spherical" => {
            rows.extend(gap);
            // R_aᵀ R_b = C0 R(q): q = c0* ⊗ q_a* ⊗ q_b, c0 = q_a0* ⊗
            // q_b0; the relative rates ω_b − R_bᵀ R_a ω_a in b's
            // axes.
            let [(qa, qa0, wa), (qb, qb0, wb)] = attitudes;
            let qa0_conjugate = conjugate(g, qa0)?;
            let c0 = quaternion_product(g, qa0_conjugate, qb0)?;
            let c0 = exact_where_rounded(g, c0)?;
            let c0_conjugate = conjugate(g, c0)?;
            let qa_conjugate = conjugate(g, qa)?;
            let q = quaternion_product(g, qa_conjugate, qb)?;
            let q = quaternion_product(g, c0_conjugate, q)?;
            for (k, c) in ["q0", "q1", "q2", "q3"].into_iter().enumerate() {
                coordinates.push((c, q[k]));
            }
            let wa_world = mat_vec(g, &pa.rot, wa)?;
            let wa_in_b = mat_t_vec(g, &pb.rot, wa_world)?;
            let w = sub3(g, wb, wa_in_b)?;
            for (k, c) in ["wx", "wy", "wz"].into_iter().enumerate() {
                coordinates.push((c, w[k]));
            }
        }
        "fixed" => {
            rows.extend(gap);
            rows.extend(attitude(g)?);
        }
        "distance" => {
            let l = extra.map_or(g.zero(), |l| l[0]);
            let d2 = dot3(g, gap, gap)?;
            let l2 = g.mul(l, l)?;
            rows.push(g.sub(d2, l2)?);
        }
        "revolute" => {
            let u = extra.unwrap_or([g.zero(); 3]);
            rows.extend(gap);
            coordinates.push(("q", turn(g, u)?));
            axis_kept(g, u, &mut rows)?;
        }
        _ => {
            let u = extra.unwrap_or([g.zero(); 3]);
            on_line(g, u, &mut rows)?;
            rows.extend(attitude(g)?);
            coordinates.push(("q", slide(g, u)?));
        }
    }
    Ok((rows, coordinates))
}
