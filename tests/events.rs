//! Events: zero crossings of `event(...)` functions located on each method's
//! continuous extension, against times known in closed form.

use daegen::prelude::*;

mod support;
use support::harness::{adaptive_methods_for, is_high_order_at_tight_tolerances, methods_for};
use support::impact_times;

/// A ball dropped from `h` that bounces with restitution `e`.
#[dae_model(taylor = 1)]
fn bouncing_ball() {
    let g = param(9.81);
    let h = param(10.0);
    let height = state(h);
    der(der(height)) == -g;
    /// The ball reaches the ground.
    let impact = event(height).falling().terminal();
}

include!("models/kepler.rs");

// Kepler's problem with e = 0.9 from perihelion; the sections are where the
// orbit crosses the axes and where it passes an apsis.
kepler_model!(fn kepler_sections(taylor = 1) {
    let perihelion = event(q2).rising();
    let y_axis = event(q1);
    let apsis = event(q1 * p1 + q2 * p2);
});

/// Bounces the ball `bounces` times, restarting after each terminal impact
/// with the velocity reversed and scaled by `restitution`.
fn bounce(method: Method, restitution: f64, bounces: usize) -> Vec<(f64, Vec<f64>)> {
    let ball = BouncingBall::default();
    let opts = Options::new().method(method).tolerance(1e-12);
    let (mut t, mut y) = (0.0, vec![ball.h, 0.0]);
    let mut impacts = Vec::new();
    for _ in 0..bounces {
        let sol =
            ball.simulate_from(t, &y, 100.0, &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let hit = sol.stopped_by().unwrap_or_else(|| panic!("{method:?}: the ball never landed"));
        assert_eq!(hit.name, "impact");
        assert!(!hit.rising);
        assert_eq!(sol.times().last(), Some(&hit.t));
        assert_eq!(sol.final_state(), &hit.state[..]);
        t = hit.t;
        y = vec![hit.state[0], -restitution * hit.state[1]];
        impacts.push((t, hit.state.clone()));
    }
    impacts
}

#[test]
fn bouncing_ball_lands_when_the_parabola_says_for_every_adaptive_method() {
    let exact = impact_times(10.0, 9.81, 0.8, 6);
    // Every adaptive method that runs the ball: each locates the impact on
    // its own continuous extension.
    for method in adaptive_methods_for::<BouncingBall>() {
        let impacts = bounce(method, 0.8, 6);
        for ((t, y), want) in impacts.iter().zip(&exact) {
            // The parabola is reproduced by every continuous extension
            // (all are exact for quadratics), so the impact is found to
            // rounding: the restarts add a few ulps each.
            assert!((t - want).abs() <= 1e-13 * want, "{method:?}: impact at {t}, exact {want}");
            assert!(y[0].abs() <= 1e-12, "{method:?}: height {} at impact", y[0]);
        }
    }
}

#[test]
fn fixed_step_methods_fire_events_from_their_interpolation() {
    // RK4 reproduces the parabola at its steps; between them the linear
    // interpolation misses the ground by at most g·h²/8, so the impact time
    // is off by at most that over the impact speed.
    let (g, h0, step) = (9.81f64, 10.0f64, 0.01f64);
    let ball = BouncingBall::default();
    let opts = Options::new().method(Method::Rk4).step(step);
    let sol = ball.simulate(0.0, 3.0, &opts).expect("runs");
    let hit = sol.stopped_by().expect("lands");
    let exact = (2.0 * h0 / g).sqrt();
    let bound = g * step * step / 8.0 / (g * exact);
    assert!((hit.t - exact).abs() <= bound, "{} vs {exact}", hit.t);
}

/// Kepler's equation: E − e sin E = t.
fn eccentric_anomaly(t: f64, e: f64) -> f64 {
    let mut big_e = t + e * t.sin();
    for _ in 0..100 {
        big_e -= (big_e - e * big_e.sin() - t) / (1.0 - e * big_e.cos());
    }
    big_e
}

#[test]
fn poincare_sections_of_the_kepler_orbit_fall_where_keplers_equation_puts_them() {
    let e = 0.9f64;
    let periods = 20;
    let t_end = periods as f64 * std::f64::consts::TAU + 1.0;
    let two_pi = std::f64::consts::TAU;
    // The orbit crosses the y axis (q1 = cos E − e = 0) at E = ±acos(e).
    let m_axis = {
        let big_e = e.acos();
        big_e - e * big_e.sin()
    };
    // The methods of high order: 1e-9 after twenty orbits of e = 0.9 at
    // tol 1e-13 is beyond the methods of order 5 (DOPRI5's perihelion 15
    // is 1.0e-9 off, RADAU5's perihelion 5 1.1e-9).
    for method in methods_for::<KeplerSections>(is_high_order_at_tight_tolerances) {
        let opts = Options::new().method(method).tolerance(1e-13);
        let sol = KeplerSections::default().simulate(0.0, t_end, &opts).expect("runs");
        // Perihelion passages at 2πk (the start itself, on the section, does not count).
        let perihelia = sol.event_times("perihelion").expect("declared");
        assert_eq!(perihelia.len(), periods, "{method:?}");
        for (k, t) in perihelia.iter().enumerate() {
            let want = two_pi * (k + 1) as f64;
            assert!((t - want).abs() <= 1e-9, "{method:?}: perihelion {k} at {t}, exact {want}");
        }
        // Apsides at πk: both directions of r·v.
        let apsides = sol.event_times("apsis").expect("declared");
        assert_eq!(apsides.len(), 2 * periods, "{method:?}");
        for (k, t) in apsides.iter().enumerate() {
            let want = std::f64::consts::PI * (k + 1) as f64;
            assert!((t - want).abs() <= 1e-9, "{method:?}: apsis {k} at {t}, exact {want}");
        }
        // Crossings of the y axis, alternately leaving and entering q1 > 0.
        let crossings: Vec<_> = sol.events().iter().filter(|h| h.name == "y_axis").collect();
        // 20 periods and 1 time unit: the first crossing of period 21 too.
        assert!(m_axis < 1.0);
        assert_eq!(crossings.len(), 2 * periods + 1, "{method:?}");
        for (k, hit) in crossings.iter().enumerate() {
            let period = (k / 2) as f64 * two_pi;
            let (want, rising) = if k % 2 == 0 {
                (period + m_axis, false)
            } else {
                (period + two_pi - m_axis, true)
            };
            assert_eq!(hit.rising, rising, "{method:?}: crossing {k}");
            assert!(
                (hit.t - want).abs() <= 1e-9,
                "{method:?}: crossing {k} at {}, exact {want}",
                hit.t
            );
            // On the section the state is the exact one there.
            let big_e = eccentric_anomaly(hit.t, e);
            let q2 = (1.0 - e * e).sqrt() * big_e.sin();
            assert!(
                hit.state[0].abs() <= 1e-9 && (hit.state[1] - q2).abs() <= 1e-8,
                "{method:?}: {:?}",
                hit.state
            );
        }
        // Non-terminal events do not stop the run.
        assert!(sol.stopped_by().is_none());
        assert_eq!(sol.times().last(), Some(&t_end));
        // All hits in time order.
        assert!(sol.events().windows(2).all(|w| w[0].t <= w[1].t));
    }
}

#[test]
fn event_metadata_and_names() {
    let info = <KeplerSections as Model>::INFO.events;
    let names: Vec<_> = info.iter().map(|e| e.name).collect();
    assert_eq!(names, ["perihelion", "y_axis", "apsis"]);
    assert_eq!(info[0].direction, daegen::EventDirection::Rising);
    assert_eq!(info[1].direction, daegen::EventDirection::Any);
    assert!(!info[0].terminal);
    let ball = <BouncingBall as Model>::INFO.events[0];
    assert!(ball.terminal && ball.direction == daegen::EventDirection::Falling);
    assert_eq!(ball.doc, "The ball reaches the ground.");
    let sol = BouncingBall::default().simulate(0.0, 0.1, &Options::new()).expect("runs");
    assert!(sol.event_times("impact").expect("declared").is_empty());
    let err = sol.event_times("impakt").unwrap_err().to_string();
    assert!(err.contains("impakt") && err.contains("impact"), "{err}");
}

/// The event function is √x − 2, which stops being finite when x < 0.
#[dae_model]
fn draining() {
    let x = state(1.0);
    der(x) == -1.0;
    let low = event(sqrt(x) - 2.0);
}

#[test]
fn a_non_finite_event_function_is_an_error_naming_the_event() {
    // Every method that runs the model: each evaluates the event functions
    // after its steps (the adaptive Taylor method at subdivisions of its
    // long steps), and the partial solution ends where one stopped being
    // finite.
    for method in methods_for::<Draining>(|_| true) {
        let err = Draining::default()
            .simulate(0.0, 3.0, &Options::new().method(method).step(0.25))
            .unwrap_err();
        match &err {
            daegen::Error::NonFinite { t, variable, partial } => {
                assert_eq!(*variable, "low");
                assert!(*t >= 1.0 - 1e-9 && *t <= 3.0, "{method:?}: {t}");
                assert!(
                    partial.times().last().is_some_and(|&tp| tp <= *t),
                    "{method:?}: {t}, the partial solution to {:?}",
                    partial.times().last()
                );
            }
            other => panic!("{method:?}: {other}"),
        }
    }
}

#[test]
fn restarting_with_a_state_of_the_wrong_length_is_an_error() {
    let err = BouncingBall::default()
        .simulate_from(0.0, &[1.0], 1.0, &Options::new())
        .unwrap_err()
        .to_string();
    assert!(err.contains("height, der(height)"), "{err}");
}

/// Backwards in time the crossings come in reverse order, and rising and
/// falling still refer to time.
#[test]
fn a_backward_run_finds_the_crossings_in_reverse_with_their_directions_in_time() {
    let e = 0.9f64;
    let two_pi = std::f64::consts::TAU;
    let m_axis = {
        let big_e = e.acos();
        big_e - e * big_e.sin()
    };
    let start = {
        // The exact state at 2π is the perihelion again.
        let p2 = ((1.0 + e) / (1.0 - e)).sqrt();
        [1.0 - e, 0.0, 0.0, p2]
    };
    // Every adaptive method that runs the model: one period backwards stays
    // within 1e-9 even at order 5.
    for method in adaptive_methods_for::<KeplerSections>() {
        let opts = Options::new().method(method).tolerance(1e-13);
        let sol =
            KeplerSections::default().simulate_from(two_pi, &start, 0.0, &opts).expect("runs");
        let axis: Vec<_> = sol.events().iter().filter(|h| h.name == "y_axis").collect();
        assert_eq!(axis.len(), 2, "{method:?}");
        // First met going back: the rising crossing at 2π − m, then the
        // falling one at m.
        assert!(
            axis[0].rising && (axis[0].t - (two_pi - m_axis)).abs() < 1e-9,
            "{method:?}: {:?}",
            axis[0].t
        );
        assert!(
            !axis[1].rising && (axis[1].t - m_axis).abs() < 1e-9,
            "{method:?}: {:?}",
            axis[1].t
        );
        // Only rising (in time) perihelion passages count: none inside (0, 2π).
        assert!(
            sol.event_times("perihelion").expect("declared").iter().all(|&t| t.abs() < 1e-9),
            "{method:?}"
        );
    }
}

#[test]
fn restarting_at_accumulating_bounces_ends_in_a_chatter_error_at_the_zeno_time() {
    // Restitution 1/2: the flights shrink geometrically and the impacts
    // accumulate at T = t₁ (1 + e)/(1 − e) = 3 t₁, t₁ = sqrt(2h/g).
    let ball = BouncingBall::default();
    let zeno = 3.0 * (2.0 * ball.h / ball.g).sqrt();
    // Every adaptive method that runs the ball: each locates the impacts
    // on its own continuous extension until they accumulate.
    for method in adaptive_methods_for::<BouncingBall>() {
        let opts = Options::new().method(method).tolerance(1e-12);
        let (mut t, mut y) = (0.0, vec![ball.h, 0.0]);
        let mut bounces = 0;
        let err = loop {
            match ball.simulate_from(t, &y, 100.0, &opts) {
                Ok(sol) => {
                    let hit = sol.stopped_by().expect("an impact");
                    t = hit.t;
                    y = vec![hit.state[0], -0.5 * hit.state[1]];
                    bounces += 1;
                    assert!(bounces < 200, "{method:?}: no end to the bounces");
                }
                Err(e) => break e,
            }
        };
        match &err {
            daegen::Error::EventChatter { t, event, after, .. } => {
                assert_eq!(*event, "impact");
                assert!(*after < 1e-12);
                assert!((t - zeno).abs() <= 1e-9, "{method:?}: {t} vs {zeno}");
            }
            other => {
                panic!("{method:?}: expected EventChatter after {bounces} bounces, got {other}")
            }
        }
        assert!(err.to_string().contains("Zeno"));
        assert!((30..100).contains(&bounces), "{method:?}: {bounces} bounces");
    }
}
