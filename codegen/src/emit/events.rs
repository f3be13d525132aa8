//! `Model::events` and `Model::event_rates`: the event functions, all at
//! once sharing their subexpressions, and their rates along the solution
//! dg/dt = ∂g/∂t + ∇g·f, which let the runtime find two crossings between
//! neighbouring samples. Nothing for a model without events.

use crate::dae::system::FirstOrder;
use crate::emit::layout::{index, program, Layout};
use crate::{Graph, Id, SymbolId};
use proc_macro2::TokenStream;
use quote::quote;

/// `events`, writing every event function.
pub(crate) fn events_method(g: &mut Graph, layout: &Layout, sys: &FirstOrder) -> TokenStream {
    let n = sys.slots.len();
    // All event functions at once, sharing their subexpressions; nothing
    // is emitted for a model without events.
    if sys.events.is_empty() {
        TokenStream::new()
    } else {
        let (m, n_lit) = (index(sys.events.len()), index(n));
        let body = program(g, layout, &sys.events, &|i, v| {
            let i = index(i);
            quote!(g[#i] = #v;)
        });
        quote! {
            #[inline]
            fn events(&self, t: f64, y: &[f64], g: &mut [f64]) {
                let (::core::result::Result::Ok(y), ::core::result::Result::Ok(g)) =
                    (<&[f64; #n_lit]>::try_from(y), <&mut [f64; #m]>::try_from(g)) else { return };
                #body
            }
        }
    }
}

/// `event_rates`, where f is explicit.
pub(crate) fn event_rates_method(
    g: &mut Graph,
    layout: &Layout,
    sys: &FirstOrder,
    (time, inputs): (SymbolId, &[(SymbolId, SymbolId)]),
    explicit: Option<&Vec<Id>>,
) -> crate::Result<TokenStream> {
    let n = sys.slots.len();
    Ok(match (explicit, sys.events.is_empty()) {
        (Some(f), false) => {
            let mut field = crate::VectorField::new();
            let one = g.one();
            field.set(time, one);
            // An input moves with the time at its rate.
            for &(u, rate) in inputs {
                let rate = g.symbol_node(rate);
                field.set(u, rate);
            }
            for (slot, &fi) in sys.slots.iter().zip(f) {
                field.set(slot.symbol, fi);
            }
            let rates = sys
                .events
                .iter()
                .map(|&e| g.total_derivative(e, &mut field))
                .collect::<crate::error::Result<Vec<Id>>>()?;
            let (m, n_lit) = (index(rates.len()), index(n));
            let body = program(g, layout, &rates, &|i, v| {
                let i = index(i);
                quote!(dg[#i] = #v;)
            });
            quote! {
                const EVENT_RATES: ::daegen::Availability = ::daegen::Availability::Available;

                #[inline]
                fn event_rates(&self, t: f64, y: &[f64], dg: &mut [f64]) {
                    let (::core::result::Result::Ok(y), ::core::result::Result::Ok(dg)) =
                        (<&[f64; #n_lit]>::try_from(y), <&mut [f64; #m]>::try_from(dg)) else { return };
                    #body
                }
            }
        }
        _ => TokenStream::new(),
    })
}
