//! The AD recurrences of the Taylor tape against the symbolic derivatives
//! of the economic scheme (course notes §1.3.1): two independent routes to
//! the same Taylor coefficients, x^[k] = y^(k)/k!, which must agree to
//! rounding at every order, on models that use every smooth function of
//! the language, at pseudo-random points. The unrolled layout (straight-line
//! recurrences emitted for fixed orders) must agree with the interpreted
//! tape to rounding, at the order of the symbolic scheme and beyond it.

use daegen::prelude::*;
use daegen::runtime::taylor_tape::TaylorWork;

include!("models/n_body.rs");

#[dae_model(taylor = 6, unroll = [6, 14])]
fn trigonometric() {
    let t = time();
    let k = param(0.3);
    let a = state(0.2);
    let b = state(0.4);
    let c = state(1.3);
    der(a) == sin(b) * cos(a) + tan(0.5 * a) - k * exp(-b) + cos(t);
    der(b) == asin(0.5 * a) + acos(0.3 * b) * atan(c) + sinh(a) / cosh(b);
    der(c) == tanh(c - t) + ln(c) * sqrt(c) + c.powf(-1.5) + atan2(b, a - 2.0);
}

#[dae_model(taylor = 6, unroll = [6, 14])]
fn rational() {
    let a = state(0.7);
    let b = state(-0.4);
    der(a) == b.powi(3) / (1.0 + a * a) - a.powi(-2) + (a + b * b).powf(2.0 / 3.0);
    der(b) == atan2(a, b) * sinh(b) - cosh(a * b).powf(0.5) + 2.0 * a;
    // Outputs are not on the tape: a non-smooth one is allowed.
    let magnitude = output(abs(b));
}

gravitating_bodies! {
    /// Three bodies in the plane, written as the outer solar system is: its
    /// interactions repeat one computation on other operands, which the
    /// unrolled layout computes as lane pairs (vectorised), in one function
    /// at order 10 and one function per order at order 34.
    #[dae_model(taylor = 1, unroll = [10, 34])]
    fn three_bodies(planar) {
        const N: usize = 3;
        let g = param(1.0);
        let m = [1.0, 0.3, 0.1];
        let x = state_array([0.0, 1.0, -0.4]);
        let y = state_array([0.0, 0.2, 1.1]);
        let u = state_array([0.0, 0.1, -0.5]);
        let v = state_array([0.1, 0.9, 0.2]);
    }
}

gravitating_bodies! {
    /// Five bodies in space, written as the outer solar system is, at an
    /// order whose jet is one function per order: its ten interactions'
    /// rows are lane groups, each computed by one loop over the interactions
    /// (the differences read lane by lane from the states).
    #[dae_model(taylor = 1, unroll = [18])]
    fn five_bodies(spatial) {
        const N: usize = 5;
        let g = param(1.0);
        let m = [1.0, 0.3, 0.1, 0.05, 0.02];
        let x = state_array([0.0, 1.0, -1.0, 0.1, 2.0]);
        let y = state_array([0.0, 0.2, 0.1, 1.5, -1.0]);
        let z = state_array([0.0, -0.3, 0.4, 0.2, 0.5]);
        let u = state_array([0.0, 0.1, -0.5, 0.3, 0.2]);
        let v = state_array([0.1, 0.9, 0.2, -0.4, 0.6]);
        let w = state_array([0.0, 0.1, 0.0, -0.1, 0.2]);
    }
}

/// Three lanes of `exp(aᵢ²)` and of `gᵢ = exp(exp(aᵢ²))`, and products
/// (under a square root, so that they are rows of their own) that all read
/// g₁, at an order whose jet is split per order: the products read that
/// lane at one place, so they must not share the loop that writes it
/// (lane 0 would read lane 1 before it is written; this fails if they do).
#[dae_model(taylor = 1, unroll = [22])]
fn shared_lane() {
    let a = state_array([0.1, -0.2, 0.3]);
    let e = [exp(a[0] * a[0]), exp(a[1] * a[1]), exp(a[2] * a[2])];
    let g = [exp(e[0]), exp(e[1]), exp(e[2])];
    der(a[0]) == 0.1 * sqrt(e[0] * g[1]) - 0.01 * g[0];
    der(a[1]) == 0.1 * sqrt(e[1] * g[1]) - 0.01 * g[1];
    der(a[2]) == 0.1 * sqrt(e[2] * g[1]) - 0.01 * g[2];
}

/// Three lanes of one expression with logarithms, quotients, arctangents,
/// exponentials and square roots, at an order whose jet is split per
/// order: the recurrences with a reciprocal 1/x₀ (ln, the square root) run
/// in lane groups' loops, the others lane by lane.
#[dae_model(taylor = 1, unroll = [16])]
fn elementary_lanes() {
    let a = state_array([0.1, -0.2, 0.3]);
    for i in 0..3 {
        der(a[i])
            == ln(1.0 + a[i] * a[i]) / (2.0 + a[i])
                + atan2(a[i], 1.5) * exp(-a[i])
                + sqrt(1.0 + a[i] * a[i]);
    }
}

/// The restricted three-body problem (Arenstorf's), whose accelerations
/// sum products that share a factor, itself or shifted by a constant:
/// (x + μ)/d₁³ and (x − μ′)/d₂³, y/d₁³ and y/d₂³, factored into one
/// convolution each with the row −μ′/d₁³ − μ/d₂³ (`taylor::factoring`); a
/// third sum shares the factor z with a product of its own. One function
/// at order 4 (checked against the symbolic scheme too), one per order at 30.
#[dae_model(taylor = 4, unroll = [4, 30])]
fn shared_factors() {
    let mu = param(0.012277471);
    let x = state(0.994);
    let y = state(0.1);
    let u = state(0.0);
    let v = state(-2.0);
    let z = state(0.3);
    let mup = 1.0 - mu;
    let d1 = ((x + mu).powi(2) + y * y).powf(1.5);
    let d2 = ((x - mup).powi(2) + y * y).powf(1.5);
    der(x) == u;
    der(y) == v;
    der(u) == x + 2.0 * v - mup * (x + mu) / d1 - mu * (x - mup) / d2;
    der(v) == y - 2.0 * u - mup * y / d1 - mu * y / d2;
    der(z) == z * exp(x) - 2.0 * (z + 1.0) * sin(y) + 0.5 * z * x;
}

/// A deterministic pseudo-random number in [lo, hi) (a 64-bit LCG).
fn uniform(seed: &mut u64, lo: f64, hi: f64) -> f64 {
    *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    lo + (hi - lo) * ((*seed >> 11) as f64 / (1u64 << 53) as f64)
}

/// Where the unrolled jet of `order` keeps state i's coefficient k.
fn at<M: Model>(model: &M, order: usize, i: usize, k: usize) -> usize {
    if model.taylor_jet_by_coefficient(order) {
        k * M::STATES + i
    } else {
        i * (order + 1) + k
    }
}

/// Compares the routes at `points` random (t, y) with y in the boxes.
fn agree<M: Model>(model: &M, boxes: &[(f64, f64)], points: usize) {
    let (n, p) = (M::STATES, M::TAYLOR_ORDER);
    let (tape, outputs) = model.taylor_tape().expect("a Taylor tape");
    let mut work = TaylorWork::new(&tape, &outputs, n, p);
    let mut jet = vec![0.0; model.taylor_jet_len(p)];
    let mut symbolic = vec![0.0; n * p];
    let mut seed = 2026;
    for _ in 0..points {
        let t = uniform(&mut seed, -1.0, 1.0);
        let y: Vec<f64> = boxes.iter().map(|&(lo, hi)| uniform(&mut seed, lo, hi)).collect();
        model.taylor_derivatives(t, &y, p, &mut symbolic).expect("derivatives");
        work.compute(t, &y);
        assert!(model.taylor_jet_unrolled(t, &y, p, &mut jet));
        let mut factorial = 1.0;
        for k in 1..=p {
            factorial *= k as f64;
            for i in 0..n {
                let from_tape = work.state(i)[k] * factorial;
                let unrolled = jet[at(model, p, i, k)] * factorial;
                let from_symbols = symbolic[(k - 1) * n + i];
                let scale = from_symbols.abs().max(1.0);
                assert!(
                    (from_tape - from_symbols).abs() <= 1e-11 * scale,
                    "y{i}^({k}) at t = {t}, y = {y:?}: tape {from_tape}, symbolic {from_symbols}"
                );
                assert!(
                    (unrolled - from_symbols).abs() <= 1e-11 * scale,
                    "y{i}^({k}) at t = {t}, y = {y:?}: unrolled {unrolled}, symbolic {from_symbols}"
                );
            }
        }
    }
}

/// The unrolled recurrences of a higher order against the interpreted tape
/// (the symbolic scheme stops at order 8): coefficient k of every state
/// within rounding of the largest coefficient k.
fn unrolled_agrees_with_the_tape<M: Model>(model: &M, order: usize, boxes: &[(f64, f64)]) {
    let n = M::STATES;
    let (tape, outputs) = model.taylor_tape().expect("a Taylor tape");
    let mut work = TaylorWork::new(&tape, &outputs, n, order);
    let mut jet = vec![0.0; model.taylor_jet_len(order)];
    let mut seed = 7;
    for _ in 0..200 {
        let t = uniform(&mut seed, -1.0, 1.0);
        let y: Vec<f64> = boxes.iter().map(|&(lo, hi)| uniform(&mut seed, lo, hi)).collect();
        work.compute(t, &y);
        assert!(model.taylor_jet_unrolled(t, &y, order, &mut jet));
        // The whole buffer, the lanes that pad lane groups to whole
        // vectors included (they start from 1, not from the buffer's 0).
        if let Some(at) = jet.iter().position(|v| !v.is_finite()) {
            panic!("slot {at} of the buffer is {} at t = {t}, y = {y:?}", jet[at]);
        }
        for k in 0..=order {
            let scale = (0..n).map(|i| work.state(i)[k].abs()).fold(1e-300, f64::max);
            for i in 0..n {
                let (a, b) = (work.state(i)[k], jet[at(model, order, i, k)]);
                assert!(
                    (a - b).abs() <= 1e-12 * scale,
                    "y{i}^[{k}] at t = {t}, y = {y:?}: tape {a}, unrolled {b}"
                );
            }
        }
    }
    // Orders not emitted are refused, and so is a short buffer.
    assert!(!model.taylor_jet_unrolled(0.0, &vec![0.5; n], order + 1, &mut jet));
    assert!(!model.taylor_jet_unrolled(0.0, &vec![0.5; n], order, &mut jet[1..]));
}

#[test]
fn unrolled_order_14_agrees_with_the_interpreted_tape() {
    assert_eq!(<Trigonometric as Model>::TAYLOR_UNROLLED, &[6, 14]);
    unrolled_agrees_with_the_tape(
        &Trigonometric::default(),
        14,
        &[(-0.9, 0.9), (-0.9, 0.9), (0.5, 2.0)],
    );
    unrolled_agrees_with_the_tape(&Rational::default(), 14, &[(0.2, 2.0), (-2.0, 2.0)]);
}

#[test]
fn lane_pairs_agree_with_the_interpreted_tape_in_both_layouts() {
    // Bodies within a box of the start, never closer than about 0.5.
    let boxes = [
        (-0.1, 0.1),
        (0.9, 1.1),
        (-0.5, -0.3),
        (-0.1, 0.1),
        (0.1, 0.3),
        (1.0, 1.2),
        (-0.2, 0.2),
        (-0.1, 0.3),
        (-0.7, -0.3),
        (-0.1, 0.3),
        (0.7, 1.1),
        (0.0, 0.4),
    ];
    for order in [10, 34] {
        unrolled_agrees_with_the_tape(&ThreeBodies::default(), order, &boxes);
    }
}

#[test]
fn lane_groups_agree_with_the_interpreted_tape() {
    // Each coordinate within 0.1 of the start: bodies at least 0.7 apart.
    let start = [
        [0.0, 1.0, -1.0, 0.1, 2.0],
        [0.0, 0.2, 0.1, 1.5, -1.0],
        [0.0, -0.3, 0.4, 0.2, 0.5],
        [0.0, 0.1, -0.5, 0.3, 0.2],
        [0.1, 0.9, 0.2, -0.4, 0.6],
        [0.0, 0.1, 0.0, -0.1, 0.2],
    ];
    let boxes: Vec<(f64, f64)> = start.iter().flatten().map(|&s| (s - 0.1, s + 0.1)).collect();
    // Jets split per order (five bodies at 18, three at 34) write their
    // states' coefficients order by order; one function (three bodies at
    // 10), state by state.
    assert!(FiveBodies::default().taylor_jet_by_coefficient(18));
    assert!(ThreeBodies::default().taylor_jet_by_coefficient(34));
    assert!(!ThreeBodies::default().taylor_jet_by_coefficient(10));
    unrolled_agrees_with_the_tape(&FiveBodies::default(), 18, &boxes);
}

#[test]
fn lane_groups_of_elementary_functions_agree_with_the_interpreted_tape() {
    unrolled_agrees_with_the_tape(
        &ElementaryLanes::default(),
        16,
        &[(-0.9, 0.9), (-0.9, 0.9), (-0.9, 0.9)],
    );
}

#[test]
fn a_lane_read_by_every_lane_is_written_before_the_loop_that_reads_it() {
    unrolled_agrees_with_the_tape(
        &SharedLane::default(),
        22,
        &[(-0.5, 0.5), (-0.5, 0.5), (-0.5, 0.5)],
    );
}

#[test]
fn products_sharing_a_factor_agree_with_the_tape_and_the_symbolic_scheme() {
    // Away from both primaries (at x = −μ and x = μ′, y = 0).
    let boxes = [(-0.6, 0.6), (0.2, 0.8), (-1.0, 1.0), (-1.0, 1.0), (-1.0, 1.0)];
    assert!(!SharedFactors::default().taylor_jet_by_coefficient(4));
    assert!(SharedFactors::default().taylor_jet_by_coefficient(30));
    for order in [4, 30] {
        unrolled_agrees_with_the_tape(&SharedFactors::default(), order, &boxes);
    }
    agree(&SharedFactors::default(), &boxes, 100);
}

#[test]
fn trigonometric_hyperbolic_and_inverse_functions() {
    agree(&Trigonometric::default(), &[(-0.9, 0.9), (-0.9, 0.9), (0.5, 2.0)], 200);
}

#[test]
fn powers_quotients_and_atan2_in_every_quadrant() {
    agree(&Rational::default(), &[(0.2, 2.0), (-2.0, 2.0)], 200);
}

/// A jet that writes its coefficients order by order (five bodies at 18)
/// steps as the interpreted tape, which writes them state by state, does:
/// the same number of steps, the same states and dense output between the
/// steps to rounding (the state update, the step size's norms and the
/// dense output each read the coefficients in the jet's layout).
#[test]
fn a_jet_written_order_by_order_steps_as_the_tape_does() {
    let model = FiveBodies::default();
    assert!(model.taylor_jet_by_coefficient(18));
    let options =
        Options::new().method(Method::Taylor).tolerance(1e-12).taylor_order(18).dense_output(true);
    let unrolled = model.simulate(0.0, 2.0, &options).unwrap();
    let tape = model.simulate(0.0, 2.0, &options.taylor_compact(true)).unwrap();
    assert!(unrolled.stats().taylor_unrolled && !tape.stats().taylor_unrolled);
    assert_eq!(unrolled.stats().steps, tape.stats().steps);
    assert!(unrolled.stats().steps > 5, "{}", unrolled.stats().steps);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
    for (a, b) in unrolled.final_state().iter().zip(tape.final_state()) {
        assert!(close(*a, *b), "{a} against {b}");
    }
    for t in [0.3, 0.77, 1.5] {
        for name in FiveBodies::INFO.states {
            let (a, b) = (unrolled.at(t, name).unwrap(), tape.at(t, name).unwrap());
            assert!(close(a, b), "{name} at {t}: {a} against {b}");
        }
    }
}
