//! # Mechanisms: multibody scenes
//!
//! Instead of writing the constraint equations of a mechanism, declare its
//! bodies and joints; the macro writes the equations of motion (course
//! notes §4.2) and hands them to the DAE pipeline of [`super::daes`].
//!
//! Planar scenes: `body(m, j, [x, y, θ], [vx, vy, ω]?)`, joints
//! `revolute(a, pa, b, pb)`, `prismatic(a, pa, b, pb, axis)`,
//! `distance(a, pa, b, pb, l)`, `fixed(a, pa, b, pb)`; loads `gravity`,
//! `force`, `torque`, `spring(a, pa, b, pb, k, l0, c)`; `position(b, p)`.
//! Points are in the body's coordinates; a joint's reactions are algebraic
//! variables named after it (`pin[0]`).
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A pendulum of two rods: four coordinates' worth of joints on six.
//! #[dae_model]
//! fn double_rod() {
//!     let ground = ground();
//!     let upper = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0]);
//!     let lower = body(1.0, 1.0 / 12.0, [1.5, 0.0, 0.0]);
//!     let pin = revolute(ground, vec3(0.0, 0.0, 0.0), upper, vec3(-0.5, 0.0, 0.0));
//!     revolute(upper, vec3(0.5, 0.0, 0.0), lower, vec3(-0.5, 0.0, 0.0));
//!     gravity(vec3(0.0, -9.81, 0.0));
//!     let tip = position(lower, vec3(0.5, 0.0, 0.0));
//!     let tip_y = output(tip[1]);
//! }
//!
//! let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
//! let sol = DoubleRod::default().simulate(0.0, 1.0, &opts)?;
//! assert_eq!(sol.degrees_of_freedom(), Some(2));
//! assert!(sol.last("tip_y")? < 0.0); // it fell
//! assert!(sol.max_constraint_residual() < 1e-12);
//! // The second joint's angle is the lower rod's relative to the upper.
//! let bend = sol.last("lower.theta")? - sol.last("upper.theta")?;
//! assert!((sol.last("revolute2.q")? - bend).abs() < 1e-12);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! `#[dae_model(scene = recursive)]` uses joint coordinates along a
//! spanning tree instead (the double rod becomes an ODE in two angles; cut
//! joints of closed loops stay constraints). The macro counts the degrees
//! of freedom as n − rank Φ_q at the initial configuration, and a joint
//! whose rows follow from the others is a compile error on that joint.
//!
//! Both formulations answer to the same names:
//!
//! | name | what |
//! |---|---|
//! | `upper.x`, `upper.y`, `upper.theta`, `der(upper.x)`, … | a body's centre of mass (m), angle (rad) and their rates |
//! | `pin.q`, `der(pin.q)` | a revolute joint's angle θ_b − θ_a (rad); a prismatic joint's slide along its axis (m) |
//! | `pin[0]`, `pin[1]` | the multipliers of the joint's constraint rows (its reaction is −Φ_qᵀλ) |
//! | `revolute2.q`, `revolute2[0]` | an unnamed joint, by its kind and place among the joints |
//!
//! In body coordinates (the default) the bodies' coordinates are states and
//! the joints' outputs; in joint coordinates the other way round (only
//! the cut joints keep multipliers there). `println!("{}", model.describe())`
//! lists them all with what they are.
//!
//! Spatial scenes: `spatial_body(m, inertia, [x, y, z], [q0, q1, q2, q3],
//! [v]?, [ω]?)` with a unit quaternion and body rates as states, joints
//! `spherical`, `revolute(a, pa, b, pb, axis)`, `prismatic`, `fixed`,
//! `distance`, loads in world axes, `orientation(b)` for R(q). A spatial
//! body answers to `bob.x`, `bob.y`, `bob.z` (centre of mass, world axes),
//! `bob.q0` … `bob.q3` (attitude, body to world) and `bob.wx` … `bob.wz`
//! (angular velocity, body axes); a revolute joint's `q` is its turn about
//! the axis since the start, a prismatic joint's the slide along it:
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A conical pendulum: a bob on a rod, on its circular orbit.
//! #[dae_model]
//! fn conical() {
//!     let g = param(9.81);
//!     let ground = ground();
//!     let bob = spatial_body(
//!         1.0,
//!         vec3(0.01, 0.01, 0.01),
//!         [sin(0.6), 0.0, -cos(0.6)],
//!         [1.0, 0.0, 0.0, 0.0],
//!         [0.0, sin(0.6) * sqrt(g / cos(0.6)), 0.0],
//!         [0.0, 0.0, 0.0],
//!     );
//!     distance(ground, vec3(0.0, 0.0, 0.0), bob, vec3(0.0, 0.0, 0.0), 1.0);
//!     gravity(vec3(0.0, 0.0, -g));
//! }
//!
//! let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
//! let sol = Conical::default().simulate(0.0, 1.0, &opts)?;
//! // It stays at its height.
//! assert!((sol.last("bob.z")? + 0.6f64.cos()).abs() < 1e-8);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! Spatial joints also include `universal(a, pa, b, pb, axis_in_a,
//! axis_in_b)` (a Cardan joint: the cross axes stay perpendicular),
//! `cylindrical(a, pa, b, pb, axis)` (slides and turns: `j.q` and
//! `j.angle`) and `planar(a, pa, b, pb, normal)`.
//!
//! `scene = recursive` works in space too: joint coordinates along a
//! spanning tree, the joint-space mass matrix by the composite-rigid-body
//! algorithm and the bias forces by recursive Newton–Euler (Featherstone,
//! 2008), written symbolically and shared; closed loops keep their cut
//! joints as constraints, and a body no joint reaches floats on a free
//! joint with its own coordinates. The joints' coordinates are states:
//!
//! | joint | states |
//! |---|---|
//! | `revolute`, `prismatic` | `j.q` (turn since the start, rad; slide, m) |
//! | `cylindrical` | `j.q` (slide), `j.angle` (turn) |
//! | `universal` | `j.q1`, `j.q2` (turns about the axis in a and in b since the start) |
//! | `planar` | `j.u`, `j.v` (slides in the plane), `j.angle` |
//! | `spherical` | `j.q0` … `j.q3` (relative quaternion), `j.wx` … `j.wz` (relative rates, b's axes) |
//!
//! and the bodies' coordinates outputs; in body coordinates the joints'
//! coordinates are outputs of the bodies' positions and attitudes, with
//! the rates `der(j.q)`, … of all but the spherical joint's, so both
//! formulations answer to the same names. For chains and trees of more than a few bodies prefer it:
//! a seven-joint arm has 14 states instead of 91 plus 35 multipliers, takes
//! 14× less time a step and compiles (release) in about a second against
//! six minutes (`bench/results/dae.md`). A scene in body coordinates whose
//! generated code would pass 2 MB (a chain of about six bodies) is refused
//! with that advice; `#[dae_model(scene = global)]` written out keeps body
//! coordinates anyway. Two differences: in joint coordinates an angle does not
//! wrap (body coordinates read a spatial joint's angle from the
//! attitudes, in (−π, π]), and the bodies must start where their joints
//! put them, moving as the joints move them: a start the joints contradict
//! is a compile error that names the joint (body coordinates would
//! project it and report `initial_corrections()`). The poses drawn are the
//! joint coordinates' zero; `init(hinge.q, 0.5)` and
//! `init(der(hinge.q), 1.0)` start a joint elsewhere, as a robot is
//! started: by its joint positions and rates.
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A rod hinged at its top about world x, released at 0.5 rad.
//! #[dae_model(scene = recursive)]
//! fn hinged() {
//!     let g = param(9.81);
//!     let ground = ground();
//!     let rod = spatial_body(
//!         2.0,
//!         vec3(0.1, 0.2, 0.05),
//!         [0.0, 0.5 * sin(0.5), -0.5 * cos(0.5)],
//!         [cos(0.25), sin(0.25), 0.0, 0.0],
//!     );
//!     let hinge = revolute(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
//!     gravity(vec3(0.0, 0.0, -g));
//! }
//!
//! let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
//! let sol = Hinged::default().simulate(0.0, 2.0, &opts)?;
//! // One state and its rate: the hinge's angle, from 0 at the start.
//! assert_eq!(Hinged::INFO.states.len(), 2);
//! let angle = 0.5 + sol.last("hinge.q")?;
//! assert!((sol.last("rod.y")? - 0.5 * angle.sin()).abs() < 1e-12);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! A robot comes from its URDF, the description every arm, leg and
//! humanoid ships with: `urdf("path")` (relative to the crate's
//! `Cargo.toml`, read at compile time, and the model rebuilt when the file
//! changes) writes one `spatial_body` per moving joint and the joint, in
//! joint coordinates:
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A UR5 arm falling from its zero configuration, its base fixed.
//! #[dae_model(scene = recursive)]
//! fn ur5() {
//!     urdf("tests/robots/ur5.urdf");
//!     gravity(vec3(0.0, 0.0, -9.81));
//! }
//!
//! let sol = Ur5::default().simulate(0.0, 0.2, &Options::new().tolerance(1e-8))?;
//! // The file's names: each joint's coordinate, each link's position.
//! let elbow: f64 = sol.last("elbow_joint.q")?;
//! let hand: f64 = sol.last("wrist_3_link.z")?;
//! assert!(elbow.is_finite() && hand.is_finite());
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! - **Joints**: revolute and continuous become `revolute` (`j.q`, the
//!   angle from the file's zero configuration), prismatic `prismatic`,
//!   planar `planar`. A fixed joint welds its child into its parent's body,
//!   their masses, centres and inertia tensors combined; a floating joint
//!   holds only the root. The root link is welded to the ground (the mass
//!   welded to it then has no effect), or, with
//!   `urdf("path").floating()`, is a body on a free joint named after the
//!   root link (`base_link.x` … `base_link.q3`, `base_link.wx` …).
//! - **Inertia**: each link's `<inertial>` (origin, mass, the full tensor).
//!   Visuals, collisions and meshes are ignored.
//! - **Names**: each moving link's pose and velocity read as a body's
//!   (`wrist_3_link.x`, `.q0`, `.wx`, …), each joint's coordinate as
//!   `elbow_joint.q`; the joints are numbered as Pinocchio numbers them. A
//!   link the file welds to a moving one (a tool flange, a foot) is its
//!   origin's position, a 3-vector: `let tip = output(tool0[2]);`.
//! - **Damping**: a joint's `<dynamics damping>` is a viscous damper across
//!   it, `<joint>_damping` (the standard library's `damper` or
//!   `translational_damper` on the joint's flange); its Coulomb `friction`
//!   is read and left out. A motor or a controller drives a joint the same
//!   way, through `elbow_joint.flange` (the example `robot_arm`), and a
//!   torque from outside is an input through `signal_torque`:
//!   `let tau = input(0.0); let drive = signal_torque();
//!   connect(drive.flange, elbow_joint.flange); drive.u == tau;`.
//! - **Start**: the zero configuration at rest, or the joint positions
//!   and rates given by `init(elbow_joint.q, -1.2)` and
//!   `init(der(elbow_joint.q), 0.5)`.
//! - **Mistakes** in the file are compile errors on the path that quote
//!   the file and line: `arm.urdf:18: joint `elbow` has type "ball"; a
//!   URDF joint is revolute, continuous, prismatic, fixed, floating or
//!   planar`, a link with two parents, a loop, a joint that moves no mass.
//!
//! The equations of motion of a tree are written in each body's own frame
//! (centre of mass, body axes), as robotics libraries compute them: the
//! mass matrix by the composite-rigid-body algorithm, the bias forces by
//! recursive Newton–Euler with gravity as the ground's acceleration, and
//! the accelerations through the mass matrix's factorisation along the
//! tree (no fill-in, no pivoting), all as expressions, so the joint
//! accelerations come out explicit and every method runs them without a
//! solve. A scene with a loop, a universal or a planar joint keeps the
//! world-axes form with a run-time solve.
//!
//! The bodies are Pinocchio's: on example-robot-data's UR5, Panda, Solo 12
//! and TALOS the placements, masses, centres and inertias agree to 1e-14,
//! in Pinocchio's order of the joints. The joint accelerations equal
//! Pinocchio's M⁻¹(τ − nle − D q̇) to 1e-14 on UR5, Panda, Solo 12 on its
//! floating base, the TALOS arm and the 32-joint TALOS on a fixed base
//! (`tests/robots.rs`, `codegen/tests/urdf.rs`). One evaluation takes
//! 0.05–0.31× the time of Pinocchio's `aba` (bench `--robots`). The
//! generated code grows with the tree: 0.1 MB for UR5 (6 joints), 0.4 MB
//! for Panda (9), 1.3 MB for TALOS (32), which a release build compiles in
//! 8 s; over half of it is the Taylor tape, which
//! `#[dae_model(taylor = 0)]` leaves out where no Taylor method runs.
//!
//! The rotations of the course notes (`rot_x`, `euler_313`, `bryan_123`,
//! `rot_seq("zyx", ..)`, `axis_angle`, `quat_to_rot`, `omega_seq`,
//! `omega_quat`, `planar_frame`, `natural_frame`) exist in the model
//! language and numerically in [`crate::runtime::kinematics`].
