//! Robots read from URDF: the file as written (with the line of each
//! mistake), and the kinematic tree made of it, links welded by fixed
//! joints merged with their inertias combined. Expected values are worked
//! by hand from the parallel-axis theorem and URDF's rpy convention.

use daegen_codegen::mechanics::urdf::parse::{parse, JointKind};
use daegen_codegen::mechanics::urdf::tree::{locate, tree};
use daegen_codegen::mechanics::urdf::Pose;

/// A base, an upper arm on a revolute joint, a hand welded to its end.
const ARM: &str = r#"<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="upper">
    <inertial>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <mass value="1.0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>
    </inertial>
    <visual><geometry><mesh filename="package://arm/upper.stl"/></geometry></visual>
  </link>
  <link name="hand">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>
    </inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
    <axis xyz="0 0 2"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="2"/>
    <dynamics damping="0.3" friction="0.1"/>
  </joint>
  <joint name="wrist" type="fixed">
    <parent link="upper"/>
    <child link="hand"/>
    <origin xyz="0.5 0 0"/>
  </joint>
</robot>
"#;

#[test]
fn a_file_reads_as_written() {
    let robot = parse(ARM).unwrap();
    assert_eq!(robot.name, "arm");
    assert_eq!(robot.links.len(), 3);
    assert_eq!(robot.links[1].line, 4);
    let shoulder = &robot.joints[0];
    assert_eq!((shoulder.kind, shoulder.line), (JointKind::Revolute, 18));
    assert_eq!(shoulder.axis, [0.0, 0.0, 1.0], "the axis is made unit");
    assert_eq!(shoulder.origin, Pose { xyz: [0.0, 0.0, 0.1], rpy: [0.0; 3] });
    assert_eq!(shoulder.limits, Some((-1.5, 1.5)));
    assert_eq!((shoulder.damping, shoulder.friction), (0.3, 0.1));
    assert_eq!(robot.joints[1].axis, [1.0, 0.0, 0.0], "the default axis");
}

#[test]
fn welded_links_merge_by_the_parallel_axis_theorem() {
    let t = tree(&parse(ARM).unwrap()).unwrap();
    // One moving joint: one body, the upper arm with the hand welded to it.
    assert_eq!(t.bodies.len(), 1);
    let body = &t.bodies[0];
    assert_eq!(body.link, "upper");
    assert_eq!(body.parent, None);
    assert_eq!(body.joint.placement.translation, [0.0, 0.0, 0.1]);
    // Two unit point masses at x = 0 and x = 0.5: the centre at 0.25, and
    // about it 2·1·0.25² = 0.125 about y and z, nothing about x.
    let m = body.mass;
    assert_eq!(m.mass, 2.0);
    assert_eq!(m.com, [0.25, 0.0, 0.0]);
    assert_eq!(m.inertia, [[0.0, 0.0, 0.0], [0.0, 0.125, 0.0], [0.0, 0.0, 0.125]]);
    let (b, hand) = locate(&t, "hand").unwrap();
    assert_eq!((b, hand.translation), (Some(0), [0.5, 0.0, 0.0]));
    assert_eq!(t.root_links.len(), 1);
    assert_eq!(t.root_mass.mass, 0.0);
}

#[test]
fn an_inertia_turns_with_its_rpy() {
    // Yaw by π/2 about z: the principal moments about x and y swap; a roll
    // by π/2 about x swaps y and z.
    let file = |rpy: &str| {
        format!(
            r#"<robot name="r"><link name="a"/><link name="b"><inertial><origin xyz="0 0 0" rpy="{rpy}"/><mass value="2"/><inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial></link><joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>"#
        )
    };
    let diagonal = |rpy: &str| {
        let t = tree(&parse(&file(rpy)).unwrap()).unwrap();
        let i = t.bodies[0].mass.inertia;
        for r in 0..3 {
            for c in 0..3 {
                if r != c {
                    assert!(i[r][c].abs() < 1e-15, "{rpy}: {i:?}");
                }
            }
        }
        [i[0][0], i[1][1], i[2][2]]
    };
    let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-15);
    let half_pi = std::f64::consts::FRAC_PI_2;
    assert!(close(diagonal(&format!("0 0 {half_pi}")), [2.0, 1.0, 3.0]));
    assert!(close(diagonal(&format!("{half_pi} 0 0")), [1.0, 3.0, 2.0]));
    assert!(close(diagonal(&format!("0 {half_pi} 0")), [3.0, 2.0, 1.0]));
}

/// The first error of `text`: (line, message).
fn first_error(text: &str) -> (u32, String) {
    let errors = match parse(text) {
        Err(e) => e,
        Ok(robot) => tree(&robot).expect_err("a mistake"),
    };
    (errors[0].line, errors[0].message.clone())
}

#[test]
fn mistakes_name_their_line() {
    let (line, message) = first_error(&ARM.replace("type=\"revolute\"", "type=\"ball\""));
    assert_eq!(line, 18);
    assert!(message.contains("\"ball\"") && message.contains("revolute, continuous"), "{message}");

    let (line, message) = first_error(&ARM.replace("xyz=\"0 0 0.1\"", "xyz=\"0 0\""));
    assert_eq!(line, 18);
    assert!(message.contains("has 2 numbers; it takes 3"), "{message}");

    let (line, message) =
        first_error(&ARM.replace("<mass value=\"1.0\"/>\n      <inertia", "<inertia"));
    assert_eq!(line, 4);
    assert!(message.contains("has no <mass>"), "{message}");

    let (line, message) =
        first_error(&ARM.replace("<link name=\"hand\">", "<link name=\"upper\">"));
    assert_eq!(line, 12);
    assert!(message.contains("a second link named `upper`"), "{message}");

    let (_, message) =
        first_error(&ARM.replace("<child link=\"hand\"/>", "<child link=\"upper\"/>"));
    assert!(
        message.contains("is the child of joint `shoulder` (line 18) and of joint `wrist`"),
        "{message}"
    );

    let (_, message) =
        first_error(&ARM.replace("<parent link=\"upper\"/>", "<parent link=\"elbow\"/>"));
    assert!(message.contains("names the parent link `elbow`"), "{message}");

    // No mass anywhere past the shoulder: its coordinate has no inertia.
    let massless = ARM.replace("<mass value=\"1.0\"/>", "<mass value=\"0\"/>");
    let (line, message) = first_error(&massless);
    assert_eq!(line, 18);
    assert!(
        message.contains("joint `shoulder` moves link `upper`, and nothing it carries has mass"),
        "{message}"
    );

    // A second root.
    let (_, message) = first_error(&ARM.replace("</robot>", "<link name=\"spare\"/></robot>"));
    assert!(message.contains("`base` (line 3), `spare`"), "{message}");

    let (line, message) = first_error("<robot name=\"r\"><link name=\"a\"></robot>");
    assert_eq!(line, 1);
    assert!(message.starts_with("not well-formed XML"), "{message}");
}

#[test]
fn loops_are_refused() {
    let closed = r#"<robot name="r">
<link name="a"/><link name="b"/>
<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>
</robot>"#;
    let apart_from_the_root = r#"<robot name="r">
<link name="a"/>
<link name="b"/><link name="c"/>
<joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>
<joint name="cb" type="fixed"><parent link="c"/><child link="b"/></joint>
</robot>"#;
    for (text, expected) in [
        (closed, "the joints form a loop"),
        (apart_from_the_root, "links `b`, `c` are not reached from the root link `a`"),
    ] {
        let (line, message) = first_error(text);
        assert_eq!(line, 3);
        assert!(message.contains(expected), "{message}");
    }
}

#[path = "../../tests/support/python_peers.rs"]
mod python_peers;

/// `tests/robots/` at the workspace's root: example-robot-data's URDF files
/// and what Pinocchio makes of them (`bench/peers/robots.py`).
fn robots_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/robots")
}

/// A robot's file: ours in tests/robots, or (`erd:`) example-robot-data's,
/// as TALOS's licence (CC BY-NC-ND) keeps its files out of the
/// repository: from the package's own environment under the target
/// directory, made on first use.
fn robot_file(urdf: &str) -> std::path::PathBuf {
    let Some(rest) = urdf.strip_prefix("erd:") else { return robots_dir().join(urdf) };
    let python = python_peers::python(&python_peers::EXAMPLE_ROBOT_DATA);
    let out = std::process::Command::new(python)
        .args(["-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"])
        .output()
        .expect("the environment's python runs");
    let purelib = String::from_utf8(out.stdout).unwrap().trim().to_string();
    let path = std::path::Path::new(&purelib)
        .join("cmeel.prefix/share/example-robot-data/robots")
        .join(rest);
    assert!(path.exists(), "{} is missing from example-robot-data 5.0.0", path.display());
    path
}

#[test]
fn the_trees_of_real_robots_are_pinocchio_s() {
    let reference: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(robots_dir().join("pinocchio.json")).unwrap(),
    )
    .unwrap();
    fn numbers(v: &serde_json::Value) -> Vec<f64> {
        match v {
            serde_json::Value::Array(a) => a.iter().flat_map(numbers).collect(),
            x => vec![x.as_f64().unwrap()],
        }
    }
    let close = |what: &str, ours: &[f64], theirs: &[f64]| {
        assert_eq!(ours.len(), theirs.len(), "{what}");
        for (a, b) in ours.iter().zip(theirs) {
            assert!(
                (a - b).abs() <= 1e-14 * (1.0 + b.abs()),
                "{what}: {ours:?} against {theirs:?}"
            );
        }
    };
    for robot in reference["robots"].as_array().unwrap() {
        let name = robot["name"].as_str().unwrap();
        let text = std::fs::read_to_string(robot_file(robot["urdf"].as_str().unwrap())).unwrap();
        let t = tree(&parse(&text).unwrap()).unwrap();
        let mut theirs = robot["bodies"].as_array().unwrap().clone();
        if robot["floating_base"].as_bool().unwrap() {
            // Pinocchio's free-flyer carries the root and what is welded to it.
            let root = theirs.remove(0);
            close(
                &format!("{name} root mass"),
                &[t.root_mass.mass],
                &[root["mass"].as_f64().unwrap()],
            );
            close(&format!("{name} root com"), &t.root_mass.com, &numbers(&root["com"]));
            close(
                &format!("{name} root inertia"),
                &t.root_mass.inertia.concat(),
                &numbers(&root["inertia"]),
            );
        }
        assert_eq!(t.bodies.len(), theirs.len(), "{name}: one body per moving joint");
        for (body, other) in t.bodies.iter().zip(&theirs) {
            let what = format!("{name} {}", body.joint.name);
            assert_eq!(
                body.joint.name,
                other["joint"].as_str().unwrap(),
                "{name}: the joints' order"
            );
            let parent = body.parent.map(|p| t.bodies[p].joint.name.as_str());
            let their_parent = other["parent"].as_str().filter(|p| *p != "root_joint");
            assert_eq!(parent, their_parent, "{what}: parent");
            close(
                &format!("{what} rotation"),
                &body.joint.placement.rotation.concat(),
                &numbers(&other["rotation"]),
            );
            close(
                &format!("{what} translation"),
                &body.joint.placement.translation,
                &numbers(&other["translation"]),
            );
            close(&format!("{what} mass"), &[body.mass.mass], &[other["mass"].as_f64().unwrap()]);
            close(&format!("{what} com"), &body.mass.com, &numbers(&other["com"]));
            close(
                &format!("{what} inertia"),
                &body.mass.inertia.concat(),
                &numbers(&other["inertia"]),
            );
        }
        println!("{name}: {} bodies as Pinocchio's", t.bodies.len());
    }
}

/// The macro's expansion of `body` under `#[dae_model(attr)]`.
fn expand(attr: &str, body: &str) -> String {
    let item: proc_macro2::TokenStream = format!("fn robot() {{ {body} }}").parse().unwrap();
    daegen_codegen::expand_dae_model(attr.parse().unwrap(), item).to_string()
}

#[test]
fn a_mistake_in_the_file_is_a_compile_error_that_quotes_its_line() {
    let out = expand("scene = recursive", r#"urdf("tests/data/broken.urdf");"#);
    assert!(out.contains("compile_error"), "{out}");
    assert!(out.contains(r#"tests/data/broken.urdf:5: joint `elbow` has type \"ball\""#), "{out}");
    let out = expand("scene = recursive", r#"urdf("tests/data/missing.urdf");"#);
    assert!(out.contains("cannot read") && out.contains("missing.urdf"), "{out}");
    let out = expand("", r#"urdf("tests/data/broken.urdf");"#);
    assert!(out.contains("write `#[dae_model(scene = recursive)]`"), "{out}");
    let out = expand("scene = recursive", r#"urdf("../tests/robots/ur5.urdf").fixed();"#);
    assert!(out.contains("takes `.floating()` (a free base), nothing else"), "{out}");
}

#[test]
fn a_robot_s_names_are_its_file_s() {
    // UR5: six joints, their coordinates states by the file's names.
    let out = expand(
        "scene = recursive",
        r#"urdf("../tests/robots/ur5.urdf"); gravity(vec3(0.0, 0.0, -9.81));"#,
    );
    assert!(!out.contains("compile_error"), "{out}");
    for joint in ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_3_joint"] {
        assert!(out.contains(&format!("\"{joint}.q\"")), "{joint}");
    }
    assert!(out.contains("\"wrist_3_link.x\""));
    // The build depends on the file.
    assert!(out.contains("include_bytes"), "{out}");
}

include!("../../tests/support/pinocchio_reference.rs");

/// The TALOS arm (7 joints) and the TALOS humanoid on a fixed base (32
/// joints), whose files stay out of the repository, through the symbolic
/// engine: the model analysed as the macro would, its joint accelerations
/// evaluated from the expressions emission writes, at Pinocchio's random
/// states, against M⁻¹(−nle − D q̇) from `pin.crba` and
/// `pin.nonLinearEffects`, D the file's joint damping.
#[test]
fn talos_accelerations_are_pinocchio_s() {
    for name in ["talos_arm", "talos"] {
        let robot = pinocchio_reference(&robots_dir(), name);
        let path = robot_file(robot["urdf"].as_str().unwrap());
        let urdf = parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let item: syn::ItemFn = syn::parse_str(&format!(
            "fn robot() {{ urdf({:?}); gravity(vec3(0.0, 0.0, -9.81)); }}",
            path.display().to_string()
        ))
        .unwrap();
        let mut cx = daegen_codegen::front::ctxt::Ctxt::default();
        let analysed =
            daegen_codegen::pipeline::analyse(&mut cx, "scene = recursive".parse().unwrap(), &item)
                .unwrap_or_else(|_| panic!("{name}: {:?}", cx.messages()));
        let (g, sys) = (&analysed.ir.graph, &analysed.model.system);
        let slot = |n: String| sys.slots.iter().position(|s| s.name == n).unwrap();
        let joints = reference_joints(&robot);
        let accelerations: Vec<daegen_codegen::Id> = joints
            .iter()
            .map(|j| match sys.derivatives[slot(format!("der({j}.q)"))] {
                daegen_codegen::dae::system::SlotDerivative::Explicit(e) => e,
                _ => panic!("{name}: {j}'s acceleration is not explicit"),
            })
            .collect();
        let damping: Vec<f64> = joints
            .iter()
            .map(|j| urdf.joints.iter().find(|u| &u.name == j).unwrap().damping)
            .collect();
        let mut worst = 0.0f64;
        for state in robot["states"].as_array().unwrap() {
            let (q, v, nle) = (floats(&state["q"]), floats(&state["v"]), floats(&state["nle"]));
            let m: Vec<Vec<f64>> = state["M"].as_array().unwrap().iter().map(floats).collect();
            let forces = nle.iter().zip(&v).zip(&damping).map(|((n, v), d)| -n - d * v).collect();
            let expected = solve(m, forces);
            let mut values = vec![f64::NAN; sys.slots.len()];
            for (k, j) in joints.iter().enumerate() {
                values[slot(format!("{j}.q"))] = q[k];
                values[slot(format!("der({j}.q)"))] = v[k];
            }
            let value = |s: daegen_codegen::SymbolId| {
                if let Some(i) = sys.slots.iter().position(|slot| slot.symbol == s) {
                    return values[i];
                }
                let name = &g.symbol(s).name;
                analysed.ir.params.iter().find(|p| p.ident == name).map_or(f64::NAN, |p| p.default)
            };
            let ours = g.eval(&accelerations, &value);
            let scale = expected.iter().fold(1.0f64, |s, a| s.max(a.abs()));
            for (a, b) in ours.iter().zip(&expected) {
                worst = worst.max((a - b).abs() / scale);
            }
        }
        println!("{name}: {} joints, worst {worst:e}", joints.len());
        assert!(worst < 1e-12, "{name}: {worst:e}");
    }
}
