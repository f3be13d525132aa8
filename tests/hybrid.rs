//! Hybrid models: events and clocks that act (`.reinit(..)`), discrete
//! values, against exact or independently computed results, with every
//! method that runs them.

use daegen::prelude::*;

mod support;
use support::harness::{adaptive_methods_for, methods_for};
use support::impact_times;

/// A ball dropped from `h0` onto a floor, rebounding with restitution `e`.
#[dae_model(taylor = 1)]
fn bouncing_ball() {
    let g = param(9.81);
    let h0 = param(10.0);
    /// Coefficient of restitution.
    let e = param(0.8);
    let h = state(h0);
    der(der(h)) == -g;
    /// The ball hits the floor and rebounds.
    let bounce = event(h).falling().reinit(der(h), -e * pre(der(h)));
}

/// The error a method's run at tolerance `tol` is held to: `tol`, but for
/// RADAU5, which works to 0.1·tol^(2/3) (Hairer's `radau5.f`, kept by the
/// runtime).
fn reach(method: Method, tol: f64) -> f64 {
    match method {
        Method::Radau5 => 0.1 * tol.powf(2.0 / 3.0),
        _ => tol,
    }
}

/// Runs `model` to `t_end` with every adaptive method at `tol` and checks
/// that it jumps `count` times, by `names[0]` and `names[1]` in turn: each
/// method with its solution.
fn alternating_runs<M: Simulate>(
    model: &M,
    t_end: f64,
    tol: f64,
    names: [&str; 2],
    count: usize,
) -> Vec<(Method, Solution)> {
    let mut runs = Vec::new();
    for method in adaptive_methods_for::<M>() {
        let opts = Options::new().method(method).tolerance(tol);
        let sol = model.simulate(0.0, t_end, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let jumps = sol.jumps();
        let times: Vec<f64> = jumps.iter().map(|j| j.t).collect();
        assert_eq!(jumps.len(), count, "{method:?}: {times:?}");
        for (k, jump) in jumps.iter().enumerate() {
            assert_eq!(jump.triggers, [names[k % 2]], "{method:?}: jump {k}");
        }
        runs.push((method, sol));
    }
    runs
}

#[test]
fn bounces_fall_on_the_geometric_series_for_every_adaptive_method() {
    let ball = BouncingBall::default();
    let exact = impact_times(ball.h0, ball.g, ball.e, 12);
    for method in adaptive_methods_for::<BouncingBall>() {
        let opts = Options::new().method(method).tolerance(1e-12);
        let sol = ball
            .simulate(0.0, exact[11] + 0.1, &opts)
            .unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let times = sol.event_times("bounce").expect("an event");
        assert_eq!(times.len(), 12, "{method:?}: {times:?}");
        for (k, (t, want)) in times.iter().zip(&exact).enumerate() {
            assert!(
                (t - want).abs() <= 1e-12 * want,
                "{method:?}: bounce {k} at {t}, exact {want}"
            );
            // Both sides of the jump are kept: speed reversed and scaled.
            let before = sol.at_left(*t, "der(h)").expect("reads");
            let after = sol.at(*t, "der(h)").expect("reads");
            assert!(before < 0.0 && after > 0.0, "{method:?}");
            assert!(
                (after + ball.e * before).abs() <= 1e-12 * after,
                "{method:?}: {before} → {after}"
            );
        }
        // Between bounces the dense output follows each parabola, never
        // the line across a jump.
        let mid = 0.5 * (exact[0] + exact[1]);
        let v1 = ball.e * (2.0 * ball.g * ball.h0).sqrt();
        let s = mid - exact[0];
        let want = v1 * s - 0.5 * ball.g * s * s;
        let got = sol.at(mid, "h").expect("reads");
        assert!((got - want).abs() <= 1e-9, "{method:?}: {got} vs {want}");
    }
}

#[test]
fn bounces_accumulate_at_the_zeno_time() {
    // The flights shrink by e: the impacts accumulate at
    // t∞ = t₁ + 2 e v₁ / (g (1 − e)).
    let ball = BouncingBall { e: 0.5, ..BouncingBall::default() };
    let t1 = (2.0 * ball.h0 / ball.g).sqrt();
    let v1 = ball.g * t1;
    let zeno = t1 + 2.0 * ball.e * v1 / (ball.g * (1.0 - ball.e));
    for method in adaptive_methods_for::<BouncingBall>() {
        let opts = Options::new().method(method).tolerance(1e-12);
        let err = ball.simulate(0.0, 10.0, &opts).expect_err("the bounces accumulate");
        match &err {
            daegen::Error::ZenoEvents { t, event, accumulation, count, partial } => {
                assert_eq!(*event, "bounce");
                assert!(
                    (accumulation - zeno).abs() <= 1e-9,
                    "{method:?}: {accumulation} vs {zeno}"
                );
                assert!(*t <= zeno + 1e-12 && zeno - t < 1e-8, "{method:?}: last at {t}");
                assert!(*count > 20, "{method:?}: {count}");
                assert_eq!(partial.event_times("bounce").unwrap().len(), *count);
            }
            other => panic!("{method:?}: expected ZenoEvents, got {other}"),
        }
        assert!(err.to_string().contains("accumulate at t = "), "{err}");
    }
}

#[test]
fn fixed_step_methods_bounce_at_their_order() {
    // A method of order 2 or more is exact on the parabola, and the
    // Hermite interpolation the impact is located on is exact for
    // quadratics: the impacts are found to rounding. First-order methods
    // are off by O(h): halving the step halves the error.
    let ball = BouncingBall::default();
    let exact = impact_times(ball.h0, ball.g, ball.e, 4);
    let t_end = exact[3] + 0.1;
    let impacts = |method: Method, step: f64| {
        let opts = Options::new().method(method).step(step);
        let sol = ball.simulate(0.0, t_end, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        sol.event_times("bounce").expect("an event")
    };
    for method in methods_for::<BouncingBall>(|m| !support::harness::is_adaptive(m)) {
        let order = match support::harness::kind(method) {
            support::harness::Kind::FixedStep { order, .. } => order,
            _ => unreachable!(),
        };
        let times = impacts(method, t_end / 1000.0);
        assert_eq!(times.len(), 4, "{method:?}: {times:?}");
        if order >= 2 {
            for (t, want) in times.iter().zip(&exact) {
                assert!((t - want).abs() <= 1e-12 * want, "{method:?}: {t} vs {want}");
            }
        } else {
            let finer = impacts(method, t_end / 2000.0);
            for k in 0..4 {
                let ratio = (times[k] - exact[k]) / (finer[k] - exact[k]);
                assert!((1.8..2.2).contains(&ratio), "{method:?}: bounce {k}, error ratio {ratio}");
            }
        }
    }
}

// The sampled PI loop of the FMU example (the plant x' = −a x + b u under
// a PI controller sampled every `h`, its output held between samples),
// so that the recursion below checks the very model the FMU exports.
#[path = "../fmi/examples/models/sampled_pi.rs"]
mod sampled_pi_loop;
use sampled_pi_loop::SampledPi;

/// The exact discrete-time recursion of the sampled loop: with the input
/// held, x_{k+1} = φ x_k + (b/a)(1 − φ) u_k, φ = e^{−a h}; the controller
/// I_k = I_{k−1} + k_i h (r − x_k), u_k = k_p (r − x_k) + I_k. The values
/// (x_k, u_k) at the sample instants k·h.
fn zero_order_hold(m: &SampledPi, samples: usize) -> Vec<(f64, f64)> {
    let phi = (-m.a * m.h).exp();
    let (mut x, mut integral) = (0.0, 0.0);
    let mut out = Vec::new();
    for _ in 0..samples {
        integral += m.ki * m.h * (m.r - x);
        let u = m.kp * (m.r - x) + integral;
        out.push((x, u));
        x = phi * x + m.b / m.a * (1.0 - phi) * u;
    }
    out
}

#[test]
fn a_sampled_pi_loop_follows_the_zero_order_hold_recursion() {
    let model = SampledPi::default();
    let samples = 40;
    let exact = zero_order_hold(&model, samples + 1);
    let t_end = samples as f64 * model.h;
    for method in adaptive_methods_for::<SampledPi>() {
        let opts = Options::new().method(method).tolerance(1e-12);
        let sol = model.simulate(0.0, t_end, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        // One jump per instant, at k·h exactly: never stepped over.
        let jumps = sol.jumps();
        assert_eq!(jumps.len(), samples + 1, "{method:?}");
        for (k, jump) in jumps.iter().enumerate() {
            assert_eq!(jump.t, k as f64 * model.h, "{method:?}: instant {k}");
            assert_eq!(jump.triggers, ["sample"]);
        }
        for (k, &(x, u)) in exact.iter().enumerate() {
            let t = k as f64 * model.h;
            let x_got = sol.at(t, "x").unwrap();
            let bound = 10.0 * reach(method, 1e-12);
            assert!((x_got - x).abs() <= bound, "{method:?}: x({t}) = {x_got}, recursion {x}");
            let u_got = sol.at(t, "u").unwrap();
            assert!((u_got - u).abs() <= bound, "{method:?}: u({t}) = {u_got}, recursion {u}");
            if k > 0 {
                // Held: just before the instant, the output of the one before.
                assert!((sol.at_left(t, "u").unwrap() - exact[k - 1].1).abs() <= bound);
                let held = sol.at(t - 0.5 * model.h, "u").unwrap();
                assert_eq!(held, sol.at_left(t, "u").unwrap(), "{method:?}");
            }
        }
    }
}

#[test]
fn fixed_step_methods_sample_at_their_order() {
    // Fixed steps fit each sample interval (the instants end the stretches),
    // so the error is the method's: halving the step divides it by 2^p.
    let model = SampledPi::default();
    let samples = 20;
    let exact = zero_order_hold(&model, samples + 1);
    let t_end = samples as f64 * model.h;
    let error = |method: Method, step: f64| {
        let sol = model
            .simulate(0.0, t_end, &Options::new().method(method).step(step))
            .unwrap_or_else(|e| panic!("{method:?}: {e}"));
        (0..=samples)
            .map(|k| (sol.at(k as f64 * model.h, "x").unwrap() - exact[k].0).abs())
            .fold(0.0, f64::max)
    };
    for method in methods_for::<SampledPi>(|m| !support::harness::is_adaptive(m)) {
        let support::harness::Kind::FixedStep { order, .. } = support::harness::kind(method) else {
            unreachable!()
        };
        let (coarse, fine) = (error(method, 0.05), error(method, 0.025));
        let ratio = coarse / fine;
        let want = 2f64.powi(order);
        assert!(
            (0.7 * want..1.4 * want).contains(&ratio),
            "{method:?}: {coarse:e} / {fine:e} = {ratio}"
        );
    }
}

/// A room heated by a thermostat with hysteresis: the heater switches off
/// above `t_high` and on below `t_low`.
#[dae_model(taylor = 1)]
fn thermostat() {
    /// Heat capacity.
    let c = param(1.0);
    /// Loss to the ambient.
    let k = param(0.5);
    /// Heater power.
    let p = param(10.0);
    let t_ambient = param(10.0);
    let t_low = param(19.0);
    let t_high = param(21.0);
    let temp = state(15.0);
    /// 1 while the heater is on.
    let on = discrete(true);
    c * der(temp) == on * p - k * (temp - t_ambient);
    let too_warm = event(temp - t_high).rising().reinit(on, 0.0);
    let too_cold = event(temp - t_low).falling().reinit(on, 1.0);
}

/// The thermostat's first `count` switching times from 15 °C: T relaxes
/// to T∞ with time constant τ = c/k, so from T0 to T1 it takes
/// τ ln((T0 − T∞)/(T1 − T∞)); T∞ = Ta + p/k heating, Ta cooling.
fn thermostat_switches(m: &Thermostat, count: usize) -> Vec<f64> {
    let tau = m.c / m.k;
    let (hot, cold) = (m.t_ambient + m.p / m.k, m.t_ambient);
    let heat = |from: f64, to: f64| tau * ((from - hot) / (to - hot)).ln();
    let cool = |from: f64, to: f64| tau * ((from - cold) / (to - cold)).ln();
    let mut switches = vec![heat(15.0, m.t_high)];
    for k in 1..count {
        let last = switches[k - 1];
        let next = if k % 2 == 1 { cool(m.t_high, m.t_low) } else { heat(m.t_low, m.t_high) };
        switches.push(last + next);
    }
    switches
}

#[test]
fn a_thermostat_switches_when_the_exponentials_say() {
    let m = Thermostat::default();
    let switches = thermostat_switches(&m, 10);
    let t_end = switches[9] + 0.2;
    for (method, sol) in alternating_runs(&m, t_end, 1e-12, ["too_warm", "too_cold"], 10) {
        for (k, (jump, want)) in sol.jumps().iter().zip(&switches).enumerate() {
            assert!(
                (jump.t - want).abs() <= 10.0 * reach(method, 1e-12) * want,
                "{method:?}: switch {k} at {}, exact {want}",
                jump.t
            );
            let on = if k % 2 == 0 { 0.0 } else { 1.0 };
            assert_eq!(sol.at(jump.t, "on").unwrap(), on);
            assert_eq!(sol.at_left(jump.t, "on").unwrap(), 1.0 - on);
        }
        // In the band the temperature stays.
        let temps = sol.column("temp").unwrap();
        let after_first = sol.times().iter().position(|&t| t >= switches[0]).unwrap();
        assert!(temps[after_first..]
            .iter()
            .all(|&t| (m.t_low - 1e-9..=m.t_high + 1e-9).contains(&t)));
    }
}

/// A first-order low-pass filter driven by an input: τ x' = u(t) − x.
#[dae_model]
fn low_pass() {
    let tau = param(0.5);
    /// The voltage applied.
    let u = input(0.0);
    let x = state(0.0);
    tau * der(x) == u - x;
}

/// An integrator of its input: x' = u(t).
#[dae_model]
fn accumulator() {
    /// The flow in.
    let u = input(0.0);
    let x = state(0.0);
    der(x) == u;
}

#[test]
fn a_function_input_drives_the_filter_as_the_exact_solution_says() {
    // u = sin ωt from x(0) = 0: x = (sin ωt − ωτ cos ωt + ωτ e^{−t/τ}) / (1 + ω²τ²).
    let omega = 3.0;
    let model =
        LowPass { u: daegen::Input::function(move |t| (omega * t).sin()), ..LowPass::default() };
    let tau = model.tau;
    let exact = |t: f64| {
        let wt = omega * tau;
        ((omega * t).sin() - wt * (omega * t).cos() + wt * (-t / tau).exp()) / (1.0 + wt * wt)
    };
    for method in adaptive_methods_for::<LowPass>() {
        let opts = Options::new().method(method).tolerance(1e-10);
        let sol = model.simulate(0.0, 4.0, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        for k in 0..=40 {
            let t = 0.1 * k as f64;
            let err = (sol.at(t, "x").unwrap() - exact(t)).abs();
            assert!(err <= 100.0 * reach(method, 1e-10), "{method:?}: error {err:e} at {t}");
            // The input reads like an output.
            assert!((sol.at(t, "u").unwrap() - (omega * t).sin()).abs() <= 1e-15);
        }
    }
    // The Taylor method needs every derivative of the input: refused.
    let refusal = Method::Taylor.refusal::<LowPass>().expect("refused");
    assert!(refusal.contains("input `u`"), "{refusal}");
    let described = model.describe();
    assert!(described.contains("inputs:\n  u "), "{described}");
    assert_eq!(<LowPass as Model>::INFO.inputs, ["u"]);
}

#[test]
fn a_table_input_has_its_breakpoints_stepped_to() {
    // x' = u(t) with u piecewise linear: x is piecewise quadratic, which
    // every method of order 2 or more integrates exactly, provided no step
    // straddles a kink: a step over one would be off by O(h²) there.
    let (times, values) = ([0.0, 0.3, 1.1, 1.7, 2.45], [0.0, 2.0, 2.0, -1.0, 0.5]);
    let table = daegen::Input::linear(&times, &values).unwrap();
    let model = Accumulator { u: table.clone() };
    let exact = |t: f64| {
        // ∫₀ᵗ u by pieces: trapezoids, the last one partial.
        let mut x = 0.0;
        for k in 0..times.len() - 1 {
            let (a, b) = (times[k], times[k + 1].min(t));
            if b <= a {
                break;
            }
            x += (b - a) * (table.at(a) + table.at(b)) / 2.0;
        }
        if t > times[times.len() - 1] {
            x += (t - times[times.len() - 1]) * values[values.len() - 1];
        }
        x
    };
    for method in methods_for::<Accumulator>(|m| {
        !matches!(support::harness::kind(m), support::harness::Kind::FixedStep { order: 1, .. })
    }) {
        let opts = Options::new().method(method).tolerance(1e-10).step(0.07);
        let sol = model.simulate(0.0, 3.0, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        for b in &times[1..] {
            assert!(sol.times().contains(b), "{method:?}: no step ends at the breakpoint {b}");
        }
        for k in 0..=60 {
            let t = 0.05 * k as f64;
            let err = (sol.at(t, "x").unwrap() - exact(t)).abs();
            assert!(err <= 1e-12, "{method:?}: error {err:e} at {t}");
        }
    }
}

#[test]
fn a_monotone_cubic_table_is_integrated_to_its_knots() {
    // The cubic pieces integrate by Simpson's rule exactly: between the
    // knots (stepped to), RK4 and the adaptive methods reproduce ∫u.
    let (times, values) = ([0.0, 0.5, 1.0, 2.0], [0.0, 1.0, 1.2, 0.0]);
    let table = daegen::Input::monotone_cubic(&times, &values).unwrap();
    let model = Accumulator { u: table.clone() };
    let mut exact = vec![0.0];
    for k in 0..times.len() - 1 {
        let (a, b) = (times[k], times[k + 1]);
        let m = 0.5 * (a + b);
        exact.push(exact[k] + (b - a) / 6.0 * (table.at(a) + 4.0 * table.at(m) + table.at(b)));
    }
    for method in methods_for::<Accumulator>(|m| {
        support::harness::is_adaptive(m) || m == Method::Rk4 || m == Method::Rk38
    }) {
        let opts = Options::new().method(method).tolerance(1e-11).step(0.3);
        let sol = model.simulate(0.0, 2.0, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        for (t, want) in times.iter().zip(&exact) {
            let got = sol.at(*t, "x").unwrap();
            assert!(
                (got - want).abs() <= 100.0 * reach(method, 1e-11),
                "{method:?}: x({t}) = {got}, exact {want}"
            );
        }
    }
}

#[test]
fn co_simulation_sets_the_input_between_communication_steps() {
    // A master steps the filter by H, reading x and setting u = k (r − x)
    // for the next step: with the input held, x_{k+1} = φ x_k + (1 − φ) u_k,
    // φ = e^{−H/τ}, exactly.
    let (big_h, gain, r) = (0.2, 1.5, 1.0);
    let mut model = LowPass::default();
    let phi = (-big_h / model.tau).exp();
    let (mut t, mut y) = (0.0, vec![0.0]);
    let mut x_exact = 0.0;
    let opts = Options::new().method(Method::Dopri5).tolerance(1e-12);
    for _ in 0..25 {
        let u = gain * (r - y[0]);
        model.u = daegen::Input::constant(u);
        let sol = model.simulate_from(t, &y, t + big_h, &opts).expect("a communication step");
        t += big_h;
        y = sol.final_state().to_vec();
        x_exact = phi * x_exact + (1.0 - phi) * gain * (r - x_exact);
        assert!((y[0] - x_exact).abs() <= 1e-11, "at {t}: {} vs {x_exact}", y[0]);
    }
}

/// A half-wave rectifier: a sine source behind a resistor feeds an RC load
/// through an ideal diode, a short while it conducts and open while it
/// blocks.
#[dae_model]
fn rectifier() {
    let v_peak = param(10.0);
    let omega = param(6.0);
    let r_s = param(1.0);
    let r = param(100.0);
    let c = param(0.01);
    let t = time();
    /// The load's voltage.
    let v_c = state(1.0);
    /// The diode's voltage and current.
    let v_d = algebraic(0.0);
    let i = algebraic(0.0);
    /// Whether the diode conducts.
    let on = discrete(false);
    let v_s = v_peak * sin(omega * t);
    v_s == r_s * i + v_d + v_c;
    c * der(v_c) == i - v_c / r;
    if on {
        v_d == 0.0;
    } else {
        i == 0.0;
    }
    let opens = event(v_d).rising().reinit(on, true);
    let closes = event(i).falling().reinit(on, false);
}

/// The first `t` in `(a, b]` where `f` changes sign, by scanning and
/// bisecting to the neighbouring floats.
fn first_root(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let n = 20_000;
    let (mut lo, mut f_lo) = (a, f(a));
    for k in 1..=n {
        let hi = a + (b - a) * k as f64 / n as f64;
        let f_hi = f(hi);
        if f_lo * f_hi < 0.0 || f_hi == 0.0 {
            let (mut lo, mut hi) = (lo, hi);
            while hi - lo > 4.0 * f64::EPSILON * hi.abs() {
                let mid = 0.5 * (lo + hi);
                if f(mid) * f_lo > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return hi;
        }
        (lo, f_lo) = (hi, f_hi);
    }
    panic!("no root in ({a}, {b}]")
}

/// The switching instants of the rectifier up to `t_end`, with the load's
/// voltage there, from its closed-form pieces: blocking, the load decays,
/// v = v₀ e^{−(t−t₀)/RC}; conducting, v' = −a v + b sin ωt with
/// a = (1/R_s + 1/R)/C, b = V/(R_s C), whose solution is
/// P sin ωt + Q cos ωt + (v₀ − P sin ωt₀ − Q cos ωt₀) e^{−a(t−t₀)},
/// P = ab/(a² + ω²), Q = −ωb/(a² + ω²). The diode opens where the source
/// reaches the load's voltage and closes where its current,
/// (V sin ωt − v)/R_s, falls to zero: each switch is the root of a closed
/// form, found by bisection.
fn rectifier_switches(m: &Rectifier, t_end: f64) -> Vec<(f64, f64)> {
    let (a, b) = ((1.0 / m.r_s + 1.0 / m.r) / m.c, m.v_peak / (m.r_s * m.c));
    let (p, q) = (a * b / (a * a + m.omega * m.omega), -m.omega * b / (a * a + m.omega * m.omega));
    let source = |t: f64| m.v_peak * (m.omega * t).sin();
    let blocking = |t0: f64, v0: f64| move |t: f64| v0 * (-(t - t0) / (m.r * m.c)).exp();
    let conducting = |t0: f64, v0: f64| {
        let particular = move |t: f64| p * (m.omega * t).sin() + q * (m.omega * t).cos();
        move |t: f64| particular(t) + (v0 - particular(t0)) * (-a * (t - t0)).exp()
    };
    let (mut t0, mut v0, mut on) = (0.0, 1.0, false);
    let mut switches = Vec::new();
    loop {
        let next = if on {
            let v = conducting(t0, v0);
            first_root(|t| source(t) - v(t), t0 + 1e-9, t_end + 1.0)
        } else {
            let v = blocking(t0, v0);
            first_root(|t| source(t) - v(t), t0 + 1e-9, t_end + 1.0)
        };
        if next > t_end {
            break;
        }
        v0 = if on { conducting(t0, v0)(next) } else { blocking(t0, v0)(next) };
        (t0, on) = (next, !on);
        switches.push((next, v0));
    }
    switches
}

#[test]
fn an_ideal_diode_rectifies_as_the_closed_form_pieces_say() {
    let m = Rectifier::default();
    let t_end = 2.6;
    let switches = rectifier_switches(&m, t_end);
    assert!(switches.len() >= 5, "{switches:?}");
    let tol = 1e-10;
    for (method, sol) in alternating_runs(&m, t_end, tol, ["opens", "closes"], switches.len()) {
        let jumps = sol.jumps();
        for (k, (jump, &(t, v))) in jumps.iter().zip(&switches).enumerate() {
            let bound = 10.0 * reach(method, tol);
            assert!(
                (jump.t - t).abs() <= bound,
                "{method:?}: switch {k} at {}, closed form {t}",
                jump.t
            );
            let got = sol.at(jump.t, "v_c").unwrap();
            assert!(
                (got - v).abs() <= 10.0 * reach(method, tol) * v.abs().max(1.0),
                "{method:?}: v_c {got} vs {v}"
            );
        }
        // While it blocks the current is zero; while it conducts, the
        // diode's voltage.
        for w in jumps.windows(2) {
            let mid = 0.5 * (w[0].t + w[1].t);
            let conducting = sol.at(mid, "on").unwrap() == 1.0;
            let quantity = if conducting { "v_d" } else { "i" };
            assert_eq!(sol.at(mid, quantity).unwrap(), 0.0, "{method:?} at {mid}");
        }
    }
}

/// A block on a belt moving at `v_belt`, held by a spring to a wall, with
/// Coulomb friction: static `mu_s`, kinetic `mu_k`. It sticks to the belt
/// until the spring outpulls static friction, slips back and forth around
/// the kinetic equilibrium, and sticks again when it moves with the belt.
#[dae_model]
fn stick_slip() {
    let m = param(1.0);
    let k = param(10.0);
    let normal = param(9.81);
    let mu_s = param(0.6);
    let mu_k = param(0.4);
    let v_belt = param(0.5);
    let x = state(0.0);
    let v = state(v_belt);
    /// Whether the block moves with the belt.
    let stuck = discrete(true);
    der(x) == v;
    if stuck {
        der(v) == 0.0;
    } else {
        m * der(v) == -k * x + mu_k * normal;
    }
    /// The spring outpulls static friction.
    let slips = event(k * x - mu_s * normal).rising().reinit(stuck, false);
    /// The block moves with the belt again.
    let sticks = event(v - v_belt).rising().reinit(stuck, true).reinit(v, v_belt);
}

#[test]
fn a_block_on_a_belt_sticks_and_slips_as_the_piecewise_closed_form_says() {
    // Stuck, x grows at the belt's speed until k x = μ_s N. Slipping,
    // x − x_k = D cos ws + (v_b/w) sin ws about x_k = μ_k N/k, w² = k/m,
    // D = (μ_s − μ_k) N/k, until v = v_b again: tan(ws/2) = −D w/v_b, so
    // ws = 2π − 2 atan(D w/v_b), at x = x_k − D (the same speed, the
    // mirror position). Then stuck for 2D/v_b, and again.
    let b = StickSlip::default();
    let w = (b.k / b.m).sqrt();
    let (x_slip, x_k) = (b.mu_s * b.normal / b.k, b.mu_k * b.normal / b.k);
    let d = x_slip - x_k;
    let slipping = (2.0 * std::f64::consts::PI - 2.0 * (d * w / b.v_belt).atan()) / w;
    let stuck_after = 2.0 * d / b.v_belt;
    let mut times = vec![x_slip / b.v_belt];
    for cycle in 0..6 {
        let last = times[times.len() - 1];
        times.push(last + if cycle % 2 == 0 { slipping } else { stuck_after });
    }
    let t_end = times[6] + 0.1;
    let tol = 1e-10;
    for (method, sol) in alternating_runs(&b, t_end, tol, ["slips", "sticks"], times.len()) {
        for (k, (jump, want)) in sol.jumps().iter().zip(&times).enumerate() {
            // Errors add up over the cycles: 10·tol each.
            let bound = 10.0 * (k + 1) as f64 * reach(method, tol);
            assert!(
                (jump.t - want).abs() <= bound,
                "{method:?}: jump {k} at {}, closed form {want}",
                jump.t
            );
            let x_want = if k % 2 == 0 { x_slip } else { x_k - d };
            assert!((sol.at(jump.t, "x").unwrap() - x_want).abs() <= bound);
        }
        // Stuck, the block moves with the belt exactly.
        let mid = 0.5 * (times[1] + times[2]);
        assert_eq!(sol.at(mid, "v").unwrap(), b.v_belt, "{method:?}");
        assert_eq!(sol.at(mid, "stuck").unwrap(), 1.0);
    }
}

/// Two switches that undo each other at once: the first action sets what
/// fires the second, whose action fires the first again.
#[dae_model]
fn flip_flop() {
    let x = state(0.0);
    let a = discrete(0.0);
    der(x) == 1.0;
    let up = event(x - 1.0 - a).rising().reinit(a, 1.0);
    let down = event(a - 0.5).rising().reinit(a, 0.0);
}

#[test]
fn actions_that_fire_each_other_forever_are_an_error() {
    // At x = 1, `up` sets a = 1, which lifts `down`'s function through
    // zero; `down` sets a = 0, which lifts `up`'s back to zero from below:
    // no fixed point.
    let err = FlipFlop::default().simulate(0.0, 2.0, &Options::new()).expect_err("no fixed point");
    match &err {
        daegen::Error::EventLoop { t, events, partial } => {
            assert!((t - 1.0).abs() <= 1e-12, "{t}");
            assert!(!events.is_empty());
            assert!((partial.final_time() - 1.0).abs() <= 1e-12);
        }
        other => panic!("expected EventLoop, got {other}"),
    }
    assert!(
        err.to_string().contains(&format!("after {} rounds", daegen::MAX_EVENT_ITERATIONS)),
        "{err}"
    );
}

#[test]
fn ensemble_members_bounce_each_at_their_own_times() {
    // Members differ in restitution: their events differ in number and
    // time, and the first comes to rest (t∞ = t₁(1 + e)/(1 − e) = 2.65)
    // before the end while the others bounce on.
    let restitutions = [0.3, 0.5, 0.7, 0.9];
    let results = daegen::Ensemble::new(restitutions.len(), |i| BouncingBall {
        e: restitutions[i],
        ..BouncingBall::default()
    })
    .threads(2)
    .run(0.0, 4.0, &Options::new().tolerance(1e-11));
    for (i, result) in results.into_iter().enumerate() {
        let ball = BouncingBall { e: restitutions[i], ..BouncingBall::default() };
        let t1 = (2.0 * ball.h0 / ball.g).sqrt();
        if i == 0 {
            match result {
                Err(daegen::Error::ZenoEvents { accumulation, .. }) => {
                    let zeno = t1 * (1.0 + ball.e) / (1.0 - ball.e);
                    assert!((accumulation - zeno).abs() <= 1e-9, "{accumulation} vs {zeno}");
                }
                other => panic!("member 0: expected ZenoEvents, got {other:?}"),
            }
            continue;
        }
        let sol = result.expect("bounces");
        let times = sol.event_times("bounce").unwrap();
        let exact: Vec<f64> =
            impact_times(ball.h0, ball.g, ball.e, 40).into_iter().filter(|&t| t <= 4.0).collect();
        assert_eq!(times.len(), exact.len(), "member {i}");
        for (t, want) in times.iter().zip(&exact) {
            assert!((t - want).abs() <= 1e-10, "member {i}: {t} vs {want}");
        }
    }
}

#[test]
fn the_bound_on_events_per_unit_time_is_an_option() {
    // With e = 0.8 the flights shrink below 0.01 s after about 20 bounces
    // (2·0.8ᵏ·v₁/g < 0.01): a minimum interval of 0.01 s stops it there.
    let ball = BouncingBall::default();
    let v1 = (2.0 * ball.g * ball.h0).sqrt();
    let first_short = (0..).find(|&k| 2.0 * ball.e.powi(k) * v1 / ball.g < 0.01).unwrap() as usize;
    let opts = Options::new().tolerance(1e-12).min_event_interval(0.01);
    match ball.simulate(0.0, 30.0, &opts) {
        Err(daegen::Error::ZenoEvents { count, .. }) => assert_eq!(count, first_short + 1),
        other => panic!("expected ZenoEvents, got {other:?}"),
    }
}

/// A ball that stops at its third bounce: a terminal event may act too.
#[dae_model]
fn counted_ball() {
    let h = state(1.0);
    let bounces = discrete(0.0);
    der(der(h)) == -9.81;
    let bounce =
        event(h).falling().reinit(der(h), -0.5 * pre(der(h))).reinit(bounces, bounces + 1.0);
    let third = event(bounces - 2.5).rising().terminal();
}

#[test]
fn an_action_can_fire_a_terminal_event_at_the_same_instant() {
    let sol = CountedBall::default()
        .simulate(0.0, 100.0, &Options::new().tolerance(1e-12))
        .expect("stops");
    let stop = sol.stopped_by().expect("stopped");
    assert_eq!(stop.name, "third");
    let bounces = sol.event_times("bounce").unwrap();
    assert_eq!(bounces.len(), 3);
    assert_eq!(stop.t, bounces[2]);
    assert_eq!(sol.final_time(), bounces[2]);
    assert_eq!(sol.last("bounces").unwrap(), 3.0);
}

/// The rectifier built from the library's parts: the same circuit.
#[dae_model]
fn rectifier_of_parts() {
    let source = sine_voltage(amplitude = 10.0, f = 1.0);
    let r_s = resistor(1.0);
    let d = ideal_diode();
    let load_c = capacitor(c = 0.01, v0 = 1.0);
    let load_r = resistor(100.0);
    let gnd = ground();
    connect(source.p, r_s.p);
    connect(r_s.n, d.p);
    connect(d.n, load_c.p, load_r.p);
    connect(load_c.n, load_r.n, source.n, gnd.p);
}

#[test]
fn the_library_ideal_diode_rectifies_like_the_flat_model() {
    let t_end = 2.6;
    // The library's source is sin 2πft, f = 1.
    let flat = Rectifier { omega: 2.0 * std::f64::consts::PI, ..Rectifier::default() };
    let switches = rectifier_switches(&flat, t_end);
    let (model, tol) = (RectifierOfParts::default(), 1e-10);
    for (method, sol) in
        alternating_runs(&model, t_end, tol, ["d.opens", "d.closes"], switches.len())
    {
        for (jump, &(t, v)) in sol.jumps().iter().zip(&switches) {
            assert!(
                (jump.t - t).abs() <= 10.0 * reach(method, tol),
                "{method:?}: {} vs {t}",
                jump.t
            );
            let got = sol.at(jump.t, "load_c.v").unwrap();
            assert!((got - v).abs() <= 10.0 * reach(method, tol) * v.abs().max(1.0), "{method:?}");
        }
    }
}

/// The sampled PI loop from the library's blocks: `sampled_pi` on the
/// plant `first_order(k, t)`, t y' + y = k u, the same loop as `SampledPi`
/// above with a = 1/t, b = k/t.
#[dae_model]
fn sampled_loop_of_parts() {
    let setpoint = constant(1.0);
    let controller = sampled_pi(kp = 0.8, ki = 1.5, period = 0.1);
    let plant = first_order(k = 1.5, t = 0.5);
    connect(setpoint.y, controller.u_s);
    connect(controller.y, plant.u);
    connect(plant.y, controller.u_m);
}

#[test]
fn the_library_sampled_pi_follows_the_zero_order_hold_recursion() {
    let exact = zero_order_hold(&SampledPi::default(), 31);
    for method in adaptive_methods_for::<SampledLoopOfParts>() {
        let tol = 1e-12;
        let opts = Options::new().method(method).tolerance(tol);
        let sol = SampledLoopOfParts::default()
            .simulate(0.0, 3.0, &opts)
            .unwrap_or_else(|e| panic!("{method:?}: {e}"));
        for (k, &(x, u)) in exact.iter().enumerate() {
            let t = k as f64 * 0.1;
            assert!(
                (sol.at(t, "plant.y").unwrap() - x).abs() <= 10.0 * reach(method, tol),
                "{method:?} at {t}"
            );
            assert!(
                (sol.at(t, "controller.y").unwrap() - u).abs() <= 10.0 * reach(method, tol),
                "{method:?} at {t}"
            );
        }
    }
}

#[test]
fn fixed_step_methods_switch_the_thermostat_at_their_order() {
    // Each switch is located on the step's Hermite interpolant between
    // fixed steps; the switching times converge at the method's order
    // (the interpolant's own error, fourth order, is below it): halving
    // the step divides the error of the fourth switch by about 2^p.
    let m = Thermostat::default();
    let fourth = thermostat_switches(&m, 4)[3];
    let error = |method: Method, step: f64| {
        let sol = m
            .simulate(0.0, fourth + 0.1, &Options::new().method(method).step(step))
            .unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let jumps = sol.jumps();
        assert_eq!(jumps.len(), 4, "{method:?}");
        (jumps[3].t - fourth).abs()
    };
    for method in methods_for::<Thermostat>(|m| !support::harness::is_adaptive(m)) {
        let support::harness::Kind::FixedStep { order, .. } = support::harness::kind(method) else {
            unreachable!()
        };
        let (coarse, fine) = (error(method, 0.02), error(method, 0.01));
        let want = 2f64.powi(order);
        let ratio = coarse / fine;
        assert!(
            (0.6 * want..1.6 * want).contains(&ratio),
            "{method:?}: {coarse:e} / {fine:e} = {ratio}"
        );
    }
}

/// A stiff relaxation towards a square wave the clock toggles:
/// y' = −1000 (y − u), u flipping between 0 and 1 every second.
#[dae_model]
fn stiff_square_wave() {
    let y = state(0.0);
    let u = discrete(1.0);
    der(y) == -1000.0 * (y - u);
    let flip = every(1.0).offset(1.0).reinit(u, 1.0 - u);
}

#[test]
fn auto_counts_the_switches_of_every_stretch() {
    // Each stretch restarts with the explicit pair, which hands over to
    // the stiff method where its steps are held by stability: the
    // switches of all stretches count (one stretch alone makes one).
    let sol = StiffSquareWave::default()
        .simulate(0.0, 4.0, &Options::new().tolerance(1e-8))
        .expect("runs");
    let stats = sol.stats();
    // Instants at 1, 2, 3 and at the end, 4, which acts too.
    assert_eq!(sol.jumps().len(), 4);
    assert!(stats.switches >= 2, "{stats:?}");
    assert!(stats.method.contains('⇄'), "{stats:?}");
    // Relaxed to the held value at the end of each second: 1, 0, 1, 0.
    for (k, want) in [1.0, 0.0, 1.0, 0.0].iter().enumerate() {
        let t = (k + 1) as f64;
        assert!((sol.at_left(t, "y").unwrap() - want).abs() <= 1e-7, "at {t}");
    }
}

/// A car accelerating through three gears against linear drag, the drive
/// force smaller in each; the gearbox shifts up at 10 and 20 m/s.
#[dae_model]
fn gearbox() {
    let m = param(1000.0);
    let c = param(50.0);
    let f1 = param(3000.0);
    let v = state(0.0);
    let force = algebraic(0.0);
    /// The gear engaged.
    let gear = discrete(1);
    m * der(v) == force - c * v;
    if gear == 1 {
        force == f1;
    } else if gear == 2 {
        force == 0.6 * f1;
    } else {
        force == 0.4 * f1;
    }
    let second = event(v - 10.0).rising().reinit(gear, 2);
    let third = event(v - 20.0).rising().reinit(gear, 3);
}

#[test]
fn an_integer_mode_shifts_gears_as_the_exponentials_say() {
    // In gear k, v relaxes to F_k/c with τ = m/c: from v₀ to v₁ it takes
    // τ ln((v∞ − v₀)/(v∞ − v₁)).
    let car = Gearbox::default();
    let tau = car.m / car.c;
    let limit = |share: f64| share * car.f1 / car.c;
    let to = |share: f64, from: f64, target: f64| {
        tau * ((limit(share) - from) / (limit(share) - target)).ln()
    };
    let t2 = to(1.0, 0.0, 10.0);
    let t3 = t2 + to(0.6, 10.0, 20.0);
    let t_end = 30.0;
    let v_end = limit(0.4) + (20.0 - limit(0.4)) * (-(t_end - t3) / tau).exp();
    let tol = 1e-10;
    for (method, sol) in alternating_runs(&car, t_end, tol, ["second", "third"], 2) {
        let jumps = sol.jumps();
        for (jump, want) in jumps.iter().zip([t2, t3]) {
            assert!(
                (jump.t - want).abs() <= 10.0 * reach(method, tol) * want,
                "{method:?}: {} vs {want}",
                jump.t
            );
        }
        assert_eq!(sol.at_left(jumps[1].t, "gear").unwrap(), 2.0);
        assert_eq!(sol.last("gear").unwrap(), 3.0);
        let v = sol.last("v").unwrap();
        assert!(
            (v - v_end).abs() <= 10.0 * reach(method, tol) * v_end,
            "{method:?}: {v} vs {v_end}"
        );
        assert!((sol.last("force").unwrap() - 0.4 * car.f1).abs() <= 1e-9);
    }
}

/// A pendulum as an index-3 DAE in Cartesian coordinates, released at
/// θ₀ = 1 rad to the left of a wall through its pivot (x > 0), against
/// which it bounces with restitution `e`.
#[dae_model]
fn pendulum_against_a_wall() {
    let l = param(1.0);
    let g = param(9.81);
    let e = param(0.7);
    let x = state(-0.8414709848078965);
    let y = state(-0.5403023058681398);
    let lambda = algebraic(0.0);
    der(der(x)) == -lambda * x;
    der(der(y)) == -lambda * y - g;
    constraint(x * x + y * y - l * l);
    let wall = event(x).rising().reinit(der(x), -e * pre(der(x)));
}

/// The period of a pendulum of length `l` swinging to `theta`:
/// 4 sqrt(l/g) K(sin(θ/2)), K by the arithmetic-geometric mean.
fn pendulum_period(l: f64, g: f64, theta: f64) -> f64 {
    let k = (theta / 2.0).sin();
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..40 {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    4.0 * (l / g).sqrt() * std::f64::consts::PI / (2.0 * a)
}

#[test]
fn a_constrained_pendulum_bounces_off_a_wall_losing_the_energy_restitution_takes() {
    // It reaches the wall at the bottom, a quarter period after release;
    // the rebound keeps e² of the kinetic energy, so it rises to θ₁ with
    // 1 − cos θ₁ = e² (1 − cos θ₀) and is back half a period of that
    // amplitude later. After each jump the run projects the state onto
    // the constraint and its hidden levels again.
    let p = PendulumAgainstAWall::default();
    let mut theta = 1.0f64;
    let mut impacts = vec![pendulum_period(p.l, p.g, theta) / 4.0];
    for _ in 0..3 {
        theta = (1.0 - p.e * p.e * (1.0 - theta.cos())).acos();
        let last = impacts[impacts.len() - 1];
        impacts.push(last + pendulum_period(p.l, p.g, theta) / 2.0);
    }
    let tol = 1e-10;
    for method in adaptive_methods_for::<PendulumAgainstAWall>() {
        let opts = Options::new().method(method).tolerance(tol);
        let sol =
            p.simulate(0.0, impacts[3] + 0.05, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let times = sol.event_times("wall").unwrap();
        assert_eq!(times.len(), 4, "{method:?}: {times:?}");
        for (t, want) in times.iter().zip(&impacts) {
            assert!((t - want).abs() <= 100.0 * reach(method, tol), "{method:?}: {t} vs {want}");
        }
        let residuals = (sol.max_constraint_residual(), sol.max_velocity_constraint_residual());
        assert!(
            residuals.0.max(residuals.1) <= 10.0 * reach(method, tol),
            "{method:?}: {residuals:?}"
        );
    }
}

/// The pendulum caught at x = x_c: its horizontal speed is set to zero,
/// and the constraint's velocity level then wants the vertical one zero
/// too.
#[dae_model]
fn caught_pendulum() {
    let g = param(9.81);
    let x_c = param(0.5);
    let x = state(-0.8414709848078965);
    let y = state(-0.5403023058681398);
    let lambda = algebraic(0.0);
    der(der(x)) == -lambda * x;
    der(der(y)) == -lambda * y - g;
    constraint(x * x + y * y - 1.0);
    let catch = event(x - x_c).rising().terminal().reinit(der(x), 0.0);
}

#[test]
fn after_an_action_a_dae_is_projected_keeping_what_the_action_set() {
    // x·ẋ + y·ẏ = 0 with ẋ = 0 and y ≠ 0 leaves ẏ = 0: the pendulum is
    // caught at rest, ẋ as the action set it.
    let p = CaughtPendulum::default();
    for method in adaptive_methods_for::<CaughtPendulum>() {
        let sol = p
            .simulate(0.0, 2.0, &Options::new().method(method).tolerance(1e-10))
            .unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let jump = &sol.jumps()[0];
        assert!(jump.before[3].abs() > 0.5, "{method:?}: it was moving: {:?}", jump.before);
        let after = &jump.after;
        assert_eq!(after[1], 0.0, "{method:?}: der(x) as set");
        assert!(after[3].abs() <= 1e-12, "{method:?}: der(y) = {}", after[3]);
        assert!((after[0] - p.x_c).abs() <= 1e-9);
    }
}

/// The proposals' forms, written as statements: an event and a clock
/// without a name act as well, named by their text.
#[dae_model]
fn unnamed_triggers() {
    let e = param(0.8);
    let h = state(10.0);
    let looks = discrete(0.0);
    der(der(h)) == -9.81;
    event(h).falling().reinit(der(h), -e * pre(der(h)));
    every(0.5).reinit(looks, looks + 1.0);
}

#[test]
fn events_and_clocks_written_as_statements_act_under_their_text() {
    let m = UnnamedTriggers::default();
    let exact = impact_times(10.0, 9.81, m.e, 3);
    let sol = m.simulate(0.0, exact[2] + 0.01, &Options::new().tolerance(1e-12)).expect("runs");
    let bounces = sol.event_times("event(h)").expect("named by its text");
    assert_eq!(bounces.len(), 3);
    for (t, want) in bounces.iter().zip(&exact) {
        assert!((t - want).abs() <= 1e-12 * want);
    }
    let instants = (exact[2] + 0.01) / 0.5;
    assert_eq!(sol.last("looks").unwrap(), instants.floor() + 1.0);
    assert_eq!(<UnnamedTriggers as Model>::INFO.clocks[0].name, "every(0.5)");
}

#[test]
fn parameters_and_inputs_are_set_by_their_index() {
    // What a tool that knows the model by its names alone sets it by.
    let mut m = LowPass::default();
    let tau = <LowPass as Model>::INFO.parameters.iter().position(|p| *p == "tau").unwrap();
    m.set_parameter(tau, 2.0);
    assert_eq!(m.tau, 2.0);
    m.set_parameter(99, 1.0);
    m.set_input(0, daegen::Input::constant(3.0));
    assert_eq!(m.u, daegen::Input::constant(3.0));
    // τ x' = 3 − x from 0: x = 3 (1 − e^{−t/τ}).
    let x = m.simulate(0.0, 1.0, &Options::new().tolerance(1e-10)).unwrap().last("x").unwrap();
    assert!((x - 3.0 * (1.0 - (-0.5f64).exp())).abs() <= 1e-9);
}

/// A clock far faster than the time can resolve.
#[dae_model]
fn too_fast_a_clock() {
    let period = param(0.1);
    let x = state(0.0);
    let n = discrete(0.0);
    der(x) == 1.0;
    let tick = every(period).reinit(n, n + 1.0);
}

#[test]
fn a_clock_below_the_time_resolution_is_refused() {
    let m = TooFastAClock { period: 1e-20 };
    let err = m.simulate(0.0, 1.0, &Options::new()).expect_err("refused");
    assert!(err.to_string().contains("below what the time resolves"), "{err}");
    let m = TooFastAClock { period: -1.0 };
    let err = m.simulate(0.0, 1.0, &Options::new()).expect_err("refused");
    assert!(err.to_string().contains("must be positive"), "{err}");
    // And a fine one ticks 11 times over [0, 1].
    let sol = TooFastAClock::default().simulate(0.0, 1.0, &Options::new()).expect("runs");
    assert_eq!(sol.last("n").unwrap(), 11.0);
}

#[test]
fn a_run_that_continues_another_acts_its_start_instant_once() {
    // One run to 1 s, and the same in two that meet at a sample instant:
    // the first acts at 0.5 s at its end, the second starts there with
    // `continues(true)` and does not act again. Every instant restarts the
    // method, so the two ways compute the same steps, bit for bit.
    let model = SampledPi::default();
    for method in adaptive_methods_for::<SampledPi>() {
        let opts = Options::new().method(method).tolerance(1e-10);
        let whole = model.simulate(0.0, 1.0, &opts).unwrap();
        let first = model.simulate(0.0, 0.5, &opts).unwrap();
        assert_eq!(first.jumps().last().map(|j| j.t), Some(0.5), "{method:?}");
        let second =
            model.simulate_from(0.5, first.final_state(), 1.0, &opts.continues(true)).unwrap();
        assert!(second.jumps().iter().all(|j| j.t > 0.5), "{method:?}");
        for name in ["x", "u", "integral"] {
            let (a, b) = (whole.last(name).unwrap(), second.last(name).unwrap());
            assert_eq!(a.to_bits(), b.to_bits(), "{method:?} {name}: {a} vs {b}");
        }
        // Without it, the instant at 0.5 s acts twice: the integral sums
        // its error twice.
        let again = model.simulate_from(0.5, first.final_state(), 1.0, &opts).unwrap();
        assert_eq!(again.jumps()[0].t, 0.5);
        assert_ne!(again.last("integral").unwrap(), whole.last("integral").unwrap());
    }
}
