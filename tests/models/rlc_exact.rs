// The exact response of the series RLC circuit of `drives.rs`.

/// `v_c(t)` and `i(t)` of `rlc_series`, exactly.
fn rlc_exact(t: f64) -> [f64; 2] {
    let (alpha, wd) = (0.5f64, 3.75f64.sqrt());
    let vc = 1.0 - (-alpha * t).exp() * ((wd * t).cos() + alpha / wd * (wd * t).sin());
    let i = (-alpha * t).exp() * (wd * t).sin() / wd;
    [vc, i]
}
