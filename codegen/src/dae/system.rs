//! The first-order system every pass after reduction reads: the states
//! as slots, how each slot's derivative and each algebraic variable is
//! computed, the blocks solved at run time, the invariants to project onto
//! and their levels. Passes produce and read it; it depends on none of
//! them.

use crate::{Id, SymbolId};

/// One first-order state of the reduced system.
#[derive(Clone)]
pub struct Slot {
    /// `x`, `der(x)`, `q[1]`, ...
    pub name: String,
    /// The symbol it reads as.
    pub symbol: SymbolId,
    /// Its initial value (constants and parameters).
    pub init: Id,
    /// Kept by consistent initialization (`state(x0).fixed()`).
    pub fixed: bool,
    /// The slot's derivative is determined by the dynamics (a velocity),
    /// not by another slot or an explicit `der(x) == u` (a position).
    pub velocity_like: bool,
}

/// `.reinit(x, value)` on the reduced system: slot `slot` takes `value`
/// (an expression of the slots, the time, the parameters and the `pre(..)`
/// symbols).
#[derive(Clone, Copy)]
pub struct SlotAction {
    /// The slot written.
    pub slot: usize,
    /// Its new value.
    pub value: Id,
}

/// How a slot's derivative is computed.
#[derive(Clone)]
pub enum SlotDerivative {
    /// `f_i` as an expression.
    Explicit(Id),
    /// An expression of the state and of run-time block unknowns (an
    /// acceleration eliminated from a KKT block), evaluated after the solve.
    AfterSolve(Id),
    /// Unknown `row` of mass block `block`, solved at run time.
    Block {
        /// Which block.
        block: usize,
        /// Which of its unknowns.
        row: usize,
    },
}

/// The reduced system.
pub struct FirstOrder {
    /// Each algebraic variable's value at `(t, y)`, in declaration order.
    pub algebraics: Vec<AlgebraicValue>,
    /// Constraints and hidden constraints to project onto.
    pub invariants: Vec<Invariant>,
    /// Projection levels fixed by construction (a variational system's:
    /// the model's levels, then the same levels for each sensitivity
    /// column); `None` to group the invariants by level.
    pub projection: Option<Vec<ProjectionLevel>>,
    /// The differentiation index.
    pub index: usize,
    /// Unknowns solved at run time: symbol, block, row.
    pub block_unknowns: Vec<(SymbolId, usize, usize)>,
    /// The user's equations as residuals `lhs − rhs`, before index
    /// reduction (a combination free of the highest derivatives in place
    /// of an equation it made dependent).
    pub residuals: Vec<Id>,
    /// Equations replaced by such a combination, each with the equations
    /// it combines.
    pub combined: Vec<(usize, Vec<usize>)>,
    /// The user's equations as residuals, as written.
    pub written: Vec<Id>,
    /// Pivots of that combination: expressions of the parameters a run
    /// must not make zero.
    pub rank_conditions: Vec<RankCondition>,
    /// How often index reduction differentiated each equation.
    pub differentiations: Vec<usize>,
    /// The highest derivative of each state.
    pub highest: Vec<SymbolId>,
    /// The algebraic variables.
    pub algebraic_symbols: Vec<SymbolId>,
    /// Only the mass-matrix form exists (an algebraic equation is
    /// nonlinear in the algebraic variables, and they do not close into a
    /// Newton block): the model is emitted as it.
    pub mass_only: bool,
    /// Algebraic equations nonlinear in their variables, solved by Newton
    /// at each evaluation; their variables are read as run-time block
    /// `blocks.len()` (after the linear blocks).
    pub newton: Option<NewtonBlock>,
    /// States in solution order.
    pub slots: Vec<Slot>,
    /// `dy_i` for each slot.
    pub derivatives: Vec<SlotDerivative>,
    /// Blocks solved at run time.
    pub blocks: Vec<MassBlock>,
    /// Output values, with highest derivatives replaced by their solutions.
    pub outputs: Vec<Id>,
    /// Event functions, likewise.
    pub events: Vec<Id>,
    /// The initial equations' residuals `lhs − rhs` (`initial(..)`),
    /// likewise: functions of the time and the slots, zero at the start.
    pub initial: Vec<Id>,
    /// What each event, then each clock, does where it fires, in order.
    pub actions: Vec<Vec<SlotAction>>,
    /// How the equations are solved for their unknowns, in causal order.
    pub structure: StructureInfo,
}

/// How the equations are solved for their unknowns: the aliases removed,
/// then in causal order the unknowns solved one equation at a time and the
/// blocks solved together.
#[derive(Clone, Debug, Default)]
pub struct StructureInfo {
    /// Variables removed as aliases, with their values.
    pub aliases: Vec<(SymbolId, Id)>,
    /// Unknowns solved one equation at a time, symbolically, in causal
    /// order.
    pub one_at_a_time: Vec<SymbolId>,
    /// The blocks solved together, in causal order.
    pub blocks: Vec<BlockInfo>,
}

/// Equations that determine their unknowns together.
#[derive(Clone, Debug)]
pub struct BlockInfo {
    /// The unknowns (as many as the equations) before tearing.
    pub unknowns: Vec<SymbolId>,
    /// How they are solved.
    pub solution: BlockSolution,
}

/// How a block is solved at each evaluation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockSolution {
    /// Linear, solved symbolically.
    Symbolic,
    /// Linear, by a run-time LU of `lu` unknowns.
    Linear {
        /// The LU's unknowns.
        lu: usize,
    },
    /// Nonlinear, by Newton on `tearing` variables.
    Newton {
        /// The tearing variables.
        tearing: usize,
    },
    /// Left to the mass-matrix form.
    MassMatrix,
}

/// `E z = g` for unknowns that no symbolic solve could separate.
pub struct MassBlock {
    /// Names of the unknowns, for the singular-matrix error.
    pub unknowns: Vec<String>,
    /// `E`, row-major, `k × k`.
    pub matrix: Vec<Id>,
    /// `g`.
    pub rhs: Vec<Id>,
}

/// A constraint or one of its derivatives that must hold along solutions
/// but that the integrated system no longer enforces.
#[derive(Clone, Debug)]
pub struct Invariant {
    /// The user's equation it comes from.
    pub equation: usize,
    /// How often the equation was differentiated to get it (0: itself).
    pub level: usize,
    /// `Φ^(level)(t, y)`, zero on the solution.
    pub residual: Id,
    /// The user's statement, as source text.
    pub text: String,
}

/// A pivot of the elimination: an expression of the parameters that must
/// not vanish for the generated code to hold.
#[derive(Clone)]
pub struct RankCondition {
    /// The pivot.
    pub pivot: Id,
    /// What it is, for the error: "the coefficient of `der(y1)` in `…`".
    pub text: String,
}

/// The nonlinear algebraic equations and the variables they determine,
/// torn: Newton iterates on the tearing variables, the others are
/// computed from them.
pub struct NewtonBlock {
    /// The tearing variables, in declaration order.
    pub unknowns: Vec<SymbolId>,
    /// Their names.
    pub names: Vec<String>,
    /// Their initial guesses (`algebraic(z0)`).
    pub guesses: Vec<Id>,
    /// The block's equations (indices into the model's), in the model's
    /// order.
    pub equations: Vec<usize>,
    /// The residuals left after tearing, `g(t, y, z)` in the tearing
    /// variables `z` alone: as many as they.
    pub residuals: Vec<Id>,
    /// The other variables of the block, in the order computed, each an
    /// expression of the tearing variables, the states and the parameters.
    pub computed: Vec<(SymbolId, Id)>,
    /// The block's size before tearing: its equations and variables.
    pub size: usize,
    /// The torn system's strongly connected parts in causal order, each
    /// `(tearing variables, residuals)` by index into `unknowns` and
    /// `residuals`: solved one after the other.
    pub components: Vec<(Vec<usize>, Vec<usize>)>,
    /// The block's equations as written, for the errors.
    pub texts: Vec<String>,
}

impl NewtonBlock {
    /// Whether the block determines `s` (iterated on or computed).
    pub fn determines(&self, s: &SymbolId) -> bool {
        self.unknowns.contains(s) || self.computed.iter().any(|(c, _)| c == s)
    }
}

/// One projection level: which invariants and which states.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProjectionLevel {
    /// Indices into the invariants.
    pub rows: Vec<usize>,
    /// Slot indices the level corrects, ascending.
    pub slots: Vec<usize>,
}

/// How an algebraic variable's value is computed.
pub type AlgebraicValue = SlotDerivative;

/// The first-order system as its tests read it: each slot with its start
/// and derivative, then the run-time blocks, the invariants with their
/// levels, the outputs and the event functions.
impl std::fmt::Display for crate::expr::display::WithGraph<'_, FirstOrder> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (g, sys) = (self.graph, self.value);
        let name = |s: SymbolId| g.symbol(s).name.clone();
        let value = |d: &SlotDerivative| match d {
            SlotDerivative::Explicit(e) => g.show(*e).to_string(),
            SlotDerivative::AfterSolve(e) => format!("{} after the solve", g.show(*e)),
            SlotDerivative::Block { block, row } => format!("block {block} unknown {row}"),
        };
        writeln!(f, "index {}", sys.index)?;
        let report = &sys.structure;
        for &(a, v) in &report.aliases {
            writeln!(f, "alias {} = {}", name(a), g.show(v))?;
        }
        if !report.one_at_a_time.is_empty() {
            let order: Vec<String> = report.one_at_a_time.iter().map(|&s| name(s)).collect();
            writeln!(f, "one at a time: {}", order.join(", "))?;
        }
        for b in &report.blocks {
            let unknowns: Vec<String> = b.unknowns.iter().map(|&s| name(s)).collect();
            let how = match b.solution {
                BlockSolution::Symbolic => "symbolic".to_string(),
                BlockSolution::Linear { lu } => format!("LU of {lu}"),
                BlockSolution::Newton { tearing } => format!("Newton on {tearing}"),
                BlockSolution::MassMatrix => "mass-matrix form".to_string(),
            };
            writeln!(f, "block {}: {how}", unknowns.join(", "))?;
        }
        for (slot, d) in sys.slots.iter().zip(&sys.derivatives) {
            let fixed = if slot.fixed { " fixed" } else { "" };
            let velocity = if slot.velocity_like { " velocity" } else { "" };
            writeln!(f, "slot {} = {}{fixed}{velocity}", slot.name, g.show(slot.init))?;
            writeln!(f, "  der = {}", value(d))?;
        }
        for (&s, d) in sys.algebraic_symbols.iter().zip(&sys.algebraics) {
            writeln!(f, "algebraic {} = {}", name(s), value(d))?;
        }
        for (b, block) in sys.blocks.iter().enumerate() {
            let k = block.rhs.len();
            writeln!(f, "block {b} in {}", block.unknowns.join(", "))?;
            for r in 0..k {
                let row: Vec<String> = block.matrix[r * k..(r + 1) * k]
                    .iter()
                    .map(|&e| g.show(e).to_string())
                    .collect();
                writeln!(f, "  [{}] = {}", row.join(", "), g.show(block.rhs[r]))?;
            }
        }
        if let Some(newton) = &sys.newton {
            writeln!(f, "newton in {} (torn from {})", newton.names.join(", "), newton.size)?;
            for &(s, v) in &newton.computed {
                writeln!(f, "  {} = {}", name(s), g.show(v))?;
            }
            for &r in &newton.residuals {
                writeln!(f, "  0 = {}", g.show(r))?;
            }
        }
        for inv in &sys.invariants {
            writeln!(f, "invariant level {}: {} = 0", inv.level, g.show(inv.residual))?;
        }
        if let Some(levels) = &sys.projection {
            for (k, level) in levels.iter().enumerate() {
                writeln!(f, "projection {k}: rows {:?} slots {:?}", level.rows, level.slots)?;
            }
        }
        for c in &sys.rank_conditions {
            writeln!(f, "nonzero {} ({})", g.show(c.pivot), c.text)?;
        }
        for &o in &sys.outputs {
            writeln!(f, "output {}", g.show(o))?;
        }
        for &e in &sys.events {
            writeln!(f, "event {}", g.show(e))?;
        }
        Ok(())
    }
}
