//! `#[dae_model(batch = L)]`: beside the model `M`, the type `MBatch` that
//! holds `L` members' parameters and states and computes their
//! right-hand sides at once, the model's own straight-line program run on
//! `daegen::runtime::lanes::Lanes<L>` values (heyoka's batch mode).

use crate::dae::system::FirstOrder;
use crate::emit::docs::{doc_attr, type_name, Naming};
use crate::emit::layout::{index, straight_program, Layout};
use crate::front::ir::ModelIr;
use crate::programs::schedule::Program;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// The batch type and its `Model` and `Batch` implementations from the
/// right-hand side's program for lanes.
pub(crate) fn batch_items(
    g: &Graph,
    ir: &ModelIr,
    naming: &Naming,
    sys: &FirstOrder,
    lanes: usize,
    program: &Program,
) -> TokenStream {
    let name = type_name(naming);
    let batch = format_ident!("{}Batch", name);
    let vis = &ir.vis;
    let (n, l) = (sys.slots.len(), lanes);
    let (n_lit, l_lit, nl_lit) = (index(n), index(l), index(n * l));
    let layout = Layout::of_system(sys);
    let body = straight_program(g, &layout, program, &|i, v| {
        let i = index(i);
        quote!(dy[#i] = ::core::convert::Into::into(#v);)
    });
    let params: Vec<&syn::Ident> = ir.params.iter().map(|p| &p.ident).collect();
    let param_docs = ir.params.iter().map(|p| {
        let doc = if p.doc.is_empty() { format!("`{}`", p.ident) } else { p.doc.clone() };
        doc_attr(&format!("{doc} (one value a lane)."))
    });
    let states: Vec<String> =
        (0..n * l).map(|k| format!("{}[lane {}]", sys.slots[k / l].name, k % l)).collect();
    let doc = doc_attr(&format!(
        "{l} members of [`{name}`] stepped together with one step size: their parameters and states side by side, component `i` of lane `l` at `i·{l} + l`, the right-hand side computed for all lanes at once. Built from members by `daegen::runtime::Batch::from_members`; run by `daegen::Ensemble::final_states_batched` or as any model, with an explicit pair, `Method::Taylor` (the members' tapes on lanes) or a fixed-step method (each lane meets the tolerance as its member would alone)."
    ));
    let name_str = batch.to_string();
    quote! {
        #[doc = #doc]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #batch {
            #( #[doc = #param_docs] pub #params: ::daegen::runtime::lanes::Lanes<#l_lit>, )*
        }

        impl ::core::default::Default for #batch {
            fn default() -> Self {
                <Self as ::daegen::runtime::Batch>::from_members(&[#name::default(); #l_lit])
            }
        }

        impl #batch {
            /// The member of lane `lane`.
            pub fn member(&self, lane: usize) -> #name {
                let mut member = #name::default();
                #( member.#params = self.#params.0.get(lane).copied().unwrap_or(f64::NAN); )*
                member
            }
        }

        impl ::daegen::runtime::Batch for #batch {
            type Member = #name;
            fn from_members(members: &[#name]) -> Self {
                Self {
                    #( #params: ::daegen::runtime::lanes::Lanes(::core::array::from_fn(|lane| {
                        members.get(lane).map_or(f64::NAN, |m| m.#params)
                    })), )*
                }
            }
        }

        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic)]
        impl ::daegen::Model for #batch {
            const STATES: usize = #nl_lit;
            type State = [f64; #nl_lit];
            const INDEX: usize = 0;
            const LANES: usize = #l_lit;
            const TAYLOR_TAPE: ::daegen::Availability = <#name as ::daegen::Model>::TAYLOR_TAPE;
            const INFO: ::daegen::ModelInfo = ::daegen::ModelInfo {
                name: #name_str,
                doc: "",
                states: &[#(#states),*],
                state_docs: &[],
                parameters: &[],
                parameter_docs: &[],
                outputs: &[],
                output_docs: &[],
                declared_outputs: &[],
                equations: #nl_lit,
                events: &[],
                clocks: &[],
                discrete: &[],
                inputs: &[],
                algebraics: &[],
                algebraic_docs: &[],
                structure: <#name as ::daegen::Model>::INFO.structure,
                components: <#name as ::daegen::Model>::INFO.components,
            };
            fn initial_state(&self, y: &mut [f64]) {
                for lane in 0..#l_lit {
                    let mut member = [0.0f64; #n_lit];
                    ::daegen::Model::initial_state(&self.member(lane), &mut member);
                    for (i, v) in member.iter().enumerate() {
                        if let Some(slot) = y.get_mut(i * #l_lit + lane) {
                            *slot = *v;
                        }
                    }
                }
            }
            fn taylor_member_tapes(&self) -> ::core::option::Option<::std::vec::Vec<::daegen::runtime::taylor_tape::Tape>> {
                (0..#l_lit).map(|lane| ::daegen::Model::taylor_tape(&self.member(lane))).collect()
            }
            fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> ::core::result::Result<(), ::daegen::EvalError> {
                let y: [::daegen::runtime::lanes::Lanes<#l_lit>; #n_lit] = ::daegen::runtime::lanes::load(y);
                let mut lanes = [::daegen::runtime::lanes::Lanes::<#l_lit>::splat(0.0); #n_lit];
                {
                    let dy = &mut lanes;
                    #body
                }
                ::daegen::runtime::lanes::store(&lanes, dy);
                ::core::result::Result::Ok(())
            }
        }
    }
}
