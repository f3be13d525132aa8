//! The programs of `output`: the outputs, then the algebraic variables,
//! alone or in groups that share most of their work, each saying whether
//! it reads an unknown solved at run time (its blocks are then solved
//! first, by their own program).

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::programs::rhs::{block_solve_programs, RhsEntry};
use crate::programs::schedule::Program;
use crate::{FxHashMap, Graph, Id, SymbolId};

/// Values computed together by one arm of `output`.
pub struct OutputGroup {
    /// Their indices among the observables.
    pub members: Vec<usize>,
    /// Whether they read an unknown a run-time block solves.
    pub reads_block: bool,
    /// Their program.
    pub program: Program,
}

/// The programs of `output`.
pub struct OutputPrograms {
    /// The run-time blocks assembled for a solve before a value that reads
    /// them: where each entry goes, and the program.
    pub block_solve: (Vec<RhsEntry>, Program),
    /// The groups, in the order of their members.
    pub groups: Vec<OutputGroup>,
}

/// The programs of `output`.
pub fn output_programs(g: &mut Graph, sys: &FirstOrder) -> crate::Result<OutputPrograms> {
    let mut observables = sys.outputs.clone();
    for a in &sys.algebraics {
        match a {
            SlotDerivative::Explicit(e) | SlotDerivative::AfterSolve(e) => observables.push(*e),
            SlotDerivative::Block { block, row } => {
                let (_, symbol) = sys
                    .block_unknowns
                    .iter()
                    .map(|&(s, b, r)| ((b, r), s))
                    .find(|&(at, _)| at == (*block, *row))
                    .ok_or_else(|| crate::Error::Unsupported {
                        message: "an algebraic variable lost its block".into(),
                    })?;
                observables.push(g.symbol_node(symbol));
            }
        }
    }
    let block_solve = block_solve_programs(g, sys);
    let solved: FxHashMap<SymbolId, ()> =
        sys.block_unknowns.iter().map(|&(s, _, _)| (s, ())).collect();
    let mut groups = Vec::new();
    for members in groups_sharing_work(g, &observables) {
        let values: Vec<Id> = members.iter().map(|&k| observables[k]).collect();
        let reads_block =
            values.iter().any(|&o| g.free_symbols(o).iter().any(|s| solved.contains_key(s)));
        let program = g.schedule(&values);
        groups.push(OutputGroup { members, reads_block, program });
    }
    Ok(OutputPrograms { block_solve, groups })
}

/// Outputs read one at a time, each computing what it needs, except
/// where consecutive outputs share most of their work (a body's position,
/// attitude and velocity at the end of a chain of joints): those form a
/// group computed together, so the chain is written once per group rather
/// than once per output. Small outputs stay alone.
fn groups_sharing_work(g: &Graph, observables: &[Id]) -> Vec<Vec<usize>> {
    const ALONE_BELOW: usize = 64;
    const MOST: usize = 16;
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut seen: FxHashMap<Id, ()> = Default::default();
    for (k, &o) in observables.iter().enumerate() {
        let needs = g.reachable(&[o]);
        let shared = needs.iter().filter(|id| seen.contains_key(id)).count();
        let joins = needs.len() >= ALONE_BELOW
            && 2 * shared >= needs.len()
            && groups.last().is_some_and(|last| last.len() < MOST);
        match (joins, groups.last_mut()) {
            (true, Some(last)) => last.push(k),
            _ => {
                groups.push(vec![k]);
                seen.clear();
            }
        }
        seen.extend(needs.into_iter().map(|id| (id, ())));
    }
    groups
}
