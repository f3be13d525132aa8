//! The last analysis: every generated item's straight-line programs, with
//! the derivatives they need (the Jacobian, the event rates, the
//! constraint rows, the Newton and mass-form Jacobians) and the verdicts
//! emission would otherwise make (a batch's eligibility, which outputs
//! read a run-time block), common subexpressions shared within each
//! program (`schedule`). Emission then only prints them.
//!
//! The order of [`programs`] is part of the output: the graph grows as
//! derivatives are taken and programs scheduled, and node ids order the
//! generated operands and temporaries.

pub mod batch;
pub mod derivatives;
pub mod hybrid;
pub mod initialization;
pub mod mass_form;
pub mod newton;
pub mod outputs;
pub mod rhs;
pub mod schedule;
pub mod taylor;

use crate::analysis::{SensitivityAnalysis, SystemAnalysis};
use crate::front::attributes::Attributes;
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::{Id, SymbolId};
use derivatives::{ConstraintPrograms, JacobianPrograms};
use hybrid::Actions;
use mass_form::{MassFormPrograms, PrimaryPrograms};
use newton::NewtonPrograms;
use outputs::OutputPrograms;
use rhs::RhsPrograms;
use schedule::Program;
use taylor::TaylorPrograms;

/// The programs of one first-order system: the model's own, or its
/// variational system's.
pub enum SystemPrograms {
    /// A model with its `Model` implementation.
    Model(Box<ModelPrograms>),
    /// A model that runs in its mass-matrix form only.
    MassOnly(Box<PrimaryPrograms>),
}

/// Every program of a model's items, in the order they were scheduled.
pub struct ModelPrograms {
    /// The Newton block's iterations.
    pub newton: Option<NewtonPrograms>,
    /// `initial_state`.
    pub initial_state: Program,
    /// `rhs`.
    pub rhs: RhsPrograms,
    /// `event_rates`, where f is explicit.
    pub event_rates: Option<Program>,
    /// `jacobian` and `time_derivative`, where symbolic.
    pub jacobian: Option<JacobianPrograms>,
    /// `output`.
    pub outputs: OutputPrograms,
    /// The constraint methods.
    pub constraints: Option<ConstraintPrograms>,
    /// `events`.
    pub events: Option<Program>,
    /// `act`, by trigger.
    pub actions: Vec<Actions>,
    /// The Taylor methods' items.
    pub taylor: TaylorPrograms,
    /// `own_rhs` of a model with sensitivity columns.
    pub own_rhs: Option<Program>,
    /// The mass-matrix form, where the model has one and is not hybrid.
    pub mass_form: Option<MassFormPrograms>,
    /// `clock`, by clock.
    pub clocks: Vec<Program>,
    /// `degenerate_parameters`.
    pub degenerate: Option<Program>,
    /// The batch type's right-hand side, where `batch = L` asks for one.
    pub batch: Option<Program>,
    /// The model with its sensitivities, a model of its own.
    pub sensitivities: Option<Box<SystemPrograms>>,
    /// The instants of switches in the time alone (`heaviside(t − t0)`),
    /// where the model has any: scheduled last, so no other item's
    /// operands move.
    pub breakpoints: Option<Program>,
    /// The initialization's residuals and Jacobian, where the model has
    /// initial equations; scheduled last, likewise.
    pub initialization: Option<initialization::InitializationPrograms>,
}

/// Whether the model has actions, clocks or inputs (its mass-matrix form
/// carries none).
pub fn is_hybrid(ir: &ModelIr, analysis: &SystemAnalysis) -> bool {
    !ir.inputs.is_empty()
        || !ir.clocks.is_empty()
        || analysis.system.actions.iter().any(|a| !a.is_empty())
}

/// The programs of `analysis`'s system, item by item in the order the
/// expansion writes them; `None` where an item met an error, reported to
/// `cx` (on the call the user wrote, for a function that is not smooth
/// where it is differentiated; else on the model's name).
pub fn programs(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    analysis: &SystemAnalysis,
    attributes: &Attributes,
    sensitivities: Option<&SensitivityAnalysis>,
) -> Option<SystemPrograms> {
    match system_programs(ir, analysis, attributes, sensitivities) {
        Ok(programs) => Some(programs),
        Err(Failure::Batch(message)) => {
            let span = attributes.batch.map_or(ir.fn_name.span(), |(_, span)| span);
            cx.error_span(span, message);
            None
        }
        Err(Failure::Analysis(e @ crate::Error::NotSmooth { node, .. })) => {
            // The call itself when the right-hand side kept the node the
            // user wrote; else the first such call.
            let calls = &ir.non_smooth_calls;
            match calls.iter().find(|(id, _)| *id == node).or(calls.first()) {
                Some((_, tokens)) => cx.error_at(tokens, e),
                None => cx.error_at(&ir.fn_name, e),
            }
            None
        }
        Err(Failure::Analysis(e)) => {
            cx.error_at(&ir.fn_name, e);
            None
        }
    }
}

/// Why a system has no programs: an analysis failed where an item needed
/// it, or `batch = L` asks for lanes the model cannot run on.
enum Failure {
    Analysis(crate::Error),
    Batch(String),
}

impl From<crate::Error> for Failure {
    fn from(e: crate::Error) -> Failure {
        Failure::Analysis(e)
    }
}

/// [`programs`], or the first failure.
fn system_programs(
    ir: &mut ModelIr,
    analysis: &SystemAnalysis,
    attributes: &Attributes,
    sensitivities: Option<&SensitivityAnalysis>,
) -> Result<SystemPrograms, Failure> {
    let sys = &analysis.system;
    if sys.mass_only {
        let programs = mass_only_programs(ir, analysis)?;
        return Ok(SystemPrograms::MassOnly(Box::new(programs)));
    }
    let hybrid = is_hybrid(ir, analysis);
    let inputs: Vec<(SymbolId, SymbolId)> = ir.inputs.iter().map(|i| (i.symbol, i.rate)).collect();
    let (time, discretes) = (ir.time, ir.discretes.clone());
    let g = &mut ir.graph;
    let newton = newton::newton_programs(g, sys);
    let inits: Vec<Id> = sys.slots.iter().map(|s| s.init).collect();
    let initial_state = g.schedule(&inits);
    let rhs = rhs::rhs_programs(g, sys);
    let explicit = rhs::explicit_derivatives(sys);
    let event_rates =
        derivatives::event_rates_program(g, sys, (time, &inputs), explicit.as_deref())?;
    let slots: Vec<SymbolId> = sys.slots.iter().map(|s| s.symbol).collect();
    let jacobian = derivatives::jacobian_programs(
        g,
        &slots,
        (time, &inputs, &discretes),
        explicit.as_deref(),
    )?;
    let outputs = outputs::output_programs(g, sys)?;
    let constraints = derivatives::constraint_programs(g, &slots, sys, &analysis.projection)?;
    let events = (!sys.events.is_empty()).then(|| g.schedule(&sys.events));
    let actions = hybrid::action_programs(g, sys);
    let taylor = analysis.taylor.as_ref().map_err(Clone::clone)?;
    let taylor = taylor::taylor_programs(g, taylor);
    let own_rhs = rhs::own_rhs_program(g, sys, attributes.sensitivity_columns);
    // A model with sensitivities has none: they would need the variational
    // equations of the mass-matrix form too.
    let mass_form = match hybrid {
        true => None,
        false => match analysis.mass_form.as_ref().map_err(Clone::clone)? {
            Some(form) => Some(mass_form::mass_form_programs(g, form)?),
            None => None,
        },
    };
    let clocks = hybrid::clock_programs(g, &ir.clocks);
    let degenerate = (!sys.rank_conditions.is_empty()).then(|| {
        let pivots: Vec<Id> = sys.rank_conditions.iter().map(|c| c.pivot).collect();
        g.schedule(&pivots)
    });
    let batch = match attributes.batch {
        Some(_) => Some(batch::batch_program(ir, sys).map_err(Failure::Batch)?),
        None => None,
    };
    let sensitivities = match sensitivities {
        Some(s) => {
            let augmented = s.model.as_ref().map_err(Clone::clone)?;
            Some(Box::new(system_programs(ir, augmented, &s.attributes, None)?))
        }
        None => None,
    };
    let breakpoints = breakpoint_program(ir)?;
    let initialization = match &analysis.initialization {
        Some(i) => Some(initialization::initialization_programs(&mut ir.graph, sys, i)?),
        None => None,
    };
    Ok(SystemPrograms::Model(Box::new(ModelPrograms {
        newton,
        initial_state,
        rhs,
        event_rates,
        jacobian,
        outputs,
        constraints,
        events,
        actions,
        taylor,
        own_rhs,
        mass_form,
        clocks,
        degenerate,
        batch,
        sensitivities,
        breakpoints,
        initialization,
    })))
}

/// The program of the instants where the model switches in the time
/// alone (`dae::time_events`), or `None` where it has none.
fn breakpoint_program(ir: &mut ModelIr) -> crate::Result<Option<Program>> {
    let mut roots: Vec<Id> = ir.equations.iter().flat_map(|e| [e.lhs, e.rhs]).collect();
    roots.extend(ir.outputs.iter().map(|o| o.value));
    roots.extend(ir.events.iter().map(|e| e.value));
    let g = &mut ir.graph;
    let instants = crate::dae::time_events::breakpoints(g, &roots, ir.time)?;
    Ok((!instants.is_empty()).then(|| g.schedule(&instants)))
}

/// The programs of a model whose algebraic equations are nonlinear in the
/// algebraic variables: its own `Model` implementation is the mass-matrix
/// form, integrated by RADAU5 (the algebraic variables are states).
fn mass_only_programs(
    ir: &mut ModelIr,
    analysis: &SystemAnalysis,
) -> crate::Result<PrimaryPrograms> {
    let sys = &analysis.system;
    if is_hybrid(ir, analysis) {
        return Err(crate::Error::Unsupported {
            message: "an algebraic equation is nonlinear in the algebraic variables and closes into no Newton block, so the model runs in its mass-matrix form, which has no actions, clocks or inputs yet: give the nonlinear equations' variables a guess each can be solved from, or leave the actions out".into(),
        });
    }
    let form = analysis.mass_form.as_ref().map_err(Clone::clone)?;
    let form = form.as_ref().ok_or_else(|| crate::Error::Unsupported {
        message: "an algebraic equation is nonlinear in the algebraic variables, and the differential equations do not solve symbolically for the highest derivatives: daegen cannot integrate this model yet".into(),
    })?;
    let mut inits: Vec<Id> = sys.slots.iter().map(|s| s.init).collect();
    inits.extend(ir.algebraics.iter().map(|a| a.init));
    mass_form::primary_programs(&mut ir.graph, form, inits, &sys.outputs)
}
