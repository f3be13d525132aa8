//! The crate's components used from another crate (a test is one): by
//! path, after a `use`, nested, and with their parameters set.

use daegen::prelude::*;
use daegen_parts_example::thermal::wall_layer;

/// The geared motor on 12 V lifting nothing: it runs up to the speed
/// where its EMF and resistance share the supply with the losses.
#[dae_model]
fn geared_run_up() {
    let supply = constant_voltage(12.0);
    let drive = daegen_parts_example::geared_motor(ratio = 5.0, b = 0.01);
    let load = inertia(0.02);
    let gnd = ground();
    connect(supply.p, drive.p);
    connect(supply.n, drive.n, gnd.p);
    connect(drive.shaft, load.flange_a);
}

#[test]
fn a_geared_motor_from_another_crate_reaches_its_exact_speed() {
    // Steady state: n k i = b ω and V = R i + k n ω, so
    // ω = n k V / (R b + (n k)²).
    let (n, k, v, r, b) = (5.0f64, 0.05, 12.0, 1.0, 0.01);
    let exact = n * k * v / (r * b + (n * k) * (n * k));
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-10);
    let sol = GearedRunUp::default().simulate(0.0, 30.0, &opts).unwrap();
    let w = sol.last("load.w").unwrap();
    assert!((w - exact).abs() < 1e-7, "ω = {w}, exact {exact}");
    // The motor and its rotor are readable through the nesting, and the
    // gear ties the rotor's states to the load's: two states remain with
    // the winding's current.
    let rotor = sol.last("drive.motor.rotor.w").unwrap();
    assert!((rotor - n * w).abs() < 1e-9);
    assert_eq!(<GearedRunUp as Model>::INFO.states.len(), 3);
    // Its parameters are fields by their flattened path.
    let faster = GearedRunUp { drive_ratio: 4.0, ..GearedRunUp::default() };
    let sol = faster.simulate(0.0, 30.0, &opts).unwrap();
    let exact = 4.0 * k * v / (r * b + (4.0 * k) * (4.0 * k));
    assert!((sol.last("load.w").unwrap() - exact).abs() < 1e-7);
}

/// Three layers from the crate between two fixed temperatures.
#[dae_model]
fn layered_wall() {
    // From the inside out, each layer joined to the one before.
    let inside = fixed_temperature(300.0);
    let l1 = wall_layer(g = 3.0);
    connect(inside.port, l1.a);
    let l2 = wall_layer(g = 1.0);
    connect(l1.b, l2.a);
    let l3 = wall_layer(g = 2.0);
    connect(l2.b, l3.a);
    let outside = fixed_temperature(270.0);
    connect(l3.b, outside.port);
}

#[test]
fn a_wall_of_layers_from_another_crate_settles_at_series_conduction() {
    // q = ΔT / Σ 1/g; each core sits half a layer's resistance in.
    let g = [3.0, 1.0, 2.0];
    let q = 30.0 / g.iter().map(|g| 1.0 / g).sum::<f64>();
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-10);
    let sol = LayeredWall::default().simulate(0.0, 1e5, &opts).unwrap();
    let mut face = 300.0;
    for (k, g) in g.iter().enumerate() {
        let core = sol.last(&format!("l{}.core.t", k + 1)).unwrap();
        assert!((core - (face - q / (2.0 * g))).abs() < 1e-7, "layer {k}: {core}");
        face -= q / g;
    }
}
