//! Diagnostics of the front end, tested without compiling a macro: each bad
//! model yields the expected messages, all of them at once.

use daegen_codegen::diagnostics;
use daegen_codegen::expand_dae_model;
use quote::quote;

fn messages(item: proc_macro2::TokenStream) -> Vec<String> {
    diagnostics(item)
}

#[test]
fn every_mistake_is_reported_in_one_expansion() {
    let m = messages(quote! {
        fn model() {
                        let gain = param(1.0);
            let x = state(1.0);
            der(x) == -gaim * x + sine(x);
            let s = x.cos();
            for i in 0..gain { }
        }
    });
    assert_eq!(m.len(), 4, "{m:#?}");
    assert!(m[0].contains("unknown name `gaim`; did you mean `gain`?"));
    assert!(m[1].contains("unknown function `sine`; did you mean `sin`?"));
    assert!(m[2].contains("write `cos(x)`"));
    assert!(m[3].contains("`gain` is a parameter"));
}

/// Each model's diagnostics include its expected message.
fn assert_each_reports(cases: &[(proc_macro2::TokenStream, &str)]) {
    for (model, expected) in cases {
        let m = messages(model.clone());
        assert!(m.iter().any(|s| s.contains(expected)), "{model}\n→ {m:#?}\nexpected `{expected}`");
    }
}

#[test]
fn structural_mistakes_name_the_derivative() {
    let cases: [(proc_macro2::TokenStream, &str); 7] = [
        (
            quote! { fn m() { let x = state(1.0); let v = state(0.0); der(x) == x; } },
            "state `v` has no equation",
        ),
        (
            quote! { fn m() { let x = state(1.0); der(x) == -x; der(x) == x; } },
            "`der(x)` already has an equation",
        ),
        (
            quote! { fn m() { let x = state(1.0); let y = state(1.0); der(x) + der(y) == x; } },
            "nothing determines `der(y)`: `der(x) + der(y) == x` is left for 2 unknowns",
        ),
        (quote! { fn m() { let x = state(1.0); der(x) * der(x) == x; } }, "not linear in `der(x)`"),
        (
            // Twice the same equation: their combination free of the
            // derivatives vanishes identically.
            quote! { fn m() { let x = state(1.0); let y = state(1.0); der(x) + der(y) == x; 2.0 * der(x) + 2.0 * der(y) == 2.0 * x; } },
            "is a combination of `2.0 * der(x) + 2.0 * der(y) == 2.0 * x`: it adds nothing",
        ),
        (
            quote! { fn m() { let x = state(1.0); init(der(x), 1.0); der(x) == x; } },
            "`der(x)` follows from its equation",
        ),
        (quote! { fn m() { let x = state(1.0); der(x) == x; x == 2.0; } }, "algebraic"),
    ];
    assert_each_reports(&cases);
}

#[test]
fn language_mistakes_say_how_to_fix_them() {
    let cases: [(proc_macro2::TokenStream, &str); 11] = [
        (
            quote! { fn m() { let k = param(1.0); let x = state(1.0); der(x) == der(k); } },
            "`k` is a parameter",
        ),
        (
            quote! { fn m() { let x = state(1.0); der(x) == der(x * x); } },
            "`x * x` is an expression",
        ),
        (
            quote! { fn m() { let x = state(1.0); der(x) == atan2(x); } },
            "`atan2` takes 2 arguments, not 1",
        ),
        (
            quote! { fn m() { let m = param(1.0); let m = state(1.0); der(m) == 1.0; } },
            "`m` is already declared as a parameter",
        ),
        (quote! { fn m() { let x = state(1.0); der(x) == 1e400; } }, "not a finite f64"),
        (
            quote! { fn m() { let x = state(1.0); der(x) == ln(0.0); } },
            "`ln(0)` has no finite value",
        ),
        (
            quote! { fn m() { let x = state(1.0); x = 2.0; der(x) == 1.0; } },
            "cannot assign to `x`, a state",
        ),
        (
            quote! { fn m() { let q = state_array([1.0, 2.0]); der(q[2]) == 1.0; } },
            "index 2 is out of bounds",
        ),
        (
            quote! { fn m() { let q = state_array([1.0, 2.0]); der(q) == 1.0; } },
            "`q` is an array of states",
        ),
        (
            quote! { fn m(a: f64) { let x = state(1.0); der(x) == a; } },
            "a model takes no arguments",
        ),
        (
            quote! { fn m() { let x = state(1.0); der(x) == 1 / 3 * x; } },
            "`1 / 3` divides whole numbers, which Rust truncates to 0: write `1.0 / 3.0`",
        ),
    ];
    assert_each_reports(&cases);
}

#[test]
fn a_model_with_errors_still_expands_to_its_type() {
    let tokens = expand_dae_model(
        proc_macro2::TokenStream::new(),
        quote! { fn decay() { let k = param(0.5); let x = state(1.0); der(x) == -k * y; } },
    );
    let text = tokens.to_string();
    assert!(text.contains("compile_error"));
    assert!(text.contains("struct Decay"), "the stub keeps the type so user code type-checks");
    assert!(text.contains("pub k : f64"));
    assert!(syn::parse2::<syn::File>(tokens).is_ok());
}

#[test]
fn good_models_have_no_diagnostics() {
    let m = messages(quote! {
        fn model() {
            const N: usize = 4;
            let t = time();
            let k = param(2.0);
            let q = state_array([0.0; N]);
            for i in 0..N {
                let mut force = -k * q[i];
                if i > 0 { force += q[i - 1] - q[i]; }
                if i + 1 < N { force += q[i + 1] - q[i]; }
                der(der(q[i])) == force + sin(t) / (1.0 + (i as f64));
            }
            init(der(q[0]), 1.0);
        }
    });
    assert!(m.is_empty(), "{m:#?}");
}

#[test]
fn a_remainder_takes_whole_number_constants() {
    let m = messages(quote! {
        fn model() {
            let x = state(1.0);
            der(x) == x % 2.0;
        }
    });
    assert!(m.iter().any(|s| s.contains("`%` takes whole-number constants")), "{m:#?}");
    let m = messages(quote! {
        fn model() {
            const N: usize = 3;
            let q = state_array([0.0; N]);
            for i in 0..N { der(q[i]) == q[(i + 1) % N] - q[(i + N - 1) % N]; }
            let bad = q[(1 + 1) % 0];
        }
    });
    assert_eq!(m.len(), 1, "{m:#?}");
    assert!(m[0].contains("the right one positive"), "{m:#?}");
}

#[test]
fn initial_values_by_index_take_a_range_and_a_closure_of_constants() {
    let cases: [(proc_macro2::TokenStream, &str); 3] = [
        (
            quote! { fn m() { let q = state_array((0..3).map(|i, j| 1.0)); der(q[0]) == 1.0; } },
            "`(0..N).map(|i| 1.0 + 0.1 * (i as f64))`",
        ),
        (
            quote! { fn m() { let q = state_array(vec.map(|i| 1.0)); der(q[0]) == 1.0; } },
            "`(0..N).map(|i| 1.0 + 0.1 * (i as f64))`",
        ),
        (
            quote! { fn m() { let x = state(1.0); let q = state_array((0..2).map(|i| x)); der(x) == 1.0; } },
            "an initial value may use constants and parameters, not `x`",
        ),
    ];
    assert_each_reports(&cases);
}

/// `x' + y' = x, 2x' + 2y' = y` has dependent derivative rows but a regular
/// pencil (det(E s + A) = 1 − 3s): an index-1 DAE, not a mistake.
#[test]
fn dependent_derivative_rows_with_a_regular_pencil_are_a_dae() {
    let m = messages(quote! {
        fn m() { let x = state(1.0); let y = state(1.0); der(x) + der(y) == x; 2.0 * der(x) + 2.0 * der(y) == y; }
    });
    assert!(m.is_empty(), "{m:#?}");
}

/// The model `name` of `tests/ui/newcomer_drive.rs`, whose compiler output
/// trybuild pins: the same models, checked here message by message.
fn newcomer_model(name: &str) -> syn::ItemFn {
    let file = syn::parse_file(include_str!("../../tests/ui/newcomer_drive.rs"))
        .expect("the newcomer's models parse");
    let found = file.items.into_iter().find_map(|item| match item {
        syn::Item::Fn(f) if f.sig.ident == name => Some(f),
        _ => None,
    });
    found.unwrap_or_else(|| panic!("no model `{name}` in tests/ui/newcomer_drive.rs"))
}

/// The newcomer's speed drive, its set point left open, with `extra`
/// statements added.
fn drive_with(extra: proc_macro2::TokenStream) -> proc_macro2::TokenStream {
    let mut model = newcomer_model("set_point_left_open");
    let extra: syn::Block = syn::parse2(quote!({ #extra })).expect("the statements parse");
    model.block.stmts.extend(extra.stmts);
    model.attrs.clear();
    quote!(#model)
}

#[test]
fn an_input_is_connected_or_set() {
    let open = messages(drive_with(quote!()));
    assert_eq!(open.len(), 1, "{open:#?}");
    assert!(open[0].starts_with("the input `u_s` of `controller` is not connected"), "{open:#?}");
    // Set by an equation, or connected: nothing to say.
    assert_eq!(messages(drive_with(quote!(controller.u_s == 100.0;))), Vec::<String>::new());
    let connected = drive_with(
        quote! { let set_point = constant(100.0); connect(set_point.y, controller.u_s); },
    );
    assert_eq!(messages(connected), Vec::<String>::new());
}

#[test]
fn a_block_s_open_input_says_how_to_connect_or_set_it() {
    let m = messages(quote! {
        fn m() {
            let g = gain(3.0);
            let x = integrator();
            connect(g.y, x.u);
        }
    });
    assert_eq!(m, ["the input `u` of `g` is not connected: connect an output to it, `connect(source.y, g.u);`, or set it, `g.u == 1.0;`"]);
}

#[test]
fn a_misspelt_parameter_is_one_message() {
    let mut model = newcomer_model("misspelt_parameter");
    model.attrs.clear();
    let m = messages(quote!(#model));
    assert_eq!(m, ["`inertia` has no parameter `jj`; its parameters are `j`, `phi0`, `w0`"]);
}
