// Models built from components, with the same physics written flat by
// hand: shared by the component tests and the benchmark.

/// A permanent-magnet DC motor: armature resistance and inductance, the
/// EMF, and the rotor's inertia, between two pins and a shaft.
#[component]
fn dc_motor() {
    /// Armature resistance (Ω).
    let r = param(1.0);
    /// Armature inductance (H).
    let l = param(0.5e-3);
    /// Motor constant (V s/rad).
    let k = param(0.05);
    /// Rotor inertia (kg m²).
    let j = param(1e-4);
    let p = pin();
    let n = pin();
    let shaft = flange();
    let armature = resistor(r);
    let winding = inductor(l);
    let emf = emf(k);
    let rotor = inertia(j);
    connect(p, armature.p);
    connect(armature.n, winding.p);
    connect(winding.n, emf.p);
    connect(emf.n, n);
    connect(emf.flange, rotor.flange_a);
    connect(rotor.flange_b, shaft);
}

/// The motor under a PI speed controller, with viscous friction and a
/// load torque of 0.02 N m from t = 0.3 s.
#[dae_model]
fn speed_drive() {
    let reference = constant(100.0);
    let controller = pi_controller(kp = 0.02, ki = 0.5);
    let sensor = speed_sensor();
    let supply = signal_voltage();
    let motor = dc_motor(k = 0.05);
    let friction = damper(1e-5);
    let housing = fixed();
    let load = signal_torque();
    let load_torque = step(height = -0.02, start_time = 0.3);
    let gnd = ground();
    connect(reference.y, controller.u_s);
    connect(sensor.w, controller.u_m);
    connect(controller.y, supply.u);
    connect(supply.p, motor.p);
    connect(supply.n, motor.n, gnd.p);
    connect(motor.shaft, friction.flange_a, sensor.flange, load.flange);
    connect(friction.flange_b, housing.flange);
    connect(load_torque.y, load.u);
}

/// The same drive written flat, by hand.
#[dae_model]
fn speed_drive_flat() {
    let r = param(1.0);
    let l = param(0.5e-3);
    let k = param(0.05);
    let j = param(1e-4);
    let b = param(1e-5);
    let kp = param(0.02);
    let ki = param(0.5);
    let w_ref = param(100.0);
    let tau_load = param(0.02);
    let t_load = param(0.3);
    let t = time();
    let i = state(0.0);
    let phi = state(0.0);
    let w = state(0.0);
    let x = state(0.0);
    let e = w_ref - w;
    let v = kp * e + x;
    l * der(i) == v - r * i - k * w;
    der(phi) == w;
    j * der(w) == k * i - b * w - tau_load * heaviside(t - t_load);
    der(x) == ki * e;
}

/// A series RLC circuit switched onto 1 V: R = 1 Ω, L = 1 H, C = 0.25 F,
/// underdamped (α = 0.5 s⁻¹, ω_d = √3.75 rad/s).
#[dae_model]
fn rlc_series() {
    let source = constant_voltage(1.0);
    let r = resistor(1.0);
    let l = inductor(1.0);
    let c = capacitor(0.25);
    let gnd = ground();
    connect(source.p, r.p);
    connect(r.n, l.p);
    connect(l.n, c.p);
    connect(c.n, source.n, gnd.p);
}

/// The series RLC circuit written flat: the inductor's current and the
/// capacitor's voltage.
#[dae_model]
fn rlc_series_flat() {
    let r = param(1.0);
    let l = param(1.0);
    let c = param(0.25);
    let v = param(1.0);
    let i = state(0.0);
    let vc = state(0.0);
    l * der(i) == v - r * i - vc;
    c * der(vc) == i;
}
