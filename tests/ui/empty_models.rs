use daegen::prelude::*;

/// Nothing at all.
#[dae_model]
fn empty() {}

/// Parameters and no state.
#[dae_model]
fn only_parameters() {
    let k = param(1.0);
}

fn main() {}
