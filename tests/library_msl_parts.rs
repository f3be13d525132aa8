//! The library's parts that carry the names and equations of the Modelica
//! Standard Library's (conductors, controlled sources, switches, sensors
//! and sources of motion, thermal resistors and radiation, limiters), each
//! in a small circuit, mechanism or loop whose solution is known exactly.

use daegen::prelude::*;

fn tight() -> Options {
    Options::new().method(Method::Radau5).rtol(1e-11).atol(1e-11)
}

/// `|a − b| ≤ bound`, said with the name.
fn close(name: &str, a: f64, b: f64, bound: f64) {
    assert!((a - b).abs() <= bound, "{name}: {a} vs {b}");
}

/// 10 V across a conductor of 0.5 S; across a variable resistor set to
/// 4 Ω; across a transformer (n = 2) loaded by 5 Ω.
#[dae_model]
fn conductors_and_transformer() {
    let gnd = ground();
    let source = constant_voltage(10.0);
    connect(source.n, gnd.p);
    let g = conductor(0.5);
    connect(source.p, g.p);
    connect(g.n, gnd.p);
    let r = variable_resistor();
    let four = constant(4.0);
    connect(four.y, r.r);
    connect(source.p, r.p);
    connect(r.n, gnd.p);
    let t = ideal_transformer(n = 2.0);
    let load = resistor(5.0);
    connect(source.p, t.p1);
    connect(t.n1, t.n2, gnd.p);
    connect(t.p2, load.p);
    connect(load.n, gnd.p);
}

#[test]
fn conductors_and_an_ideal_transformer_obey_their_laws() {
    let sol = ConductorsAndTransformer::default().simulate(0.0, 1.0, &tight()).unwrap();
    close("g.i", sol.last("g.i").unwrap(), 5.0, 1e-12);
    close("r.i", sol.last("r.i").unwrap(), 2.5, 1e-12);
    // v2 = v1/n = 5 V into 5 Ω: 1 A leaves p2, so i2 = −1 and i1 = 0.5.
    close("t.v2", sol.last("t.v2").unwrap(), 5.0, 1e-12);
    close("t.i2", sol.last("t.i2").unwrap(), -1.0, 1e-12);
    close("t.i1", sol.last("t.i1").unwrap(), 0.5, 1e-12);
}

/// The four controlled sources, each controlled by 2 V across a 1 Ω
/// resistor (2 A through it), each driving a 4 Ω resistor.
#[dae_model]
fn controlled_sources() {
    let gnd = ground();
    let source = constant_voltage(2.0);
    connect(source.n, gnd.p);
    let sense = resistor(1.0);
    let e = vcvs(gain = 3.0);
    let g = vccs(transconductance = 0.5);
    let h = ccvs(transresistance = 2.0);
    let f = cccs(gain = 0.25);
    // The voltage-controlled ones across the source; the current-controlled
    // ones in series with `sense`.
    connect(source.p, e.p1, g.p1, h.p1);
    connect(h.n1, f.p1);
    connect(f.n1, sense.p);
    connect(sense.n, e.n1, g.n1, gnd.p);
    let re = resistor(4.0);
    let rg = resistor(4.0);
    let rh = resistor(4.0);
    let rf = resistor(4.0);
    connect(e.p2, re.p);
    connect(g.p2, rg.p);
    connect(h.p2, rh.p);
    connect(f.p2, rf.p);
    connect(re.n, rg.n, rh.n, rf.n, e.n2, g.n2, h.n2, f.n2, gnd.p);
}

#[test]
fn controlled_sources_follow_their_control() {
    let sol = ControlledSources::default().simulate(0.0, 1.0, &tight()).unwrap();
    // VCVS: 3·2 = 6 V across 4 Ω.
    close("e.v2", sol.last("e.v2").unwrap(), 6.0, 1e-12);
    // VCCS: 0.5·2 = 1 A into p2, out of the resistor's p: −4 V across it.
    close("g.i2", sol.last("g.i2").unwrap(), 1.0, 1e-12);
    close("rg.v", sol.last("rg.v").unwrap(), -4.0, 1e-12);
    // The control current is 2 A through the 1 Ω sense resistor.
    close("h.i1", sol.last("h.i1").unwrap(), 2.0, 1e-12);
    close("h.v2", sol.last("h.v2").unwrap(), 4.0, 1e-12);
    close("f.i2", sol.last("f.i2").unwrap(), 0.5, 1e-12);
}

/// 1 V charging 1 F through 1 Ω and a switch closed at t = 0.5 (its
/// control a step), and opened again at t = 2 through an opening switch.
#[dae_model]
fn switched_rc() {
    let gnd = ground();
    let source = constant_voltage(1.0);
    connect(source.n, gnd.p);
    let close_at = step(height = 1.0, start_time = 0.5);
    let on = ideal_closing_switch();
    connect(close_at.y, on.control);
    let open_at = step(height = 1.0, start_time = 2.0);
    let off = ideal_opening_switch();
    connect(open_at.y, off.control);
    connect(source.p, on.p);
    connect(on.n, off.p);
    let r = resistor(1.0);
    let c = capacitor(1.0);
    connect(off.n, r.p);
    connect(r.n, c.p);
    connect(c.n, gnd.p);
}

#[test]
fn ideal_switches_open_and_close_with_their_control() {
    // The resistance in series: 1/goff + ron while the closing switch is
    // open, 2 ron + 1 Ω while both are closed, ron + 1/goff after.
    let (ron, goff) = (1e-5f64, 1e-5);
    let r_open = 1.0 / goff + ron + 1.0;
    let r_closed = 1.0 + 2.0 * ron;
    let v = |t: f64| {
        let v1 = 1.0 - (-0.5 / r_open).exp();
        if t <= 0.5 {
            return 1.0 - (-t / r_open).exp();
        }
        let v2 = 1.0 - (1.0 - v1) * (-(2.0 - 0.5) / r_closed).exp();
        if t <= 2.0 {
            return 1.0 - (1.0 - v1) * (-(t - 0.5) / r_closed).exp();
        }
        1.0 - (1.0 - v2) * (-(t - 2.0) / r_open).exp()
    };
    let sol = SwitchedRc::default().simulate(0.0, 3.0, &tight()).unwrap();
    for t in [0.25, 0.5, 1.0, 2.0, 2.5, 3.0] {
        close(&format!("c.v at {t}"), sol.at(t, "c.v").unwrap(), v(t), 1e-9);
    }
}

/// A half-wave rectifier: a 1 V, 1 Hz sine through a piecewise-linear
/// diode into 1 Ω.
#[dae_model]
fn half_wave() {
    let gnd = ground();
    let source = sine_voltage(amplitude = 1.0, f = 1.0);
    let d = piecewise_diode();
    let load = resistor(1.0);
    connect(source.p, d.p);
    connect(d.n, load.p);
    connect(load.n, source.n, gnd.p);
}

#[test]
fn a_piecewise_diode_conducts_forward_and_leaks_backward() {
    let (ron, goff) = (1e-5f64, 1e-5);
    // No state bounds the steps of this circuit: a step longer than half
    // a period could pass over two crossings of the sine unseen.
    let sol = HalfWave::default().simulate(0.0, 2.0, &tight().max_step(0.05)).unwrap();
    for t in [0.1, 0.25, 0.4, 0.6, 0.75, 0.9, 1.25, 1.75] {
        let v = (2.0 * std::f64::consts::PI * t).sin();
        // Forward: i = v/(1 + ron); backward: s = v/(1 + goff), i = goff s.
        let i = if v > 0.0 { v / (1.0 + ron) } else { goff * v / (1.0 + goff) };
        close(&format!("load.i at {t}"), sol.at(t, "load.i").unwrap(), i, 1e-9);
    }
    // It switches where the sine crosses zero: at 0.5, 1 and 1.5.
    let times: Vec<f64> = sol.events().iter().map(|e| e.t).collect();
    assert_eq!(times.len(), 3, "{times:?}");
    for (t, at) in times.iter().zip([0.5, 1.0, 1.5]) {
        close("switch", *t, at, 1e-9);
    }
}

/// An inertia (1 kg m²) dragged by a damper (1 N m s) from a flange
/// turning at 2 rad/s, watched by the relative and absolute sensors.
#[dae_model]
fn dragged_inertia() {
    let two = constant(2.0);
    let drive = speed_source();
    connect(two.y, drive.w_ref);
    let drag = damper(1.0);
    let power = power_sensor();
    let rotor = inertia(j = 1.0);
    connect(drive.flange, drag.flange_a);
    connect(drag.flange_b, power.flange_a);
    connect(power.flange_b, rotor.flange_a);
    let angle = relative_angle_sensor();
    let speed = relative_speed_sensor();
    connect(drive.flange, angle.flange_a, speed.flange_a);
    connect(rotor.flange_b, angle.flange_b, speed.flange_b);
    let housing = fixed();
    let acceleration = relative_acceleration_sensor();
    let absolute = acceleration_sensor();
    connect(housing.flange, acceleration.flange_a);
    connect(rotor.flange_b, acceleration.flange_b, absolute.flange);
}

#[test]
fn rotational_sensors_read_the_dragged_inertia() {
    // w' = 2 − w from rest: w = 2(1 − e^{−t}), φ = 2t − w.
    let sol = DraggedInertia::default().simulate(0.0, 3.0, &tight()).unwrap();
    for t in [0.5f64, 1.0, 3.0] {
        let e = (-t).exp();
        let (w, a) = (2.0 * (1.0 - e), 2.0 * e);
        close("rotor.w", sol.at(t, "rotor.w").unwrap(), w, 1e-9);
        close("angle.phi_rel", sol.at(t, "angle.phi_rel").unwrap(), -w, 1e-9);
        close("speed.w_rel", sol.at(t, "speed.w_rel").unwrap(), w - 2.0, 1e-9);
        close("acceleration.a_rel", sol.at(t, "acceleration.a_rel").unwrap(), a, 1e-9);
        close("absolute.a", sol.at(t, "absolute.a").unwrap(), a, 1e-9);
        // The torque reaching the rotor, j a, times its speed.
        close("power.power", sol.at(t, "power.power").unwrap(), a * w, 1e-9);
    }
}

/// An inertia (2 kg m²) whose angle follows a sine of 1 rad at 1 Hz,
/// through a torque sensor; another accelerated at 3 rad/s².
#[dae_model]
fn prescribed_motion() {
    let wave = sine(amplitude = 1.0, f = 1.0);
    let follow = angle_source();
    connect(wave.y, follow.phi_ref);
    let sensor = torque_sensor();
    let rotor = inertia(j = 2.0);
    connect(follow.flange, sensor.flange_a);
    connect(sensor.flange_b, rotor.flange_a);
    let three = constant(3.0);
    let push = acceleration_source();
    connect(three.y, push.a_ref);
    let angle = angle_sensor();
    connect(push.flange, angle.flange);
}

#[test]
fn motion_sources_prescribe_angle_and_acceleration() {
    let sol = PrescribedMotion::default().simulate(0.0, 1.0, &tight()).unwrap();
    let tau = std::f64::consts::TAU;
    for t in [0.2f64, 0.5, 1.0] {
        // τ = j φ'' = −2 (2π)² sin 2πt, the second derivative the index
        // reduction takes of the sine block.
        let torque = -2.0 * tau * tau * (tau * t).sin();
        close("sensor.tau", sol.at(t, "sensor.tau").unwrap(), torque, 1e-7);
        close("angle.phi", sol.at(t, "angle.phi").unwrap(), 1.5 * t * t, 1e-9);
    }
}

/// A 1 kg mass pulled through a spring-damper (1 N/m, 1 N s/m) by a
/// flange moving at 1 m/s.
#[dae_model]
fn towed_mass() {
    let one = constant(1.0);
    let tow = velocity_source();
    connect(one.y, tow.v_ref);
    let rope = translational_spring_damper(c = 1.0, d = 1.0);
    let pull = force_sensor();
    let body = mass(m = 1.0);
    connect(tow.flange, rope.flange_a);
    connect(rope.flange_b, pull.flange_a);
    connect(pull.flange_b, body.flange_a);
    let gap = relative_position_sensor();
    let speed = velocity_sensor();
    connect(tow.flange, gap.flange_a);
    connect(body.flange_b, gap.flange_b, speed.flange);
}

#[test]
fn translational_sensors_read_the_towed_mass() {
    // e = t − x: e'' + e' + e = 0, e(0) = 0, e'(0) = 1.
    let sol = TowedMass::default().simulate(0.0, 5.0, &tight()).unwrap();
    let w = 3f64.sqrt() / 2.0;
    for t in [0.5f64, 2.0, 5.0] {
        let e = (-t / 2.0).exp() * (w * t).sin() / w;
        let de = (-t / 2.0).exp() * ((w * t).cos() - (w * t).sin() / (2.0 * w));
        close("gap.s_rel", sol.at(t, "gap.s_rel").unwrap(), -e, 1e-9);
        close("speed.v", sol.at(t, "speed.v").unwrap(), 1.0 - de, 1e-9);
        // The rope's pull is the mass's acceleration, e + e'.
        close("pull.f", sol.at(t, "pull.f").unwrap(), e + de, 1e-8);
    }
}

/// 100 °C through a thermal resistor of 2 K/W to 20 °C; radiation
/// between 400 K and 300 K; a 1 J/K body at 400 K cooled by convection
/// (2 W/K as a signal) towards 300 K.
#[dae_model]
fn heat_paths() {
    let hot = fixed_temperature_celsius(100.0);
    let path = thermal_resistor(2.0);
    let cold = fixed_temperature(293.15);
    connect(hot.port, path.port_a);
    connect(path.port_b, cold.port);
    let celsius = celsius_sensor();
    let fahrenheit = fahrenheit_sensor();
    connect(hot.port, celsius.port);
    connect(cold.port, fahrenheit.port);
    let warm = fixed_temperature(400.0);
    let cool = fixed_temperature(300.0);
    let glow = body_radiation(gr = 1.0);
    connect(warm.port, glow.port_a);
    connect(glow.port_b, cool.port);
    let body = heat_capacitor(c = 1.0, t0 = 400.0);
    let two = constant(2.0);
    let film = signal_convection();
    connect(two.y, film.gc);
    let air_temperature = constant(300.0);
    let air = signal_temperature();
    connect(air_temperature.y, air.t);
    connect(body.port, film.solid);
    connect(film.fluid, air.port);
}

#[test]
fn thermal_parts_conduct_radiate_and_read_in_celsius() {
    let sol = HeatPaths::default().simulate(0.0, 1.0, &tight()).unwrap();
    close("path.q", sol.last("path.q").unwrap(), 40.0, 1e-10);
    close("celsius.t_c", sol.last("celsius.t_c").unwrap(), 100.0, 1e-10);
    close("fahrenheit.t_f", sol.last("fahrenheit.t_f").unwrap(), 68.0, 1e-10);
    let sigma = 5.670374419e-8;
    let q = sigma * (400f64.powi(4) - 300f64.powi(4));
    close("glow.q", sol.last("glow.q").unwrap(), q, 1e-10);
    for t in [0.25f64, 1.0] {
        let body = 300.0 + 100.0 * (-2.0 * t).exp();
        close("body.t", sol.at(t, "body.t").unwrap(), body, 1e-9 * body);
    }
}

/// A sine of amplitude 2 through a limiter (±1) and a dead zone (±0.5);
/// a ramp of slope 1 through a derivative block (T = 0.01).
#[dae_model]
fn shaped_signals() {
    let wave = sine(amplitude = 2.0, f = 1.0);
    let clamp = limiter(u_max = 1.0, u_min = -1.0);
    let zone = dead_zone(u_max = 0.5, u_min = -0.5);
    connect(wave.y, clamp.u, zone.u);
    let slope = ramp(height = 10.0, duration = 10.0);
    let rate = derivative(k = 1.0, t = 0.01);
    connect(slope.y, rate.u);
}

#[test]
fn nonlinear_blocks_clamp_and_cut_and_the_derivative_follows_the_slope() {
    let sol = ShapedSignals::default().simulate(0.0, 1.0, &tight()).unwrap();
    for t in [0.02f64, 0.05, 0.25, 0.5, 0.6, 0.75, 0.95] {
        let u = 2.0 * (std::f64::consts::TAU * t).sin();
        let zone = if u > 0.5 {
            u - 0.5
        } else if u < -0.5 {
            u + 0.5
        } else {
            0.0
        };
        close(&format!("clamp.y at {t}"), sol.at(t, "clamp.y").unwrap(), u.clamp(-1.0, 1.0), 1e-9);
        close(&format!("zone.y at {t}"), sol.at(t, "zone.y").unwrap(), zone, 1e-9);
        // x' = (t − x)/T from 0: y = (t − x)/T = 1 − e^{−t/T}.
        close("rate.y", sol.at(t, "rate.y").unwrap(), 1.0 - (-t / 0.01).exp(), 1e-7);
    }
    // The limiter and the dead zone each switch where ±2 sin 2πt crosses
    // their ends: 4 crossings each in a period.
    assert!(sol.events().len() >= 8, "{:?}", sol.events().len());
}

/// A torque of 1 N m between a rotor (1 kg m²) and a housing free to turn
/// (2 kg m²): the source's support is the housing; and a 2:1 gear whose
/// support turns with a third inertia, driven by a torque on its input.
#[dae_model]
fn reacting_supports() {
    let one = constant(1.0);
    let motor = signal_torque();
    connect(one.y, motor.u);
    let rotor = inertia(j = 1.0);
    let housing = inertia(j = 2.0);
    connect(motor.flange, rotor.flange_a);
    connect(motor.support, housing.flange_a);
    let push = torque_source(2.0);
    let input = inertia(j = 1.0);
    let gear = ideal_gear(2.0);
    let output = inertia(j = 4.0);
    let carrier = inertia(j = 3.0);
    connect(push.flange, input.flange_a);
    connect(input.flange_b, gear.flange_a);
    connect(gear.flange_b, output.flange_a);
    connect(gear.support, carrier.flange_a);
    let anchor = fixed();
    connect(push.support, anchor.flange);
}

#[test]
fn supports_carry_the_reaction() {
    let sol = ReactingSupports::default().simulate(0.0, 1.0, &tight()).unwrap();
    // The rotor speeds up at 1 rad/s², the housing back at 1/2.
    close("rotor.w", sol.last("rotor.w").unwrap(), 1.0, 1e-9);
    close("housing.w", sol.last("housing.w").unwrap(), -0.5, 1e-9);
    // The gear: φ_in − φ_c = 2 (φ_out − φ_c), τ_out = −2 τ_in, its support
    // taking τ_s = −τ_in − τ_out = τ_in. With τ the torque the gear takes at
    // its input, the accelerations a_in = 2 − τ, a_out = 2τ/4, a_c = −τ/3,
    // and a_in − a_c = 2 (a_out − a_c): 2 − τ + τ/3 = τ + 2τ/3, τ = 6/7.
    let tau = 6.0 / 7.0;
    let (a_in, a_out, a_c) = (2.0 - tau, 2.0 * tau / 4.0, -tau / 3.0);
    close("input.w", sol.last("input.w").unwrap(), a_in, 1e-9);
    close("output.w", sol.last("output.w").unwrap(), a_out, 1e-9);
    close("carrier.w", sol.last("carrier.w").unwrap(), a_c, 1e-9);
}

/// A pulse of 2 for 30 % of each 0.5 s from 0.1 s, on 1, integrated.
#[dae_model]
fn pulsed_wave() {
    let wave = pulse(amplitude = 2.0, width = 30.0, period = 0.5, offset = 1.0, start_time = 0.1);
    let total = integrator();
    connect(wave.y, total.u);
}

#[test]
fn a_pulse_switches_at_its_instants() {
    let sol = PulsedWave::default().simulate(0.0, 1.2, &tight()).unwrap();
    for (t, y) in [(0.05, 1.0), (0.2, 3.0), (0.3, 1.0), (0.65, 3.0), (0.8, 1.0), (1.15, 3.0)] {
        close(&format!("wave.y at {t}"), sol.at(t, "wave.y").unwrap(), y, 1e-12);
    }
    // ∫ y = t + 2 × (time high): 0.15 s high in each of 0.1–0.6, 0.6–1.1,
    // and 0.1 s of the third pulse by 1.2.
    close("total.y", sol.last("total.y").unwrap(), 1.2 + 2.0 * 0.4, 1e-9);
}

/// A flywheel (2 kg m²) at 10 rad/s braked from t = 0.5 s (μ = 0.5,
/// cgeo = 0.2, 40 N: 4 N m), then held by the brake against a 1 N m
/// torque from t = 6 s, which its static friction (peak 1.5, 6 N m)
/// withstands.
#[dae_model]
fn braked_flywheel() {
    let flywheel = inertia(j = 2.0, w0 = 10.0);
    let brake = brake(mu = 0.5, peak = 1.5, cgeo = 0.2, fn_max = 40.0);
    let press = step(height = 1.0, start_time = 0.5);
    connect(press.y, brake.f_normalized);
    connect(flywheel.flange_b, brake.flange_a);
    let pull = step(height = 1.0, start_time = 6.0);
    let motor = signal_torque();
    connect(pull.y, motor.u);
    connect(motor.flange, flywheel.flange_a);
}

#[test]
fn a_brake_slides_to_a_stop_and_holds() {
    let sol = BrakedFlywheel::default().simulate(0.0, 8.0, &tight()).unwrap();
    // Sliding from 0.5 s: w = 10 − 4 (t − 0.5)/2, stopping at t = 5.5.
    for t in [0.25f64, 1.0, 3.0, 5.0] {
        let w = if t < 0.5 { 10.0 } else { 10.0 - 2.0 * (t - 0.5) };
        close(&format!("flywheel.w at {t}"), sol.at(t, "flywheel.w").unwrap(), w, 1e-8);
    }
    // Stuck from 5.5 s, also under the 1 N m pull from 6 s.
    for t in [5.75f64, 6.5, 8.0] {
        close(&format!("flywheel.w at {t}"), sol.at(t, "flywheel.w").unwrap(), 0.0, 1e-8);
        assert_eq!(sol.at(t, "brake.mode").unwrap(), 1.0, "t = {t}");
    }
    close("brake.tau", sol.at(7.0, "brake.tau").unwrap(), 1.0, 1e-8);
}

/// A unit step at 0.1 s through a rate limiter of 2/s up (td = 1 ms).
#[dae_model]
fn slewed_step() {
    let command = step(height = 1.0, start_time = 0.1);
    let slew = rate_limiter(rising = 2.0, falling = -2.0, td = 1e-3);
    connect(command.y, slew.u);
}

#[test]
fn a_rate_limiter_ramps_then_follows() {
    let sol = SlewedStep::default().simulate(0.0, 1.0, &tight()).unwrap();
    // Up at 2/s until the gap falls to 2·td = 0.002 (t1 = 0.1 + 0.499),
    // then y = 1 − 0.002 e^{−(t − t1)/td}.
    let t1 = 0.1 + 0.998 / 2.0;
    for t in [0.05f64, 0.3, 0.5, 0.6, 0.62, 1.0] {
        let y = if t <= 0.1 {
            0.0
        } else if t <= t1 {
            2.0 * (t - 0.1)
        } else {
            1.0 - 0.002 * (-(t - t1) / 1e-3).exp()
        };
        close(&format!("slew.y at {t}"), sol.at(t, "slew.y").unwrap(), y, 1e-8);
    }
}
