//! Snapshots of the generated code of small models, one per generated
//! item (`rhs`, `jacobian`, the Taylor jet, the constraints, …), each
//! formatted alone with prettyplease and short enough to review: every
//! change to what a model expands to is read here.

use daegen::codegen::expand_dae_model;
use quote::quote;
use std::collections::BTreeMap;

include!("models/items.rs");

/// The longest snapshot a reviewer is asked to read.
const MAX_LINES: usize = 80;

/// The whole expansion as text, for tests that search it.
fn expand_with(attr: proc_macro2::TokenStream, item: proc_macro2::TokenStream) -> String {
    prettyplease::unparse(&parsed(attr, item))
}

fn parsed(attr: proc_macro2::TokenStream, item: proc_macro2::TokenStream) -> syn::File {
    let tokens = expand_dae_model(attr, item);
    match syn::parse2::<syn::File>(tokens.clone()) {
        Ok(file) => file,
        Err(e) => panic!("expansion does not parse: {e}\n{tokens}"),
    }
}

/// Each generated item, formatted alone, by `Type::item`: the methods and
/// constants of every `impl` (the `Model` implementation, the mass-matrix
/// form's, inherent ones), and each struct by its name.
fn items(
    attr: proc_macro2::TokenStream,
    item: proc_macro2::TokenStream,
) -> BTreeMap<String, String> {
    let file = parsed(attr, item);
    let alone = |item: syn::Item| {
        prettyplease::unparse(&syn::File { shebang: None, attrs: Vec::new(), items: vec![item] })
    };
    let mut out = BTreeMap::new();
    for item in &file.items {
        match item {
            syn::Item::Struct(s) => {
                out.insert(s.ident.to_string(), alone(item.clone()));
            }
            syn::Item::Impl(i) => {
                let ty = match &*i.self_ty {
                    syn::Type::Path(p) => p.path.segments.last().map(|s| s.ident.to_string()),
                    _ => None,
                }
                .unwrap_or_default();
                for member in &i.items {
                    let name = match member {
                        syn::ImplItem::Fn(f) => f.sig.ident.to_string(),
                        syn::ImplItem::Const(c) => c.ident.to_string(),
                        syn::ImplItem::Type(t) => t.ident.to_string(),
                        _ => continue,
                    };
                    // The item alone, without the impl's lint attributes.
                    let mut one = i.clone();
                    one.attrs.clear();
                    one.items = vec![member.clone()];
                    out.insert(format!("{ty}::{name}"), alone(syn::Item::Impl(one)));
                }
            }
            _ => {}
        }
    }
    out
}

/// Snapshots the items `keys` of a model's expansion, each at most
/// `MAX_LINES` long, as `{test}__{Type}__{item}`.
fn snapshot(test: &str, items: &BTreeMap<String, String>, keys: &[&str]) {
    for key in keys {
        let Some(text) = items.get(*key) else {
            panic!("no item `{key}`; there are {:?}", items.keys().collect::<Vec<_>>());
        };
        let lines = text.lines().count();
        assert!(lines <= MAX_LINES, "`{key}` is {lines} lines: snapshot a smaller model");
        let name = format!("{test}__{}", key.replace("::", "__"));
        insta::assert_snapshot!(name.as_str(), text);
    }
}

/// A test that expands a model (with the attribute's arguments in
/// parentheses) and snapshots the items named.
macro_rules! expansion_test {
    ($(#[$doc:meta])* $test:ident, ($($attr:tt)*), [$($key:literal),*], $($model:tt)*) => {
        $(#[$doc])*
        #[test]
        fn $test() {
            let items = items(quote!($($attr)*), quote!($($model)*));
            snapshot(stringify!($test), &items, &[$($key),*]);
        }
    };
}

expansion_test! {
    pendulum_in_its_angle, (), ["Pendulum::rhs", "Pendulum::jacobian", "Pendulum::output", "Pendulum::INFO"],
    /// Planar pendulum in its angle: the contract's pendulum as an ODE.
    fn pendulum() {
        /// Length (m).
        let l = param(1.0);
        /// Gravity (m/s²).
        let g = param(9.81);
        let theta = state(1.0);
        init(der(theta), 0.0);
        der(der(theta)) == -g / l * sin(theta);
        /// Energy per unit mass (J/kg).
        let energy = output(0.5 * l * l * der(theta) * der(theta) - g * l * cos(theta));
    }
}

expansion_test! {
    harmonic_oscillator_with_second_derivative, (), ["Oscillator::rhs", "Oscillator::taylor_tape"],
    fn oscillator() {
        let omega = param(2.0);
        let x = state(1.0);
        der(der(x)) == -omega.powi(2) * x;
    }
}

example_1_1!(expansion_test! {
    example_1_1_third_order_system, (), ["Example11::rhs", "Example11::initial_state", "Example11::time_derivative"],
});

include!("models/n_body.rs");

gravitating_bodies!(@then expansion_test {
    three_body_with_state_arrays_and_loops, (), ["ThreeBody::rhs", "ThreeBody::JACOBIAN"],
} fn three_body(planar) {
    const N: usize = 3;
    let g = param(1.0);
    let m = [1.0; N];
    let x = state_array([1.0, -0.5, -0.5]);
    let y = state_array([0.0, 0.8660254037844386, -0.8660254037844386]);
    let u = state_array([0.0; N]);
    let v = state_array([0.0; N]);
});

double_pendulum_angles!(expansion_test! {
    double_pendulum_with_a_mass_matrix_solved_symbolically, (), ["DoublePendulum::rhs", "DoublePendulum::jacobian"],
} {});

expansion_test! {
    /// A chain of ten cells: the eight inner cells' right-hand sides differ
    /// only in the states they read and are written by one loop over a
    /// table of indices (the two ends stay straight-line code); so are the
    /// Jacobian's diagonal and its 18 entries equal to the diffusion
    /// coefficient; ∂f/∂t, zero everywhere, is one `fill`.
    heat_chain_with_repeated_jacobian_entries, (), ["HeatChain::rhs", "HeatChain::jacobian", "HeatChain::time_derivative"],
    fn heat_chain() {
        const N: usize = 10;
        let c = param(4.0);
        let u = state_array([1.0; N]);
        for i in 0..N {
            let left = if i == 0 { 0.0 } else { u[i - 1] };
            let right = if i + 1 == N { 0.0 } else { u[i + 1] };
            der(u[i]) == c * (left - 2.0 * u[i] + right) - u[i] * u[i];
        }
    }
}

expansion_test! {
    /// y′ = −k·y with its sensitivities to k and to y(0): S′ = −k·S − y
    /// and S′ = −k·S, from S(0) = 0 and 1.
    decay_with_sensitivities, (sensitivities = [k, init(y)]), ["DecaySensitivities::rhs", "DecaySensitivities::own_rhs", "DecaySensitivities::initial_state", "Decay::with_sensitivities"],
    fn decay() {
        let k = param(0.7);
        let y = state(2.0);
        der(y) == -k * y;
    }
}

include!("models/lotka_volterra.rs");

lotka_volterra!(expansion_test! {
    /// Lotka–Volterra with the sensitivities to a: each Jacobian entry
    /// (a − b·y, −b·x, c·y, c·x − d) one row of the Taylor tape, shared with
    /// the right-hand side where it occurs there, times the column.
    lotka_volterra_with_sensitivities_as_a_taylor_tape, (taylor = 1, sensitivities = [a]), ["LotkaVolterraSensitivities::taylor_tape"],
});

// Course notes Example 1.4 with the economic Taylor derivatives of order 4.
example_1_4!(expansion_test! {
    example_1_4_with_taylor_derivatives_of_order_4, (taylor = 4), ["Example14::taylor_derivatives"],
});

#[test]
fn bouncing_ball_with_a_terminal_event() {
    // The event function and its rate along the solution (for crossings
    // hidden between two samples), each emitted once for all events.
    let items = items(
        proc_macro2::TokenStream::new(),
        quote! {
            fn bouncing_ball() {
                let g = param(9.81);
                let height = state(10.0);
                der(der(height)) == -g;
                /// The ball reaches the ground.
                let impact = event(height).falling().terminal();
                let apex = event(der(height) * height);
            }
        },
    );
    snapshot(
        "bouncing_ball_with_a_terminal_event",
        &items,
        &["BouncingBall::events", "BouncingBall::event_rates", "BouncingBall::INFO"],
    );
}

expansion_test! {
    /// The unrolled Taylor recurrences of order 2 for a forced logistic
    /// equation: a product, a sine/cosine pair of the time and a constant, each
    /// coefficient one slot of `r`, one function per order; the negation and
    /// `1 − x` are one folded sum, and `k·x·(1 − x)` is folded into the output
    /// with its weight `k` computed once (`taylor::folding`).
    logistic_with_unrolled_taylor_recurrences_of_order_2, (unroll = [2]), ["ForcedLogistic::taylor_jet_unrolled"],
    fn forced_logistic() {
        let t = time();
        let k = param(2.0);
        let x = state(0.5);
        der(x) == k * x * (1.0 - x) + sin(t);
    }
}

/// Products that differ only by constant factors share one convolution on
/// the Taylor tape: x·y once, then scaled by 2 and by −3.
#[test]
fn taylor_tape_shares_products_that_differ_by_constants() {
    let code = expand_with(
        quote!(taylor = 1),
        quote! {
            fn shared() {
                let x = state(1.0);
                let y = state(2.0);
                der(x) == 2.0 * x * y;
                der(y) == -3.0 * x * y;
            }
        },
    );
    let tape = &code[code.find("fn taylor_tape").expect("a tape")..];
    // The tape names `TapeOp` T and `Operand` O.
    let products = tape.matches("T::Mul(").count();
    let convolutions = tape.matches("T::Mul(O::State(0)").count();
    assert_eq!((products, convolutions), (3, 1), "{tape}");
}

/// The two bodies' forces use x2 − x1 and x1 − x2: the tape knows the second
/// is the negation of the first, so the product with r⁻³ is one convolution.
#[test]
fn taylor_tape_shares_a_product_with_a_negated_difference() {
    let code = expand_with(
        quote!(taylor = 1),
        quote! {
            fn two_bodies() {
                let x1 = state(0.0);
                let x2 = state(1.0);
                let v1 = state(0.0);
                let v2 = state(0.0);
                let r3 = ((x2 - x1) * (x2 - x1)).powf(-1.5);
                der(x1) == v1;
                der(x2) == v2;
                der(v1) == (x2 - x1) * r3;
                der(v2) == (x1 - x2) * r3;
            }
        },
    );
    let tape = &code[code.find("fn taylor_tape").expect("a tape")..];
    // The tape names `TapeOp` T.
    let ops: Vec<&str> = tape.split("T::").skip(1).collect();
    // Products of two time-dependent operands (not scalings by a constant).
    let convolutions = ops
        .iter()
        .filter(|op| op.starts_with("Mul(") && !op.split(')').take(2).any(|s| s.contains("Const")))
        .count();
    // (x2 − x1)², and (x2 − x1)·r⁻³ once.
    assert_eq!(convolutions, 2, "{tape}");
}

// The contract's pendulum: index 3, the KKT system solved at run time,
// position and velocity constraints projected onto.
contract_pendulum!(expansion_test! {
    cartesian_pendulum_as_an_index_3_dae, (), ["Pendulum::rhs", "Pendulum::constraints", "Pendulum::constraint_jacobian", "Pendulum::CONSTRAINTS", "PendulumMassForm::rhs"],
});

// The same pendulum with its sensitivities to its length: each constraint
// linearised along the column (Φ_y·S + Φ_l), projected after the model's
// own levels on the column's states.
contract_pendulum!(expansion_test! {
    cartesian_pendulum_with_sensitivities, (sensitivities = [l]), ["PendulumSensitivities::constraints", "PendulumSensitivities::PROJECTION", "PendulumSensitivities::CONSTRAINTS"],
});

double_pendulum_cartesian!(expansion_test! {
    cartesian_double_pendulum_reduces_its_kkt_system_to_the_multipliers, (), ["DoublePendulumCartesian::rhs", "DoublePendulumCartesian::output", "DoublePendulumCartesian::constraints"],
} {});

expansion_test! {
    /// Two products sharing the factor x, once shifted by a constant, at order
    /// 2 (`taylor::factoring`): `(x + 1)·sin y + x·cos y` is written as its heads
    /// `(x + 1)^[0]·sin^[k]` and `x^[0]·cos^[k]` plus one convolution
    /// `Σ_{j≥1} x^[j]·e^[k−j]` on the row `e = sin y + cos y`.
    products_sharing_a_factor_with_unrolled_taylor_recurrences_of_order_2, (unroll = [2]), ["SharedFactor::taylor_jet_unrolled"],
    fn shared_factor() {
        let x = state(0.5);
        let y = state(0.2);
        der(x) == (x + 1.0) * sin(y) + x * cos(y);
        der(y) == -x;
    }
}

expansion_test! {
    /// Two symmetric rows unrolled at order 2, x' = −x s, y' = −y s with
    /// s = x + y (Kepler's shape in first order, without the power): x and y
    /// are a lane pair (`taylor::vector_rows`) — their rows interleaved in `r`,
    /// written side by side and copied to `seeds` for the vectoriser — and the
    /// shared s is one row read by both lanes.
    symmetric_rows_as_a_lane_pair_at_order_2, (unroll = [2]), ["Central::taylor_jet_unrolled"],
    fn central() {
        let x = state(0.5);
        let y = state(0.25);
        der(x) == -x * (x + y);
        der(y) == -y * (x + y);
    }
}

expansion_test! {
    /// A capacitor between two nodes written at both: the rows of the node
    /// equations are opposite, and their sum stands in for the second as an
    /// equation without derivatives (differentiated once: index 1). The
    /// capacitance divides the combination, so a run checks it is not zero
    /// (`degenerate_parameters`); the mass-matrix form keeps the singular
    /// matrix as written (`MassMatrix::Pattern`).
    a_capacitor_between_two_nodes_combines_their_equations, (), ["TwoNodes::rhs", "TwoNodes::degenerate_parameters", "TwoNodes::CONSTRAINTS", "TwoNodesMassForm::mass_values"],
    fn two_nodes() {
        let c = param(1e-6);
        let r = param(1000.0);
        let v1 = state(1.0);
        let v2 = state(0.0);
        c * der(v1) - c * der(v2) == -v1 / r;
        -c * der(v1) + c * der(v2) == -v2 / r + v1 / r;
    }
}

expansion_test! {
    /// An algebraic equation quadratic in its variable: the model solves it by
    /// Newton's method at each evaluation (`__daegen_algebraics`, the residual
    /// and ∂g/∂z generated), and the rest reads z from that solve.
    a_nonlinear_algebraic_equation_is_solved_by_newton, (), ["Quadratic::__daegen_algebraics", "Quadratic::rhs", "Quadratic::output"],
    fn quadratic() {
        let y = state(2.0);
        let z = algebraic(1.0);
        der(y) == -z;
        0.0 == z * z + z - y;
    }
}

expansion_test! {
    lorenz_in_batches_of_four, (batch = 4), ["LorenzBatch::rhs", "LorenzBatch::from_members"],
    /// Lorenz's system, four members a run: the model's own program on
    /// lanes, its constants and time mixed with them.
    fn lorenz() {
        let sigma = param(10.0);
        let rho = param(28.0);
        let beta = param(8.0 / 3.0);
        let x = state(1.0);
        let y = state(0.0);
        let z = state(0.0);
        der(x) == sigma * (y - x);
        der(y) == x * (rho - z) - y;
        der(z) == x * y - beta * z;
    }
}

expansion_test! {
    /// A spatial compound pendulum in joint coordinates: one revolute
    /// joint, its 1 × 1 mass matrix (the inertia about the axis) and its
    /// bias force (gravity's moment) from the composite-rigid-body and
    /// recursive Newton–Euler algorithms.
    spatial_pendulum_in_joint_coordinates, (scene = recursive), ["SwingRecursive::rhs"],
    fn swing_recursive() {
        let g = param(9.81);
        let ground = ground();
        let rod = spatial_body(2.0, vec3(0.1, 0.2, 0.05), [0.0, 0.0, -0.5], [1.0, 0.0, 0.0, 0.0]);
        let hinge = revolute(ground, vec3(0.0, 0.0, 0.0), rod, vec3(0.0, 0.0, 0.5), vec3(1.0, 0.0, 0.0));
        gravity(vec3(0.0, 0.0, -g));
    }
}

expansion_test! {
    /// A bouncing ball counting its bounces, sampled by a clock, driven by
    /// an input: the actions, the clock, the breakpoints.
    hybrid_ball_with_a_clock_and_an_input, (), ["Ball::act", "Ball::clock", "Ball::input_breakpoints", "Ball::rhs"],
    fn ball() {
        let e = param(0.8);
        let period = param(0.5);
        let wind = input(0.0);
        let h = state(1.0);
        let bounces = discrete(0.0);
        let seen = discrete(0.0);
        der(der(h)) == -9.81 + wind;
        let bounce = event(h).falling().reinit(der(h), -e * pre(der(h))).reinit(bounces, bounces + 1.0);
        let look = every(period).offset(0.1).reinit(seen, h);
    }
}
