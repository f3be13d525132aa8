//! Hybrid models: events and clocks that act (`.reinit(..)`), discrete
//! values, against exact or independently computed results, with every
//! method that runs them.

use daegen::prelude::*;

mod support;
use support::harness::{adaptive_methods_for, methods_for};

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

/// The impact times: a drop of sqrt(2h/g), then flights of 2·eᵏ·v₁/g with
/// v₁ = sqrt(2gh).
fn impact_times(h: f64, g: f64, e: f64, bounces: usize) -> Vec<f64> {
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

/// The error a method's run at tolerance `tol` is held to: `tol`, but for
/// RADAU5, which works to 0.1·tol^(2/3) (Hairer's `radau5.f`, kept by the
/// runtime).
fn reach(method: Method, tol: f64) -> f64 {
    match method {
        Method::Radau5 => 0.1 * tol.powf(2.0 / 3.0),
        _ => tol,
    }
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

/// A first-order plant x' = −a x + b u under a PI controller sampled
/// every `h`, its output held between samples (a zero-order hold).
#[dae_model(taylor = 1)]
fn sampled_pi() {
    let a = param(2.0);
    let b = param(3.0);
    let kp = param(0.8);
    let ki = param(1.5);
    let r = param(1.0);
    let h = param(0.1);
    let x = state(0.0);
    /// The controller's output, held between samples.
    let u = discrete(0.0);
    /// The integral of the error, summed at the samples.
    let integral = discrete(0.0);
    der(x) == -a * x + b * u;
    /// The controller reads x and sets u.
    let sample =
        every(h).reinit(integral, integral + ki * h * (r - x)).reinit(u, kp * (r - x) + integral);
}

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

#[test]
fn a_thermostat_switches_when_the_exponentials_say() {
    // T relaxes to T∞ with time constant τ = c/k: from T0 to T1 it takes
    // τ ln((T0 − T∞)/(T1 − T∞)); T∞ = Ta + p/k heating, Ta cooling.
    let m = Thermostat::default();
    let tau = m.c / m.k;
    let (hot, cold) = (m.t_ambient + m.p / m.k, m.t_ambient);
    let heat = |from: f64, to: f64| tau * ((from - hot) / (to - hot)).ln();
    let cool = |from: f64, to: f64| tau * ((from - cold) / (to - cold)).ln();
    let mut switches = vec![heat(15.0, m.t_high)];
    for k in 1..10 {
        let last = switches[k - 1];
        switches.push(
            last + if k % 2 == 1 { cool(m.t_high, m.t_low) } else { heat(m.t_low, m.t_high) },
        );
    }
    let t_end = switches[9] + 0.2;
    for method in adaptive_methods_for::<Thermostat>() {
        let opts = Options::new().method(method).tolerance(1e-12);
        let sol = m.simulate(0.0, t_end, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let jumps = sol.jumps();
        assert_eq!(jumps.len(), 10, "{method:?}");
        for (k, (jump, want)) in jumps.iter().zip(&switches).enumerate() {
            assert!(
                (jump.t - want).abs() <= 10.0 * reach(method, 1e-12) * want,
                "{method:?}: switch {k} at {}, exact {want}",
                jump.t
            );
            let (name, on) = if k % 2 == 0 { ("too_warm", 0.0) } else { ("too_cold", 1.0) };
            assert_eq!(jump.triggers, [name], "{method:?}");
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
