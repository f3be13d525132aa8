//! Exact linear algebra for DAEs with constant coefficients (course notes
//! §2.1): whether the pencil (E, A) of `E y' + A y = c(t)` is regular, and
//! the left null space of a constant coefficient matrix, which the index
//! reduction turns into hidden constraints (Luenberger's shuffle
//! algorithm). Exact rationals throughout; `None` where a value is a float
//! that is not a small rational, or a rational overflows, so the caller
//! falls back to what it would do without the answer.

use crate::Number;

/// Gaussian elimination on `rows` (each `cols` wide) with exact pivots;
/// the determinant of a square matrix.
fn determinant(mut m: Vec<Vec<Number>>) -> Option<Number> {
    let n = m.len();
    let mut det = Number::ONE;
    for col in 0..n {
        let Some(pivot) = (col..n).find(|&r| !m[r][col].is_zero()) else {
            return Some(Number::ZERO);
        };
        if pivot != col {
            m.swap(col, pivot);
            det = det.negated();
        }
        let p = m[col][col];
        exact(p)?;
        det = det.checked_mul(p)?;
        let inverse = p.pow(Number::MINUS_ONE)?;
        for row in col + 1..n {
            if m[row][col].is_zero() {
                continue;
            }
            let factor = m[row][col].checked_mul(inverse)?.negated();
            let (above, below) = m.split_at_mut(row);
            for (target, &v) in below[0][col..].iter_mut().zip(&above[col][col..]) {
                *target = target.checked_add(factor.checked_mul(v)?)?;
            }
        }
    }
    Some(det)
}

fn exact(n: Number) -> Option<Number> {
    n.as_rational().map(|_| n)
}

/// Whether `det(E·s + A)` vanishes identically. It is a polynomial of
/// degree at most n in s, so it vanishes identically exactly when it
/// vanishes at n + 1 distinct points; evaluated at s = 0, 1, …, n exactly.
pub fn pencil_is_singular(e: &[Vec<Number>], a: &[Vec<Number>]) -> Option<bool> {
    let n = e.len();
    for s in 0..=n {
        let s = Number::integer(s as i64);
        let mut m = Vec::with_capacity(n);
        for (er, ar) in e.iter().zip(a) {
            let row = er
                .iter()
                .zip(ar)
                .map(|(&x, &y)| exact(x)?.checked_mul(s)?.checked_add(exact(y)?))
                .collect::<Option<Vec<Number>>>()?;
            m.push(row);
        }
        if !determinant(m)?.is_zero() {
            return Some(false);
        }
    }
    Some(true)
}

/// A basis of the left null space of `m` (vectors α with αᵀ m = 0), each
/// with its pivot row: the row it replaces, whose coefficient in α is 1.
/// Row reduction of `[m | I]`: a row whose `m` part vanishes is a null
/// vector in its `I` part.
pub fn left_null_space(m: &[Vec<Number>]) -> Option<Vec<(usize, Vec<Number>)>> {
    let rows = m.len();
    let cols = m.first().map_or(0, Vec::len);
    // (original row, m part, I part)
    let mut work: Vec<(usize, Vec<Number>, Vec<Number>)> = m
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mut unit = vec![Number::ZERO; rows];
            unit[i] = Number::ONE;
            Some((i, r.iter().map(|&x| exact(x)).collect::<Option<Vec<_>>>()?, unit))
        })
        .collect::<Option<_>>()?;
    let mut next = 0;
    for col in 0..cols {
        let Some(pivot) = (next..rows).find(|&r| !work[r].1[col].is_zero()) else {
            continue;
        };
        work.swap(next, pivot);
        let inverse = work[next].1[col].pow(Number::MINUS_ONE)?;
        for row in next + 1..rows {
            if work[row].1[col].is_zero() {
                continue;
            }
            let factor = work[row].1[col].checked_mul(inverse)?.negated();
            let (above, below) = work.split_at_mut(row);
            let (source, target) = (&above[next], &mut below[0]);
            for (t, &v) in target.1.iter_mut().zip(&source.1) {
                *t = t.checked_add(factor.checked_mul(v)?)?;
            }
            for (t, &v) in target.2.iter_mut().zip(&source.2) {
                *t = t.checked_add(factor.checked_mul(v)?)?;
            }
        }
        next += 1;
    }
    Some(work.into_iter().skip(next).map(|(original, _, alpha)| (original, alpha)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(rows: &[&[i64]]) -> Vec<Vec<Number>> {
        rows.iter().map(|r| r.iter().map(|&x| Number::integer(x)).collect()).collect()
    }

    #[test]
    fn the_notes_example_2_2_is_a_singular_pencil() {
        // E = [1 1; 0 0], A = [0 1; 0 0]: det(E s + A) = 0 for every s.
        let (e, a) = (m(&[&[1, 1], &[0, 0]]), m(&[&[0, 1], &[0, 0]]));
        assert_eq!(pencil_is_singular(&e, &a), Some(true));
        // A singular E alone is not enough: N α' + α = d is regular.
        let (e, a) = (m(&[&[0, 1], &[0, 0]]), m(&[&[1, 0], &[0, 1]]));
        assert_eq!(pencil_is_singular(&e, &a), Some(false));
    }

    #[test]
    fn left_null_vectors_annihilate_the_matrix() {
        let e = m(&[&[1, 2, 0], &[2, 4, 0], &[0, 1, 1], &[1, 3, 1]]);
        let null = left_null_space(&e).unwrap();
        assert_eq!(null.len(), 2);
        for (pivot, alpha) in &null {
            assert!(alpha[*pivot].is_one());
            for c in 0..3 {
                let mut sum = Number::ZERO;
                for r in 0..4 {
                    sum = sum.checked_add(alpha[r].checked_mul(e[r][c]).unwrap()).unwrap();
                }
                assert!(sum.is_zero(), "column {c}");
            }
        }
    }
}
