// The slider-crank of the course notes (Figure 4.7) as a planar scene,
// shared by the scene tests, the drives of parts (tests/models/drives.rs)
// and the FMU tests and examples (`#[path]`).

// Already in scope where the file is `include!`d.
#[allow(unused_imports)]
use daegen::prelude::*;

/// `slider_crank_scene!([pub] name, (attributes), crank: (pose[, velocity]),
/// slider: (pose[, velocity]), { statements })`: the slider-crank as a
/// scene (crank r = 0.15 of mass m1 = 1 about the origin, a massless rod
/// l = 0.4 to the slider of mass m2 = 0.5 on the x axis, gravity g), the
/// pivot `pivot` and the rod `rod`, started from the given body poses,
/// followed by `statements`.
#[allow(unused_macros)]
macro_rules! slider_crank_scene {
    ($vis:vis $name:ident, ($($attr:tt)*), crank: ($($crank:tt)*), slider: ($($slider:tt)*),
     { $($statements:tt)* }) => {
        /// A slider-crank mechanism as a scene: a crank on a revolute joint to
        /// the ground, a rod of fixed length to a slider on a horizontal
        /// prismatic joint, under gravity.
        #[dae_model($($attr)*)]
        $vis fn $name() {
            /// Crank length (m).
            let r = param(0.15);
            /// Rod length (m).
            let l = param(0.4);
            /// Crank mass (kg).
            let m1 = param(1.0);
            /// Slider mass (kg).
            let m2 = param(0.5);
            /// Gravity (m/s²).
            let g = param(9.81);
            let ground = ground();
            let crank = body(m1, m1 * r * r / 12.0, $($crank)*);
            let slider = body(m2, 1.0, $($slider)*);
            let pivot = revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
            let rod = distance(crank, vec3(0.5 * r, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), l);
            prismatic(ground, vec3(0.0, 0.0, 0.0), slider, vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0));
            gravity(vec3(0.0, -g, 0.0));
            $($statements)*
        }
    };
}

// Falling from rough guesses of the body poses: consistent initialization
// closes the joints.
slider_crank_scene!(pub slider_crank_scene, (), crank: ([0.04, 0.06, 1.0]), slider: ([0.45, 0.0, 0.0]), {
    let pin = position(crank, vec3(0.5 * r, 0.0, 0.0));
    /// The crank pin's horizontal position (m).
    let pin_x = output(pin[0]);
});
