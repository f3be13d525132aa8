//! Combinations of equations in which the highest derivatives cancel.
//!
//! A circuit written node by node reads `−c1·der(y1) + c1·der(y2) == f1`
//! and `c1·der(y1) − c1·der(y2) == f2`: every equation has a derivative, a
//! structural count (Pantelides) sees a regular system, yet the two rows of
//! the mass matrix are opposite and their sum says `0 == f1 + f2`, an
//! algebraic equation. This pass finds such combinations by exact Gaussian
//! elimination over the derivatives' coefficients — parameters kept
//! symbolic, pivots chosen where a generic parameter value makes them
//! largest — and replaces each dependent equation by its combination, free
//! of the highest derivatives. Index reduction then treats it as any other
//! constraint (differentiated once for the transistor amplifier: index 1).
//!
//! The elimination divides by pivots; where a run's parameters make one of
//! them zero the rank differs from the one the code was generated for, and
//! the run is refused ([`RankCondition`]). Coefficients may depend on the
//! states and time too (a nonlinear capacitor, `c(v)·(der(y1) − der(y2))`):
//! the rank is then the generic one, and a state where a pivot vanishes
//! shows as a non-finite derivative.

use crate::dae::system::RankCondition;
use crate::{FxHashMap, Graph, Id, SymbolId, SymbolKind};

/// The equations with their derivative-free combinations.
pub struct Separated {
    /// The residuals; a dependent equation's replaced by its combination.
    pub residuals: Vec<Id>,
    /// The equations replaced, each with the equations it combines.
    pub combined: Vec<(usize, Vec<usize>)>,
    /// Conditions on the parameters the elimination assumed.
    pub conditions: Vec<RankCondition>,
}

/// Why the separation stopped.
pub enum Failure {
    /// The model's equations could not be combined (a graph error).
    Graph(crate::Error),
    /// A combination vanishes identically: equation `equation` repeats the
    /// equations `of`.
    Dependent {
        /// The equation that adds nothing.
        equation: usize,
        /// The equations it is a combination of.
        of: Vec<usize>,
    },
}

impl From<crate::Error> for Failure {
    fn from(e: crate::Error) -> Failure {
        Failure::Graph(e)
    }
}

/// A deterministic stream of generic values in [1, 2): the same model
/// always expands to the same code.
struct Generic(u64);

impl Generic {
    fn next(&mut self) -> f64 {
        // SplitMix64.
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        1.0 + (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Finds the combinations of `residuals` free of the highest derivatives
/// `z`; `texts` are the equations as written, `z_names` the derivatives'.
pub fn separate(
    g: &mut Graph,
    residuals: &[Id],
    z: &[SymbolId],
    texts: &[String],
    z_names: &[String],
) -> Result<Separated, Failure> {
    // Gaussian elimination with its pivot choice and the bookkeeping of which equations each
    // row combines, kept together so the invariants between them are in view.
    let mut out =
        Separated { residuals: residuals.to_vec(), combined: Vec::new(), conditions: Vec::new() };
    let z_index: FxHashMap<SymbolId, usize> = z.iter().enumerate().map(|(j, &s)| (s, j)).collect();
    // The rows: equations linear in their highest derivatives, with
    // coefficients of the parameters, the states and time (not of the
    // algebraic variables).
    let mut rows: Vec<(usize, Vec<(usize, Id)>)> = Vec::new();
    for (i, &r) in residuals.iter().enumerate() {
        let derivatives: Vec<usize> =
            g.free_symbols(r).into_iter().filter_map(|s| z_index.get(&s).copied()).collect();
        if derivatives.is_empty() {
            continue;
        }
        let mut coefficients = Vec::with_capacity(derivatives.len());
        let mut eligible = true;
        for &j in &derivatives {
            let c = g.partial(r, z[j])?;
            let known = g.free_symbols(c).iter().all(|&s| {
                !z_index.contains_key(&s) && !matches!(g.symbol(s).kind, SymbolKind::Algebraic)
            });
            // A coefficient that switches with a mode may vanish in it: no
            // combination divides by it.
            if !known || g.reads_switching(c) {
                eligible = false;
                break;
            }
            coefficients.push((j, c));
        }
        if eligible {
            rows.push((i, coefficients));
        }
    }
    if rows.len() < 2 {
        return Ok(out);
    }
    // The coefficients at a generic point of the parameters and states.
    let mut generic = Generic(0x6461_6567_656e_2d72);
    let mut generic_value: FxHashMap<SymbolId, f64> = FxHashMap::default();
    let m = rows.len();
    let columns: Vec<usize> = {
        let mut c: Vec<usize> =
            rows.iter().flat_map(|(_, cs)| cs.iter().map(|&(j, _)| j)).collect();
        c.sort_unstable();
        c.dedup();
        c
    };
    let zero = g.zero();
    let one = g.one();
    let mut symbolic: Vec<Vec<Id>> = vec![vec![zero; columns.len()]; m];
    let mut numeric: Vec<Vec<f64>> = vec![vec![0.0; columns.len()]; m];
    for (k, (_, coefficients)) in rows.iter().enumerate() {
        for &(j, c) in coefficients {
            let col = columns.binary_search(&j).unwrap_or(0);
            symbolic[k][col] = c;
            for s in g.free_symbols(c) {
                generic_value.entry(s).or_insert_with(|| generic.next());
            }
            numeric[k][col] = g.eval(&[c], &|s| generic_value.get(&s).copied().unwrap_or(1.0))[0];
        }
    }
    let scale = numeric.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs())).max(f64::MIN_POSITIVE);
    // W: each row as a combination of the original rows.
    let mut weights: Vec<Vec<Id>> =
        (0..m).map(|k| (0..m).map(|i| if i == k { one } else { zero }).collect()).collect();
    let mut pivoted = vec![false; m];
    for col in 0..columns.len() {
        let Some(p) = (0..m)
            .filter(|&k| !pivoted[k])
            .max_by(|&a, &b| numeric[a][col].abs().total_cmp(&numeric[b][col].abs()))
        else {
            break;
        };
        if numeric[p][col].abs() <= 1e-9 * scale {
            continue;
        }
        pivoted[p] = true;
        let pivot = symbolic[p][col];
        // A pivot of the parameters is checked before a run; one of the
        // states would surface as a non-finite derivative where it vanishes.
        let of_parameters = g
            .free_symbols(pivot)
            .iter()
            .all(|&s| matches!(g.symbol(s).kind, SymbolKind::Parameter));
        if g.as_number(pivot).is_none() && of_parameters {
            let (i, _) = rows[p];
            out.conditions.push(RankCondition {
                pivot,
                text: format!("the coefficient of `{}` in `{}`", z_names[columns[col]], texts[i]),
            });
        }
        for k in 0..m {
            if pivoted[k] || numeric[k][col] == 0.0 {
                continue;
            }
            let factor = g.div(symbolic[k][col], pivot)?;
            let ratio = numeric[k][col] / numeric[p][col];
            for c in 0..columns.len() {
                numeric[k][c] -= ratio * numeric[p][c];
                let scaled = g.mul(factor, symbolic[p][c])?;
                symbolic[k][c] = g.sub(symbolic[k][c], scaled)?;
            }
            numeric[k][col] = 0.0;
            for i in 0..m {
                let scaled = g.mul(factor, weights[p][i])?;
                weights[k][i] = g.sub(weights[k][i], scaled)?;
            }
        }
    }
    // Rows never pivoted are zero: their weights combine the equations
    // into one free of the highest derivatives.
    let z_zero: FxHashMap<SymbolId, Id> = z.iter().map(|&s| (s, zero)).collect();
    for k in (0..m).filter(|&k| !pivoted[k]) {
        let mut terms = Vec::new();
        let mut combines = Vec::new();
        for (i, &w) in weights[k].iter().enumerate() {
            if g.as_number(w).is_some_and(|v| v.is_zero()) {
                continue;
            }
            let without = g.substitute(residuals[rows[i].0], &z_zero)?;
            terms.push(g.mul(w, without)?);
            combines.push(rows[i].0);
        }
        let combination = g.sum(&terms)?;
        // A combination that vanishes at a generic point of everything
        // repeats the others.
        let mut everything = Generic(0x636f_6d62_696e_6564);
        let mut values: FxHashMap<SymbolId, f64> = FxHashMap::default();
        let mut value_of = |g: &Graph, ids: &[Id]| {
            for &id in ids {
                for s in g.free_symbols(id) {
                    values.entry(s).or_insert_with(|| everything.next());
                }
            }
            let vals = values.clone();
            g.eval(ids, &|s| vals.get(&s).copied().unwrap_or(1.0))
        };
        let value = value_of(g, &[combination])[0];
        let sizes = value_of(g, &terms);
        let size = sizes.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let equation = rows[k].0;
        if value.abs() <= 1e-12 * size || combination == zero {
            return Err(Failure::Dependent {
                equation,
                of: combines.into_iter().filter(|&i| i != equation).collect(),
            });
        }
        out.residuals[equation] = combination;
        out.combined.push((equation, combines));
    }
    // Without a combination the pivots divided nothing the code uses.
    if out.combined.is_empty() {
        out.conditions.clear();
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// States y1, y2 in `g`, and the symbols of y1', y2'.
    fn two_states_and_their_rates(g: &mut Graph) -> [SymbolId; 2] {
        let y = g.state_symbols(&["y1", "y2"]).unwrap();
        let (s1, s2) = (y[0], y[1]);
        let d1 = g.derivative(s1, 1).unwrap();
        let d2 = g.derivative(s2, 1).unwrap();
        [g.as_symbol(d1).unwrap(), g.as_symbol(d2).unwrap()]
    }

    #[test]
    fn opposite_rows_combine_into_an_algebraic_equation() {
        let mut g = Graph::new();
        g.parameter("c").unwrap();
        let z = two_states_and_their_rates(&mut g);
        // c·(y2' − y1') − y1 and c·(y1' − y2') − y2 + 1.
        let r1 = g.parse("c*(der(y2) - der(y1)) - y1").unwrap();
        let r2 = g.parse("c*(der(y1) - der(y2)) - y2 + 1").unwrap();
        let texts = ["a".to_string(), "b".to_string()];
        let names = ["der(y1)".to_string(), "der(y2)".to_string()];
        let Ok(out) = separate(&mut g, &[r1, r2], &z, &texts, &names) else { panic!("separates") };
        assert_eq!(out.combined.len(), 1);
        let (replaced, _) = out.combined[0];
        let combination = out.residuals[replaced];
        // −y1 − y2 + 1 up to the sign of the combination.
        let v = g.eval_named(combination, &[("y1", 0.25), ("y2", 0.5), ("c", 3.0)]);
        assert!((v.abs() - 0.25).abs() < 1e-15, "{v}");
        assert!(g.free_symbols(combination).iter().all(|s| !z.contains(s)));
        assert_eq!(out.conditions.len(), 1, "one pivot: c");
    }

    #[test]
    fn regular_and_repeated_systems_are_told_apart() {
        let mut g = Graph::new();
        let z = two_states_and_their_rates(&mut g);
        let texts = ["a".to_string(), "b".to_string()];
        let names = ["der(y1)".to_string(), "der(y2)".to_string()];
        // Regular: nothing to combine.
        let r1 = g.parse("der(y1) + der(y2) - y1").unwrap();
        let r2 = g.parse("der(y1) - der(y2) - y2").unwrap();
        let Ok(out) = separate(&mut g, &[r1, r2], &z, &texts, &names) else { panic!("separates") };
        assert!(out.combined.is_empty());
        // The same equation twice, scaled: dependent.
        let r3 = g.parse("2*der(y1) + 2*der(y2) - 2*y1").unwrap();
        assert!(matches!(
            separate(&mut g, &[r1, r3], &z, &texts, &names),
            Err(Failure::Dependent { .. })
        ));
    }
}
