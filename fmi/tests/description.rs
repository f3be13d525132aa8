//! The model descriptions of generated models, FMI 2.0 and 3.0: the
//! variables by value reference, the derivatives and their dependencies
//! from the Jacobian's pattern.

use daegen::prelude::*;
use daegen_fmi::description::Capabilities;
use daegen_fmi::{model_description, FmiVersion};

/// Van der Pol's oscillator.
#[dae_model]
fn van_der_pol() {
    /// Damping.
    let mu = param(1.0);
    /// Position.
    let x = state(2.0);
    init(der(x), 0.0);
    der(der(x)) == mu * (1.0 - x * x) * der(x) - x;
    /// Energy-like.
    let energy = output(x * x + der(x) * der(x));
}

#[test]
fn fmi2_numbers_variables_by_position_and_the_structure_follows_the_jacobian() {
    let xml = model_description(
        &VanDerPol::default(),
        FmiVersion::V2,
        "van_der_pol",
        Capabilities::default(),
    );
    assert!(xml.contains("fmiVersion=\"2.0\" modelName=\"VanDerPol\" guid=\"{"), "{xml}");
    assert!(xml.contains("numberOfEventIndicators=\"0\""));
    // time, x, der(x), der(x,2), mu, energy.
    for (k, name) in ["time", "x", "der(x)", "der(x,2)", "mu", "energy"].iter().enumerate() {
        assert!(xml.contains(&format!("name=\"{name}\" valueReference=\"{k}\"")), "{name}: {xml}");
    }
    assert!(xml.contains("name=\"x\" valueReference=\"1\" causality=\"local\" variability=\"continuous\" initial=\"exact\" description=\"Position.\"><Real start=\"2.0\"/>"), "{xml}");
    // der(x) is x's derivative (position 2) and a state; der(x,2) is its.
    assert!(xml.contains("<Real start=\"0.0\" derivative=\"2\"/>"), "{xml}");
    assert!(xml.contains("<Real derivative=\"3\"/>"), "{xml}");
    assert!(xml.contains("name=\"mu\" valueReference=\"4\" causality=\"parameter\" variability=\"tunable\" description=\"Damping.\"><Real start=\"1.0\"/>"), "{xml}");
    // x' = der(x) reads der(x); der(x)' reads x and der(x).
    assert!(xml.contains("<Derivatives>\n      <Unknown index=\"3\" dependencies=\"3\"/>\n      <Unknown index=\"4\" dependencies=\"2 3\"/>\n    </Derivatives>"), "{xml}");
    assert!(xml.contains("<Outputs>\n      <Unknown index=\"6\"/>\n    </Outputs>"), "{xml}");
    assert!(xml.contains("<InitialUnknowns>\n      <Unknown index=\"4\"/>\n      <Unknown index=\"6\"/>\n    </InitialUnknowns>"), "{xml}");
}

#[test]
fn fmi3_refers_by_value_reference_and_the_token_changes_with_the_model() {
    let xml = model_description(
        &VanDerPol::default(),
        FmiVersion::V3,
        "van_der_pol",
        Capabilities::default(),
    );
    assert!(xml.contains("fmiVersion=\"3.0\" modelName=\"VanDerPol\" instantiationToken=\"{"));
    assert!(xml.contains("<Float64 name=\"der(x,2)\" valueReference=\"3\" causality=\"local\" variability=\"continuous\" initial=\"calculated\" description=\"the rate of `der(x)`\" derivative=\"2\"/>"), "{xml}");
    assert!(
        xml.contains("<ContinuousStateDerivative valueReference=\"3\" dependencies=\"1 2\"/>"),
        "{xml}"
    );
    assert!(xml.contains("<Output valueReference=\"5\"/>"));
    let other = VanDerPol { mu: 2.0 };
    let changed = model_description(&other, FmiVersion::V3, "van_der_pol", Capabilities::default());
    let token = |x: &str| x.split("instantiationToken=\"").nth(1).map(|t| t[..38].to_string());
    assert_ne!(token(&xml), token(&changed));
}

// A ball that bounces: an event function (an event indicator), a
// derivative kept as a state.
#[path = "../examples/models/bouncing_ball.rs"]
mod bouncing_ball;
use bouncing_ball::BouncingBall;

#[test]
fn the_descriptions_of_a_bouncing_ball() {
    use daegen_fmi::description::Capabilities;
    let ball = BouncingBall::default();
    insta::assert_snapshot!(
        "fmi3_bouncing_ball",
        model_description(&ball, FmiVersion::V3, "ball", Capabilities::EXPORTED)
    );
    insta::assert_snapshot!(
        "fmi2_bouncing_ball",
        model_description(&ball, FmiVersion::V2, "ball", Capabilities::EXPORTED)
    );
}

/// A flywheel on a torsion spring, of library parts: the structure
/// eliminates the spring's angle and the flanges' variables, which stay
/// readable by name.
#[dae_model]
fn torsion() {
    let rotor = inertia(j = 2.0, phi0 = 1.0);
    let spring = spring(c = 8.0);
    let housing = fixed();
    connect(rotor.flange_a, spring.flange_a);
    connect(spring.flange_b, housing.flange);
    /// The spring's energy (J).
    let energy = output(4.0 * spring.phi_rel * spring.phi_rel);
}

#[test]
fn only_the_model_s_own_outputs_are_outputs() {
    let xml =
        model_description(&Torsion::default(), FmiVersion::V3, "torsion", Capabilities::EXPORTED);
    let causality = |name: &str| {
        let at = xml.find(&format!("name=\"{name}\"")).unwrap_or_else(|| panic!("{name}: {xml}"));
        xml[at..].split("causality=\"").nth(1).unwrap().split('"').next().unwrap().to_string()
    };
    assert_eq!(causality("energy"), "output");
    for eliminated in ["spring.phi_rel", "spring.tau", "rotor.flange_a.tau", "housing.flange.tau"] {
        assert_eq!(causality(eliminated), "local", "{eliminated}");
    }
    insta::assert_snapshot!("fmi3_torsion", xml);
    insta::assert_snapshot!(
        "fmi2_torsion",
        model_description(&Torsion::default(), FmiVersion::V2, "torsion", Capabilities::EXPORTED)
    );
}
