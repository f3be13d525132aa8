//! `Model::act`, `Model::clock` and `Model::input_breakpoints`: the
//! actions of events and clocks, each `.reinit(x, value)` in the order
//! written on the state the ones before it left (`pre(x)` read from the
//! state before the instant), each clock's period and first instant, and
//! the instants where inputs are not smooth. Nothing for a model without
//! them.

use crate::dae::system::FirstOrder;
use crate::emit::layout::{index, straight_program, Layout};
use crate::programs::hybrid::Actions;
use crate::programs::schedule::Program;
use crate::{emit_program, FxHashMap, Graph, SymbolId};
use proc_macro2::TokenStream;
use quote::quote;

/// `act`, one arm per event or clock with actions.
pub(crate) fn act_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    pre: &[(SymbolId, SymbolId)],
    programs: &[Actions],
) -> TokenStream {
    if programs.iter().all(Vec::is_empty) {
        return TokenStream::new();
    }
    // `pre(x)` reads x's slot of the state before the instant.
    let pre_slot: FxHashMap<SymbolId, usize> =
        pre.iter().filter_map(|&(p, of)| layout.slot_of.get(&of).map(|&i| (p, i))).collect();
    let n = index(sys.slots.len());
    let mut arms = Vec::new();
    for (trigger, actions) in programs.iter().enumerate() {
        if actions.is_empty() {
            continue;
        }
        let mut body = TokenStream::new();
        for (slot, program) in actions {
            let slot = index(*slot);
            let tokens = |s: SymbolId| match pre_slot.get(&s) {
                Some(&i) => {
                    let i = index(i);
                    quote!(pre[#i])
                }
                None => layout.tokens(g, s),
            };
            let code = emit_program(g, program, &tokens, &|_, v| quote!(y[#slot] = #v;));
            body.extend(quote!({ #code }));
        }
        let trigger = index(trigger);
        arms.push(quote!(#trigger => { #body }));
    }
    quote! {
        fn act(&self, trigger: usize, t: f64, pre: &[f64], y: &mut [f64]) {
            let (::core::result::Result::Ok(pre), ::core::result::Result::Ok(y)) =
                (<&[f64; #n]>::try_from(pre), <&mut [f64; #n]>::try_from(y)) else { return };
            match trigger {
                #(#arms)*
                _ => {}
            }
        }
    }
}

/// `clock`, each clock's period and first instant from the parameters.
pub(crate) fn clock_method(g: &Graph, layout: &Layout, programs: &[Program]) -> TokenStream {
    if programs.is_empty() {
        return TokenStream::new();
    }
    let mut arms = Vec::new();
    for (k, program) in programs.iter().enumerate() {
        let code = straight_program(g, layout, program, &|i, v| {
            if i == 0 {
                quote!(period = #v;)
            } else {
                quote!(offset = #v;)
            }
        });
        let k = index(k);
        arms.push(quote!(#k => { #code }));
    }
    quote! {
        fn clock(&self, index: usize) -> (f64, f64) {
            let (mut period, mut offset) = (f64::INFINITY, 0.0);
            match index {
                #(#arms)*
                _ => {}
            }
            (period, offset)
        }
    }
}

/// `input_breakpoints`, every input's breakpoints and the instants of the
/// model's switches in the time alone (`time_events`), and `set_input`.
pub(crate) fn input_breakpoints_method(
    g: &Graph,
    layout: &Layout,
    inputs: &[crate::front::ir::InputDecl],
    time_events: Option<&Program>,
) -> TokenStream {
    let switches = match time_events {
        Some(program) => {
            let code = straight_program(g, layout, program, &|_, v| quote!(breakpoints.push(#v);));
            quote!({ #code })
        }
        None => TokenStream::new(),
    };
    if inputs.is_empty() {
        if time_events.is_none() {
            return TokenStream::new();
        }
        return quote! {
            fn input_breakpoints(&self) -> ::std::vec::Vec<f64> {
                let mut breakpoints = ::std::vec::Vec::new();
                #switches
                breakpoints
            }
        };
    }
    let fields = inputs.iter().map(|i| &i.ident);
    let set_arms = inputs.iter().enumerate().map(|(k, i)| {
        let (k, ident) = (index(k), &i.ident);
        quote!(#k => self.#ident = input,)
    });
    quote! {
        fn input_breakpoints(&self) -> ::std::vec::Vec<f64> {
            let mut breakpoints = ::std::vec::Vec::new();
            #(breakpoints.extend_from_slice(self.#fields.breakpoints());)*
            #switches
            breakpoints
        }

        fn set_input(&mut self, index: usize, input: ::daegen::Input) {
            match index {
                #(#set_arms)*
                _ => {}
            }
        }
    }
}

/// `start_relations`: each relation's discrete boolean set from its value
/// at the start, through the event function that watches it, again until
/// none changes (a relation may read a value another switches).
pub(crate) fn start_relations_method(
    sys: &FirstOrder,
    relations: &[crate::front::ir::Relation],
) -> TokenStream {
    if relations.is_empty() {
        return TokenStream::new();
    }
    let events = index(sys.events.len());
    let rounds = index(relations.len() + 1);
    let sets = relations.iter().filter_map(|r| {
        let slot = sys.slots.iter().position(|s| s.symbol == r.discrete)?;
        let (slot, event) = (index(slot), index(r.event));
        let holds = match r.inclusive {
            true => quote!(g[#event] >= 0.0),
            false => quote!(g[#event] > 0.0),
        };
        Some(quote! {
            let held = if #holds { 1.0 } else { 0.0 };
            if let ::core::option::Option::Some(value) = y.get_mut(#slot) {
                if *value != held {
                    *value = held;
                    changed = true;
                }
            }
        })
    });
    quote! {
        fn start_relations(&self, t: f64, y: &mut [f64]) {
            let mut g = [0.0f64; #events];
            for _ in 0..#rounds {
                <Self as ::daegen::Model>::events(self, t, y, &mut g);
                let mut changed = false;
                #(#sets)*
                if !changed {
                    break;
                }
            }
        }
    }
}
