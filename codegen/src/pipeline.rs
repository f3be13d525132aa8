//! The compile-time pipeline in one function, [`analyse`]: every stage in
//! order, each a pass of its own, returning the analysed model that
//! `emit` assembles into tokens.
//!
//! The order is part of the output: the graph grows as the stages run,
//! and node ids order the generated code's operands and temporaries.

pub use crate::analysis::{SensitivityAnalysis, SystemAnalysis};
use crate::dae::system::FirstOrder;
use crate::dae::variational::Wrt;
use crate::front::attributes::Attributes;
use crate::front::components::definitions::Definitions;
use crate::front::ctxt::Ctxt;
use crate::front::ir::ModelIr;
use crate::taylor::analysis::TaylorAnalysis;
use crate::verify;
use crate::{FxHashMap, Graph, SymbolId};
use proc_macro2::TokenStream;

/// A model that lowered and reduced without error, with everything
/// emission needs decided.
pub struct Analysed {
    /// The model IR: its graph, declarations, names and spans.
    pub ir: ModelIr,
    /// The attribute's arguments.
    pub attributes: Attributes,
    /// The model's first-order system and its analyses.
    pub model: SystemAnalysis,
    /// The forward sensitivities asked for with `sensitivities = [..]`.
    pub sensitivities: Option<SensitivityAnalysis>,
    /// Every generated item's programs.
    pub programs: crate::programs::SystemPrograms,
}

/// Runs every stage in order: attributes → lower → tied states (those
/// hidden behind algebraic variables too) → structure (equations,
/// combinations free of derivatives, index reduction) → reduction
/// (structural check, aliases, causal order, the Newton block, the linear
/// blocks, the first-order system; mode by mode for a model with modes) →
/// inputs not differentiated → the starts initial equations decide →
/// variational →
/// mass form → Taylor → projection levels → programs. `Err` holds the
/// IR as far as it got (for the stub) when a stage reported errors to `cx`.
pub fn analyse(
    cx: &mut Ctxt,
    attr: TokenStream,
    item: &syn::ItemFn,
) -> Result<Analysed, Box<ModelIr>> {
    analyse_with_parts(cx, attr, item, Definitions::default())
}

/// [`analyse`], with the user's components `parts` callable by the model.
/// A part the model calls and `parts` lacks ends the analysis after
/// lowering (`Err`, with `ir.missing_parts` naming them).
pub fn analyse_with_parts(
    cx: &mut Ctxt,
    attr: TokenStream,
    item: &syn::ItemFn,
    parts: Definitions,
) -> Result<Analysed, Box<ModelIr>> {
    let attributes = crate::front::attributes::attributes(cx, attr);
    let mut ir = lower(cx, item, attributes.recursive, parts);
    if !ir.missing_parts.is_empty() {
        return Err(Box::new(ir));
    }
    if cx.is_ok() && !verify::after(cx, "lowering", &ir, None) {
        return Err(Box::new(ir));
    }
    if cx.is_ok() && !ir.instances.is_empty() {
        // What it found is for the pass's snapshots; the IR holds the result.
        let _found = crate::dae::tied_states::eliminate_tied_states(cx, &mut ir);
        if cx.is_ok() && !verify::after(cx, "the tied states", &ir, None) {
            return Err(Box::new(ir));
        }
    }
    let system = match cx.is_ok() {
        true => crate::dae::modes::reduce_modes(cx, &mut ir, structure_and_reduction),
        false => None,
    };
    let Some(system) = system.filter(|_| cx.is_ok()) else { return Err(Box::new(ir)) };
    if !verify::after(cx, "the reduction", &ir, Some(&system)) {
        return Err(Box::new(ir));
    }
    if !crate::dae::inputs::inputs_not_differentiated(cx, &ir, &system) {
        return Err(Box::new(ir));
    }
    let Some(initialization) = crate::dae::initialization::initialization(cx, &ir, &system) else {
        return Err(Box::new(ir));
    };
    let sensitivities = variational(cx, &mut ir, &attributes, &system);
    if !cx.is_ok() {
        return Err(Box::new(ir));
    }
    if let Some((_, Ok(augmented), _)) = &sensitivities {
        if !verify::after(cx, "the variational equations", &ir, Some(augmented)) {
            return Err(Box::new(ir));
        }
    }
    let mut model = system_analysis(&mut ir.graph, ir.time, system, &attributes);
    model.initialization = initialization;
    let sensitivities = sensitivities.map(|(wrt, augmented, attributes)| {
        let model =
            augmented.map(|system| system_analysis(&mut ir.graph, ir.time, system, &attributes));
        SensitivityAnalysis { wrt, attributes, model }
    });
    if !verify::after(cx, "the mass form, Taylor and projection analyses", &ir, None) {
        return Err(Box::new(ir));
    }
    let programs =
        crate::programs::programs(cx, &mut ir, &model, &attributes, sensitivities.as_ref());
    let Some(programs) = programs else { return Err(Box::new(ir)) };
    if !verify::after(cx, "the programs", &ir, None) {
        return Err(Box::new(ir));
    }
    Ok(Analysed { ir, attributes, model, sensitivities, programs })
}

/// The structure and reduction of one mode's equations (all of them for a
/// model without modes), step by step: the equations as residuals and
/// each state's order, combinations free of the highest derivatives, the
/// index reduced; then [`reduction`].
pub fn structure_and_reduction(cx: &mut Ctxt, ir: &mut ModelIr) -> Option<FirstOrder> {
    use crate::dae::structure;
    let equations = structure::equations(cx, ir)?;
    let separated = structure::separated(cx, ir, &equations)?;
    let structure = structure::index_reduced(cx, ir, equations, separated)?;
    reduction(cx, ir, structure)
}

/// The reduction of the structured equations, step by step: the
/// structural check, the aliases, the causal order, the Newton block and
/// its tearing, the linear blocks, and the first-order system they make.
pub fn reduction(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    structure: crate::dae::structure::Structure,
) -> Option<FirstOrder> {
    use crate::dae::reduce;
    if !reduce::check(cx, ir, &structure) {
        return None;
    }
    let left = reduce::without_aliases(cx, ir, &structure)?;
    let sorted = reduce::sorted(cx, ir, &structure, &left)?;
    let newton = reduce::newton(cx, ir, &structure, &left, &sorted)?;
    let unknowns = reduce::solved_unknowns(cx, ir, &structure, &left, &sorted, newton.as_ref())?;
    reduce::first_order(cx, ir, structure, left, sorted, newton, unknowns)
}

/// The model function lowered into the model IR, its scenes by
/// `mechanics` (in relative joint coordinates when `recursive`). Errors go
/// to `cx`; the IR is returned even then, with the parts that could be
/// read.
pub fn lower(cx: &mut Ctxt, item: &syn::ItemFn, recursive: bool, parts: Definitions) -> ModelIr {
    crate::front::lower::lower_with::<crate::mechanics::Scene>(cx, item, recursive, parts)
}

/// The forward sensitivities the attribute asks for, resolved against the
/// model, with their variational system and the attributes it is expanded
/// with; `None` when none were asked for.
fn variational(
    cx: &mut Ctxt,
    ir: &mut ModelIr,
    attributes: &Attributes,
    system: &FirstOrder,
) -> Option<(Vec<Wrt>, crate::Result<FirstOrder>, Attributes)> {
    let wrt = crate::dae::variational::resolve(cx, &attributes.sensitivities, ir, system);
    if wrt.is_empty() {
        return None;
    }
    if let Some(why) = crate::dae::variational::unsupported(system) {
        // Said on the attribute's list, which asked for them.
        let list = &attributes.sensitivities;
        cx.error_at(quote::quote!(#(#list),*), why);
        return None;
    }
    let augmented = crate::dae::variational::variational_system(&mut ir.graph, system, &wrt)
        .map_err(|message| crate::Error::Unsupported { message });
    let plain = Attributes {
        batch: None,
        sensitivities: Vec::new(),
        sensitivity_columns: wrt.len(),
        ..attributes.clone()
    };
    Some((wrt, augmented, plain))
}

/// The analyses of one first-order system after its reduction: the
/// mass-matrix form, the Taylor methods' part, the projection levels.
fn system_analysis(
    g: &mut Graph,
    time: SymbolId,
    system: FirstOrder,
    attributes: &Attributes,
) -> SystemAnalysis {
    // A model with sensitivities has none: it would need the variational
    // equations of the mass-matrix form too.
    // A form too large for a symbolic Jacobian (a robot's dynamics with
    // its joints' dampers) is left out where the explicit form runs: its
    // Jacobian has no differenced fallback.
    let mass_form = match system.mass_only || attributes.sensitivity_columns == 0 {
        true => crate::dae::mass_form::mass_form(g, &system).map(|form| {
            form.filter(|f| {
                system.mass_only || crate::expr::jacobian::symbolic_jacobian_pays(g, &f.rows)
            })
        }),
        false => Ok(None),
    };
    // A model that runs in mass-matrix form only has no Taylor code.
    let taylor = match system.mass_only {
        true => Ok(TaylorAnalysis::Refused(String::new())),
        false => crate::taylor::analysis::taylor_analysis(g, &system, time, attributes),
    };
    let slot_of: FxHashMap<SymbolId, usize> =
        system.slots.iter().enumerate().map(|(i, s)| (s.symbol, i)).collect();
    let projection = crate::dae::constraints::projection_levels(g, &system, &slot_of);
    SystemAnalysis { system, mass_form, taylor, projection, initialization: None }
}
