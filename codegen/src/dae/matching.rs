//! Bipartite matching of rows (equations) to columns (unknowns) and what
//! follows from one: Kuhn's augmenting paths, the strongly connected
//! components of the matched system in causal order (Tarjan 1972; Duff &
//! Reid 1978), and the alternating paths of the Dulmage–Mendelsohn
//! decomposition that name an over- or under-determined part (Dulmage &
//! Mendelsohn 1958; Pothen & Fan 1990, §2).

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

/// A maximum matching of the rows `0..rows.len()` to the columns
/// `0..n_columns`, `rows[r]` the columns row `r` involves: `owner[c]` is
/// the row matched to column `c`. A cheap pass first gives each row the
/// free column that fewest rows involve (a derivative only its own
/// equation has, before a node voltage three equations share; after
/// Karp & Sipser 1981), so the augmenting searches (Kuhn 1955) only run
/// for the rows it left and the matching follows the equations' own
/// unknowns, whose entries pivot the symbolic eliminations: a sparse
/// system of thousands of equations matches in about linear time.
pub fn maximum_matching(rows: &[Vec<usize>], n_columns: usize) -> Vec<Option<usize>> {
    let mut degree = vec![0usize; n_columns];
    rows.iter().flatten().for_each(|&c| degree[c] += 1);
    let mut owner: Vec<Option<usize>> = vec![None; n_columns];
    let mut left = Vec::new();
    for (r, columns) in rows.iter().enumerate() {
        let free = columns.iter().filter(|&&c| owner[c].is_none());
        match free.min_by_key(|&&c| degree[c]) {
            Some(&c) => owner[c] = Some(r),
            None => left.push(r),
        }
    }
    let columns = |r: usize| rows[r].iter().copied();
    let mut seen = vec![false; n_columns];
    for r in left {
        augment(r, &columns, &mut owner, &mut seen);
        seen.iter_mut().for_each(|s| *s = false);
    }
    owner
}

/// The rows and columns reachable from the unmatched row `r` by alternating
/// paths (a row to each of its columns, a column to the row matched to it):
/// an over-determined part, more rows than columns (Dulmage–Mendelsohn).
/// Both sorted.
pub fn over_determined(
    r: usize,
    rows: &[Vec<usize>],
    owner: &[Option<usize>],
) -> (Vec<usize>, Vec<usize>) {
    let (mut found_rows, mut found_columns) = (vec![r], Vec::new());
    let mut row_seen = std::collections::BTreeSet::from([r]);
    let mut column_seen = std::collections::BTreeSet::new();
    let mut k = 0;
    while k < found_rows.len() {
        for &c in &rows[found_rows[k]] {
            if column_seen.insert(c) {
                found_columns.push(c);
                if let Some(next) = owner[c].filter(|&o| row_seen.insert(o)) {
                    found_rows.push(next);
                }
            }
        }
        k += 1;
    }
    (row_seen.into_iter().collect(), column_seen.into_iter().collect())
}

/// The rows and columns reachable from the unmatched column `c` by
/// alternating paths (a column to each row that involves it, a row to the
/// column matched to it): an under-determined part, more columns than rows.
/// `column_of[r]` is the column matched to row `r`. Both sorted.
pub fn under_determined(
    c: usize,
    rows_of_column: &[Vec<usize>],
    column_of: &[Option<usize>],
) -> (Vec<usize>, Vec<usize>) {
    let mut found_columns = vec![c];
    let mut column_seen = std::collections::BTreeSet::from([c]);
    let mut row_seen = std::collections::BTreeSet::new();
    let mut k = 0;
    while k < found_columns.len() {
        for &r in &rows_of_column[found_columns[k]] {
            if row_seen.insert(r) {
                if let Some(next) = column_of[r].filter(|&m| column_seen.insert(m)) {
                    found_columns.push(next);
                }
            }
        }
        k += 1;
    }
    (row_seen.into_iter().collect(), column_seen.into_iter().collect())
}

/// The strongly connected components of the graph with edges
/// `successors[v]`, each after every component it reaches (Tarjan 1972,
/// iterative, so a chain of thousands of nodes needs no deep stack). With
/// "equation i reads the unknown matched to equation k" as the edges, this
/// is the block-lower-triangular order: each block after the blocks whose
/// unknowns it reads. Each component's nodes are sorted.
pub fn strongly_connected(successors: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let m = successors.len();
    let (mut index, mut low) = (vec![usize::MAX; m], vec![0; m]);
    let mut on_stack = vec![false; m];
    let (mut stack, mut out) = (Vec::new(), Vec::new());
    let mut next = 0;
    for root in 0..m {
        if index[root] != usize::MAX {
            continue;
        }
        // (node, position in its successor list)
        let mut call: Vec<(usize, usize)> = vec![(root, 0)];
        index[root] = next;
        low[root] = next;
        next += 1;
        stack.push(root);
        on_stack[root] = true;
        while let Some(&mut (v, ref mut pos)) = call.last_mut() {
            if let Some(&w) = successors[v].get(*pos) {
                *pos += 1;
                if index[w] == usize::MAX {
                    index[w] = next;
                    low[w] = next;
                    next += 1;
                    stack.push(w);
                    on_stack[w] = true;
                    call.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            call.pop();
            if let Some(&(parent, _)) = call.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut component = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                component.sort_unstable();
                out.push(component);
            }
        }
    }
    out
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

    #[test]
    fn maximum_matching_of_a_long_chain_is_perfect() {
        // Row k involves columns k and k+1, the greedy pass takes column k
        // for each; the last row has only the last column.
        let n = 5000;
        let rows: Vec<Vec<usize>> =
            (0..n).map(|k| if k + 1 < n { vec![k + 1, k] } else { vec![k] }).collect();
        let owner = maximum_matching(&rows, n);
        assert!(owner.iter().all(Option::is_some));
    }

    #[test]
    fn alternating_paths_name_the_defective_parts() {
        // Rows 0, 1, 2 over columns 0, 1 (three equations, two unknowns);
        // column 2 in no row (nothing determines it).
        let rows = vec![vec![0, 1], vec![0], vec![1]];
        let owner = maximum_matching(&rows, 3);
        let unmatched_row = (0..3).find(|r| !owner.contains(&Some(*r))).unwrap();
        assert_eq!(over_determined(unmatched_row, &rows, &owner), (vec![0, 1, 2], vec![0, 1]));
        let mut rows_of_column = vec![Vec::new(); 3];
        let mut column_of = vec![None; 3];
        for (r, cols) in rows.iter().enumerate() {
            cols.iter().for_each(|&c| rows_of_column[c].push(r));
        }
        for (c, o) in owner.iter().enumerate() {
            if let Some(r) = o {
                column_of[*r] = Some(c);
            }
        }
        assert_eq!(under_determined(2, &rows_of_column, &column_of), (vec![], vec![2]));
        // One row over two columns: both columns reached, the row too.
        let rows = vec![vec![0, 1]];
        let owner = maximum_matching(&rows, 2);
        let free = (0..2).find(|&c| owner[c].is_none()).unwrap();
        let rows_of_column = vec![vec![0], vec![0]];
        let column_of = vec![Some(1 - free)];
        assert_eq!(under_determined(free, &rows_of_column, &column_of), (vec![0], vec![0, 1]));
    }

    #[test]
    fn components_come_after_the_ones_they_read() {
        // 0 reads 1, 1 and 2 read each other, 3 reads nothing.
        let successors = vec![vec![1], vec![2], vec![1], vec![]];
        assert_eq!(strongly_connected(&successors), [vec![1, 2], vec![0], vec![3]]);
    }
}
