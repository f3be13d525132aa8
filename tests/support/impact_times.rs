// The exact impact times of a bouncing ball, shared by the tests
// (tests/support) and the benchmark of hybrid models (`include!`d).

/// The impact times of a ball dropped from `h` under gravity `g` that
/// rebounds with restitution `e`: a drop of sqrt(2h/g), then flights of
/// 2·eᵏ·v₁/g with v₁ = sqrt(2gh).
pub fn impact_times(h: f64, g: f64, e: f64, bounces: usize) -> Vec<f64> {
    let mut t = (2.0 * h / g).sqrt();
    let mut v = (2.0 * g * h).sqrt();
    let mut times = vec![t];
    for _ in 1..bounces {
        v *= e;
        t += 2.0 * v / g;
        times.push(t);
    }
    times
}
