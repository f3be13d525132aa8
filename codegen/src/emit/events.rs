//! `Model::events` and `Model::event_rates`: the event functions, all at
//! once sharing their subexpressions, and their rates along the solution
//! dg/dt = ∂g/∂t + ∇g·f, which let the runtime find two crossings between
//! neighbouring samples. Nothing for a model without events.

use crate::dae::system::FirstOrder;
use crate::emit::layout::{index, program_into, Layout};
use crate::emit::newton::block_solve_code;
use crate::programs::rhs::RhsEntry;
use crate::programs::schedule::Program;
use crate::Graph;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// `events`, writing every event function, all at once sharing their
/// subexpressions; nothing for a model without events. Where one reads
/// an unknown a run-time block solves, the blocks are solved first
/// (`blocks`: the program assembling them), and a singular block makes
/// every event function NaN, which the run reports.
pub(crate) fn events_method(
    g: &Graph,
    layout: &mut Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
    blocks: &(Vec<RhsEntry>, Program),
) -> TokenStream {
    if !crate::programs::derivatives::events_read_blocks(g, sys) {
        return per_event_method(g, layout, sys, program, "events", "g", TokenStream::new());
    }
    let m = index(sys.events.len());
    let on_singular = quote! {
        *g = [f64::NAN; #m];
        return
    };
    let solve = block_solve_code(g, layout, sys, blocks, on_singular);
    layout.block_of = sys.block_unknowns.iter().map(|&(s, b, r)| (s, (b, r))).collect();
    let method = per_event_method(g, layout, sys, program, "events", "g", solve);
    layout.block_of.clear();
    method
}

/// `event_rates`, where f is explicit.
pub(crate) fn event_rates_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
) -> TokenStream {
    let method = per_event_method(g, layout, sys, program, "event_rates", "dg", TokenStream::new());
    if method.is_empty() {
        return method;
    }
    quote! {
        const EVENT_RATES: ::daegen::Availability = ::daegen::Availability::Available;

        #method
    }
}

/// `fn method(&self, t, y, out)` writing one value per event function into
/// `out`, after `solve`.
fn per_event_method(
    g: &Graph,
    layout: &Layout,
    sys: &FirstOrder,
    program: Option<&Program>,
    method: &str,
    out: &str,
    solve: TokenStream,
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
            #solve
            #body
        }
    }
}
