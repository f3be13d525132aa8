//! The programs of a hybrid model's instants: each event's or clock's
//! actions, one program per `.reinit(x, value)` in the order written,
//! and each clock's period and first instant.

use crate::dae::system::FirstOrder;
use crate::front::ir::Clock;
use crate::programs::schedule::Program;
use crate::Graph;

/// The actions of one event or clock: each target slot with the program
/// of its new value.
pub type Actions = Vec<(usize, Program)>;

/// Every trigger's actions, by trigger (empty where it has none).
pub fn action_programs(g: &mut Graph, sys: &FirstOrder) -> Vec<Actions> {
    sys.actions
        .iter()
        .map(|actions| actions.iter().map(|a| (a.slot, g.schedule(&[a.value]))).collect())
        .collect()
}

/// Each clock's period and first instant, one program each.
pub fn clock_programs(g: &mut Graph, clocks: &[Clock]) -> Vec<Program> {
    clocks.iter().map(|c| g.schedule(&[c.period, c.offset])).collect()
}
