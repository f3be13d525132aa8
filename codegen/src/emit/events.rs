//! `Model::events` and `Model::event_rates`: the event functions, all at
//! once sharing their subexpressions, and their rates along the solution
//! dg/dt = ∂g/∂t + ∇g·f, which let the runtime find two crossings between
//! neighbouring samples. Nothing for a model without events.

use crate::dae::system::FirstOrder;
use crate::emit::layout::{index, straight_program, Layout};
use crate::programs::schedule::Program;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::quote;

/// `events`, writing every event function, all at once sharing their
/// subexpressions; nothing for a model without events.
pub(crate) fn events_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
) -> TokenStream {
    let Some(program) = program else { return TokenStream::new() };
    let (m, n_lit) = (index(sys.events.len()), index(sys.slots.len()));
    let body = straight_program(g, layout, program, &|i, v| {
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

/// `event_rates`, where f is explicit.
pub(crate) fn event_rates_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
) -> TokenStream {
    let Some(program) = program else { return TokenStream::new() };
    let (m, n_lit) = (index(sys.events.len()), index(sys.slots.len()));
    let body = straight_program(g, layout, program, &|i, v| {
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
