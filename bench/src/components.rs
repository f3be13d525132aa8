//! Models built from components against the same physics written flat
//! (`--components`): the states and the blocks left to solve at run
//! time, the right-hand side's cost per evaluation both ways, and the
//! expansion time of models of a hundred parts and more. Writes
//! `results/components.md`.

use super::*;
use crate::structure::{expansion_seconds, rhs_ns};
use daegen::ModelInfo;
use proc_macro2::TokenStream;

include!("../../tests/models/drives.rs");
include!("../../tests/models/ladders_of_parts.rs");

rc_ladder_of_parts!(
    ladder_of_parts,
    50,
    {
        let r = param(1.0);
        let c = param(1.0);
    },
    r,
    c
);
rc_ladder_of_parts!(ladder_of_tunable_parts, 50, {}, 1.0, 1.0);
rc_ladder_flat!(ladder_flat, 50);

/// A wall of layers from the library between two fixed temperatures.
#[dae_model]
fn wall_of_parts() {
    const N: usize = 20;
    let inside = fixed_temperature(313.15);
    let outside = fixed_temperature(273.15);
    let layers = [heat_capacitor(c = 500.0, t0 = 293.15); N];
    let conductors = [thermal_conductor(2.0); N + 1];
    connect(inside.port, conductors[0].port_a);
    for k in 0..N {
        connect(conductors[k].port_b, layers[k].port, conductors[k + 1].port_a);
    }
    connect(conductors[N].port_b, outside.port);
}

/// The same wall written flat: the layers' temperatures.
#[dae_model]
fn wall_flat() {
    const N: usize = 20;
    let c = param(500.0);
    let g = param(2.0);
    let t_in = param(313.15);
    let t_out = param(273.15);
    let t = state_array([293.15; N]);
    for k in 0..N {
        let left = if k == 0 { t_in } else { t[k - 1] };
        let right = if k + 1 < N { t[k + 1] } else { t_out };
        c * der(t[k]) == g * (left - t[k]) + g * (right - t[k]);
    }
}

/// States and blocks of a model: `4 states, no block`.
fn size(info: &ModelInfo) -> String {
    let blocks: Vec<String> = info.structure.blocks.iter().map(|b| b.size.to_string()).collect();
    match blocks.is_empty() {
        true => format!("{} states, no block", info.states.len()),
        false => format!("{} states, blocks of {}", info.states.len(), blocks.join(", ")),
    }
}

/// The ladder of `n` sections from the library's parts, as tokens.
fn ladder_tokens(n: usize) -> TokenStream {
    let n = proc_macro2::Literal::usize_unsuffixed(n);
    quote::quote! {
        fn ladder() {
            const N: usize = #n;
            let source = constant_voltage(1.0);
            let r = [resistor(1.0); N];
            let c = [capacitor(1.0); N];
            let gnd = ground();
            connect(source.p, r[0].p);
            connect(source.n, gnd.p);
            for k in 0..N {
                connect(r[k].n, c[k].p);
                connect(c[k].n, gnd.p);
                if k + 1 < N {
                    connect(r[k].n, r[k + 1].p);
                }
            }
        }
    }
}

/// The `--components` report.
pub fn components_section() -> String {
    let mut out = String::from("# Components against the same physics written flat\n\n");
    out.push_str(&format!("Machine: {}.\n\n", machine()));
    out.push_str(
        "Each model built from the standard library's parts (and, for the drive, a \
         user's `#[component]` DC motor) and the same physics written flat by hand. \
         Sizes after simplification (aliases, tied states, sorting); nanoseconds per \
         `rhs` at the initial state moved off zero, median of 21 alternated rounds.\n\n",
    );
    out.push_str("| model | parts | components: size | flat: size | components (ns) | flat (ns) | ratio |\n|---|---|---|---|---|---|---|\n");
    let mut row = |name: &str, parts: usize, a: &ModelInfo, b: &ModelInfo, (ta, tb): (f64, f64)| {
        out.push_str(&format!(
            "| {name} | {parts} | {} | {} | {ta:.1} | {tb:.1} | {:.3}× |\n",
            size(a),
            size(b),
            ta / tb
        ));
    };
    row(
        "DC motor, PI speed control, friction, load step",
        14,
        &<SpeedDrive as Model>::INFO,
        &<SpeedDriveFlat as Model>::INFO,
        rhs_ns(&SpeedDrive::default(), &SpeedDriveFlat::default()),
    );
    row(
        "series RLC circuit",
        5,
        &<RlcSeries as Model>::INFO,
        &<RlcSeriesFlat as Model>::INFO,
        rhs_ns(&RlcSeries::default(), &RlcSeriesFlat::default()),
    );
    row(
        "RC ladder, 50 sections, the parts reading the model's r and c",
        <LadderOfParts as Model>::INFO.components.len(),
        &<LadderOfParts as Model>::INFO,
        &<LadderFlat as Model>::INFO,
        rhs_ns(&LadderOfParts::default(), &LadderFlat::default()),
    );
    row(
        "RC ladder, 50 sections, each part its own r or c (100 parameters; flat: 2)",
        <LadderOfTunableParts as Model>::INFO.components.len(),
        &<LadderOfTunableParts as Model>::INFO,
        &<LadderFlat as Model>::INFO,
        rhs_ns(&LadderOfTunableParts::default(), &LadderFlat::default()),
    );
    row(
        "thermal wall, 20 layers",
        <WallOfParts as Model>::INFO.components.len(),
        &<WallOfParts as Model>::INFO,
        &<WallFlat as Model>::INFO,
        rhs_ns(&WallOfParts::default(), &WallFlat::default()),
    );
    out.push_str("\n## Expansion time against the number of parts\n\n");
    out.push_str(
        "The whole macro (lowering the parts, connections, aliases, tied states, \
         sorting, emission) on RC ladders of library parts, called as a library, best of 3.\n\n",
    );
    out.push_str("| sections | parts | expansion (s) |\n|---|---|---|\n");
    for n in [50usize, 100, 250, 500] {
        let seconds = expansion_seconds(&ladder_tokens(n), 3);
        out.push_str(&format!("| {n} | {} | {seconds:.3} |\n", 2 * n + 2));
    }
    out
}
