//! The joint-space mass matrix solved along its tree, symbolically: the
//! sparse LᵀDL factorisation (Featherstone, "Efficient factorization of
//! the joint-space inertia matrix for branched kinematic trees", IJRR 24,
//! 2005; *Rigid Body Dynamics Algorithms*, 2008, §6.5, Tables 6.3–6.4).
//! H_kl is nonzero only where k and l lie on one path to the root, and
//! with every speed numbered after its parent's the factors fill in
//! nothing: the cost is Σ depth² rather than n³/3, with no pivoting (H is
//! positive definite). Written as expressions, the joint accelerations
//! become explicit in the state, and every method reads them without a
//! run-time solve.

use crate::{Graph, Id};

/// x = H⁻¹ b, where `parent[k]` is the speed before k on its path to the
/// root (`None` at the root, always less than k) and `h` is symmetric with
/// entries only between speeds on one path.
pub(super) fn solve_along_tree(
    g: &mut Graph,
    h: &[Vec<Id>],
    parent: &[Option<usize>],
    b: &[Id],
) -> crate::Result<Vec<Id>> {
    let n = b.len();
    let ancestors = |k: usize| std::iter::successors(parent[k], |&i| parent[i]);
    // H = Lᵀ D L in place: the strict lower part of `l` holds L (unit
    // diagonal), `d` the reciprocals of D.
    let mut l: Vec<Vec<Id>> = h.to_vec();
    let mut inverse_d = vec![g.zero(); n];
    for k in (0..n).rev() {
        let one = g.one();
        inverse_d[k] = g.div(one, l[k][k])?;
        for i in ancestors(k) {
            let a = g.mul(l[k][i], inverse_d[k])?;
            for j in std::iter::once(i).chain(ancestors(i)) {
                let t = g.mul(a, l[k][j])?;
                l[i][j] = g.sub(l[i][j], t)?;
            }
            l[k][i] = a;
        }
    }
    // Lᵀ w = b, leaves first.
    let mut w = b.to_vec();
    for i in (0..n).rev() {
        for j in ancestors(i) {
            let t = g.mul(l[i][j], w[i])?;
            w[j] = g.sub(w[j], t)?;
        }
    }
    // L x = D⁻¹ w, root first.
    let mut x = vec![g.zero(); n];
    for i in 0..n {
        let mut terms = vec![g.mul(w[i], inverse_d[i])?];
        for j in ancestors(i) {
            let t = g.mul(l[i][j], x[j])?;
            terms.push(g.neg(t)?);
        }
        x[i] = g.sum(&terms)?;
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A branched tree (0 → 1 → 2, 0 → 3) with a positive definite H of
    /// its sparsity: the solve satisfies H x = b exactly in rationals.
    #[test]
    fn a_branched_tree_solves_exactly() {
        let mut g = Graph::new();
        let parent = [None, Some(0), Some(1), Some(0)];
        let entries = [[9, 2, 1, 3], [2, 7, 2, 0], [1, 2, 5, 0], [3, 0, 0, 4]];
        let h: Vec<Vec<Id>> =
            entries.iter().map(|row| row.iter().map(|&v| g.int(v)).collect()).collect();
        let b: Vec<Id> = [1, -2, 3, 5].iter().map(|&v| g.int(v)).collect();
        let x = solve_along_tree(&mut g, &h, &parent, &b).unwrap();
        for (row, &bk) in entries.iter().zip(&b) {
            let mut terms = Vec::new();
            for (&hkl, &xl) in row.iter().zip(&x) {
                let hkl = g.int(hkl);
                terms.push(g.mul(hkl, xl).unwrap());
            }
            let s = g.sum(&terms).unwrap();
            let r = g.sub(s, bk).unwrap();
            assert!(g.as_number(r).is_some_and(|v| v.is_zero()), "residual {}", g.show(r));
        }
    }
}
