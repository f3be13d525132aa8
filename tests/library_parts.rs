//! The standard library's parts one domain at a time, each in a small
//! circuit, mechanism or loop whose solution is known exactly.

use daegen::prelude::*;

fn tight() -> Options {
    Options::new().method(Method::Radau5).rtol(1e-11).atol(1e-11)
}

/// A mass on a spring and a damper to a fixed wall, pushed by a constant
/// force from t = 0: m = 2, c = 8, d = 1.6, F = 4.
#[dae_model]
fn sliding_mass() {
    let wall = translational_fixed();
    let spring = translational_spring(8.0);
    let damper = translational_damper(1.6);
    let body = mass(m = 2.0);
    let push = force_source(4.0);
    let sensor = position_sensor();
    connect(wall.flange, spring.flange_a, damper.flange_a);
    connect(spring.flange_b, damper.flange_b, body.flange_a);
    connect(body.flange_b, push.flange, sensor.flange);
}

#[test]
fn a_pushed_mass_on_a_spring_damper_settles_as_the_exact_solution() {
    // m s'' + d s' + c s = F from rest: s = F/c (1 − e^{−ζω t}(cos ω_d t + ζω/ω_d sin ω_d t)).
    let (m, c, d, f) = (2.0f64, 8.0, 1.6, 4.0);
    let (a, w0) = (d / (2.0 * m), (c / m).sqrt());
    let wd = (w0 * w0 - a * a).sqrt();
    let exact =
        |t: f64| f / c * (1.0 - (-a * t).exp() * ((wd * t).cos() + a / wd * (wd * t).sin()));
    let sol = SlidingMass::default().simulate(0.0, 10.0, &tight()).unwrap();
    for &t in &[0.5, 2.0, 10.0] {
        let s = sol.at(t, "sensor.s").unwrap();
        assert!((s - exact(t)).abs() < 1e-8, "t = {t}: {s} vs {}", exact(t));
        // The spring's force is its stretch times its stiffness.
        assert!((sol.at(t, "spring.f").unwrap() - c * s).abs() < 1e-9);
    }
    // Two states, as by hand: the damper's relative position is the mass's.
    assert_eq!(<SlidingMass as Model>::INFO.states, ["body.s", "body.v"]);
}

/// An inverting integrator: an ideal op-amp with 10 kΩ in and 1 µF in
/// its feedback, fed 0.5 V.
#[dae_model]
fn opamp_integrator() {
    let source = constant_voltage(0.5);
    let r_in = resistor(1e4);
    let c_f = capacitor(1e-6);
    let amp = ideal_opamp();
    let meter = voltage_sensor();
    let gnd = ground();
    connect(source.p, r_in.p);
    connect(r_in.n, amp.in_n, c_f.p);
    connect(c_f.n, amp.out, meter.p);
    connect(amp.in_p, source.n, meter.n, gnd.p);
}

#[test]
fn an_opamp_integrator_ramps_exactly() {
    // v_out = −v_in t / (R C): −50 V/s.
    let sol = OpampIntegrator::default().simulate(0.0, 0.1, &tight()).unwrap();
    for &t in &[0.01, 0.05, 0.1] {
        let v = sol.at(t, "meter.v").unwrap();
        assert!((v + 50.0 * t).abs() < 1e-9, "t = {t}: {v}");
    }
    // The inverting input is a virtual ground and draws no current.
    assert!(sol.last("amp.in_n.v").unwrap().abs() < 1e-12);
    assert!(sol.last("amp.in_n.i").unwrap().abs() < 1e-15);
}

/// A diode behind 100 Ω on 1 V, a capacitor across it.
#[dae_model]
fn diode_drop() {
    let gnd = ground();
    let source = constant_voltage(1.0);
    let load = resistor(100.0);
    connect(source.p, load.p);
    let d = diode(ids = 1e-9, vt = 0.025);
    let store = capacitor(1e-6);
    connect(load.n, d.p, store.p);
    connect(d.n, store.n, source.n, gnd.p);
}

#[test]
fn a_diode_settles_where_its_law_meets_the_resistor_s() {
    let sol = DiodeDrop::default().simulate(0.0, 1e-2, &tight()).unwrap();
    // At rest (1 − v)/100 = ids (exp(v/vt) − 1): by bisection.
    let f = |v: f64| (1.0 - v) / 100.0 - 1e-9 * ((v / 0.025).exp() - 1.0);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let v = sol.last("d.v").unwrap();
    assert!((v - lo).abs() < 1e-9, "{v} vs {lo}");
    assert!((sol.last("d.i").unwrap() - (1.0 - lo) / 100.0).abs() < 1e-10);
}

/// Signal blocks: a first-order lag and an integrator fed a step, a
/// feedback loop of a gain and an integrator, a sine integrated, a ramp
/// into a saturation.
#[dae_model]
fn blocks() {
    let command = step(height = 2.0, start_time = -1.0);
    let lag = first_order(k = 3.0, t = 0.5);
    let sum = integrator(k = 1.5);
    connect(command.y, lag.u, sum.u);
    // y' = k (r − y): a loop of a feedback, a gain and an integrator.
    let setpoint = constant(1.0);
    let error = feedback();
    let amplify = gain(4.0);
    let follow = integrator();
    connect(setpoint.y, error.u1);
    connect(error.y, amplify.u);
    connect(amplify.y, follow.u);
    connect(follow.y, error.u2);
    let wave = sine(amplitude = 1.0, f = 0.5);
    let area = integrator();
    connect(wave.y, area.u);
    let rise = ramp(height = 4.0, duration = 2.0, offset = -2.0);
    let limit = saturation(y_max = 1.0, y_min = -1.0, eps = 1e-4);
    let weights = add(k1 = 2.0, k2 = -1.0);
    connect(rise.y, limit.u, weights.u1);
    connect(limit.y, weights.u2);
}

#[test]
fn the_blocks_follow_their_exact_responses() {
    let sol = Blocks::default().simulate(0.0, 3.0, &tight()).unwrap();
    let pi = std::f64::consts::PI;
    for &t in &[0.25f64, 1.0, 2.0, 3.0] {
        let close = |name: &str, exact: f64, tol: f64| {
            let got = sol.at(t, name).unwrap();
            assert!((got - exact).abs() < tol, "t = {t}: {name} = {got}, exact {exact}");
        };
        close("lag.y", 6.0 * (1.0 - (-t / 0.5).exp()), 1e-8);
        close("sum.y", 3.0 * t, 1e-8);
        close("follow.y", 1.0 - (-4.0 * t).exp(), 1e-8);
        close("area.y", (1.0 - (pi * t).cos()) / pi, 1e-8);
        // The ramp from −2 to 2 over two seconds, clamped to ±1 (within
        // eps/2 where it bends), and 2 u − y after.
        let u = (-2.0 + 2.0 * t).min(2.0);
        close("rise.y", u, 1e-12);
        close("limit.y", u.clamp(-1.0, 1.0), 5e-5);
        close("weights.y", 2.0 * u - u.clamp(-1.0, 1.0), 1e-4);
    }
}

/// A PI speed loop with output limits and anti-windup on a lagging
/// plant: the output never leaves its limits.
#[dae_model]
fn limited_loop() {
    let controller = limited_pi(kp = 2.0, ki = 5.0, y_max = 3.0, y_min = -3.0, k_aw = 10.0);
    let plant = first_order(k = 2.0, t = 1.0);
    connect(controller.y, plant.u);
    connect(plant.y, controller.u_m);
    let setpoint = constant(10.0);
    connect(setpoint.y, controller.u_s);
}

#[test]
fn a_limited_pi_stays_within_its_limits_and_winds_back() {
    let sol = LimitedLoop::default().simulate(0.0, 20.0, &tight()).unwrap();
    // The set point 10 is out of reach (the plant gives at most 2 · 3 = 6):
    // the output saturates at 3 and the plant settles at 6.
    for &t in sol.times() {
        let y = sol.at(t, "controller.y").unwrap();
        assert!((-3.0 - 1e-3..=3.0 + 1e-3).contains(&y), "t = {t}: {y}");
    }
    assert!((sol.last("plant.y").unwrap() - 6.0).abs() < 1e-3);
    // Back-calculation holds the integral where kp e + x stays near the
    // limit, x = 3 − kp e + (y − v) ki/k_aw… bounded, not growing as t.
    let x = sol.last("controller.x").unwrap();
    assert!(x.abs() < 10.0, "wound up: {x}");
}

/// Rotational parts: an inertia on a spring-damper to the housing, driven
/// by a constant torque through a 2:1 gear, measured by sensors.
#[dae_model]
fn geared_oscillator() {
    let drive = torque_source(0.3);
    let gear = ideal_gear(2.0);
    let wheel = inertia(j = 0.5);
    let coupling = spring_damper(c = 4.0, d = 0.4);
    let housing = fixed();
    let angle = angle_sensor();
    let speed = speed_sensor();
    let meter = torque_sensor();
    connect(drive.flange, gear.flange_a);
    connect(gear.flange_b, meter.flange_a);
    connect(meter.flange_b, wheel.flange_a, angle.flange, speed.flange);
    connect(wheel.flange_b, coupling.flange_a);
    connect(coupling.flange_b, housing.flange);
}

#[test]
fn a_geared_oscillator_rings_as_the_exact_solution() {
    // The gear doubles the torque on the wheel (τ_b = ratio τ_a) with no
    // inertia of its own: j φ'' + d φ' + c φ = 2 · 0.3, from rest.
    let (j, c, d, tau) = (0.5f64, 4.0, 0.4, 0.6);
    let (a, w0) = (d / (2.0 * j), (c / j).sqrt());
    let wd = (w0 * w0 - a * a).sqrt();
    let exact =
        |t: f64| tau / c * (1.0 - (-a * t).exp() * ((wd * t).cos() + a / wd * (wd * t).sin()));
    let sol = GearedOscillator::default().simulate(0.0, 8.0, &tight()).unwrap();
    for &t in &[0.5, 3.0, 8.0] {
        let phi = sol.at(t, "angle.phi").unwrap();
        assert!((phi - exact(t)).abs() < 1e-8, "t = {t}: {phi} vs {}", exact(t));
        assert!((sol.at(t, "speed.w").unwrap() - sol.at(t, "wheel.w").unwrap()).abs() < 1e-12);
        assert!((sol.at(t, "meter.tau").unwrap() - tau).abs() < 1e-9);
    }
    assert_eq!(<GearedOscillator as Model>::INFO.states.len(), 2);
}

/// A wire heated by 5 W, convecting to air, its temperature measured.
#[dae_model]
fn heated_wire() {
    let heater = heat_flow_source(5.0);
    let wire = heat_capacitor(c = 20.0, t0 = 300.0);
    let film = convection(0.5);
    let air = fixed_temperature(300.0);
    let probe = temperature_sensor();
    connect(heater.port, wire.port, film.solid, probe.port);
    connect(film.fluid, air.port);
}

#[test]
fn a_heated_wire_warms_as_the_exact_solution() {
    // c T' = P − h (T − T_air): T = T_air + P/h (1 − e^{−h t / c}).
    let sol = HeatedWire::default().simulate(0.0, 100.0, &tight()).unwrap();
    for &t in &[10.0f64, 40.0, 100.0] {
        let exact = 300.0 + 10.0 * (1.0 - (-0.5 * t / 20.0).exp());
        let got = sol.at(t, "probe.t").unwrap();
        // rtol 1e-11 on 300 K: a global error of a few 1e-9 relative.
        assert!((got - exact).abs() < 1e-6, "t = {t}: {got} vs {exact}");
    }
}
