// The Lorenz attractor (Hairer–Nørsett–Wanner I, problem LRNZ), shared by
// tests/taylor_adaptive.rs and the benchmark (`include!`d), as a macro so
// each chooses the start and the `#[dae_model]` arguments: the tests start
// from HNW's (−8, 8, 27) with the reference of reference-problems.md §12d,
// the benchmark from heyoka's peer problem, (1, 0, 0).

macro_rules! lorenz_model {
    ([$x0:expr, $y0:expr, $z0:expr], $($arguments:tt)*) => {
/// Lorenz's convection model with σ = 10, r = 28, b = 8/3: chaotic, a
/// perturbation grows about as e^(0.9 t).
#[dae_model($($arguments)*)]
fn lorenz() {
    let sigma = param(10.0);
    let r = param(28.0);
    let b = param(8.0 / 3.0);
    let x = state($x0);
    let y = state($y0);
    let z = state($z0);
    der(x) == sigma * (y - x);
    der(y) == x * (r - z) - y;
    der(z) == x * y - b * z;
}
    };
}

/// y(16) from HNW's start (−8, 8, 27): reference-problems.md §12d
/// (recomputed with mpmath at 32 and 44 digits, agreeing to 21).
#[allow(dead_code)]
const LORENZ_HNW_AT_16: [f64; 3] = [
    -9.13131302736875292786,
    -12.4761788110782533339,
    22.8433389609823882055,
];

/// y(20) from (1, 0, 0), the peer's problem: no published value;
/// bench/references/lorenz_reference.py (mpmath Taylor series, two runs of
/// 50 and 60 digits agreeing to 3e-36).
#[allow(dead_code)]
const LORENZ_AT_20: [f64; 3] = [
    -8.02114361331743706771255570066,
    -11.9054647491717503752127026323,
    19.8563748583984131205032463778,
];
