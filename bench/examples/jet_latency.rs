//! Times the unrolled order-18 Taylor jet alone (the order `Method::Taylor`
//! picks at 1e-12 for these models), without the step around
//! it: `cargo run --release --example jet_latency -- [kepler|arenstorf|oss]`.
//! Each round times it twice: each call's state waiting for the previous
//! call's last coefficient (as in a solve, where the next state needs the
//! whole jet), and calls whose states do not wait for each other. Close
//! figures mean the jet is bound by its own work, not by the chain from
//! one call to the next; the gap to a solve's time per step is the step
//! size rule and the state update.

use daegen::prelude::*;
use std::time::Instant;

include!("../../tests/models/kepler.rs");
include!("../../tests/models/arenstorf.rs");
include!("../../tests/models/outer_solar_system.rs");

kepler_model!(taylor = 1, unroll = [18]);
arenstorf_model!(taylor = 1, unroll = [18]);
outer_solar_system_model!(taylor = 1, unroll = [18]);

const ORDER: usize = 18;

fn main() -> Result<(), String> {
    match std::env::args().nth(1).as_deref() {
        None | Some("kepler") => time_jet(&Kepler::default()),
        Some("arenstorf") => time_jet(&Arenstorf::default()),
        Some("oss") => time_jet(&OuterSolarSystem::default()),
        Some(other) => return Err(format!("unknown model {other}: kepler, arenstorf or oss")),
    }
    Ok(())
}

/// Prints three rounds of mean times per jet, dependent and independent.
fn time_jet<M: Model>(model: &M) {
    let mut jet = vec![0.0; model.taylor_jet_len(ORDER)];
    let mut y = vec![0.0; M::STATES];
    model.initial_state(&mut y);
    let last = M::STATES * (ORDER + 1) - 1;
    let calls = if M::STATES > 4 { 100_000 } else { 2_000_000 };
    for round in 0..3 {
        let start = Instant::now();
        for _ in 0..calls {
            model.taylor_jet_unrolled(0.0, &y, ORDER, &mut jet);
            // Adds nothing, but only once the jet is done.
            y[0] += jet[last] * 1e-300;
        }
        let dependent = start.elapsed().as_secs_f64() / calls as f64;
        let start = Instant::now();
        for i in 0..calls {
            y[0] += (i & 7) as f64 * 1e-300;
            model.taylor_jet_unrolled(0.0, &y, ORDER, &mut jet);
            std::hint::black_box(&jet);
        }
        let independent = start.elapsed().as_secs_f64() / calls as f64;
        println!(
            "round {round}: dependent {:.1} ns, independent {:.1} ns",
            dependent * 1e9,
            independent * 1e9
        );
    }
}
