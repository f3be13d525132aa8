//! FMPy, the importer engineers script with, validates each exported FMU
//! (FMI 2.0 and 3.0) and simulates it in both interfaces: Model Exchange
//! through FMPy's own CVODE, Co-Simulation through the FMU's own method.
//! Both must equal the native run (DOP853 or RADAU5 at 1e-12) within the
//! tolerances they ran at.
//!
//! FMPy comes from an environment of its own under the target directory,
//! made with a pinned version by the first test that needs it
//! (`tests/support/python_peers.rs` at the workspace's root); the machine
//! needs only `python3`.

mod support;

use daegen::prelude::*;
use daegen::Solution;
use serde_json::json;

#[path = "../examples/models/bouncing_ball.rs"]
mod bouncing_ball;
/// The contract's pendulum, as `pendulum_fmu` exports it.
mod pendulum {
    use daegen::prelude::*;
    include!("../../tests/models/items.rs");
    contract_pendulum!(dae_model_with! { () });
}
#[path = "../examples/models/sampled_pi.rs"]
mod sampled_pi;
#[path = "../../tests/models/slider_crank_scene.rs"]
mod slider_crank;
#[path = "../../tests/models/speed_drive.rs"]
mod speed_drive;
#[path = "../examples/models/tank.rs"]
mod tank;
#[path = "../examples/models/van_der_pol.rs"]
mod van_der_pol;

/// Model Exchange runs CVODE at this relative tolerance (its absolute
/// tolerance is the same, each state's nominal being 1).
const ME_RTOL: f64 = 1e-9;
/// Co-Simulation runs the FMU's `Auto` at this tolerance.
const CS_TOL: f64 = 1e-10;

/// The largest error of `interface`'s results against `native`, relative
/// to 1 + |value|, over every output and time.
fn worst(results: &serde_json::Value, interface: &str, native: &Solution, outputs: &[&str]) -> f64 {
    worst_of(results, interface, &|t, name| native.at(t, name).expect("a native value"), outputs)
}

/// As [`worst`], against the values `exact(t, name)`.
fn worst_of(
    results: &serde_json::Value,
    interface: &str,
    exact: &dyn Fn(f64, &str) -> f64,
    outputs: &[&str],
) -> f64 {
    let run = &results[interface];
    let times: Vec<f64> = serde_json::from_value(run["time"].clone()).expect("times");
    assert!(times.len() > 5, "{interface}: {} rows", times.len());
    let mut worst = 0.0f64;
    for name in outputs {
        let values: Vec<f64> = serde_json::from_value(run[*name].clone()).expect("values");
        for (t, v) in times.iter().zip(values) {
            let exact = exact(*t, name);
            if exact.is_nan() {
                continue; // an instant where either side is right
            }
            let e = (v - exact).abs() / (1.0 + exact.abs());
            assert!(e.is_finite(), "{interface} {name} at {t}: {v} vs {exact}");
            worst = worst.max(e);
        }
    }
    worst
}

/// CVODE's global error over a run at `ME_RTOL` (local error control)
/// reaches a few hundred times it on these problems; the FMU's own
/// methods hold theirs within a hundred times `CS_TOL`.
const BOUNDS: (f64, f64) = (2e3 * ME_RTOL, 1e2 * CS_TOL);

/// Validates and runs example `name` through FMPy in both versions and
/// both interfaces; each result within [`BOUNDS`] of `native`. The FMI
/// 3.0 results.
fn check(name: &str, native: &Solution, stop: f64, outputs: &[&str]) -> serde_json::Value {
    let bounds = BOUNDS;
    let mut kept = serde_json::Value::Null;
    let archives = support::fmus(name, &format!("fmpy-{name}"));
    for (version, tag) in [("3.0", "fmi3"), ("2.0", "fmi2")] {
        let fmu = if tag == "fmi3" { &archives.fmi3 } else { &archives.fmi2 };
        let results = support::fmpy(json!({
            "fmu": fmu,
            "stop": stop,
            "interval": stop / 40.0,
            "rtol": ME_RTOL,
            "outputs": outputs,
            "cs_start": {"solver.tolerance": CS_TOL},
        }));
        let problems = results["problems"].as_array().expect("a list");
        assert!(problems.is_empty(), "FMI {version} {name}: FMPy's validation: {problems:?}");
        let me = worst(&results, "ModelExchange", native, outputs);
        let cs = worst(&results, "CoSimulation", native, outputs);
        println!("FMI {version} {name}: Model Exchange {me:.1e}, Co-Simulation {cs:.1e}");
        assert!(me < bounds.0, "FMI {version} {name}: Model Exchange off by {me:e}");
        assert!(cs < bounds.1, "FMI {version} {name}: Co-Simulation off by {cs:e}");
        if tag == "fmi3" {
            kept = results;
        }
    }
    kept
}

#[test]
fn the_fmpy_environment_is_made_from_an_empty_cache() {
    use support::python_peers::{bootstrap, target_dir, BASE_PYTHON, FMPY};
    let root = target_dir().join("python-peers-empty-cache-test");
    let _ = std::fs::remove_dir_all(&root);
    let python = bootstrap(&FMPY, BASE_PYTHON, &root).expect("the environment is made");
    assert!(python.starts_with(root.join(FMPY.name)), "{}", python.display());
    // The pinned FMPy runs from it: it validates an FMU of ours.
    let archives = support::fmus("van_der_pol_fmu", "fmpy-bootstrap");
    let out = std::process::Command::new(&python)
        .args(["-c", "import sys, fmpy; from fmpy.validation import validate_fmu; print(fmpy.__version__, len(validate_fmu(sys.argv[1])))"])
        .arg(&archives.fmi3)
        .output()
        .unwrap();
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        "0.3.32 0",
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Made once: a second call finds it and makes nothing.
    let made =
        std::fs::metadata(root.join(FMPY.name).join("complete")).unwrap().modified().unwrap();
    assert_eq!(bootstrap(&FMPY, BASE_PYTHON, &root).unwrap(), python);
    let kept =
        std::fs::metadata(root.join(FMPY.name).join("complete")).unwrap().modified().unwrap();
    assert_eq!(made, kept);
    let left: Vec<_> = std::fs::read_dir(&root).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, [FMPY.name], "nothing but the environment is left");
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn without_python_the_bootstrap_says_what_to_install() {
    use support::python_peers::{bootstrap, target_dir, FMPY};
    let root = target_dir().join("python-peers-no-python-test");
    let message = bootstrap(&FMPY, "python3-not-on-this-machine", &root).unwrap_err();
    assert_eq!(message.lines().count(), 1, "{message}");
    assert!(
        message.starts_with("`python3-not-on-this-machine` not found: install Python 3"),
        "{message}"
    );
    assert!(!root.join(FMPY.name).exists());
}

fn native<M: Model + Clone + Send + Sync + 'static>(
    model: M,
    stop: f64,
    method: Method,
) -> Solution {
    let options = Options::new().method(method).rtol(1e-12).atol(1e-12);
    model.simulate(0.0, stop, &options).expect("the native run")
}

#[test]
fn van_der_pol_through_fmpy() {
    let sol = native(van_der_pol::VanDerPol::default(), 10.0, Method::Dop853);
    check("van_der_pol_fmu", &sol, 10.0, &["x", "der(x)", "energy"]);
}

#[test]
fn the_pendulum_dae_through_fmpy() {
    let sol = native(pendulum::Pendulum::default(), 3.0, Method::Dop853);
    let results = check("pendulum_fmu", &sol, 3.0, &["x", "y", "u", "v", "energy"]);
    // The importer's CVODE integrates the index-reduced ODE; the FMU
    // projects it back onto x² + y² = l² whenever it drifts past the
    // tolerance relative to the state's size: FMPy gives no tolerance in
    // Model Exchange, so the FMU's default, 1e-6.
    let me = &results["ModelExchange"];
    let (x, y): (Vec<f64>, Vec<f64>) = (
        serde_json::from_value(me["x"].clone()).unwrap(),
        serde_json::from_value(me["y"].clone()).unwrap(),
    );
    let drift = x.iter().zip(&y).map(|(x, y)| (x * x + y * y - 1.0).abs()).fold(0.0, f64::max);
    assert!(drift <= 1e-6, "|x² + y² − 1| reached {drift:e}");
    println!("pendulum through Model Exchange: |x² + y² − 1| ≤ {drift:.1e}");
}

#[test]
fn a_slider_crank_scene_through_fmpy() {
    let sol = native(slider_crank::SliderCrankScene::default(), 1.0, Method::Dop853);
    check("slider_crank_fmu", &sol, 1.0, &["pin_x", "crank.theta"]);
}

#[test]
fn a_pi_speed_drive_of_parts_through_fmpy() {
    let sol = native(speed_drive::SpeedDrive::default(), 1.0, Method::Radau5);
    check("speed_drive_fmu", &sol, 1.0, &["motor.rotor.w", "motor.winding.i", "controller.x"]);
}

#[test]
fn a_bouncing_ball_through_fmpy() {
    let sol = native(bouncing_ball::BouncingBall::default(), 3.0, Method::Dop853);
    check("bouncing_ball_fmu", &sol, 3.0, &["h", "der(h)"]);
}

#[test]
fn an_input_set_by_the_importer_through_fmpy() {
    // The inflow steps from 0.2 to 0.6 m³/s at t = 5: the native run in
    // two pieces, the second from where the first ended.
    let options = Options::new().method(Method::Dop853).rtol(1e-12).atol(1e-12);
    let first = tank::Tank::default().simulate(0.0, 5.0, &options).unwrap();
    let filling = tank::Tank { q: Input::constant(0.6), ..Default::default() };
    let second = filling.simulate_from(5.0, first.final_state(), 10.0, &options).unwrap();
    let exact = |t: f64, name: &str| -> f64 {
        if t == 5.0 && name == "q" {
            return f64::NAN; // the step itself: 0.2 before it, 0.6 after
        }
        let piece = if t <= 5.0 { &first } else { &second };
        piece.at(t, name).unwrap()
    };
    let archives = support::fmus("tank_fmu", "fmpy-tank");
    for tag in ["fmi3", "fmi2"] {
        let fmu = if tag == "fmi3" { &archives.fmi3 } else { &archives.fmi2 };
        let results = support::fmpy(json!({
            "fmu": fmu,
            "stop": 10.0,
            "interval": 0.25,
            "rtol": ME_RTOL,
            "outputs": ["h", "outflow", "q"],
            "cs_start": {"solver.tolerance": CS_TOL},
            "input": {"name": "q", "points": [[0.0, 0.2], [5.0, 0.2], [5.0, 0.6], [10.0, 0.6]]},
        }));
        assert!(results["problems"].as_array().unwrap().is_empty(), "{}", results["problems"]);
        let me = worst_of(&results, "ModelExchange", &exact, &["h", "outflow", "q"]);
        let cs = worst_of(&results, "CoSimulation", &exact, &["h", "outflow", "q"]);
        println!("{tag} tank with an input: Model Exchange {me:.1e}, Co-Simulation {cs:.1e}");
        assert!(me < BOUNDS.0, "{tag}: Model Exchange off by {me:e}");
        assert!(cs < BOUNDS.1, "{tag}: Co-Simulation off by {cs:e}");
    }
}

#[test]
fn a_sampled_controller_through_fmpy() {
    // The exact discrete-time recursion of the loop: with u held,
    // x(kh + s) = φ(s) x_k + (b/a)(1 − φ(s)) u_k, φ(s) = e^{−a s}; the
    // controller I_k = I_{k−1} + k_i h (r − x_k), u_k = k_p (r − x_k) + I_k.
    let m = sampled_pi::SampledPi::default();
    let samples = 30;
    let mut held = Vec::new();
    let (mut x, mut integral) = (0.0f64, 0.0f64);
    for _ in 0..=samples {
        integral += m.ki * m.h * (m.r - x);
        let u = m.kp * (m.r - x) + integral;
        held.push((x, u));
        x = (-m.a * m.h).exp() * x + m.b / m.a * (1.0 - (-m.a * m.h).exp()) * u;
    }
    let exact = |t: f64, name: &str| -> f64 {
        let k = (t / m.h).round();
        let at_instant = (t / m.h - k).abs() < 1e-9;
        if at_instant && name == "u" {
            return f64::NAN; // the instant: u before the sample, or after it
        }
        let k = if at_instant { k } else { (t / m.h).floor() } as usize;
        let (xk, uk) = held[k];
        let s = t - k as f64 * m.h;
        let phi = (-m.a * s).exp();
        match name {
            "x" => phi * xk + m.b / m.a * (1.0 - phi) * uk,
            _ => uk,
        }
    };
    let archives = support::fmus("sampled_pi_fmu", "fmpy-sampled");
    for tag in ["fmi3", "fmi2"] {
        let fmu = if tag == "fmi3" { &archives.fmi3 } else { &archives.fmi2 };
        let stop = samples as f64 * m.h;
        let results = support::fmpy(json!({
            "fmu": fmu,
            "stop": stop,
            "interval": m.h / 4.0,
            "rtol": ME_RTOL,
            "outputs": ["x", "u"],
            "cs_start": {"solver.tolerance": CS_TOL},
        }));
        assert!(results["problems"].as_array().unwrap().is_empty(), "{}", results["problems"]);
        let me = worst_of(&results, "ModelExchange", &exact, &["x", "u"]);
        let cs = worst_of(&results, "CoSimulation", &exact, &["x", "u"]);
        println!("{tag} sampled PI: Model Exchange {me:.1e}, Co-Simulation {cs:.1e}");
        assert!(me < BOUNDS.0, "{tag}: Model Exchange off by {me:e}");
        assert!(cs < BOUNDS.1, "{tag}: Co-Simulation off by {cs:e}");
    }
}
