//! Expansion: the generated struct, its `Default`, and its `daegen::Model`
//! implementation, assembled from one emitter per item (`rhs`, `jacobian`,
//! `events`, `outputs`, `taylor_items`, `newton`, `docs`), each printing
//! the programs the pipeline scheduled (`programs`). The last step; it
//! decides nothing.

use crate::analysis::{SensitivityAnalysis, SystemAnalysis};
use crate::dae::system::FirstOrder;
use crate::emit::docs::{
    dae_analysis, info, info_with, parameter_method, struct_and_default, type_name, Naming,
};
use crate::emit::events::{event_rates_method, events_method};
use crate::emit::jacobian::jacobian_items;
use crate::emit::layout::{fixed_size_body, index, program_into, rolled_program, Layout};
use crate::emit::newton::newton_block_code;
use crate::emit::outputs::output_arms;
use crate::emit::rhs::rhs_items;
use crate::emit::taylor_items::taylor_items;
use crate::front::attributes::Attributes;
use crate::front::ir::ModelIr;
use crate::pipeline::Analysed;
use crate::programs::mass_form::PrimaryPrograms;
use crate::programs::schedule::Program;
use crate::programs::{ModelPrograms, SystemPrograms};
use crate::Graph;
use proc_macro2::TokenStream;
use quote::{quote, quote_spanned};

/// The full expansion of an analysed model: each item of the `Model`
/// implementation printed from its programs.
pub fn expand(model: &Analysed) -> TokenStream {
    let Analysed { ir, attributes, model, sensitivities, programs } = model;
    expand_system(ir, &Naming::of(ir), model, attributes, sensitivities.as_ref(), programs)
}

/// The expansion of one first-order system of the model: its own, or its
/// variational system's.
fn expand_system(
    ir: &ModelIr,
    naming: &Naming,
    analysis: &SystemAnalysis,
    attributes: &Attributes,
    sensitivities: Option<&SensitivityAnalysis>,
    programs: &SystemPrograms,
) -> TokenStream {
    // Most of its length is the quoted `Model` implementation the items fill.
    let sys = &analysis.system;
    let programs = match programs {
        SystemPrograms::MassOnly(programs) => {
            return expand_mass_only(ir, naming, analysis, programs)
        }
        SystemPrograms::Model(programs) => programs,
    };
    let p: &ModelPrograms = programs;
    let g = &ir.graph;
    let name = type_name(naming);
    let n = sys.slots.len();
    let mut layout = Layout::of_system(sys);
    let (newton_method, newton_solve, newton_solve_for_outputs) =
        newton_block_code(g, &layout, sys, p.newton.as_ref(), &name);
    let initial_state = program_into(g, &layout, &p.initial_state, "y");
    let (block_setup, rhs_body, block_solve) = rhs_items(g, &layout, sys, &p.rhs);
    let event_rates_method = event_rates_method(g, &layout, sys, p.event_rates.as_ref());
    let jacobian = jacobian_items(g, &layout, n, p.jacobian.as_ref());
    let output_arms = output_arms(g, &mut layout, sys, &newton_solve_for_outputs, &p.outputs);
    let constraint_methods = crate::emit::constraints::constraint_methods(
        g,
        &layout,
        sys,
        &analysis.projection,
        p.constraints.as_ref(),
    );
    let initialization_methods = crate::emit::initialization::initialization_methods(
        g,
        &layout,
        n,
        p.initialization.as_ref(),
    );
    let events_method =
        events_method(g, &mut layout, sys, p.events.as_ref(), &p.outputs.block_solve);
    let start_relations = crate::emit::actions::start_relations_method(sys, &ir.relations);
    let act_method = crate::emit::actions::act_method(g, &layout, sys, &ir.pre, &p.actions);
    let rhs_method_body = fixed_size_body(
        &index(n),
        "dy",
        &index(n),
        quote!(#newton_solve #block_setup #rhs_body #block_solve),
    );
    let (taylor_tokens, taylor_unavailable) = match &analysis.taylor {
        Ok(analysis) => taylor_items(g, &mut layout, n, analysis, &p.taylor),
        Err(_) => (TokenStream::new(), None),
    };
    let taylor_unavailable_const = match &taylor_unavailable {
        Some(reason) => {
            quote!(const TAYLOR_TAPE: ::daegen::Availability = ::daegen::Availability::Unavailable(#reason);)
        }
        None => quote!(
            const TAYLOR_TAPE: ::daegen::Availability = ::daegen::Availability::Available;
        ),
    };
    let own_rhs =
        own_rhs_method(g, &layout, sys, attributes.sensitivity_columns, p.own_rhs.as_ref());
    // A model with sensitivities has none: they would need the variational
    // equations of the mass-matrix form too.
    let (mass_form_type, mass_form_method) = match (&p.mass_form, &analysis.mass_form) {
        (Some(programs), Ok(Some(form))) => {
            let params: Vec<syn::Ident> = ir.params.iter().map(|p| p.ident.clone()).collect();
            crate::emit::mass_form::emit_mass_form(g, form, programs, &name, &ir.vis, &params)
        }
        _ => (TokenStream::new(), TokenStream::new()),
    };
    let clock_method = crate::emit::actions::clock_method(g, &layout, &p.clocks);
    let input_breakpoints = crate::emit::actions::input_breakpoints_method(
        g,
        &layout,
        &ir.inputs,
        p.breakpoints.as_ref(),
    );
    let info = info(ir, naming, sys);
    let parameter = parameter_method(ir);
    let degenerate = degenerate_parameters_method(g, &layout, sys, p.degenerate.as_ref());
    let model_index = index(sys.index);
    let mut analysis = dae_analysis(ir, sys);
    if let Some(reason) = &taylor_unavailable {
        let note = format!("`Method::Taylor` is not available: {reason}.");
        analysis = if analysis.is_empty() { note } else { format!("{analysis}\n\n{note}") };
    }
    let struct_and_default = struct_and_default(ir, naming, &analysis);
    let n_lit = index(n);
    let batch = match (attributes.batch, &p.batch) {
        (Some((lanes, _)), Some(program)) => {
            crate::emit::batch::batch_items(g, ir, naming, sys, lanes, program)
        }
        _ => TokenStream::new(),
    };
    let sensitivity_columns = match attributes.sensitivity_columns {
        0 => TokenStream::new(),
        k => {
            let k = index(k);
            quote!(const SENSITIVITY_COLUMNS: usize = #k;)
        }
    };
    // The sensitivities' type is a model of its own.
    let sensitivity_type = match (sensitivities, &p.sensitivities) {
        (Some(sensitivities), Some(programs)) => {
            sensitivity_items(ir, naming, sensitivities, programs)
        }
        _ => TokenStream::new(),
    };
    // A file the model was built from: `include_bytes!` makes the build
    // depend on it, so editing it expands the model again.
    let dependencies = ir.depends_on.iter().map(|path| {
        let path = path.to_string_lossy();
        quote!(
            const _: &[u8] = ::core::include_bytes!(#path);
        )
    });
    quote! {
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

            #initialization_methods

            #start_relations

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
    }
}

/// `<Model>Sensitivities`, the model with its forward sensitivities as
/// states (`dae::variational`), expanded as a model of its own, and
/// `<Model>::with_sensitivities` that makes one with the same parameters.
fn sensitivity_items(
    ir: &ModelIr,
    naming: &Naming,
    sensitivities: &SensitivityAnalysis,
    programs: &SystemPrograms,
) -> TokenStream {
    let name = type_name(naming);
    let Ok(augmented) = &sensitivities.model else { return TokenStream::new() };
    let wrt = &sensitivities.wrt;
    let listed: Vec<String> = wrt.iter().map(|w| format!("`{}`", w.name())).collect();
    let fn_name = &naming.fn_name;
    let own = Naming {
        fn_name: syn::Ident::new(&format!("{fn_name}_sensitivities"), fn_name.span()),
        doc: format!(
            "The model `{name}` with its forward sensitivities with respect to {}: its states, then for each of them the states `d(x)/d(w)` = ∂x/∂w, integrated with them by any method (`Solution::sensitivity(t, \"x\", \"w\")` reads them). Made by `{name}::with_sensitivities`.",
            listed.join(", ")
        ),
    };
    let model = expand_system(ir, &own, augmented, &sensitivities.attributes, None, programs);
    let sensitivity_name = type_name(&own);
    let fields: Vec<&syn::Ident> = ir.params.iter().map(|p| &p.ident).collect();
    let vis = &ir.vis;
    let method_doc = format!(
        " This model with its forward sensitivities with respect to {}, as the model [`{sensitivity_name}`].",
        listed.join(", ")
    );
    quote! {
        #model

        impl #name {
            #[doc = #method_doc]
            #vis fn with_sensitivities(&self) -> #sensitivity_name {
                #sensitivity_name { #(#fields: self.#fields),* }
            }
        }
    }
}

/// A model whose algebraic equations are nonlinear in the algebraic
/// variables: its own `Model` implementation is the mass-matrix form,
/// integrated by RADAU5 (the algebraic variables are states).
fn expand_mass_only(
    ir: &ModelIr,
    naming: &Naming,
    analysis: &SystemAnalysis,
    programs: &PrimaryPrograms,
) -> TokenStream {
    let sys = &analysis.system;
    let name = type_name(naming);
    let form = match &analysis.mass_form {
        Ok(Some(form)) => form,
        _ => return TokenStream::new(),
    };
    let items = crate::emit::mass_form::primary_items(&ir.graph, form, programs);
    let model_index = index(sys.index);
    let struct_and_default = struct_and_default(ir, naming, &dae_analysis(ir, sys));
    // The algebraic variables are states here.
    let states: Vec<&str> = form.names.iter().map(String::as_str).collect();
    let info = info_with(ir, naming, &states, &[], &sys.structure);
    let parameter = parameter_method(ir);
    let reason = "the model runs in mass-matrix form only (an algebraic equation is nonlinear in its variable)";
    quote! {
        #struct_and_default

        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic)]
        impl ::daegen::Model for #name {
            const INDEX: usize = #model_index;
            const INFO: ::daegen::ModelInfo = #info;
            const TAYLOR_TAPE: ::daegen::Availability = ::daegen::Availability::Unavailable(#reason);
            #parameter
            #items
        }
    }
}

/// `Model::degenerate_parameters`: the first pivot of the elimination that
/// combined the model's equations (see `derivative_free`) that the run's
/// parameters make zero or not finite.
fn degenerate_parameters_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
) -> TokenStream {
    let Some(program) = program else { return TokenStream::new() };
    let k = index(sys.rank_conditions.len());
    let values = program_into(g, layout, program, "pivots");
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
    let naming = Naming::of(ir);
    let name = type_name(&naming);
    let struct_and_default = struct_and_default(ir, &naming, "");
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
/// derivatives (the first `n / (1 + columns)` slots) without the
/// columns'; nothing for other models.
fn own_rhs_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    columns: usize,
    program: Option<&Program>,
) -> TokenStream {
    let Some(program) = program else { return TokenStream::new() };
    let n = sys.slots.len();
    let own = n / (1 + columns);
    let slots: Vec<usize> = (0..own).collect();
    let body = fixed_size_body(
        &index(n),
        "dy",
        &index(own),
        rolled_program(g, layout, program, ("dy", &slots)),
    );
    quote! {
        #[inline]
        fn own_rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::option::Option<::core::result::Result<(), ::daegen::EvalError>> {
            ::core::option::Option::Some((|| -> ::core::result::Result<(), ::daegen::EvalError> { #body })())
        }
    }
}
