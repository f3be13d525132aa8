// Odd orders of `unroll` warn (denied here so that the warning is checked):
// `Method::Taylor` never picks them.
#![deny(deprecated)]
use daegen::prelude::*;

#[dae_model(unroll = [14, 15])]
fn growth() {
    let x = state(1.0);
    der(x) == x;
}

fn main() {}
