//! Expansion: the generated struct, its `Default`, and its `daegen::Model`
//! implementation, assembled from one emitter per item (`rhs`, `jacobian`,
//! `events`, `outputs`, `taylor_items`, `newton`, `docs`). The last step;
//! everything it needs was decided before.

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::emit::docs::{
    dae_analysis, info, info_with, parameter_method, struct_and_default, type_name,
};
use crate::emit::events::{event_rates_method, events_method};
use crate::emit::jacobian::jacobian_items;
use crate::emit::layout::{fixed_size_body, index, program, rolled_program, Layout};
use crate::emit::newton::newton_block_code;
use crate::emit::outputs::output_arms;
use crate::emit::rhs::{explicit_derivatives, rhs_items};
use crate::emit::taylor_items::taylor_items;
use crate::front::attributes::Attributes;
use crate::front::ir::ModelIr;
use crate::pipeline::{Analysed, SensitivityAnalysis, SystemAnalysis};
use crate::{Graph, Id, SymbolId};
use proc_macro2::TokenStream;
use quote::{quote, quote_spanned};

/// The full expansion of an analysed model: each item of the `Model`
/// implementation from its emitter, in the order that fixes the shared
/// subexpressions (the graph grows as they run).
pub fn expand(model: &mut Analysed) -> crate::Result<TokenStream> {
    let Analysed { ir, attributes, model, sensitivities } = model;
    expand_system(ir, model, attributes, sensitivities.as_ref())
}

/// The expansion of one first-order system of the model: its own, or its
/// variational system's.
fn expand_system(
    ir: &mut ModelIr,
    analysis: &SystemAnalysis,
    attributes: &Attributes,
    sensitivities: Option<&SensitivityAnalysis>,
) -> crate::Result<TokenStream> {
    // Most of its length is the quoted `Model` implementation the items fill.
    let sys = &analysis.system;
    let name = type_name(ir);
    if sys.mass_only {
        return expand_mass_only(ir, analysis);
    }
    let n = sys.slots.len();
    let mut layout = Layout::of_system(sys);
    let (newton_method, newton_solve, newton_solve_for_outputs) =
        newton_block_code(&mut ir.graph, &layout, sys, &name);
    let g = &mut ir.graph;
    let inits: Vec<Id> = sys.slots.iter().map(|s| s.init).collect();
    let initial_state = program(g, &layout, &inits, &|i, v| {
        let i = index(i);
        quote!(y[#i] = #v;)
    });
    let (block_setup, rhs_body, block_solve) = rhs_items(g, &layout, sys);
    let explicit = explicit_derivatives(sys);
    let inputs: Vec<(SymbolId, SymbolId)> = ir.inputs.iter().map(|i| (i.symbol, i.rate)).collect();
    let event_rates_method =
        event_rates_method(g, &layout, sys, (ir.time, &inputs), explicit.as_ref())?;
    let slot_symbols: Vec<SymbolId> = sys.slots.iter().map(|s| s.symbol).collect();
    let jacobian =
        jacobian_items(g, &layout, &slot_symbols, (ir.time, &inputs, &ir.discretes), explicit)?;
    let output_arms = output_arms(g, &mut layout, sys, &newton_solve_for_outputs)?;
    let constraint_methods = crate::emit::constraints::constraint_methods(
        g,
        &|g, ids, assign| program(g, &layout, ids, assign),
        &slot_symbols,
        sys,
        &analysis.projection,
    )?;
    let events_method = events_method(g, &layout, sys);
    let act_method = crate::emit::actions::act_method(g, &layout, sys, &ir.pre);
    let rhs_method_body = fixed_size_body(
        &index(n),
        "dy",
        &index(n),
        quote!(#newton_solve #block_setup #rhs_body #block_solve),
    );
    let taylor = analysis.taylor.as_ref().map_err(Clone::clone)?;
    let (taylor_tokens, taylor_unavailable) = taylor_items(g, &mut layout, n, taylor);
    let taylor_unavailable_const = match &taylor_unavailable {
        Some(reason) => {
            quote!(const TAYLOR_TAPE: ::daegen::Availability = ::daegen::Availability::Unavailable(#reason);)
        }
        None => quote!(
            const TAYLOR_TAPE: ::daegen::Availability = ::daegen::Availability::Available;
        ),
    };
    // Last, so its partial derivatives cannot change the code above.
    let own_rhs = own_rhs_method(&mut ir.graph, &layout, sys, attributes.sensitivity_columns);
    // A model with sensitivities has none: they would need the variational
    // equations of the mass-matrix form too.
    let (mass_form_type, mass_form_method) = mass_form_items(ir, analysis, &name)?;
    let clock_method = crate::emit::actions::clock_method(&mut ir.graph, &layout, &ir.clocks);
    let input_breakpoints = crate::emit::actions::input_breakpoints_method(&ir.inputs);
    let info = info(ir, sys);
    let parameter = parameter_method(ir);
    let degenerate = degenerate_parameters_method(&mut ir.graph, &layout, sys);
    let model_index = index(sys.index);
    let mut analysis = dae_analysis(ir, sys);
    if let Some(reason) = &taylor_unavailable {
        let note = format!("`Method::Taylor` is not available: {reason}.");
        analysis = if analysis.is_empty() { note } else { format!("{analysis}\n\n{note}") };
    }
    let struct_and_default = struct_and_default(ir, &analysis);
    let n_lit = index(n);
    // Last of all: its program cannot change the model's own code.
    let batch = match attributes.batch {
        Some((lanes, span)) => match crate::emit::batch::batch_items(ir, sys, lanes) {
            Ok(items) => items,
            Err(message) => quote_spanned!(span=> ::core::compile_error!(#message);),
        },
        None => TokenStream::new(),
    };
    let sensitivity_columns = match attributes.sensitivity_columns {
        0 => TokenStream::new(),
        k => {
            let k = index(k);
            quote!(const SENSITIVITY_COLUMNS: usize = #k;)
        }
    };
    // Last too: the sensitivities' type is a model of its own.
    let sensitivity_type = match sensitivities {
        Some(sensitivities) => sensitivity_items(ir, sensitivities, &name)?,
        None => TokenStream::new(),
    };
    // A file the model was built from: `include_bytes!` makes the build
    // depend on it, so editing it expands the model again.
    let dependencies = ir.depends_on.iter().map(|path| {
        let path = path.to_string_lossy();
        quote!(
            const _: &[u8] = ::core::include_bytes!(#path);
        )
    });
    Ok(quote! {
        #struct_and_default

        #(#dependencies)*

        #batch

        #sensitivity_type

        #mass_form_type

        #newton_method

        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic)]
        impl ::daegen::Model for #name {
            const STATES: usize = #n_lit;
            type State = [f64; #n_lit];
            const INDEX: usize = #model_index;
            const INFO: ::daegen::ModelInfo = #info;
            #sensitivity_columns

            #parameter
            #degenerate

            fn initial_state(&self, y: &mut [f64]) {
                let ::core::result::Result::Ok(y) = <&mut [f64; #n_lit]>::try_from(y) else { return };
                #initial_state
            }

            fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                #rhs_method_body
            }

            #own_rhs

            #jacobian

            #taylor_tokens
            #taylor_unavailable_const

            #events_method

            #event_rates_method

            #act_method

            #clock_method

            #input_breakpoints

            #constraint_methods

            #mass_form_method

            #[inline]
            fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
                let ::core::result::Result::Ok(y) = <&[f64; #n_lit]>::try_from(y) else { return f64::NAN };
                match index {
                    #(#output_arms)*
                    _ => f64::NAN,
                }
            }
        }
    })
}

/// `<Model>Sensitivities`, the model with its forward sensitivities as
/// states (`dae::variational`), expanded as a model of its own, and
/// `<Model>::with_sensitivities` that makes one with the same parameters.
fn sensitivity_items(
    ir: &mut ModelIr,
    sensitivities: &SensitivityAnalysis,
    name: &syn::Ident,
) -> crate::Result<TokenStream> {
    let augmented = sensitivities.model.as_ref().map_err(Clone::clone)?;
    let wrt = &sensitivities.wrt;
    let listed: Vec<String> = wrt.iter().map(|w| format!("`{}`", w.name())).collect();
    let (fn_name, doc) = (ir.fn_name.clone(), ir.doc.clone());
    ir.fn_name = syn::Ident::new(&format!("{fn_name}_sensitivities"), fn_name.span());
    ir.doc = format!(
        "The model `{name}` with its forward sensitivities with respect to {}: its states, then for each of them the states `d(x)/d(w)` = ∂x/∂w, integrated with them by any method (`Solution::sensitivity(t, \"x\", \"w\")` reads them). Made by `{name}::with_sensitivities`.",
        listed.join(", ")
    );
    let expanded = expand_system(ir, augmented, &sensitivities.attributes, None);
    let sensitivity_name = type_name(ir);
    (ir.fn_name, ir.doc) = (fn_name, doc);
    let model = expanded?;
    let fields: Vec<&syn::Ident> = ir.params.iter().map(|p| &p.ident).collect();
    let vis = &ir.vis;
    let method_doc = format!(
        " This model with its forward sensitivities with respect to {}, as the model [`{sensitivity_name}`].",
        listed.join(", ")
    );
    Ok(quote! {
        #model

        impl #name {
            #[doc = #method_doc]
            #vis fn with_sensitivities(&self) -> #sensitivity_name {
                #sensitivity_name { #(#fields: self.#fields),* }
            }
        }
    })
}

/// The mass-matrix form's type and the `simulate_mass_form` that runs it,
/// for a DAE whose differential equations solve symbolically.
fn mass_form_items(
    ir: &mut ModelIr,
    analysis: &SystemAnalysis,
    name: &syn::Ident,
) -> crate::Result<(TokenStream, TokenStream)> {
    // The mass-matrix form carries no actions, clocks or inputs: a run
    // refuses the formulation for such a model.
    if is_hybrid(ir, &analysis.system) {
        return Ok((TokenStream::new(), TokenStream::new()));
    }
    Ok(match analysis.mass_form.as_ref().map_err(Clone::clone)? {
        Some(form) => {
            let form_layout = Layout::of_components(&form.components);
            let params: Vec<syn::Ident> = ir.params.iter().map(|p| p.ident.clone()).collect();
            crate::emit::mass_form::emit_mass_form(
                &mut ir.graph,
                form,
                name,
                &ir.vis,
                &params,
                &|g, ids, assign| program(g, &form_layout, ids, assign),
            )?
        }
        None => (TokenStream::new(), TokenStream::new()),
    })
}

/// Whether the model has actions, clocks or inputs.
fn is_hybrid(ir: &ModelIr, sys: &FirstOrder) -> bool {
    !ir.inputs.is_empty() || !ir.clocks.is_empty() || sys.actions.iter().any(|a| !a.is_empty())
}

/// A model whose algebraic equations are nonlinear in the algebraic
/// variables: its own `Model` implementation is the mass-matrix form,
/// integrated by RADAU5 (the algebraic variables are states).
fn expand_mass_only(ir: &mut ModelIr, analysis: &SystemAnalysis) -> crate::Result<TokenStream> {
    let sys = &analysis.system;
    if is_hybrid(ir, sys) {
        return Err(crate::Error::Unsupported {
            message: "an algebraic equation is nonlinear in the algebraic variables and closes into no Newton block, so the model runs in its mass-matrix form, which has no actions, clocks or inputs yet: give the nonlinear equations' variables a guess each can be solved from, or leave the actions out".into(),
        });
    }
    let name = type_name(ir);
    let g = &mut ir.graph;
    let form = analysis.mass_form.as_ref().map_err(Clone::clone)?;
    let form = form.as_ref().ok_or_else(|| crate::Error::Unsupported {
        message: "an algebraic equation is nonlinear in the algebraic variables, and the differential equations do not solve symbolically for the highest derivatives: daegen cannot integrate this model yet".into(),
    })?;
    let layout = Layout::of_components(&form.components);
    let zero = g.zero();
    let mut inits: Vec<Id> = sys.slots.iter().map(|s| s.init).collect();
    inits.extend(ir.algebraics.iter().map(|a| a.init));
    inits.resize(form.components.len(), zero);
    let items =
        crate::emit::mass_form::primary_items(g, form, &inits, &sys.outputs, &|g, ids, assign| {
            program(g, &layout, ids, assign)
        })?;
    let model_index = index(sys.index);
    let struct_and_default = struct_and_default(ir, &dae_analysis(ir, sys));
    // The algebraic variables are states here.
    let states: Vec<&str> = form.names.iter().map(String::as_str).collect();
    let info = info_with(ir, &states, &[], &sys.structure);
    let parameter = parameter_method(ir);
    let reason = "the model runs in mass-matrix form only (an algebraic equation is nonlinear in its variable)";
    Ok(quote! {
        #struct_and_default

        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic)]
        impl ::daegen::Model for #name {
            const INDEX: usize = #model_index;
            const INFO: ::daegen::ModelInfo = #info;
            const TAYLOR_TAPE: ::daegen::Availability = ::daegen::Availability::Unavailable(#reason);
            #parameter
            #items
        }
    })
}

/// `Model::degenerate_parameters`: the first pivot of the elimination that
/// combined the model's equations (see `derivative_free`) that the run's
/// parameters make zero or not finite.
fn degenerate_parameters_method(g: &mut Graph, layout: &Layout, sys: &FirstOrder) -> TokenStream {
    if sys.rank_conditions.is_empty() {
        return TokenStream::new();
    }
    let pivots: Vec<Id> = sys.rank_conditions.iter().map(|c| c.pivot).collect();
    let k = index(pivots.len());
    let values = program(g, layout, &pivots, &|i, v| {
        let i = index(i);
        quote!(pivots[#i] = #v;)
    });
    let texts = sys.rank_conditions.iter().map(|c| c.text.as_str());
    quote! {
        fn degenerate_parameters(&self) -> ::core::option::Option<&'static str> {
            let t = 0.0f64;
            let mut pivots = [0.0f64; #k];
            #values
            const CONDITIONS: [&str; #k] = [#(#texts),*];
            pivots
                .iter()
                .position(|p| *p == 0.0 || !p.is_finite())
                .map(|i| CONDITIONS[i])
        }
    }
}

/// What a model with errors expands to besides the errors: the struct and a
/// `Model` implementation that does nothing, so the user's other code still
/// type-checks and only the real mistakes are reported.
pub fn stub(ir: &ModelIr) -> TokenStream {
    let name = type_name(ir);
    let struct_and_default = struct_and_default(ir, "");
    let name_str = name.to_string();
    quote_spanned! {name.span()=>
        #struct_and_default

        #[allow(unused_variables)]
        impl ::daegen::Model for #name {
            const STATES: usize = 0;
            type State = [f64; 0];
            const INDEX: usize = 0;
            const INFO: ::daegen::ModelInfo = ::daegen::ModelInfo {
                name: #name_str, doc: "", states: &[], state_docs: &[], parameters: &[], parameter_docs: &[],
                outputs: &[], output_docs: &[], declared_outputs: &[], equations: 0, events: &[], clocks: &[], discrete: &[], inputs: &[], algebraics: &[], algebraic_docs: &[],
                structure: ::daegen::StructureInfo::NONE,
                components: &[],
            };
            fn initial_state(&self, y: &mut [f64]) {}
            fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                ::core::result::Result::Ok(())
            }
            fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
                f64::NAN
            }
        }
    }
}

/// `own_rhs` of a model with `columns` sensitivity columns: the model's own
/// derivatives (the first `n / (1 + columns)` slots, explicit in a
/// variational system) without the columns'; nothing for other models.
fn own_rhs_method(g: &mut Graph, layout: &Layout, sys: &FirstOrder, columns: usize) -> TokenStream {
    if columns == 0 {
        return TokenStream::new();
    }
    let n = sys.slots.len();
    let own = n / (1 + columns);
    let mut outputs = Vec::with_capacity(own);
    for d in &sys.derivatives[..own] {
        match d {
            SlotDerivative::Explicit(e) => outputs.push(*e),
            _ => return TokenStream::new(),
        }
    }
    let slots: Vec<usize> = (0..own).collect();
    let body = fixed_size_body(
        &index(n),
        "dy",
        &index(own),
        rolled_program(g, layout, &outputs, ("dy", &slots)),
    );
    quote! {
        #[inline]
        fn own_rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::option::Option<::core::result::Result<(), ::daegen::EvalError>> {
            ::core::option::Option::Some((|| -> ::core::result::Result<(), ::daegen::EvalError> { #body })())
        }
    }
}
