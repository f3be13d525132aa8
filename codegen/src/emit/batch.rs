//! `#[dae_model(batch = L)]`: beside the model `M`, the type `MBatch` that
//! holds `L` members' parameters and states and computes their
//! right-hand sides at once, the model's own straight-line program run on
//! `daegen::runtime::lanes::Lanes<L>` values (heyoka's batch mode).

use crate::dae::system::{FirstOrder, SlotDerivative};
use crate::emit::docs::{doc_attr, type_name};
use crate::emit::layout::{index, program, Layout};
use crate::expr::node::Node;
use crate::front::ir::ModelIr;
use crate::{Graph, Id, SymbolKind};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// The batch type and its `Model` and `Batch` implementations; `Err` with
/// what to do instead where the model is not an explicit ODE whose
/// right-hand side runs on lanes.
pub(crate) fn batch_items(
    ir: &mut ModelIr,
    sys: &FirstOrder,
    lanes: usize,
) -> Result<TokenStream, String> {
    let fix = "batch lanes run explicit ODEs without events, clocks or inputs: drop `batch`, and run the members one by one with `daegen::Ensemble`";
    let what = if sys.index > 0 || !ir.algebraics.is_empty() || sys.mass_only {
        Some("is a DAE")
    } else if !sys.blocks.is_empty() || sys.newton.is_some() {
        Some("has equations solved for their derivatives at run time")
    } else if !ir.events.is_empty() || !ir.clocks.is_empty() {
        Some("has events or clocks")
    } else if !ir.inputs.is_empty() {
        Some("reads inputs")
    } else if !sys.invariants.is_empty() || !ir.invariants.is_empty() {
        Some("has invariants to project onto")
    } else {
        None
    };
    if let Some(what) = what {
        return Err(format!("this model {what}; {fix}"));
    }
    let outputs: Vec<Id> = sys
        .derivatives
        .iter()
        .filter_map(|d| match d {
            SlotDerivative::Explicit(e) => Some(*e),
            _ => None,
        })
        .collect();
    if outputs.len() != sys.slots.len() {
        return Err(format!("this model has derivatives solved at run time; {fix}"));
    }
    if let Some(why) = not_on_lanes(&ir.graph, &outputs) {
        return Err(format!(
            "its right-hand side has {why}, which lanes do not compute yet; {fix}"
        ));
    }
    let name = type_name(ir);
    let batch = format_ident!("{}Batch", name);
    let vis = &ir.vis;
    let (n, l) = (sys.slots.len(), lanes);
    let (n_lit, l_lit, nl_lit) = (index(n), index(l), index(n * l));
    let layout = Layout::of_system(sys);
    let body = program(&mut ir.graph, &layout, &outputs, &|i, v| {
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
    Ok(quote! {
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
    })
}

/// What in the program of `outputs` lanes cannot compute, if anything: a
/// sign (an `if` on a value), or a power or `atan2` whose first operand is
/// the same in every lane while the second differs (`2^x`, with `x` a
/// state: a number's method would be called with lanes).
fn not_on_lanes(g: &Graph, outputs: &[Id]) -> Option<&'static str> {
    let varies = |id: Id| {
        g.free_symbols(id).iter().any(|&s| {
            matches!(
                g.symbol(s).kind,
                SymbolKind::State | SymbolKind::Parameter | SymbolKind::Derivative { .. }
            )
        })
    };
    for id in g.reachable(outputs) {
        match g.node(id) {
            Node::Call(f, _) if *f == crate::Func::Sign => {
                return Some("a sign (`sign` or `abs`'s derivative)")
            }
            Node::Pow([b, e]) if g.as_number(*e).is_none() && !varies(*b) && varies(*e) => {
                return Some("a number raised to a varying power")
            }
            Node::Atan2([y, x]) if !varies(*y) && varies(*x) => {
                return Some("an `atan2` of a number")
            }
            _ => {}
        }
    }
    None
}
