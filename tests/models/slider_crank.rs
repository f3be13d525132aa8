// The slider-crank of the course notes (Figure 4.7, rigid) as a DAE in
// global coordinates and as its crank-angle ODE, shared by the DAE tests
// and the benchmark.

/// Slider-crank (course notes Figure 4.7, rigid): a crank (uniform rod of
/// mass m1, length r) turning about the origin, a massless connecting rod
/// of length l from the crank pin A to the slider (mass m2) on the x axis,
/// gravity in −y. Global coordinates: the crank's centre (x1, y1) and angle
/// θ1, the slider (xs, ys); joint forces as algebraic variables: the pivot
/// force (fx, fy), the rod's multiplier and the slider's normal force.
#[dae_model]
fn slider_crank() {
    let r = param(0.15);
    let l = param(0.4);
    let m1 = param(1.0);
    let m2 = param(0.5);
    let g = param(9.81);
    // Rough guesses: consistent initialization moves them onto the joints.
    let x1 = state(0.04);
    let y1 = state(0.06);
    let theta1 = state(1.0);
    let xs = state(0.45);
    let ys = state(0.0);
    let fx = algebraic(0.0);
    let fy = algebraic(0.0);
    let rod = algebraic(0.0);
    let normal = algebraic(0.0);
    let xa = x1 + 0.5 * r * cos(theta1);
    let ya = y1 + 0.5 * r * sin(theta1);
    let i1 = m1 * r * r / 12.0;
    // The rod pulls A towards the slider by 2·rod·(S − A), and the slider back.
    let ax = 2.0 * rod * (xs - xa);
    let ay = 2.0 * rod * (ys - ya);
    m1 * der(der(x1)) == fx + ax;
    m1 * der(der(y1)) == fy + ay - m1 * g;
    // Torques about the centre: the pivot force at −r/2, the rod's at +r/2.
    i1 * der(der(theta1))
        == 0.5 * r * (-cos(theta1) * fy + sin(theta1) * fx)
            + 0.5 * r * (cos(theta1) * ay - sin(theta1) * ax);
    m2 * der(der(xs)) == -ax;
    m2 * der(der(ys)) == -ay + normal - m2 * g;
    constraint(x1 - 0.5 * r * cos(theta1));
    constraint(y1 - 0.5 * r * sin(theta1));
    constraint((xs - xa) * (xs - xa) + (ys - ya) * (ys - ya) - l * l);
    constraint(ys);
}

/// The same mechanism in its crank angle φ (Lagrange): with the slider at
/// x_s(φ) = r cos φ + w, w = √(l² − r² sin² φ), f = dx_s/dφ and
/// f' = d²x_s/dφ², the kinetic energy is ½ (m1 r²/3 + m2 f²) φ'² and the
/// potential m1 g (r/2) sin φ, so
/// (m1 r²/3 + m2 f²) φ'' + m2 f f' φ'² + m1 g (r/2) cos φ = 0.
#[dae_model]
fn slider_crank_angle() {
    let r = param(0.15);
    let l = param(0.4);
    let m1 = param(1.0);
    let m2 = param(0.5);
    let g = param(9.81);
    let phi0 = param(1.0);
    let phi = state(phi0);
    init(der(phi), 0.0);
    let s = sin(phi);
    let c = cos(phi);
    let w = sqrt(l * l - r * r * s * s);
    let f = -r * s - r * r * s * c / w;
    let fp = -r * c - r * r * (c * c - s * s) / w - r * r * r * r * s * s * c * c / (w * w * w);
    (m1 * r * r / 3.0 + m2 * f * f) * der(der(phi))
        == -m2 * f * fp * der(phi) * der(phi) - m1 * g * 0.5 * r * c;
}

