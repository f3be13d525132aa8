// The Arenstorf orbit (Hairer–Nørsett–Wanner I, eq. 0.1), periodic with
// period T, shared by tests/taylor_adaptive.rs and the benchmark
// (`include!`d), as a macro so each chooses the `#[dae_model]` arguments
// (reference-problems.md §9).

macro_rules! arenstorf_model {
    ($($arguments:tt)*) => {
/// The restricted three-body problem (Earth, Moon, satellite) in the
/// rotating frame, started on Arenstorf's periodic orbit.
#[dae_model($($arguments)*)]
fn arenstorf() {
    let mu = param(0.012277471);
    let y1 = state(0.994);
    let y2 = state(0.0);
    let v1 = state(0.0);
    let v2 = state(-2.00158510637908252240537862224);
    let mup = 1.0 - mu;
    let d1 = ((y1 + mu).powi(2) + y2 * y2).powf(1.5);
    let d2 = ((y1 - mup).powi(2) + y2 * y2).powf(1.5);
    der(y1) == v1;
    der(y2) == v2;
    der(v1) == y1 + 2.0 * v2 - mup * (y1 + mu) / d1 - mu * (y1 - mup) / d2;
    der(v2) == y2 - 2.0 * v1 - mup * y2 / d1 - mu * y2 / d2;
}
    };
}

/// The period of the orbit.
#[allow(dead_code)]
const ARENSTORF_T: f64 = 17.0652165601579625588917206249;
/// The start, which the orbit returns to after one period.
#[allow(dead_code)]
const ARENSTORF_Y0: [f64; 4] = [0.994, 0.0, 0.0, -2.00158510637908252240537862224];
