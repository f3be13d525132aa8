//! The programs of the Taylor methods' items: the economic scheme's
//! derivatives, one program per order, and the constants of the tape.

use crate::programs::schedule::Program;
use crate::taylor::analysis::TaylorAnalysis;
use crate::Graph;

/// The Taylor methods' programs.
pub struct TaylorPrograms {
    /// The economic derivatives of each order (`taylor = p`).
    pub economic: Vec<Program>,
    /// The tape's constants, where the model has a tape.
    pub constants: Option<Program>,
}

/// The Taylor methods' programs from the Taylor analysis.
pub fn taylor_programs(g: &mut Graph, analysis: &TaylorAnalysis) -> TaylorPrograms {
    match analysis {
        TaylorAnalysis::Scheme { economic, tape } => {
            let economic = economic.levels.iter().map(|level| g.schedule(level)).collect();
            TaylorPrograms { economic, constants: Some(g.schedule(&tape.constants)) }
        }
        TaylorAnalysis::Tape(tape) => {
            TaylorPrograms { economic: Vec::new(), constants: Some(g.schedule(&tape.constants)) }
        }
        TaylorAnalysis::Refused(_) => TaylorPrograms { economic: Vec::new(), constants: None },
    }
}
