//! Solving the reduced equations `E(t, y) w = g(t, y)` for the unknowns
//! `w` (highest derivatives and algebraic variables), block by block in
//! block-lower-triangular order (Tarjan's strongly connected components on
//! the matching; Duff & Reid 1978): a block of one equation or with
//! constant coefficients is solved symbolically and substituted into the
//! blocks after it; any other block is left to a dense solve at run time
//! (the KKT system of a mechanism), merged with the later blocks that read
//! its unknowns so each run-time block is solved once per evaluation.

use crate::dae::system::MassBlock;
use crate::{Graph, Id, Number, SymbolId};

/// The solution: each unknown symbolic, or row `r` of run-time block `b`.
pub struct Solved {
    /// Symbolic solutions.
    pub symbolic: Vec<Option<Id>>,
    /// `(block, row)` of the unknowns solved at run time.
    pub block_of: Vec<Option<(usize, usize)>>,
    /// The run-time blocks.
    pub blocks: Vec<MassBlock>,
    /// Unknowns eliminated from a run-time block: expressions of the state
    /// and of that block's unknowns, evaluated after its solve.
    pub after_solve: Vec<Option<Id>>,
}

/// Why the system could not be solved.
pub enum Unsolvable {
    /// A constant block is singular: its equations repeat each other.
    Dependent {
        /// An equation of the block.
        equation: usize,
        /// The block's unknowns.
        unknowns: Vec<usize>,
    },
    /// An expression could not be built (overflow of an exact constant).
    Graph(crate::Error),
}

impl From<crate::Error> for Unsolvable {
    fn from(e: crate::Error) -> Unsolvable {
        Unsolvable::Graph(e)
    }
}

/// Solves `E w = g`, `e[i]` the non-zero `(column, coefficient)` of row i,
/// `owner[j]` the equation matched to unknown j, `symbols[j]` and
/// `names[j]` its symbol and name.
pub fn solve_unknowns(
    g: &mut Graph,
    e: &[Vec<(usize, Id)>],
    rhs: &[Id],
    owner: &[usize],
    symbols: &[SymbolId],
    names: &[String],
) -> Result<Solved, Unsolvable> {
    // Block-triangular ordering, then each block solved symbolically or left to run time, with
    // the KKT elimination: the blocks' bookkeeping is shared.
    let n = owner.len();
    let mut unknown_of = vec![0; n];
    for (j, &i) in owner.iter().enumerate() {
        unknown_of[i] = j;
    }
    let entry = |i: usize, j: usize| e[i].iter().find(|(c, _)| *c == j).map(|x| x.1);
    let mut symbolic: Vec<Option<Id>> = vec![None; n];
    let mut group_of: Vec<Option<usize>> = vec![None; n];
    // Run-time groups: rows and columns; `None` once merged into another.
    let mut groups: Vec<Option<(Vec<usize>, Vec<usize>)>> = Vec::new();
    for rows in blt_order(e, owner) {
        let cols: Vec<usize> = rows.iter().map(|&i| unknown_of[i]).collect();
        let mut deps: Vec<usize> = rows
            .iter()
            .flat_map(|&i| e[i].iter().map(|&(j, _)| j))
            .filter(|j| !cols.contains(j))
            .filter_map(|j| group_of[j])
            .collect();
        deps.sort_unstable();
        deps.dedup();
        if !deps.is_empty() {
            let (mut all_rows, mut all_cols) = (rows, cols);
            for d in deps {
                if let Some((r, c)) = groups[d].take() {
                    all_rows.extend(r);
                    all_cols.extend(c);
                }
            }
            let id = groups.len();
            for &j in &all_cols {
                group_of[j] = Some(id);
            }
            groups.push(Some((all_rows, all_cols)));
            continue;
        }
        let b = block_rhs(g, e, rhs, &rows, &cols, &symbolic)?;
        if rows.len() == 1 {
            let c = entry(rows[0], cols[0]).unwrap_or(g.zero());
            symbolic[cols[0]] = Some(g.div(b[0], c)?);
            continue;
        }
        let constant: Option<Vec<Vec<Number>>> = rows
            .iter()
            .map(|&i| {
                cols.iter()
                    .map(|&j| match entry(i, j) {
                        Some(c) => g.as_number(c),
                        None => Some(Number::ZERO),
                    })
                    .collect()
            })
            .collect();
        match constant {
            Some(m) => match solve_constant(g, m, b) {
                Some(w) => {
                    for (k, &j) in cols.iter().enumerate() {
                        symbolic[j] = Some(w[k]);
                    }
                }
                None => return Err(Unsolvable::Dependent { equation: rows[0], unknowns: cols }),
            },
            None => {
                let id = groups.len();
                for &j in &cols {
                    group_of[j] = Some(id);
                }
                groups.push(Some((rows, cols)));
            }
        }
    }
    let mut blocks = Vec::new();
    let mut block_of = vec![None; n];
    let mut after_solve = vec![None; n];
    let zero = g.zero();
    for (mut rows, mut cols) in groups.into_iter().flatten() {
        // Declaration order reads best; the solves pivot anyway.
        rows.sort_unstable();
        cols.sort_unstable();
        let mut b = block_rhs(g, e, rhs, &rows, &cols, &symbolic)?;
        let mut a: Vec<Vec<Id>> = rows
            .iter()
            .map(|&i| cols.iter().map(|&j| entry(i, j).unwrap_or(zero)).collect())
            .collect();
        // Unknowns with a constant or parameter pivot (the accelerations of a
        // mechanism with a constant mass matrix) are eliminated symbolically;
        // what is left is the Schur complement G M⁻¹ Gᵀ in the multipliers.
        let eliminated = eliminate_constant_pivots(g, &mut a, &mut b)?;
        let rest_rows: Vec<usize> =
            (0..rows.len()).filter(|r| !eliminated.iter().any(|e| e.1 == *r)).collect();
        let rest_cols: Vec<usize> =
            (0..cols.len()).filter(|c| !eliminated.iter().any(|e| e.0 == *c)).collect();
        let mut value: Vec<Option<Id>> = vec![None; cols.len()];
        let mut at_run_time = false;
        if !rest_cols.is_empty() {
            let sub: Vec<Vec<Id>> =
                rest_rows.iter().map(|&r| rest_cols.iter().map(|&c| a[r][c]).collect()).collect();
            let sub_b: Vec<Id> = rest_rows.iter().map(|&r| b[r]).collect();
            // A block whose coefficients switch with a mode is solved at
            // run time, with pivoting: in some mode a pivot vanishes.
            let switching = sub.iter().flatten().any(|&c| g.reads_switching(c));
            let symbolic_rest = if rest_cols.len() <= SYMBOLIC_BLOCK && !switching {
                solve_symbolic(g, sub.clone(), sub_b.clone())?
            } else {
                None
            };
            match symbolic_rest {
                Some(w) => {
                    for (k, &c) in rest_cols.iter().enumerate() {
                        value[c] = Some(w[k]);
                    }
                }
                None => {
                    at_run_time = true;
                    let block = blocks.len();
                    for (k, &c) in rest_cols.iter().enumerate() {
                        block_of[cols[c]] = Some((block, k));
                        value[c] = Some(g.symbol_node(symbols[cols[c]]));
                    }
                    blocks.push(MassBlock {
                        unknowns: rest_cols.iter().map(|&c| names[cols[c]].clone()).collect(),
                        matrix: sub.into_iter().flatten().collect(),
                        rhs: sub_b,
                    });
                }
            }
        }
        // Back substitution, last eliminated first.
        for &(c, r) in eliminated.iter().rev() {
            let mut terms = vec![b[r]];
            for (j, &arj) in a[r].iter().enumerate() {
                if j == c || g.as_number(arj).is_some_and(|v| v.is_zero()) {
                    continue;
                }
                let w = value[j].ok_or_else(|| crate::Error::Unsupported {
                    message: "back substitution reads an unknown not yet solved".into(),
                })?;
                let t = g.mul(arj, w)?;
                terms.push(g.negate_terms(t)?);
            }
            let numerator = g.sum(&terms)?;
            value[c] = Some(g.div(numerator, a[r][c])?);
        }
        for (c, &j) in cols.iter().enumerate() {
            if block_of[j].is_some() {
                continue;
            }
            if at_run_time {
                after_solve[j] = value[c];
            } else {
                symbolic[j] = value[c];
            }
        }
    }
    Ok(Solved { symbolic, block_of, blocks, after_solve })
}

/// A block's right-hand side `g_B − Σ E_BC w_C` over the unknowns `C`
/// outside it, all solved symbolically before it (blocks that read a
/// run-time block's unknowns were merged with it).
fn block_rhs(
    g: &mut Graph,
    e: &[Vec<(usize, Id)>],
    rhs: &[Id],
    rows: &[usize],
    cols: &[usize],
    symbolic: &[Option<Id>],
) -> crate::Result<Vec<Id>> {
    let mut b = Vec::with_capacity(rows.len());
    for &i in rows {
        let mut terms = vec![rhs[i]];
        for &(j, c) in &e[i] {
            if !cols.contains(&j) {
                let w = symbolic[j].ok_or_else(|| crate::Error::Unsupported {
                    message: "an unknown is read before it is solved".into(),
                })?;
                let t = g.mul(c, w)?;
                terms.push(g.negate_terms(t)?);
            }
        }
        b.push(g.sum(&terms)?);
    }
    Ok(b)
}

/// Eliminates, column by column, each unknown that has a pivot which is a
/// non-zero number or depends on parameters only, from every other row;
/// returns the eliminated `(column, pivot row)` pairs in order. The rows
/// and columns left form the Schur complement.
fn eliminate_constant_pivots(
    g: &mut Graph,
    a: &mut [Vec<Id>],
    b: &mut [Id],
) -> crate::Result<Vec<(usize, usize)>> {
    let k = a.len();
    let mut eliminated: Vec<(usize, usize)> = Vec::new();
    for c in 0..k {
        let best = (0..k)
            .filter(|r| !eliminated.iter().any(|e| e.1 == *r))
            .filter_map(|r| {
                pivot_class(g, a[r][c]).filter(|&class| class <= 1).map(|class| (class, r))
            })
            .min();
        let Some((_, r)) = best else { continue };
        for i in 0..k {
            if i == r
                || eliminated.iter().any(|e| e.1 == i)
                || g.as_number(a[i][c]).is_some_and(|v| v.is_zero())
            {
                continue;
            }
            let f = g.div(a[i][c], a[r][c])?;
            for j in 0..k {
                if j == c || g.as_number(a[r][j]).is_some_and(|v| v.is_zero()) {
                    continue;
                }
                let t = g.mul(f, a[r][j])?;
                a[i][j] = g.sub(a[i][j], t)?;
            }
            let t = g.mul(f, b[r])?;
            b[i] = g.sub(b[i], t)?;
            a[i][c] = g.zero();
        }
        eliminated.push((c, r));
    }
    Ok(eliminated)
}

/// Blocks up to this size are solved symbolically: no run-time LU, an
/// analytic Jacobian, and Taylor recurrences for the index-1 form of a
/// small mechanism (the pendulum's KKT system is 3 × 3).
const SYMBOLIC_BLOCK: usize = 3;

/// How safe an expression is as a pivot: a non-zero number, then an
/// expression of parameters only, then one that depends on the state.
fn pivot_class(g: &Graph, e: Id) -> Option<u8> {
    if let Some(n) = g.as_number(e) {
        return (!n.is_zero()).then_some(0);
    }
    let state_free =
        g.free_symbols(e).iter().all(|&s| matches!(g.symbol(s).kind, crate::SymbolKind::Parameter));
    Some(if state_free { 1 } else { 2 })
}

/// Gaussian elimination on expressions while every column has a constant
/// or parameter pivot; Cramer's rule once a pivot would depend on the
/// state. An intermediate pivot of the elimination (sin θ of a slider-crank)
/// can vanish where the system is regular, and the solution would divide
/// by zero there; Cramer's rule divides by the determinant alone, which
/// vanishes only where the block is singular (where the constraints of a
/// mechanism are dependent: the determinant of its KKT system is the
/// product of the constant pivots eliminated before and this one). `None`
/// when the determinant is structurally zero.
fn solve_symbolic(g: &mut Graph, a: Vec<Vec<Id>>, b: Vec<Id>) -> crate::Result<Option<Vec<Id>>> {
    match eliminate_with_parameter_pivots(g, a.clone(), b.clone())? {
        Some(w) => Ok(Some(w)),
        None => cramer(g, &a, &b),
    }
}

/// The determinant of the `n × n` matrix `a` (n ≤ 3 in use) by cofactor
/// expansion along the first row.
fn determinant(g: &mut Graph, a: &[Vec<Id>]) -> crate::Result<Id> {
    let n = a.len();
    match n {
        0 => Ok(g.one()),
        1 => Ok(a[0][0]),
        _ => {
            let mut terms = Vec::with_capacity(n);
            for (c, &entry) in a[0].iter().enumerate() {
                if g.as_number(entry).is_some_and(|v| v.is_zero()) {
                    continue;
                }
                let minor: Vec<Vec<Id>> = a[1..]
                    .iter()
                    .map(|row| {
                        row.iter().enumerate().filter(|&(j, _)| j != c).map(|(_, &v)| v).collect()
                    })
                    .collect();
                let m = determinant(g, &minor)?;
                let t = g.mul(entry, m)?;
                terms.push(if c % 2 == 0 { t } else { g.negate_terms(t)? });
            }
            g.sum(&terms)
        }
    }
}

/// Cramer's rule: w_i = det(A with column i replaced by b) / det(A).
fn cramer(g: &mut Graph, a: &[Vec<Id>], b: &[Id]) -> crate::Result<Option<Vec<Id>>> {
    let det = determinant(g, a)?;
    if g.as_number(det).is_some_and(|v| v.is_zero()) {
        return Ok(None);
    }
    let one = g.one();
    let inverse = g.div(one, det)?;
    let mut w = Vec::with_capacity(a.len());
    for i in 0..a.len() {
        let replaced: Vec<Vec<Id>> = a
            .iter()
            .zip(b)
            .map(|(row, &bi)| {
                row.iter().enumerate().map(|(j, &v)| if j == i { bi } else { v }).collect()
            })
            .collect();
        let numerator = determinant(g, &replaced)?;
        w.push(g.mul(numerator, inverse)?);
    }
    Ok(Some(w))
}

/// Gaussian elimination on expressions, each column's pivot a constant or
/// an expression of the parameters; `None` where a column has none.
fn eliminate_with_parameter_pivots(
    g: &mut Graph,
    mut a: Vec<Vec<Id>>,
    mut b: Vec<Id>,
) -> crate::Result<Option<Vec<Id>>> {
    let n = a.len();
    for col in 0..n {
        let best = (col..n).filter_map(|r| pivot_class(g, a[r][col]).map(|c| (c, r))).min();
        let Some((class, pivot)) = best else {
            return Ok(None);
        };
        if class > 1 {
            return Ok(None);
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..n {
            if g.as_number(a[row][col]).is_some_and(|v| v.is_zero()) {
                continue;
            }
            let factor = g.div(a[row][col], a[col][col])?;
            for c in col + 1..n {
                let t = g.mul(factor, a[col][c])?;
                a[row][c] = g.sub(a[row][c], t)?;
            }
            let t = g.mul(factor, b[col])?;
            b[row] = g.sub(b[row], t)?;
            a[row][col] = g.zero();
        }
    }
    let mut w = vec![g.zero(); n];
    for row in (0..n).rev() {
        let mut acc = b[row];
        for c in row + 1..n {
            let t = g.mul(a[row][c], w[c])?;
            acc = g.sub(acc, t)?;
        }
        w[row] = g.div(acc, a[row][row])?;
    }
    Ok(Some(w))
}

/// The equations grouped into strongly connected components of "equation
/// i reads the unknown matched to equation k", each after the ones it reads.
fn blt_order(e: &[Vec<(usize, Id)>], owner: &[usize]) -> Vec<Vec<usize>> {
    let successors: Vec<Vec<usize>> = e
        .iter()
        .enumerate()
        .map(|(i, row)| row.iter().map(|&(j, _)| owner[j]).filter(|&k| k != i).collect())
        .collect();
    crate::dae::matching::strongly_connected(&successors)
}

/// `w = M⁻¹ g` for a constant matrix, by Gaussian elimination with exact
/// rational pivots (largest magnitude for floats); `None` if singular.
pub fn solve_constant(g: &mut Graph, mut m: Vec<Vec<Number>>, mut rhs: Vec<Id>) -> Option<Vec<Id>> {
    let k = m.len();
    for col in 0..k {
        let pivot = (col..k)
            .filter(|&r| !m[r][col].is_zero())
            .max_by(|&a, &b| m[a][col].abs().to_f64().total_cmp(&m[b][col].abs().to_f64()))?;
        m.swap(col, pivot);
        rhs.swap(col, pivot);
        for row in col + 1..k {
            if m[row][col].is_zero() {
                continue;
            }
            let factor = m[row][col].checked_mul(reciprocal(m[col][col])?)?;
            let (above, below) = m.split_at_mut(row);
            for (target, &p) in below[0][col..].iter_mut().zip(&above[col][col..]) {
                *target = target.checked_add(factor.checked_mul(p)?.negated())?;
            }
            let f = g.num(factor.negated());
            let scaled = g.mul(f, rhs[col]).ok()?;
            rhs[row] = g.add(rhs[row], scaled).ok()?;
        }
    }
    let mut z = vec![g.zero(); k];
    for row in (0..k).rev() {
        let mut acc = rhs[row];
        for c in row + 1..k {
            let coefficient = g.num(m[row][c].negated());
            let t = g.mul(coefficient, z[c]).ok()?;
            acc = g.add(acc, t).ok()?;
        }
        let inv = g.num(reciprocal(m[row][row])?);
        z[row] = g.mul(inv, acc).ok()?;
    }
    Some(z)
}

fn reciprocal(n: Number) -> Option<Number> {
    n.pow(Number::MINUS_ONE)
}
