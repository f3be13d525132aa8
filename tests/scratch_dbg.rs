use daegen::prelude::*;
include!("models/stiff.rs");
robertson_rates_model!(sensitivities = [k1, k2, k3]);
#[test]
fn dbg() {
    for tol in [1e-6, 1e-9] {
        let o = Options::new().method(Method::Radau5).rtol(tol).atol(tol * 1e-6);
        let a = RobertsonRates::default().simulate(0.0, 1e5, &o).unwrap();
        let b = RobertsonRates::default().with_sensitivities().simulate(0.0, 1e5, &o).unwrap();
        println!("{tol}: alone {:?}\n with {:?}", a.stats(), b.stats());
    }
}
