//! The front end on arbitrary text: anything that lexes as Rust tokens is
//! wrapped as a model body and expanded. It must return (an expansion or
//! compile errors), never panic. Run: `cd fuzz && cargo +nightly fuzz run
//! front_end -- -max_total_time=300` (seeds in `corpus/front_end`).

#![no_main]

use libfuzzer_sys::fuzz_target;
use std::str::FromStr;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // The first line is the attribute, the rest the body.
    let (attr, body) = text.split_once('\n').unwrap_or(("", text));
    let (Ok(attr), Ok(item)) = (
        proc_macro2::TokenStream::from_str(attr),
        proc_macro2::TokenStream::from_str(&format!("fn m() {{ {body} }}")),
    ) else {
        return;
    };
    let _ = daegen_codegen::expand_dae_model(attr, item);
});
