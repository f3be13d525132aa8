//! Warnings for models that compile but will not run as written.
//!
//! A proc macro on stable Rust cannot raise a warning itself; it can use a
//! deprecated item, whose note the compiler then prints as a warning at
//! the span of the use (the `proc-macro-warning` crate's technique). The
//! use is spanned on the user's tokens, so the warning points at them.

use proc_macro2::{Span, TokenStream};
use quote::{quote, quote_spanned};

/// One warning per odd order in `unroll = [..]`: `Method::Taylor` picks
/// even orders only (see `daegen_runtime::taylor_order::choose_order`), so
/// the straight-line code of an odd order runs only when the order is fixed
/// with `Options::taylor_order`, and a model that lists only odd orders
/// runs on the interpreted tape, several times slower.
pub fn odd_unrolled_orders(odd: &[(usize, Span)]) -> TokenStream {
    odd.iter()
        .map(|&(p, span)| {
            let note = format!(
                "`unroll` order {p} is odd: `Method::Taylor` picks even orders, so this code runs only with `Options::taylor_order({p})`; unroll {} or {} instead",
                p - 1,
                p + 1
            );
            let used = quote_spanned!(span=> odd_unrolled_order);
            quote! {
                const _: () = {
                    #[deprecated(note = #note)]
                    #[allow(non_upper_case_globals)]
                    const odd_unrolled_order: () = ();
                    #used
                };
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_odd_order_gets_its_own_warning_naming_its_even_neighbours() {
        let tokens = odd_unrolled_orders(&[(15, Span::call_site()), (19, Span::call_site())]);
        let text = tokens.to_string();
        assert_eq!(text.matches("deprecated").count(), 2);
        assert!(text.contains("taylor_order(15)"), "{text}");
        assert!(text.contains("unroll 14 or 16 instead"), "{text}");
        assert!(text.contains("unroll 18 or 20 instead"), "{text}");
        assert!(odd_unrolled_orders(&[]).is_empty());
    }
}
