include!("n_body.rs");

// The model shared by tests/taylor_adaptive.rs and the benchmark
// (`include!`d: bench/ is a separate workspace), as a macro so each can
// choose the `#[dae_model]` arguments (the benchmark unrolls its orders).

macro_rules! outer_solar_system_model {
    ($($arguments:tt)*) => {
gravitating_bodies! {
/// The outer solar system of Hairer, Lubich & Wanner (GNI, Ch. I): the Sun
/// with the inner planets, Jupiter, Saturn, Uranus, Neptune and Pluto, in
/// AU and days (reference-problems.md §11a).
#[dae_model($($arguments)*)]
fn outer_solar_system(spatial) {
    const N: usize = 6;
    /// Gravitational constant in AU³/(solar mass · day²).
    let g = param(2.95912208286e-4);
    let m = [
        1.00000597682,
        0.000954786104043,
        0.000285583733151,
        0.0000437273164546,
        0.0000517759138449,
        1.0 / 1.3e8,
    ];
    let x = state_array([
        0.0,
        -3.5023653,
        9.0755314,
        8.3101420,
        11.4707666,
        -15.5387357,
    ]);
    let y = state_array([
        0.0,
        -3.8169847,
        -3.0458353,
        -16.2901086,
        -25.7294829,
        -25.2225594,
    ]);
    let z = state_array([
        0.0,
        -1.5507963,
        -1.6483708,
        -7.2521278,
        -10.8169456,
        -3.1902382,
    ]);
    let u = state_array([
        0.0, 0.00565429, 0.00168318, 0.00354178, 0.00288930, 0.00276725,
    ]);
    let v = state_array([
        0.0,
        -0.00412490,
        0.00483525,
        0.00137102,
        0.00114527,
        -0.00170702,
    ]);
    let w = state_array([
        0.0,
        -0.00190589,
        0.00192462,
        0.00055029,
        0.00039677,
        -0.00136504,
    ]);
}
}
    };
}
