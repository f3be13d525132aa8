//! Kuhn's augmenting paths for a matching of rows (equations) to columns
//! (unknowns), shared by the reduction and the mass-matrix form.

/// Tries to match row `r` by an augmenting path through `columns(r)`:
/// `owner[c]` is the row matched to column `c`; `seen` marks the columns
/// this search visited (the alternating paths from `r`, which the caller
/// may read to name a structurally singular subsystem).
pub fn augment<C: IntoIterator<Item = usize>>(
    r: usize,
    columns: &impl Fn(usize) -> C,
    owner: &mut [Option<usize>],
    seen: &mut [bool],
) -> bool {
    for c in columns(r) {
        if !seen[c] {
            seen[c] = true;
            if owner[c].is_none_or(|other| augment(other, columns, owner, seen)) {
                owner[c] = Some(r);
                return true;
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn augmenting_paths_reassign_earlier_rows() {
        // Row 0 takes column 0 first; row 1 can only use column 0, so row 0
        // moves to column 1.
        let rows: [&[usize]; 2] = [&[0, 1], &[0]];
        let columns = |r: usize| rows[r].iter().copied();
        let mut owner = vec![None; 2];
        for r in 0..2 {
            assert!(augment(r, &columns, &mut owner, &mut [false; 2]));
        }
        assert_eq!(owner, [Some(1), Some(0)]);
        // A third row over the same columns finds no path.
        let more: [&[usize]; 3] = [&[0, 1], &[0], &[1]];
        let columns = |r: usize| more[r].iter().copied();
        let mut owner = vec![None; 2];
        let matched: Vec<bool> =
            (0..3).map(|r| augment(r, &columns, &mut owner, &mut [false; 2])).collect();
        assert_eq!(matched, [true, true, false]);
    }
}
