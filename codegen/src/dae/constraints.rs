//! The constraint methods of a DAE model: the invariants that index
//! reduction left (a constraint and its derivatives below the level the
//! integrated system uses), grouped by level for projection, with each
//! level's Jacobian with respect to the states it corrects.
//!
//! Level k corrects the states that its invariants involve and no lower
//! level does: positions for `Φ = 0`, velocities for `Φ_q v + Φ_t = 0`
//! (Hairer–Wanner II §VII.2; Simbody's project-every-step policy), so a
//! correction at one level leaves the levels below it satisfied.

use crate::dae::system::{FirstOrder, ProjectionLevel};
use crate::{FxHashMap, Graph, SymbolId};

/// Groups the invariants by level and picks the states each level corrects.
pub fn projection_levels(
    g: &Graph,
    sys: &FirstOrder,
    slot_of: &FxHashMap<SymbolId, usize>,
) -> Vec<ProjectionLevel> {
    if let Some(levels) = &sys.projection {
        return levels.clone();
    }
    let deepest = sys.invariants.iter().map(|i| i.level).max();
    let mut levels = Vec::new();
    let mut lower: Vec<usize> = Vec::new();
    for level in 0..=deepest.unwrap_or(0) {
        let rows: Vec<usize> =
            (0..sys.invariants.len()).filter(|&r| sys.invariants[r].level == level).collect();
        if rows.is_empty() {
            continue;
        }
        let mut involved: Vec<usize> = rows
            .iter()
            .flat_map(|&r| g.free_symbols(sys.invariants[r].residual))
            .filter_map(|s| slot_of.get(&s).copied())
            .collect();
        involved.sort_unstable();
        involved.dedup();
        let new: Vec<usize> = involved.iter().copied().filter(|s| !lower.contains(s)).collect();
        lower.extend(&involved);
        // A velocity-level constraint (non-holonomic, A(q) v = 0) corrects
        // the velocities it is linear in, not the positions it reads.
        let velocities: Vec<usize> =
            new.iter().copied().filter(|&s| sys.slots[s].velocity_like).collect();
        let new =
            if !velocities.is_empty() && velocities.len() < new.len() { velocities } else { new };
        match levels.last_mut() {
            // Nothing of its own to correct (the hidden constraints of a
            // linear DAE involve every state): projected jointly with the
            // level below, which a correction of its own would undo.
            Some(below) if new.is_empty() => {
                let below: &mut ProjectionLevel = below;
                below.rows.extend(rows);
                below.slots.extend(&involved);
                below.slots.sort_unstable();
                below.slots.dedup();
            }
            _ => {
                let slots = if new.is_empty() { involved } else { new };
                levels.push(ProjectionLevel { rows, slots });
            }
        }
    }
    levels
}
