// Three spatial scenes shared by the tests of joint coordinates and
// the benchmark, each written once and generated in either formulation:
// a spatial double pendulum, a spatial four-bar (RSSR) loop and a
// seven-joint arm.

/// `spatial_double_pendulum!(name, attributes)`: two links (m = 1, length
/// 1, inertia 0.1, 0.1, 0.02 about the centre, body z along the link) on
/// spherical joints, released from rest tilted a = 0.7 about world x and
/// b = 0.5 about world y, spinning about their own axes at 2 and −3 rad/s
/// (which moves no joint point, so the start is consistent).
#[allow(unused_macros)]
macro_rules! spatial_double_pendulum {
    ($name:ident, $($attr:tt)*) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let g = param(9.81);
            let a = 0.7;
            let b = 0.5;
            let ground = ground();
            let upper = spatial_body(
                1.0,
                vec3(0.1, 0.1, 0.02),
                [0.0, 0.5 * sin(a), -0.5 * cos(a)],
                [cos(a / 2.0), sin(a / 2.0), 0.0, 0.0],
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 2.0],
            );
            let lower = spatial_body(
                1.0,
                vec3(0.1, 0.1, 0.02),
                [-0.5 * sin(b), sin(a), -cos(a) - 0.5 * cos(b)],
                [cos(b / 2.0), 0.0, sin(b / 2.0), 0.0],
                [0.0, 0.0, 0.0],
                [0.0, 0.0, -3.0],
            );
            let shoulder = spherical(ground, vec3(0.0, 0.0, 0.0), upper, vec3(0.0, 0.0, 0.5));
            let elbow = spherical(upper, vec3(0.0, 0.0, -0.5), lower, vec3(0.0, 0.0, 0.5));
            gravity(vec3(0.0, 0.0, -g));
            let tip = position(lower, vec3(0.0, 0.0, -0.5));
            let tip_x = output(tip[0]);
            let tip_y = output(tip[1]);
            let tip_z = output(tip[2]);
        }
    };
}

/// `rssr_loop!(name, attributes)`: a spatial four-bar. A crank (0.3 m)
/// turns about world z at the origin, a rocker (0.4 m) about world x at
/// (0.6, 0.6, 0), standing up; a coupler (√0.61 m) joins the crank's tip
/// (0.3, 0, 0) to the rocker's (0.6, 0.6, 0.4) by spherical joints.
/// Released from rest under gravity along −z with a push of the crank
/// (a torque of 0.5 N·m about z). Two degrees of freedom: the loop's one
/// and the coupler's spin about its own axis.
#[allow(unused_macros)]
macro_rules! rssr_loop {
    ($name:ident, $($attr:tt)*) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let g = param(9.81);
            let ground = ground();
            let crank = spatial_body(0.5, vec3(0.001, 0.004, 0.004), [0.15, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let coupler = spatial_body(1.0, vec3(0.05, 0.05, 0.01), [0.45, 0.3, 0.2], [1.0, 0.0, 0.0, 0.0]);
            let rocker = spatial_body(0.8, vec3(0.011, 0.011, 0.002), [0.6, 0.6, 0.2], [1.0, 0.0, 0.0, 0.0]);
            let hub = revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.15, 0.0, 0.0), vec3(0.0, 0.0, 1.0));
            let wrist = spherical(crank, vec3(0.15, 0.0, 0.0), coupler, vec3(-0.15, -0.3, -0.2));
            let pivot = revolute(ground, vec3(0.6, 0.6, 0.0), rocker, vec3(0.0, 0.0, -0.2), vec3(1.0, 0.0, 0.0));
            let ball = spherical(coupler, vec3(0.15, 0.3, 0.2), rocker, vec3(0.0, 0.0, 0.2));
            gravity(vec3(0.0, 0.0, -g));
            torque(crank, vec3(0.0, 0.0, 0.5));
            let rocker_tip = position(rocker, vec3(0.0, 0.0, 0.2));
            let tip_y = output(rocker_tip[1]);
            let tip_z = output(rocker_tip[2]);
        }
    };
}

/// `seven_joint_arm!(name, attributes)`: seven links (m = 1, 0.3 m along
/// body x, centre 2 cm off the axis along body y, inertia 0.002, 0.008,
/// 0.008) stretched along world x from the origin, on revolute joints
/// about z, y, x, y, x, y, x (a yaw, then alternating pitch and roll, as
/// redundant arms are built), released from rest under a gravity with
/// a sideways part, (1, −2, −9.81).
#[allow(unused_macros)]
macro_rules! seven_joint_arm {
    ($name:ident, $($attr:tt)*) => {
        #[dae_model($($attr)*)]
        fn $name() {
            let ground = ground();
            let j = vec3(0.002, 0.008, 0.008);
            let l1 = spatial_body(1.0, j, [0.15, 0.02, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let l2 = spatial_body(1.0, j, [0.45, 0.02, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let l3 = spatial_body(1.0, j, [0.75, 0.02, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let l4 = spatial_body(1.0, j, [1.05, 0.02, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let l5 = spatial_body(1.0, j, [1.35, 0.02, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let l6 = spatial_body(1.0, j, [1.65, 0.02, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let l7 = spatial_body(1.0, j, [1.95, 0.02, 0.0], [1.0, 0.0, 0.0, 0.0]);
            let base = vec3(-0.15, -0.02, 0.0);
            let end = vec3(0.15, -0.02, 0.0);
            let j1 = revolute(ground, vec3(0.0, 0.0, 0.0), l1, base, vec3(0.0, 0.0, 1.0));
            let j2 = revolute(l1, end, l2, base, vec3(0.0, 1.0, 0.0));
            let j3 = revolute(l2, end, l3, base, vec3(1.0, 0.0, 0.0));
            let j4 = revolute(l3, end, l4, base, vec3(0.0, 1.0, 0.0));
            let j5 = revolute(l4, end, l5, base, vec3(1.0, 0.0, 0.0));
            let j6 = revolute(l5, end, l6, base, vec3(0.0, 1.0, 0.0));
            let j7 = revolute(l6, end, l7, base, vec3(1.0, 0.0, 0.0));
            gravity(vec3(1.0, -2.0, -9.81));
            let hand = position(l7, end);
            let hand_x = output(hand[0]);
            let hand_y = output(hand[1]);
            let hand_z = output(hand[2]);
        }
    };
}
