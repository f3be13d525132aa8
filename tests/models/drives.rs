// Models built from components, with the same physics written flat by
// hand where there is one: shared by the component tests and the
// benchmark.

include!("speed_drive.rs");
include!("slider_crank_scene.rs");

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

/// A wall of four layers between 40 °C inside and 0 °C outside: each
/// layer a heat capacity, conductances between them and to either side.
#[dae_model]
fn thermal_wall() {
    const LAYERS: usize = 4;
    let g = [2.0, 5.0, 1.0, 4.0, 3.0];
    let inside = fixed_temperature(313.15);
    let outside = fixed_temperature(273.15);
    let layers = (0..LAYERS).map(|k| heat_capacitor(c = 500.0 * (1.0 + k as f64), t0 = 293.15));
    let conductors = (0..LAYERS + 1).map(|k| thermal_conductor(g[k]));
    connect(inside.port, conductors[0].port_a);
    for k in 0..LAYERS {
        connect(conductors[k].port_b, layers[k].port);
        connect(layers[k].port, conductors[k + 1].port_a);
    }
    connect(conductors[LAYERS].port_b, outside.port);
}

/// A resistor heating up: 2 A through R(T) = 10 Ω (1 + 0.004/K (T − 20 °C)),
/// its losses into a heat capacity of 50 J/K that convects 1.5 W/K to
/// 20 °C air.
#[dae_model]
fn heating_up() {
    let source = constant_current(2.0);
    let heater = heating_resistor(r = 10.0, t_ref = 293.15, alpha = 0.004);
    let body = heat_capacitor(c = 50.0, t0 = 293.15);
    let air = convection(1.5);
    let ambient = fixed_temperature(293.15);
    let gnd = ground();
    connect(source.n, heater.p);
    connect(heater.n, source.p, gnd.p);
    connect(heater.heat_port, body.port, air.solid);
    connect(air.fluid, ambient.port);
}

/// The DC motor on 12 V behind a 10:1 gear, its output the flange
/// `shaft`.
#[component]
fn geared_drive() {
    let supply = constant_voltage(12.0);
    let motor = daegen_parts_example::dc_motor(r = 1.0, l = 0.01, k = 0.05, j = 1e-5);
    let gear = ideal_gear(10.0);
    let gnd = ground();
    let shaft = flange();
    connect(supply.p, motor.p);
    connect(supply.n, motor.n, gnd.p);
    connect(motor.shaft, gear.flange_a);
    connect(gear.flange_b, shaft);
}

/// `geared_slider_crank!(name, (attributes))`: the DC motor above, on
/// 12 V, turning the slider-crank of the scene tests (crank r = 0.15 of
/// mass 1 about the origin, rod l = 0.4, slider 0.5 on the x axis, from
/// θ = 1 at rest) through a 10:1 gear on its pivot's flange.
macro_rules! geared_slider_crank {
    ($name:ident, ($($attr:tt)*)) => {
        // The poses at θ = 1 with every joint closed.
        slider_crank_scene!($name, ($($attr)*),
            crank: ([0.5 * r * cos(1.0), 0.5 * r * sin(1.0), 1.0]),
            slider: ([r * cos(1.0) + sqrt(l * l - r * r * sin(1.0) * sin(1.0)), 0.0, 0.0]),
            {
                let drive = geared_drive();
                connect(drive.shaft, pivot.flange);
            });
    };
}

geared_slider_crank!(geared_slider_crank_global, ());
geared_slider_crank!(geared_slider_crank_recursive, (scene = recursive));

/// The same machine written flat: the slider-crank in its crank angle φ
/// (Lagrange, as `slider_crank_angle` in the scene tests) with the rotor's
/// inertia reflected through the gear, `J_m n²`, and the motor's torque
/// `n k i`; the winding `L di/dt = V − R i − k n φ'`.
#[dae_model]
fn geared_slider_crank_flat() {
    let r = param(0.15);
    let l = param(0.4);
    let m1 = param(1.0);
    let m2 = param(0.5);
    let g = param(9.81);
    let n = 10.0;
    let k = 0.05;
    let jm = 1e-5;
    let ra = 1.0;
    let la = 0.01;
    let v = 12.0;
    let phi = state(1.0);
    init(der(phi), 0.0);
    let i = state(0.0);
    let s = sin(phi);
    let c = cos(phi);
    let w = sqrt(l * l - r * r * s * s);
    let f = -r * s - r * r * s * c / w;
    let fp = -r * c - r * r * (c * c - s * s) / w - r * r * r * r * s * s * c * c / (w * w * w);
    (m1 * r * r / 3.0 + m2 * f * f + jm * n * n) * der(der(phi))
        == -m2 * f * fp * der(phi) * der(phi) - m1 * g * 0.5 * r * c + n * k * i;
    la * der(i) == v - ra * i - k * n * der(phi);
}
