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
