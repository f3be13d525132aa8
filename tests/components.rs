//! Components and connectors: circuits, drives and thermal networks built
//! from the standard library and from the user's own components, each
//! checked against an exact solution or the same physics written flat.

use daegen::prelude::*;

mod support;
use support::harness::{adaptive_methods_for, kind, methods_for, Kind};

include!("models/drives.rs");

include!("models/rlc_exact.rs");
include!("models/ladders_of_parts.rs");

/// `rc_charging!(name, (attributes))`: RC charging, a 10 V source
/// through R = 100 Ω into C = 1 mF.
macro_rules! rc_charging {
    ($name:ident, ($($attr:tt)*)) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let source = constant_voltage(10.0);
            let r1 = resistor(100.0);
            let c1 = capacitor(1e-3);
            let gnd = ground();
            connect(source.p, r1.p);
            connect(r1.n, c1.p);
            connect(c1.n, source.n, gnd.p);
        }
    };
}

rc_charging!(rc_charging, ());

#[test]
fn rc_charging_follows_the_exponential() {
    let model = RcCharging::default();
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = model.simulate(0.0, 0.5, &opts).unwrap();
    let tau: f64 = 100.0 * 1e-3;
    for &t in &[0.05f64, 0.1, 0.3, 0.5] {
        let exact = 10.0 * (1.0 - (-t / tau).exp());
        let v: f64 = sol.at(t, "c1.v").unwrap();
        assert!((v - exact).abs() < 1e-7, "t = {t}: {v} vs {exact}");
        let i: f64 = sol.at(t, "r1.i").unwrap();
        assert!((i - (10.0 - exact) / 100.0).abs() < 1e-9, "t = {t}: i = {i}");
        // Kirchhoff at the source: the current leaves `p` and returns at `n`.
        let (p, n): (f64, f64) =
            (sol.at(t, "source.p.i").unwrap(), sol.at(t, "source.n.i").unwrap());
        assert!((p + n).abs() < 1e-12 && (p + i).abs() < 1e-9);
    }
    // One state, as by hand; every connector variable still reads.
    assert_eq!(<RcCharging as Model>::INFO.states, ["c1.v"]);
    let model = RcCharging { r1_r: 50.0, ..RcCharging::default() };
    let sol = model.simulate(0.0, 0.05, &opts).unwrap();
    let exact = 10.0 * (1.0 - (-0.05f64 / 0.05).exp());
    assert!((sol.last("c1.v").unwrap() - exact).abs() < 1e-7);
}

#[test]
fn rlc_series_rings_as_the_exact_solution() {
    for method in adaptive_methods_for::<RlcSeries>() {
        let opts = Options::new().method(method).rtol(1e-10).atol(1e-10);
        let sol = RlcSeries::default().simulate(0.0, 10.0, &opts).unwrap();
        for &t in &[0.5, 2.0, 5.0, 10.0] {
            let [v_c, i] = rlc_exact(t);
            let (vc, il): (f64, f64) = (sol.at(t, "c.v").unwrap(), sol.at(t, "l.i").unwrap());
            assert!((vc - v_c).abs() < 1e-7, "{method:?} t = {t}: v_c {vc} vs {v_c}");
            assert!((il - i).abs() < 1e-7, "{method:?} t = {t}: i {il} vs {i}");
            let vr: f64 = sol.at(t, "r.v").unwrap();
            assert!((vr - il).abs() < 1e-9);
        }
    }
    assert_eq!(
        <RlcSeries as Model>::INFO.states.len(),
        <RlcSeriesFlat as Model>::INFO.states.len()
    );
}

rc_ladder_of_parts!(
    rc_ladder_of_parts_20,
    20,
    {
        let r = param(1.0);
        let c = param(1.0);
    },
    r,
    c
);
rc_ladder_of_parts!(rc_ladder_of_tunable_parts_20, 20, {}, 1.0, 1.0);
rc_ladder_flat!(rc_ladder_flat_20, 20);

#[test]
fn a_ladder_of_forty_parts_is_the_flat_ladder() {
    let (parts, flat) = (<RcLadderOfParts20 as Model>::INFO, <RcLadderFlat20 as Model>::INFO);
    assert_eq!(parts.states.len(), flat.states.len());
    // Nothing is left to solve at run time: every equation is solved in
    // turn, as in the flat ladder.
    assert!(parts.structure.blocks.is_empty(), "{:?}", parts.structure);
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-10);
    let a = RcLadderOfParts20::default().simulate(0.0, 50.0, &opts).unwrap();
    let b = RcLadderFlat20::default().simulate(0.0, 50.0, &opts).unwrap();
    let tunable = RcLadderOfTunableParts20 { resistors_3_r: 2.0, ..Default::default() };
    let c = tunable.simulate(0.0, 50.0, &opts).unwrap();
    assert_eq!(a.stats().steps, b.stats().steps);
    for k in 0..20 {
        let name = format!("capacitors[{k}].v");
        let (x, y) = (a.last(&name).unwrap(), b.last(&format!("v[{k}]")).unwrap());
        assert!((x - y).abs() < 1e-12, "node {k}: {x} vs {y}");
        // The fourth resistor's own value slows the charge behind it.
        if k >= 3 {
            assert!(c.at(5.0, &name).unwrap() < a.at(5.0, &name).unwrap());
        }
    }
    // Each resistor its r, each capacitor its c and v0, and the source.
    assert_eq!(<RcLadderOfTunableParts20 as Model>::INFO.parameters.len(), 61);
}

#[test]
fn a_speed_drive_of_components_is_the_flat_drive() {
    let info = <SpeedDrive as Model>::INFO;
    let flat = <SpeedDriveFlat as Model>::INFO;
    assert_eq!(info.states.len(), flat.states.len(), "{:?}", info.states);
    // Stiff (L/R = 0.5 ms against J R/k² = 40 ms): the explicit methods
    // report it, and Auto switches.
    for method in methods_for::<SpeedDrive>(|m| kind(m) == Kind::Stiff) {
        let opts = Options::new().method(method).rtol(1e-9).atol(1e-9);
        let a = SpeedDrive::default().simulate(0.0, 1.0, &opts).unwrap();
        let b = SpeedDriveFlat::default().simulate(0.0, 1.0, &opts).unwrap();
        for &t in &[0.1, 0.29, 0.35, 0.6, 1.0] {
            for (x, y) in [
                ("motor.winding.i", "i"),
                ("motor.rotor.w", "w"),
                ("controller.x", "x"),
                ("motor.rotor.phi", "phi"),
            ] {
                let (u, v): (f64, f64) = (a.at(t, x).unwrap(), b.at(t, y).unwrap());
                assert!(
                    (u - v).abs() < 1e-6 * (1.0 + v.abs()),
                    "{method:?} t = {t}: {x} = {u}, {y} = {v}"
                );
            }
        }
    }
}

#[test]
fn the_speed_drive_settles_at_the_exact_steady_state() {
    // ω = ω_ref, and the motor's torque k i carries friction and load:
    // i = (b ω_ref + τ_L) / k.
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = SpeedDrive::default().simulate(0.0, 20.0, &opts).unwrap();
    let (w, i): (f64, f64) = (sol.last("sensor.w").unwrap(), sol.last("motor.winding.i").unwrap());
    let exact_i = (1e-5 * 100.0 + 0.02) / 0.05;
    assert!((w - 100.0).abs() < 1e-6, "ω = {w}");
    assert!((i - exact_i).abs() < 1e-7, "i = {i} vs {exact_i}");
    let v: f64 = sol.last("supply.v").unwrap();
    assert!((v - (1.0 * exact_i + 0.05 * 100.0)).abs() < 1e-6, "v = {v}");
}

const LAYERS: usize = 4;

#[test]
fn a_thermal_wall_settles_at_the_series_conduction_profile() {
    // Steady state: one heat flow q = ΔT / Σ 1/g through every
    // conductor, and each layer below the previous by q / g.
    let g = [2.0, 5.0, 1.0, 4.0, 3.0];
    let q = 40.0 / g.iter().map(|g| 1.0 / g).sum::<f64>();
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-10);
    let sol = ThermalWall::default().simulate(0.0, 1e5, &opts).unwrap();
    let mut t = 313.15;
    for k in 0..LAYERS {
        t -= q / g[k];
        let got: f64 = sol.last(&format!("layers[{k}].t")).unwrap();
        assert!((got - t).abs() < 1e-7, "layer {k}: {got} vs {t}");
        let flow: f64 = sol.last(&format!("conductors[{k}].q")).unwrap();
        assert!((flow - q).abs() < 1e-7, "conductor {k}: {flow} vs {q}");
    }
    assert_eq!(<ThermalWall as Model>::INFO.states.len(), LAYERS);
}

#[test]
fn a_resistor_heats_up_as_the_exact_solution() {
    // C dT/dt = I² R0 (1 + α (T − T_ref)) − G (T − T_amb): linear in T,
    // T = T* + (T0 − T*) e^{λ t}.
    let (i, r0, alpha, t_ref, c, g, t_amb) = (2.0f64, 10.0, 0.004, 293.15, 50.0, 1.5, 293.15);
    let lambda = (i * i * r0 * alpha - g) / c;
    let b = (i * i * r0 * (1.0 - alpha * t_ref) + g * t_amb) / c;
    let t_star = -b / lambda;
    let exact = |t: f64| t_star + (293.15 - t_star) * (lambda * t).exp();
    for method in adaptive_methods_for::<HeatingUp>() {
        let opts = Options::new().method(method).rtol(1e-11).atol(1e-11);
        let sol = HeatingUp::default().simulate(0.0, 200.0, &opts).unwrap();
        for &t in &[10.0, 50.0, 200.0] {
            let got: f64 = sol.at(t, "body.t").unwrap();
            assert!((got - exact(t)).abs() < 1e-6, "{method:?} t = {t}: {got} vs {}", exact(t));
            // The heater's losses are v i at its temperature.
            let (v, r): (f64, f64) =
                (sol.at(t, "heater.v").unwrap(), sol.at(t, "heater.r_actual").unwrap());
            assert!(
                (v - 2.0 * r).abs() < 1e-9 && (r - r0 * (1.0 + alpha * (got - t_ref))).abs() < 1e-9
            );
        }
    }
}

#[test]
fn a_motor_turns_a_slider_crank_through_a_gear_in_both_formulations() {
    let tol = 1e-9;
    let opts = Options::new().method(Method::Radau5).rtol(tol).atol(tol);
    let flat = GearedSliderCrankFlat::default().simulate(0.0, 1.0, &opts).unwrap();
    let global = GearedSliderCrankGlobal::default().simulate(0.0, 1.0, &opts).unwrap();
    let recursive = GearedSliderCrankRecursive::default().simulate(0.0, 1.0, &opts).unwrap();
    for t in [0.1, 0.3, 0.6, 1.0] {
        let (phi, i) = (flat.at(t, "phi").unwrap(), flat.at(t, "i").unwrap());
        for (name, sol, angle) in
            [("global", &global, "crank.theta"), ("recursive", &recursive, "pivot.q")]
        {
            let (a, b) = (sol.at(t, angle).unwrap(), sol.at(t, "drive.motor.winding.i").unwrap());
            assert!((a - phi).abs() < 1e-6, "{name} t = {t}: θ {a} vs {phi}");
            assert!((b - i).abs() < 1e-6, "{name} t = {t}: i {b} vs {i}");
            // The rotor turns n times the crank.
            let rotor = sol.at(t, "drive.motor.rotor.phi").unwrap();
            assert!((rotor - 10.0 * a).abs() < 1e-9, "{name}: rotor {rotor}");
        }
    }
}

#[test]
fn describe_shows_the_hierarchy_and_every_path_reads() {
    let text = SpeedDrive::default().describe();
    println!("{text}");
    let section: Vec<&str> = text
        .lines()
        .skip_while(|l| *l != "components:")
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .collect();
    assert!(section
        .iter()
        .any(|l| l.trim_start().starts_with("motor") && l.trim_end().ends_with("dc_motor")));
    // The motor's parts sit one level deeper than the motor.
    let indent = |l: &&str| l.len() - l.trim_start().len();
    let motor = section.iter().find(|l| l.trim_start().starts_with("motor ")).unwrap();
    let emf = section.iter().find(|l| l.trim_start().starts_with("emf ")).unwrap();
    assert_eq!(indent(emf), indent(motor) + 2);
    let info = <SpeedDrive as Model>::INFO;
    assert!(info.components.iter().any(|c| c.path == "motor.emf" && c.part == "emf"));
    // Every connector variable and internal variable reads by its path,
    // also those that alias elimination or tied states removed.
    let opts = Options::new().method(Method::Radau5).rtol(1e-8).atol(1e-8);
    let sol = SpeedDrive::default().simulate(0.0, 0.1, &opts).unwrap();
    for name in [
        "motor.emf.i",
        "motor.emf.w",
        "motor.emf.phi",
        "motor.shaft.tau",
        "friction.flange_b.phi",
        "sensor.w",
        "motor.p.v",
        "supply.i",
    ] {
        assert!(sol.last(name).unwrap().is_finite(), "{name}");
    }
    let (w, emf_w): (f64, f64) =
        (sol.last("motor.rotor.w").unwrap(), sol.last("motor.emf.w").unwrap());
    assert!((w - emf_w).abs() < 1e-12);
    let (i, emf_i): (f64, f64) =
        (sol.last("motor.winding.i").unwrap(), sol.last("motor.emf.i").unwrap());
    assert!((i - emf_i).abs() < 1e-12);
}

/// A tank draining through an orifice, its flow a function of the model
/// written once: Torricelli, `q = cd a √(2 g Δh)`.
#[dae_model]
fn draining_tank() {
    let cd = param(0.6);
    let a = param(1e-3);
    let area = param(0.5);
    let orifice = |dh| cd * a * sqrt(2.0 * 9.81 * dh);
    let h = state(2.0);
    area * der(h) == -orifice(h);
    let flow = output(orifice(h));
}

#[test]
fn a_function_of_the_model_is_inlined_where_it_is_called() {
    // √h falls linearly: √h = √h0 − cd a √(2g) t / (2 A).
    let rate = 0.6 * 1e-3 * (2.0f64 * 9.81).sqrt() / (2.0 * 0.5);
    let opts = Options::new().method(Method::Dop853).rtol(1e-11).atol(1e-11);
    let sol = DrainingTank::default().simulate(0.0, 500.0, &opts).unwrap();
    for &t in &[100.0, 300.0, 500.0] {
        let exact = (2.0f64.sqrt() - rate * t).powi(2);
        let h = sol.at(t, "h").unwrap();
        assert!((h - exact).abs() < 1e-8, "t = {t}: {h} vs {exact}");
    }
    let h = sol.last("h").unwrap();
    assert!((sol.last("flow").unwrap() - 0.6 * 1e-3 * (2.0 * 9.81 * h).sqrt()).abs() < 1e-14);
}

#[test]
fn the_guide_lists_every_part_of_the_standard_library() {
    let guide = include_str!("../src/guide/components.rs");
    let library = daegen::codegen::front::components::definitions::LIBRARY_SOURCE;
    let parts: Vec<&str> = library
        .lines()
        .filter_map(|l| l.strip_prefix("fn "))
        .filter_map(|l| l.split('(').next())
        .collect();
    assert!(parts.len() >= 45, "{parts:?}");
    for part in parts {
        assert!(guide.contains(&format!("`{part}(")), "the guide does not list `{part}`");
    }
}

/// `geared_spatial_crank!(name, (attributes))`: the DC motor on 12 V
/// turning a crank in space (a rod of mass 1 and length 0.15 hinged at
/// one end about the world's z axis, gravity along −y, from θ = 1 at
/// rest) through a 10:1 gear on the hinge's flange.
macro_rules! geared_spatial_crank {
    ($name:ident, ($($attr:tt)*)) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let m = param(1.0);
            let r = param(0.15);
            let ground = ground();
            let crank = spatial_body(
                m,
                vec3(1e-3, m * r * r / 12.0, m * r * r / 12.0),
                [0.5 * r * cos(1.0), 0.5 * r * sin(1.0), 0.0],
                [cos(0.5), 0.0, 0.0, sin(0.5)],
            );
            let hinge = revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0), vec3(0.0, 0.0, 1.0));
            gravity(vec3(0.0, -9.81, 0.0));
            let drive = geared_drive();
            connect(drive.shaft, hinge.flange);
        }
    };
}

geared_spatial_crank!(geared_spatial_crank_global, ());
geared_spatial_crank!(geared_spatial_crank_recursive, (scene = recursive));

/// The same crank written flat: `(m r²/3 + J_m n²) φ'' = −m g (r/2) cos φ + n k i`.
#[dae_model]
fn geared_crank_flat() {
    let m = param(1.0);
    let r = param(0.15);
    let n = 10.0;
    let k = 0.05;
    let phi = state(1.0);
    init(der(phi), 0.0);
    let i = state(0.0);
    (m * r * r / 3.0 + 1e-5 * n * n) * der(der(phi)) == -m * 9.81 * 0.5 * r * cos(phi) + n * k * i;
    0.01 * der(i) == 12.0 - 1.0 * i - k * n * der(phi);
}

#[test]
fn a_motor_turns_a_crank_in_space() {
    let tol = 1e-9;
    let opts = Options::new().method(Method::Radau5).rtol(tol).atol(tol);
    let flat = GearedCrankFlat::default().simulate(0.0, 0.5, &opts).unwrap();
    let global = GearedSpatialCrankGlobal::default().simulate(0.0, 0.5, &opts).unwrap();
    let recursive = GearedSpatialCrankRecursive::default().simulate(0.0, 0.5, &opts).unwrap();
    // In joint coordinates the machine keeps the flat model's states: the
    // hinge's angle and rate and the winding's current; the rotor's angle,
    // rate and the EMF's are tied to the hinge's through the gear.
    assert_eq!(
        <GearedSpatialCrankRecursive as Model>::INFO.states,
        ["drive.motor.winding.i", "hinge.q", "der(hinge.q)"]
    );
    // Every name reads a number: the torques along the gear too, which
    // alias values a run-time block gives.
    for sol in [&global, &recursive] {
        for name in sol.names() {
            let v = sol.at(0.2, name).unwrap();
            assert!(v.is_finite(), "{name} = {v}");
        }
    }
    for t in [0.05, 0.2, 0.5] {
        let (phi, i) = (flat.at(t, "phi").unwrap(), flat.at(t, "i").unwrap());
        for (name, sol) in [("global", &global), ("recursive", &recursive)] {
            // The hinge's flange turns from where the crank started.
            let a = sol.at(t, "hinge.angle").unwrap() + 1.0;
            let b = sol.at(t, "drive.motor.winding.i").unwrap();
            assert!((a - phi).abs() < 1e-6, "{name} t = {t}: θ {a} vs {phi}");
            assert!((b - i).abs() < 1e-6, "{name} t = {t}: i {b} vs {i}");
            let rotor = sol.at(t, "drive.motor.rotor.phi").unwrap();
            assert!((rotor - 10.0 * (a - 1.0)).abs() < 1e-9, "{name}: rotor {rotor}");
        }
    }
}

// RC charging with the sensitivity of the capacitor's voltage to the
// resistance, a parameter of an instance.
rc_charging!(rc_sensitivity, (sensitivities = [r1_r]));

#[test]
fn an_instance_s_parameter_has_its_sensitivity() {
    // v = V (1 − e^{−t/RC}): ∂v/∂R = −V t / (R² C) e^{−t/RC}.
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = RcSensitivity::default().with_sensitivities().simulate(0.0, 0.3, &opts).unwrap();
    for &t in &[0.05f64, 0.1, 0.3] {
        let exact = -10.0 * t / (100.0 * 100.0 * 1e-3) * (-t / 0.1).exp();
        let got = sol.sensitivity(t, "c1.v", "r1_r").unwrap();
        assert!((got - exact).abs() < 1e-7, "t = {t}: {got} vs {exact}");
    }
}

/// A heater of the user's own that reports its power and stops the run
/// when its body reaches a temperature: outputs and events in a part.
#[component]
fn guarded_heater() {
    /// Power (W).
    let power = param(10.0);
    /// Temperature that ends the run (K).
    let limit = param(320.0);
    let port = heat_port();
    let body = heat_capacitor(c = 100.0, t0 = 300.0);
    let source = heat_flow_source(power);
    connect(source.port, body.port, port);
    /// Heat stored above the start (J).
    let stored = output(100.0 * (body.t - 300.0));
    let too_hot = event(body.t - limit).rising().terminal();
}

#[dae_model]
fn guarded_heating() {
    let heater = guarded_heater(power = 20.0);
    let loss = thermal_conductor(0.5);
    let air = fixed_temperature(300.0);
    connect(heater.port, loss.port_a);
    connect(loss.port_b, air.port);
}

#[test]
fn a_part_s_outputs_and_events_read_by_their_paths() {
    // 100 T' = 20 − 0.5 (T − 300): T = 300 + 40 (1 − e^{−t/200}), which
    // reaches 320 at t = 200 ln 2.
    let opts = Options::new().method(Method::Dop853).rtol(1e-12).atol(1e-12);
    let sol = GuardedHeating::default().simulate(0.0, 1000.0, &opts).unwrap();
    let t_end = 200.0 * 2f64.ln();
    let end = *sol.times().last().unwrap();
    assert!((end - t_end).abs() < 1e-8, "stopped at {end}");
    assert_eq!(sol.events()[0].name, "heater.too_hot");
    assert!((sol.last("heater.stored").unwrap() - 2000.0).abs() < 1e-6);
    assert_eq!(<GuardedHeating as Model>::INFO.events[0].name, "heater.too_hot");
}
