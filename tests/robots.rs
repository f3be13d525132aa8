//! Robots from their URDF files (`tests/robots/`, example-robot-data's),
//! against Pinocchio: the joint accelerations of the generated model at
//! Pinocchio's random states equal M⁻¹(τ − nle − D q̇) from `pin.crba` and
//! `pin.nonLinearEffects` (`bench/peers/robots.py` wrote them), here with
//! τ = 0 as the model has no joint torques, and D the file's joint
//! damping, which the model applies and Pinocchio's dynamics leave out.

use daegen::prelude::*;

#[dae_model(scene = recursive)]
fn ur5() {
    urdf("tests/robots/ur5.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
    /// The tool flange, welded to the last link.
    let tool0_x = output(tool0[0]);
    let tool0_y = output(tool0[1]);
    let tool0_z = output(tool0[2]);
}

#[dae_model(scene = recursive)]
fn panda() {
    urdf("tests/robots/panda.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
}

include!("support/pinocchio_reference.rs");

/// `tests/robots/`: example-robot-data's URDF files and what Pinocchio
/// makes of them.
fn robots_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/robots")
}

/// The largest error of the model's joint accelerations against
/// Pinocchio's, relative to the largest of them, over its five states, and
/// how many coordinates of welded links were compared (each within 1e-14 m).
fn worst_against_pinocchio<M: Model>(model: &M, name: &str) -> (f64, usize) {
    let robot = pinocchio_reference(&robots_dir(), name);
    let joints = reference_joints(&robot);
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/robots/");
    let text =
        std::fs::read_to_string(format!("{file}{}", robot["urdf"].as_str().unwrap())).unwrap();
    let urdf = daegen_codegen::mechanics::urdf::parse::parse(&text).unwrap();
    let damping: Vec<f64> =
        joints.iter().map(|j| urdf.joints.iter().find(|u| &u.name == j).unwrap().damping).collect();
    let info = &M::INFO;
    let (mut worst, mut links) = (0.0f64, 0);
    for state in robot["states"].as_array().unwrap() {
        let (q, v, nle) = (floats(&state["q"]), floats(&state["v"]), floats(&state["nle"]));
        let m: Vec<Vec<f64>> = state["M"].as_array().unwrap().iter().map(floats).collect();
        let forces = nle.iter().zip(&v).zip(&damping).map(|((n, v), d)| -n - d * v).collect();
        let expected = solve(m, forces);
        let mut y = vec![0.0; M::STATES];
        model.initial_state(&mut y);
        for (k, joint) in joints.iter().enumerate() {
            let at = |n: &str| {
                info.states
                    .iter()
                    .position(|s| *s == n)
                    .unwrap_or_else(|| panic!("{n} in {:?}", info.states))
            };
            y[at(&format!("{joint}.q"))] = q[k];
            y[at(&format!("der({joint}.q)"))] = v[k];
        }
        let mut dy = vec![0.0; M::STATES];
        model.rhs(0.0, &y, &mut dy).unwrap();
        let (gap, checked) = welded_link_gap(model, &y, state);
        assert!(gap < 1e-14, "{name}: a welded link {gap:e} m from Pinocchio's");
        links += checked;
        let scale = expected.iter().fold(1.0f64, |s, a| s.max(a.abs()));
        for (k, joint) in joints.iter().enumerate() {
            let at = info.states.iter().position(|s| *s == format!("der({joint}.q)")).unwrap();
            worst = worst.max((dy[at] - expected[k]).abs() / scale);
        }
    }
    (worst, links)
}

#[test]
fn ur5_accelerations_are_pinocchio_s() {
    let (worst, links) = worst_against_pinocchio(&Ur5::default(), "ur5");
    println!("ur5: {worst:e}");
    // The tool flange at each of the five states.
    assert_eq!(links, 15);
    assert!(worst < 1e-12, "{worst:e}");
}

#[test]
fn panda_accelerations_are_pinocchio_s() {
    let (worst, _) = worst_against_pinocchio(&Panda::default(), "panda");
    println!("panda: {worst:e}");
    assert!(worst < 1e-12, "{worst:e}");
}

/// UR5 with a torque from outside on every joint: an input driving the
/// standard library's `signal_torque` on the joint's flange.
#[dae_model(scene = recursive)]
fn ur5_driven() {
    urdf("tests/robots/ur5.urdf");
    gravity(vec3(0.0, 0.0, -9.81));
    let tau_1 = input(0.0);
    let drive_1 = signal_torque();
    connect(drive_1.flange, shoulder_pan_joint.flange);
    drive_1.u == tau_1;
    let tau_2 = input(0.0);
    let drive_2 = signal_torque();
    connect(drive_2.flange, shoulder_lift_joint.flange);
    drive_2.u == tau_2;
    let tau_3 = input(0.0);
    let drive_3 = signal_torque();
    connect(drive_3.flange, elbow_joint.flange);
    drive_3.u == tau_3;
    let tau_4 = input(0.0);
    let drive_4 = signal_torque();
    connect(drive_4.flange, wrist_1_joint.flange);
    drive_4.u == tau_4;
    let tau_5 = input(0.0);
    let drive_5 = signal_torque();
    connect(drive_5.flange, wrist_2_joint.flange);
    drive_5.u == tau_5;
    let tau_6 = input(0.0);
    let drive_6 = signal_torque();
    connect(drive_6.flange, wrist_3_joint.flange);
    drive_6.u == tau_6;
}

#[test]
fn ur5_driven_by_joint_torques_is_pinocchio_s_aba() {
    // With the reference's random torques as inputs, the accelerations are
    // pin.aba's themselves.
    let robot = pinocchio_reference(&robots_dir(), "ur5");
    let info = &<Ur5Driven as Model>::INFO;
    let at = |n: &str| info.states.iter().position(|s| *s == n).unwrap();
    let joints = [
        "shoulder_pan_joint",
        "shoulder_lift_joint",
        "elbow_joint",
        "wrist_1_joint",
        "wrist_2_joint",
        "wrist_3_joint",
    ];
    let mut worst = 0.0f64;
    for state in robot["states"].as_array().unwrap() {
        let (q, v, tau, ddq) = (
            floats(&state["q"]),
            floats(&state["v"]),
            floats(&state["tau"]),
            floats(&state["ddq"]),
        );
        let model = Ur5Driven {
            tau_1: Input::constant(tau[0]),
            tau_2: Input::constant(tau[1]),
            tau_3: Input::constant(tau[2]),
            tau_4: Input::constant(tau[3]),
            tau_5: Input::constant(tau[4]),
            tau_6: Input::constant(tau[5]),
        };
        let mut y = vec![0.0; <Ur5Driven as Model>::STATES];
        model.initial_state(&mut y);
        for (k, joint) in joints.iter().enumerate() {
            y[at(&format!("{joint}.q"))] = q[k];
            y[at(&format!("der({joint}.q)"))] = v[k];
        }
        let mut dy = vec![0.0; <Ur5Driven as Model>::STATES];
        model.rhs(0.0, &y, &mut dy).unwrap();
        let scale = ddq.iter().fold(1.0f64, |s, a| s.max(a.abs()));
        for (k, joint) in joints.iter().enumerate() {
            worst = worst.max((dy[at(&format!("der({joint}.q)"))] - ddq[k]).abs() / scale);
        }
    }
    println!("ur5 with torques: {worst:e}");
    assert!(worst < 1e-12, "{worst:e}");
}

/// Solo 12, a quadruped on a floating base.
#[dae_model(scene = recursive)]
fn solo12() {
    urdf("tests/robots/solo12.urdf").floating();
    gravity(vec3(0.0, 0.0, -9.81));
    /// The feet, welded to the lower legs.
    let FL_FOOT_x = output(FL_FOOT[0]);
    let FL_FOOT_y = output(FL_FOOT[1]);
    let FL_FOOT_z = output(FL_FOOT[2]);
    let HR_FOOT_x = output(HR_FOOT[0]);
    let HR_FOOT_y = output(HR_FOOT[1]);
    let HR_FOOT_z = output(HR_FOOT[2]);
}

/// The largest distance between the model's welded links (its outputs
/// `<link>_x`, `_y`, `_z`) and Pinocchio's, at the state `y`, and how many
/// coordinates were compared.
fn welded_link_gap<M: Model>(model: &M, y: &[f64], state: &serde_json::Value) -> (f64, usize) {
    let mut worst = 0.0f64;
    let mut checked = 0;
    for (k, name) in M::INFO.outputs.iter().enumerate() {
        let Some((link, axis)) = name.rsplit_once('_') else { continue };
        let Some(theirs) = state["welded_links"][link].as_array() else { continue };
        let axis = ["x", "y", "z"].iter().position(|a| *a == axis).unwrap();
        let ours = model.output(k, 0.0, y);
        worst = worst.max((ours - theirs[axis].as_f64().unwrap()).abs());
        checked += 1;
    }
    (worst, checked)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// R v for the rotation of the unit quaternion (w, x, y, z).
fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let (w, u) = (q[0], [q[1], q[2], q[3]]);
    let t = cross(u, v).map(|x| 2.0 * x);
    add(add(v, t.map(|x| w * x)), cross(u, t))
}

#[test]
fn solo12_on_its_floating_base_is_pinocchio_s() {
    // Pinocchio's free flyer: q = (p, qx, qy, qz, qw), the link frame's
    // origin and attitude; v = (v, ω), the origin's velocity and the
    // angular velocity in the base's axes; its accelerations the rates of
    // those components. The model's base is the body at the base's centre
    // of mass c (base axes): x_c = p + R c, ẋ_c = R (v + ω × c), body rates
    // ω, and ẍ_c = R (v̇ + ω × v + ω̇ × c + ω × (ω × c)).
    let robot = pinocchio_reference(&robots_dir(), "solo12");
    let c = floats(&robot["bodies"][0]["com"]);
    let c = [c[0], c[1], c[2]];
    let info = &<Solo12 as Model>::INFO;
    let at = |n: &str| {
        info.states
            .iter()
            .position(|s| *s == n)
            .unwrap_or_else(|| panic!("{n} in {:?}", info.states))
    };
    let joints: Vec<String> = robot["bodies"].as_array().unwrap()[1..]
        .iter()
        .map(|b| b["joint"].as_str().unwrap().to_string())
        .collect();
    let model = Solo12::default();
    let mut worst = 0.0f64;
    for state in robot["states"].as_array().unwrap() {
        let (q, v, nle) = (floats(&state["q"]), floats(&state["v"]), floats(&state["nle"]));
        let m: Vec<Vec<f64>> = state["M"].as_array().unwrap().iter().map(floats).collect();
        let ddq = solve(m, nle.iter().map(|n| -n).collect());
        let quaternion = [q[6], q[3], q[4], q[5]];
        let (lin, w) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]]);
        let (a, dw) = ([ddq[0], ddq[1], ddq[2]], [ddq[3], ddq[4], ddq[5]]);
        let mut y = vec![0.0; <Solo12 as Model>::STATES];
        model.initial_state(&mut y);
        let centre = add([q[0], q[1], q[2]], rotate(quaternion, c));
        let centre_velocity = rotate(quaternion, add(lin, cross(w, c)));
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            y[at(&format!("base_link.{axis}"))] = centre[k];
            y[at(&format!("der(base_link.{axis})"))] = centre_velocity[k];
            y[at(&format!("base_link.w{axis}"))] = w[k];
        }
        for (k, part) in ["q0", "q1", "q2", "q3"].iter().enumerate() {
            y[at(&format!("base_link.{part}"))] = quaternion[k];
        }
        for (k, joint) in joints.iter().enumerate() {
            y[at(&format!("{joint}.q"))] = q[7 + k];
            y[at(&format!("der({joint}.q)"))] = v[6 + k];
        }
        let mut dy = vec![0.0; <Solo12 as Model>::STATES];
        model.rhs(0.0, &y, &mut dy).unwrap();
        let (gap, checked) = welded_link_gap(&model, &y, state);
        assert!(gap < 1e-14 && checked == 6, "solo12: a foot {gap:e} m from Pinocchio's");
        let classical = add(add(a, cross(w, lin)), add(cross(dw, c), cross(w, cross(w, c))));
        let centre_acceleration = rotate(quaternion, classical);
        let mut pairs: Vec<(f64, f64)> = Vec::new();
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            pairs.push((dy[at(&format!("der(base_link.{axis})"))], centre_acceleration[k]));
            pairs.push((dy[at(&format!("base_link.w{axis}"))], dw[k]));
        }
        for (k, joint) in joints.iter().enumerate() {
            pairs.push((dy[at(&format!("der({joint}.q)"))], ddq[6 + k]));
        }
        let scale = pairs.iter().fold(1.0f64, |s, p| s.max(p.1.abs()));
        for (ours, theirs) in pairs {
            worst = worst.max((ours - theirs).abs() / scale);
        }
    }
    println!("solo12: {worst:e}");
    assert!(worst < 1e-12, "{worst:e}");
}
