//! Robots from their URDF against Pinocchio (`--robots`): the time of one
//! forward-dynamics evaluation (the joint accelerations at a state, the
//! model's right-hand side) against `pin.aba` through Pinocchio's Python
//! binding, timed by `peers/robots.py --timing` in the same run, its
//! binding's own cost (`aba` on an empty model) stated beside it. The
//! states are Pinocchio's reference states (`tests/robots/pinocchio.json`),
//! with zero joint torques. Writes `results/robots.md`.

use super::*;
use daegen_workprecision::median_time;

#[dae_model(scene = recursive)]
fn ur5_robot() {
    urdf("../tests/robots/ur5.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
}

#[dae_model(scene = recursive)]
fn panda_robot() {
    urdf("../tests/robots/panda.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
}

#[dae_model(scene = recursive)]
fn talos_arm_robot() {
    urdf("target/robots/talos_left_arm.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
}

#[dae_model(scene = recursive)]
fn talos_robot() {
    urdf("target/robots/talos_reduced.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
}

#[dae_model(scene = recursive)]
fn solo12_robot() {
    urdf("../tests/robots/solo12.urdf").floating();
    gravity(vec3(0.0, 0.0, -9.81));
}

/// Pinocchio's times (µs): per robot `(aba, crba)`, and `aba` on an empty
/// model.
fn pinocchio() -> Result<(Vec<(String, f64)>, f64), String> {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/peers/robots.py");
    let out = Command::new("python3")
        .args([script, "--timing"])
        .output()
        .map_err(|e| format!("python3: {e}"))?;
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).into_owned());
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let number = |key: &str, from: &str| -> Option<f64> {
        let at = from.find(&format!("\"{key}\": "))? + key.len() + 4;
        from[at..].split([',', '}']).next()?.trim().parse().ok()
    };
    let mut rows = Vec::new();
    for robot in ["ur5", "panda", "solo12", "talos_arm", "talos"] {
        let at = text.find(&format!("\"{robot}\": {{")).ok_or("no robot")?;
        rows.push((robot.to_string(), number("aba", &text[at..]).ok_or("no aba")?));
    }
    let overhead = number("aba_empty_model", &text).ok_or("no overhead")?;
    Ok((rows, overhead))
}

/// Seconds per evaluation of `model`'s right-hand side at a state with
/// every joint at 0.3 rad moving at 0.5 rad/s.
fn evaluation<M: Model + Default>(settings: &Settings) -> f64 {
    const CALLS: usize = 10_000;
    let model = M::default();
    let mut y = vec![0.0; M::STATES];
    model.initial_state(&mut y);
    for (i, name) in M::INFO.states.iter().enumerate() {
        if name.ends_with(".q") {
            y[i] = 0.3;
        } else if name.starts_with("der(") {
            y[i] = 0.5;
        }
    }
    let mut dy = vec![0.0; M::STATES];
    let (seconds, _) = median_time(settings, || {
        for k in 0..CALLS {
            y[0] += 1e-15 * k as f64;
            let _ = model.rhs(0.0, std::hint::black_box(&y), &mut dy);
        }
        dy[1]
    });
    seconds / CALLS as f64
}

/// Writes results/robots.md.
pub fn robots_section() -> String {
    let settings = Settings::default();
    let ours = [
        ("ur5", evaluation::<Ur5Robot>(&settings)),
        ("panda", evaluation::<PandaRobot>(&settings)),
        ("solo12", evaluation::<Solo12Robot>(&settings)),
        ("talos_arm", evaluation::<TalosArmRobot>(&settings)),
        ("talos", evaluation::<TalosRobot>(&settings)),
    ];
    let mut text = format!(
        "# Robots from their URDF against Pinocchio\n\nMachine: {}. Written by `cd bench && cargo run --release -- --robots` (bench/src/robots.rs, peers/robots.py). One forward-dynamics evaluation: our generated right-hand side (joint accelerations by the composite-rigid-body algorithm and recursive Newton–Euler in body frames, the mass matrix factored along the tree, all written symbolically; Solo 12 on its floating base, TALOS's 32 joints on a fixed one; TALOS's files from `pip install example-robot-data`, copied by `build.rs`) against `pin.aba` through Pinocchio's Python binding, the median of its timings; the binding's own cost is `aba` on an empty model. Ratio: ours over Pinocchio's time less that cost.\n\n",
        machine()
    );
    match pinocchio() {
        Ok((rows, overhead)) => {
            text.push_str(&format!("Pinocchio's binding costs {overhead:.2} µs a call.\n\n| robot | ours | Pinocchio aba | less the binding | ratio |\n|---|---|---|---|---|\n"));
            for ((robot, aba), (_, mine)) in rows.iter().zip(&ours) {
                let net = aba - overhead;
                text.push_str(&format!(
                    "| {robot} | {:.2} µs | {aba:.2} µs | {net:.2} µs | {:.2} |\n",
                    mine * 1e6,
                    mine * 1e6 / net
                ));
            }
        }
        Err(e) => {
            text.push_str(&format!("Pinocchio did not run ({e}): `python3 -m pip install pin`.\n\n| robot | ours |\n|---|---|\n"));
            for (robot, mine) in ours {
                text.push_str(&format!("| {robot} | {:.2} µs |\n", mine * 1e6));
            }
        }
    }
    text
}
