//! `Model::events` and `Model::event_rates`: the event functions, all at
//! once sharing their subexpressions, and their rates along the solution
//! dg/dt = ∂g/∂t + ∇g·f, which let the runtime find two crossings between
//! neighbouring samples. Nothing for a model without events.

use crate::dae::system::FirstOrder;
use crate::emit::layout::{index, program_into, Layout};
use crate::programs::schedule::Program;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// `events`, writing every event function, all at once sharing their
/// subexpressions; nothing for a model without events.
pub(crate) fn events_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
) -> TokenStream {
    per_event_method(g, layout, sys, program, "events", "g")
}

/// `event_rates`, where f is explicit.
pub(crate) fn event_rates_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
) -> TokenStream {
    let method = per_event_method(g, layout, sys, program, "event_rates", "dg");
    if method.is_empty() {
        return method;
    }
    quote! {
        const EVENT_RATES: ::daegen::Availability = ::daegen::Availability::Available;

        #method
    }
}

/// `fn method(&self, t, y, out)` writing one value per event function into
/// `out`.
fn per_event_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
    method: &str,
    out: &str,
) -> TokenStream {
    let Some(program) = program else { return TokenStream::new() };
    let (m, n_lit) = (index(sys.events.len()), index(sys.slots.len()));
    let body = program_into(g, layout, program, out);
    let (method, out) = (format_ident!("{}", method), format_ident!("{}", out));
    quote! {
        #[inline]
        fn #method(&self, t: f64, y: &[f64], #out: &mut [f64]) {
            let (::core::result::Result::Ok(y), ::core::result::Result::Ok(#out)) =
                (<&[f64; #n_lit]>::try_from(y), <&mut [f64; #m]>::try_from(#out)) else { return };
            #body
        }
    }
}
