//! A crate of components for daegen models, as a user publishes one.
//! Each `#[component]` is a function in the model language; a model in
//! any crate that depends on this one instantiates it by path
//! (`daegen_parts_example::geared_motor(..)`) or after a `use`.

use daegen::component;

/// A permanent-magnet DC motor between the pins `p` and `n`, driving the
/// flange `shaft`: armature resistance and inductance, the EMF and the
/// rotor's inertia.
#[component]
pub fn dc_motor() {
    /// Armature resistance (Ω).
    let r = param(1.0);
    /// Armature inductance (H).
    let l = param(1e-3);
    /// Motor constant (V s/rad = N m/A).
    let k = param(0.05);
    /// Rotor inertia (kg m²).
    let j = param(1e-5);
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

/// The motor behind a gear with viscous losses at the output: its shaft
/// turns `ratio` times the output flange `shaft`.
#[component]
pub fn geared_motor() {
    /// Gear ratio, motor turns per output turn.
    let ratio = param(10.0);
    /// Viscous friction at the output (N m s/rad).
    let b = param(0.0);
    let p = pin();
    let n = pin();
    let shaft = flange();
    let motor = dc_motor();
    let gear = ideal_gear(ratio);
    let losses = damper(b);
    let housing = fixed();
    connect(p, motor.p);
    connect(motor.n, n);
    connect(motor.shaft, gear.flange_a);
    connect(gear.flange_b, losses.flange_a, shaft);
    connect(losses.flange_b, housing.flange);
}

/// Thermal parts.
pub mod thermal {
    use daegen::component;

    /// One layer of a wall: a heat capacity at its middle, half its
    /// conductance to either face.
    #[component]
    pub fn wall_layer() {
        /// Heat capacity (J/K).
        let c = param(1000.0);
        /// Conductance through the whole layer (W/K).
        let g = param(1.0);
        /// Initial temperature (K).
        let t0 = param(293.15);
        let a = heat_port();
        let b = heat_port();
        let core = heat_capacitor(c, t0);
        let to_a = thermal_conductor(2.0 * g);
        let to_b = thermal_conductor(2.0 * g);
        connect(a, to_a.port_a);
        connect(to_a.port_b, core.port, to_b.port_a);
        connect(to_b.port_b, b);
    }
}
