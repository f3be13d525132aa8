//! The economic Taylor scheme (course notes §1.3.1) through the generated
//! `taylor_derivatives` of `#[dae_model(taylor = p)]`.

use daegen::prelude::*;

include!("models/items.rs");

example_1_4!(dae_model_with! { (taylor = 4) });

#[test]
fn derivatives_are_those_of_the_exact_solution() {
    let x: f64 = 0.7;
    let e = (x * x / 2.0).exp();
    let exact = [
        2.0 * x * e,
        2.0 * (1.0 + x * x) * e,
        2.0 * (3.0 * x + x.powi(3)) * e,
        2.0 * (3.0 + 6.0 * x * x + x.powi(4)) * e,
    ];
    let mut out = [0.0; 4];
    Example14::default().taylor_derivatives(x, &[2.0 * e - 1.0], 4, &mut out).unwrap();
    for (k, (got, want)) in out.iter().zip(exact).enumerate() {
        assert!((got - want).abs() < 1e-13 * want.abs(), "y^({}) = {got}, exact {want}", k + 1);
    }
    assert_eq!(<Example14 as Model>::TAYLOR_ORDER, 4);
}

#[test]
fn the_scheme_of_order_p_converges_with_order_p() {
    let exact = 2.0 * 0.5f64.exp() - 1.0;
    for order in 1..=4 {
        let error = |step: f64| {
            let sol = Example14::default()
                .simulate(0.0, 1.0, &Options::new().method(Method::TaylorFixed { order, step }))
                .unwrap();
            (sol.last("y").unwrap() - exact).abs()
        };
        let rate = (error(1.0 / 40.0) / error(1.0 / 80.0)).log2();
        assert!((rate - order as f64).abs() < 0.15, "order {order}: observed {rate:.3}");
    }
}

/// A second-order state is reduced to the slots x, der(x): their Taylor
/// derivatives must not alias each other. x = cos ωt.
#[dae_model(taylor = 6)]
fn oscillator() {
    let omega = param(3.0);
    let x = state(1.0);
    der(der(x)) == -omega * omega * x;
}

#[test]
fn reduced_higher_order_states_get_their_own_coefficients() {
    let sol = Oscillator::default()
        .simulate(0.0, 2.0, &Options::new().method(Method::TaylorFixed { order: 6, step: 0.01 }))
        .unwrap();
    assert!((sol.last("x").unwrap() - 6f64.cos()).abs() < 1e-10);
    assert!((sol.last("der(x)").unwrap() + 3.0 * 6f64.sin()).abs() < 1e-9);
}

#[test]
fn an_order_above_the_generated_one_is_refused() {
    let err = Example14::default()
        .simulate(0.0, 1.0, &Options::new().method(Method::TaylorFixed { order: 5, step: 0.1 }))
        .unwrap_err();
    assert!(err.to_string().contains("#[dae_model(taylor = 5)]"), "{err}");
}
