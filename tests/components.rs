//! Components and connectors: circuits, drives and thermal networks built
//! from the standard library and from the user's components, each checked
//! against an exact solution or the same physics written flat.

use daegen::prelude::*;

/// RC charging: a 10 V source through R = 100 Ω into C = 1 mF.
#[dae_model]
fn rc_charging() {
    let source = constant_voltage(10.0);
    let r1 = resistor(100.0);
    let c1 = capacitor(1e-3);
    let gnd = ground();
    connect(source.p, r1.p);
    connect(r1.n, c1.p);
    connect(c1.n, source.n, gnd.p);
}

#[test]
fn rc_charging_follows_the_exponential() {
    let model = RcCharging::default();
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = model.simulate(0.0, 0.5, &opts).unwrap();
    let tau: f64 = 100.0 * 1e-3;
    for &t in &[0.05f64, 0.1, 0.3, 0.5] {
        let exact = 10.0 * (1.0 - (-t / tau).exp());
        let v: f64 = sol.at(t, "c1.v").unwrap();
        assert!((v - exact).abs() < 1e-7, "t = {t}: {v} vs {exact}");
        let i: f64 = sol.at(t, "r1.i").unwrap();
        assert!((i - (10.0 - exact) / 100.0).abs() < 1e-9, "t = {t}: i = {i}");
    }
    println!("{}", model.describe());
}
