//! The items of a model's mass-matrix form (`dae::mass_form`): its `Model`
//! implementation for RADAU5, and the consistent start its primary form
//! hands over.

use crate::dae::mass_form::MassForm;
use crate::emit::layout::{fixed_size_body, program_into, straight_program, Layout};
use crate::programs::mass_form::{MassFormPrograms, PrimaryPrograms};
use crate::Graph;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// The `Model` items both uses of the form share: sizes, mass, the
/// right-hand side and its analytic Jacobian.
fn model_items(g: &Graph, form: &MassForm, programs: &MassFormPrograms) -> TokenStream {
    let index = Literal::usize_unsuffixed;
    let layout = Layout::of_components(&form.components);
    let n = index(form.components.len());
    let rhs = program_into(g, &layout, &programs.rhs, "dy");
    let nnz = index(programs.pattern.len());
    let pattern = programs.pattern.iter().map(|&(r, c)| {
        let (r, c) = (index(r), index(c));
        quote!((#r, #c))
    });
    let values = program_into(g, &layout, &programs.jacobian, "values");
    let mass = match &programs.mass {
        None => {
            let diagonal = (0..form.components.len()).map(|i| {
                if i < form.differential {
                    quote!(1.0)
                } else {
                    quote!(0.0)
                }
            });
            quote!(const MASS: ::daegen::MassMatrix = ::daegen::MassMatrix::Diagonal(&[#(#diagonal),*]);)
        }
        Some((entries, program)) => {
            let pattern = entries.iter().map(|&(r, c)| {
                let (r, c) = (index(r), index(c));
                quote!((#r, #c))
            });
            let k = index(entries.len());
            let values = program_into(g, &layout, program, "values");
            quote! {
                const MASS: ::daegen::MassMatrix = ::daegen::MassMatrix::Pattern(&[#(#pattern),*]);
                fn mass_values(&self, values: &mut [f64]) {
                    let ::core::result::Result::Ok(values) = <&mut [f64; #k]>::try_from(values) else { return };
                    let t = 0.0f64;
                    #values
                }
            }
        }
    };
    let index2 = form.index2.iter().map(|&i| index(i));
    let rhs = fixed_size_body(&n, "dy", &n, rhs);
    let values = fixed_size_body(&n, "values", &nnz, values);
    quote! {
        const STATES: usize = #n;
        type State = [f64; #n];
        const JACOBIAN: ::daegen::Jacobian = ::daegen::Jacobian::Symbolic {
            pattern: &[#(#pattern),*],
            time_derivative: false,
        };
        #mass
        const INDEX2_COMPONENTS: &'static [usize] = &[#(#index2),*];
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
            #rhs
        }
        fn jacobian(&self, t: f64, y: &[f64], values: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
            #values
        }
    }
}

/// The items of the model's own `Model` implementation when only the
/// mass-matrix form exists: initial values (states, then the algebraic
/// variables' guesses, then μ = 0) and outputs read from the components.
pub fn primary_items(g: &Graph, form: &MassForm, programs: &PrimaryPrograms) -> TokenStream {
    let index = Literal::usize_unsuffixed;
    let layout = Layout::of_components(&form.components);
    let n = index(form.components.len());
    let items = model_items(g, form, &programs.form);
    let initial = program_into(g, &layout, &programs.initial, "y");
    let arms: Vec<TokenStream> = programs
        .outputs
        .iter()
        .enumerate()
        .map(|(k, program)| {
            let body = straight_program(g, &layout, program, &|_, v| v);
            let k = index(k);
            quote!(#k => { #body })
        })
        .collect();
    quote! {
        #items
        fn initial_state(&self, y: &mut [f64]) {
            let ::core::result::Result::Ok(y) = <&mut [f64; #n]>::try_from(y) else { return };
            *y = [0.0; #n];
            #initial
        }
        fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
            let ::core::result::Result::Ok(y) = <&[f64; #n]>::try_from(y) else { return f64::NAN };
            match index {
                #(#arms)*
                _ => f64::NAN,
            }
        }
    }
}

/// The generated `{Name}MassForm` type and what the model needs to reach it.
pub fn emit_mass_form(
    g: &Graph,
    form: &MassForm,
    programs: &MassFormPrograms,
    name: &syn::Ident,
    vis: &syn::Visibility,
    params: &[syn::Ident],
) -> (TokenStream, TokenStream) {
    let index = Literal::usize_unsuffixed;
    let form_name = format_ident!("{}MassForm", name);
    let n = index(form.components.len());
    let items = model_items(g, form, programs);
    let names = &form.names;
    let name_str = form_name.to_string();
    let differential = index(form.differential);
    let doc = if form.general.is_some() {
        format!("The mass-matrix form of [`{name}`] for RADAU5: its equations as written, M w' = F(t, w), with the singular mass matrix M of their derivatives' coefficients.")
    } else if form.index2.is_empty() {
        format!("The mass-matrix form of [`{name}`] for RADAU5 with a singular mass matrix: its states, then its algebraic variables, their equations kept as written.")
    } else {
        format!("The mass-matrix form of [`{name}`] for RADAU5 with a singular mass matrix: states, algebraic variables and the Gear–Gupta–Leimkuhler multipliers `mu[k]`, which vanish on the solution.")
    };
    let form_type = quote! {
        #[doc = #doc]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #form_name { #(#[doc = "Parameter, as in the model."] pub #params: f64,)* }

        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic)]
        impl ::daegen::Model for #form_name {
            const INDEX: usize = 2;
            const INFO: ::daegen::ModelInfo = ::daegen::ModelInfo {
                name: #name_str, doc: #doc, states: &[#(#names),*], state_docs: &[], parameters: &[], parameter_docs: &[],
                outputs: <#name as ::daegen::Model>::INFO.outputs,
                output_docs: <#name as ::daegen::Model>::INFO.output_docs,
                declared_outputs: <#name as ::daegen::Model>::INFO.declared_outputs,
                equations: #n, events: &[], clocks: &[], discrete: &[], inputs: &[], algebraics: &[], algebraic_docs: &[],
                structure: <#name as ::daegen::Model>::INFO.structure,
                components: <#name as ::daegen::Model>::INFO.components,
            };
            // The model's constraints, measured at every step but never
            // projected onto: the form keeps them itself.
            const CONSTRAINTS: &'static [::daegen::ConstraintInfo] = <#name as ::daegen::Model>::CONSTRAINTS;
            #items
            fn initial_state(&self, y: &mut [f64]) {
                y.iter_mut().for_each(|v| *v = 0.0);
            }
            fn constraints(&self, t: f64, y: &[f64], out: &mut [f64]) {
                let model = #name { #(#params: self.#params,)* };
                // The model's own states: w's first components (all of a
                // shorter slice, which the model then refuses).
                let y = y.get(..#differential).unwrap_or(y);
                ::daegen::Model::constraints(&model, t, y, out)
            }
            fn output(&self, index: usize, t: f64, y: &[f64]) -> f64 {
                let model = #name { #(#params: self.#params,)* };
                ::daegen::Model::output(&model, index, t, y.get(..#differential).unwrap_or(y))
            }
        }
    };
    let algebraic_count = index(form.components.len() - form.differential);
    let method = quote! {
        fn simulate_mass_form(
            &self,
            t0: f64,
            y0: &[f64],
            t1: f64,
            options: &::daegen::Options,
        ) -> ::core::option::Option<::core::result::Result<::daegen::Solution, ::daegen::Error>> {
            let form = #form_name { #(#params: self.#params,)* };
            // The algebraic variables from the index-1 form at the start;
            // the multipliers μ are zero on the solution.
            let mut w0 = [0.0f64; #n];
            for (w, y) in w0[..#differential].iter_mut().zip(y0) {
                *w = *y;
            }
            let outputs = <Self as ::daegen::Model>::INFO.outputs.len();
            for k in 0..(<Self as ::daegen::Model>::INFO.algebraics.len()).min(#algebraic_count) {
                w0[#differential + k] = ::daegen::Model::output(self, outputs + k, t0, y0);
            }
            ::core::option::Option::Some(::daegen::runtime::simulate_from(&form, t0, &w0, t1, options))
        }
    };
    (form_type, method)
}
