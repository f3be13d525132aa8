// A chain of ten uniform rods (mass 1, length 1) hanging from the ground,
// released horizontal: the scene shared by the scene tests and the
// benchmark, in either formulation.

/// `rod_chain_model!(name, attributes)`.
#[allow(unused_macros)]
macro_rules! rod_chain_model {
    ($name:ident, $($attr:tt)*) => {
        /// Ten rods on revolute joints: 30 coordinates and 20 constraint
        /// rows in body coordinates, 10 joint angles in the recursive.
        #[dae_model($($attr)*)]
        fn $name() {
            let g = param(9.81);
            let ground = ground();
            let rod0 = body(1.0, 1.0 / 12.0, [0.5, 0.0, 0.0]);
            let rod1 = body(1.0, 1.0 / 12.0, [1.5, 0.0, 0.0]);
            let rod2 = body(1.0, 1.0 / 12.0, [2.5, 0.0, 0.0]);
            let rod3 = body(1.0, 1.0 / 12.0, [3.5, 0.0, 0.0]);
            let rod4 = body(1.0, 1.0 / 12.0, [4.5, 0.0, 0.0]);
            let rod5 = body(1.0, 1.0 / 12.0, [5.5, 0.0, 0.0]);
            let rod6 = body(1.0, 1.0 / 12.0, [6.5, 0.0, 0.0]);
            let rod7 = body(1.0, 1.0 / 12.0, [7.5, 0.0, 0.0]);
            let rod8 = body(1.0, 1.0 / 12.0, [8.5, 0.0, 0.0]);
            let rod9 = body(1.0, 1.0 / 12.0, [9.5, 0.0, 0.0]);
            revolute(ground, vec3(0.0, 0.0, 0.0), rod0, vec3(-0.5, 0.0, 0.0));
            revolute(rod0, vec3(0.5, 0.0, 0.0), rod1, vec3(-0.5, 0.0, 0.0));
            revolute(rod1, vec3(0.5, 0.0, 0.0), rod2, vec3(-0.5, 0.0, 0.0));
            revolute(rod2, vec3(0.5, 0.0, 0.0), rod3, vec3(-0.5, 0.0, 0.0));
            revolute(rod3, vec3(0.5, 0.0, 0.0), rod4, vec3(-0.5, 0.0, 0.0));
            revolute(rod4, vec3(0.5, 0.0, 0.0), rod5, vec3(-0.5, 0.0, 0.0));
            revolute(rod5, vec3(0.5, 0.0, 0.0), rod6, vec3(-0.5, 0.0, 0.0));
            revolute(rod6, vec3(0.5, 0.0, 0.0), rod7, vec3(-0.5, 0.0, 0.0));
            revolute(rod7, vec3(0.5, 0.0, 0.0), rod8, vec3(-0.5, 0.0, 0.0));
            revolute(rod8, vec3(0.5, 0.0, 0.0), rod9, vec3(-0.5, 0.0, 0.0));
            gravity(vec3(0.0, -g, 0.0));
            let tip = position(rod9, vec3(0.5, 0.0, 0.0));
            let tip_x = output(tip[0]);
            let tip_y = output(tip[1]);
        }
    };
}
