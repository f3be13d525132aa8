// Kepler's problem with e = 0.9 and its exact solution, shared by
// tests/taylor_adaptive.rs and the benchmark (`include!`d: bench/ is a
// separate workspace), as a macro so each chooses the `#[dae_model]`
// arguments (reference-problems.md §10).

macro_rules! kepler_model {
    // `kepler_model!(fn name(arguments) { statements })`: the same orbit
    // under another name, with more statements (events, outputs).
    (fn $name:ident($($arguments:tt)*) { $($more:tt)* }) => {
/// Kepler's problem q'' = −q/|q|³ with e = 0.9 from perihelion (semi-major
/// axis 1, period 2π).
#[dae_model($($arguments)*)]
fn $name() {
    let e = param(0.9);
    let q1 = state(1.0 - e);
    let q2 = state(0.0);
    let p1 = state(0.0);
    let p2 = state(sqrt((1.0 + e) / (1.0 - e)));
    let r3 = (q1 * q1 + q2 * q2).powf(-1.5);
    der(q1) == p1;
    der(q2) == p2;
    der(p1) == -q1 * r3;
    der(p2) == -q2 * r3;
    $($more)*
}
    };
    ($($arguments:tt)*) => {
        kepler_model!(fn kepler($($arguments)*) {
            let energy = output(0.5 * (p1 * p1 + p2 * p2) - (q1 * q1 + q2 * q2).powf(-0.5));
        });
    };
}

/// The exact state at t for e = 0.9: Newton on Kepler's equation
/// E − e sin E = t, then q = (cos E − e, √(1−e²) sin E).
#[allow(dead_code)]
fn kepler_exact(t: f64) -> [f64; 4] {
    let e = 0.9;
    let mut big_e = t + e * t.sin();
    for _ in 0..100 {
        big_e -= (big_e - e * big_e.sin() - t) / (1.0 - e * big_e.cos());
    }
    let (s, c) = big_e.sin_cos();
    let w = (1.0 - e * e).sqrt();
    [c - e, w * s, -s / (1.0 - e * c), w * c / (1.0 - e * c)]
}

/// The largest error against [`kepler_exact`] at a solution's stored steps,
/// and at `samples + 1` equally spaced times over one period by its dense
/// output: `(at the steps, between them)`.
#[allow(dead_code)]
fn kepler_errors_at_and_between_steps(sol: &daegen::Solution, samples: usize) -> (f64, f64) {
    // NaN wins, so that a NaN anywhere fails the caller's comparison.
    let max = |a: f64, b: f64| if a.is_nan() || b.is_nan() { f64::NAN } else { a.max(b) };
    let worst =
        |got: &[f64], t: f64| got.iter().zip(kepler_exact(t)).map(|(g, e)| (g - e).abs()).fold(0.0, max);
    let at_steps = (0..sol.times().len())
        .map(|k| worst(sol.state(k).expect("a stored step"), sol.times()[k]))
        .fold(0.0, max);
    let between = (0..=samples)
        .map(|j| {
            let t = 2.0 * std::f64::consts::PI * j as f64 / samples as f64;
            let got: Vec<f64> =
                ["q1", "q2", "p1", "p2"].iter().map(|n| sol.at(t, n).expect("in the run")).collect();
            worst(&got, t)
        })
        .fold(0.0, max);
    (at_steps, between)
}

/// Component `i` at `t` by the cubic Hermite polynomial through a
/// solution's stored steps around `t`, with component `di` as its
/// derivative (p1 is q1's: `hermite_between_steps(&sol, t, 0, 2)`).
#[allow(dead_code)]
fn hermite_between_steps(sol: &daegen::Solution, t: f64, i: usize, di: usize) -> f64 {
    let k = sol.times().partition_point(|&s| s < t);
    let (t0, t1) = (sol.times()[k - 1], sol.times()[k]);
    let (a, b) = (sol.state(k - 1).unwrap(), sol.state(k).unwrap());
    let (h, s) = (t1 - t0, (t - t0) / (t1 - t0));
    let (s2, s3) = (s * s, s * s * s);
    (2.0 * s3 - 3.0 * s2 + 1.0) * a[i]
        + (s3 - 2.0 * s2 + s) * h * a[di]
        + (3.0 * s2 - 2.0 * s3) * b[i]
        + (s3 - s2) * h * b[di]
}
