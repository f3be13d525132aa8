//! One pass's output on one small model each, printed in the language of
//! its IR and pinned as a snapshot, as cranelift's filetests do: a change
//! to a pass is read here, apart from the generated code.

use daegen_codegen::dae::structure::{structure, Structure};
use daegen_codegen::dae::system::FirstOrder;
use daegen_codegen::front::ctxt::Ctxt;
use daegen_codegen::front::ir::ModelIr;
use daegen_codegen::taylor::analysis::{taylor_analysis, TaylorAnalysis};
use proc_macro2::TokenStream;
use quote::quote;

/// The model `item` lowered with the attribute's arguments `attr`.
fn lowered(cx: &mut Ctxt, attr: TokenStream, item: TokenStream) -> ModelIr {
    let item: syn::ItemFn = syn::parse2(item).expect("a function");
    let attributes = daegen_codegen::front::attributes::attributes(cx, attr);
    let ir = daegen_codegen::pipeline::lower(cx, &item, attributes.recursive, Default::default());
    assert!(cx.is_ok(), "{:?}", cx.messages());
    ir
}

/// The model `name` of a test file of the workspace, its `#[dae_model]`
/// taken off: the passes are pinned on the model the run tests run.
fn model_in(file: &str, name: &str) -> TokenStream {
    let file = syn::parse_file(file).expect("a Rust file");
    let mut model = file
        .items
        .into_iter()
        .find_map(|item| match item {
            syn::Item::Fn(f) if f.sig.ident == name => Some(f),
            _ => None,
        })
        .expect("the model");
    model.attrs.retain(|a| !a.path().is_ident("dae_model"));
    quote::ToTokens::into_token_stream(model)
}

/// The structure and the reduced system of `item`.
fn reduced(item: TokenStream) -> (ModelIr, Structure, FirstOrder) {
    let mut cx = Ctxt::default();
    let mut ir = lowered(&mut cx, TokenStream::new(), item);
    let s = structure(&mut cx, &mut ir).expect("a structure");
    let printed = ir.graph.with(&s).to_string();
    // `reduce` takes the structure; a second, equal one is printed.
    let again = structure(&mut cx, &mut ir).expect("a structure");
    assert_eq!(ir.graph.with(&again).to_string(), printed, "structure is deterministic");
    let sys = daegen_codegen::pipeline::reduction(&mut cx, &mut ir, again).expect("reduced");
    assert!(cx.is_ok(), "{:?}", cx.messages());
    (ir, s, sys)
}

/// The planar pendulum in Cartesian coordinates, index 3 (course notes
/// §2, Hairer–Wanner II §VII.1).
fn pendulum() -> TokenStream {
    quote! {
        fn pendulum() {
            let l = param(1.0);
            let g = param(9.81);
            let x = state(1.0);
            let y = state(0.0);
            let lambda = algebraic(0.0);
            der(der(x)) == -lambda * x;
            der(der(y)) == -lambda * y - g;
            constraint(x * x + y * y - l * l);
        }
    }
}

#[test]
fn lower_unrolls_loops_and_evaluates_constants() {
    let mut cx = Ctxt::default();
    let ir = lowered(
        &mut cx,
        TokenStream::new(),
        quote! {
            fn chain() {
                const N: usize = 3;
                let k = param(2.0);
                let x = state_array([1.0, 0.0, 0.0]);
                der(x[0]) == -k * x[0];
                for i in 1..N {
                    der(x[i]) == k * (x[i - 1] - x[i]);
                }
                let total = output(x[0] + x[1] + x[2]);
                let empty = event(x[0] - 0.5).falling().terminal();
            }
        },
    );
    insta::assert_snapshot!("lower", ir.to_string());
}

#[test]
fn index_reduction_differentiates_the_pendulum_constraint_twice() {
    let (ir, s, _) = reduced(pendulum());
    insta::assert_snapshot!("index_reduction", ir.graph.with(&s).to_string());
}

#[test]
fn reduce_solves_the_pendulum_for_accelerations_and_the_multiplier() {
    let (ir, _, sys) = reduced(pendulum());
    insta::assert_snapshot!("reduce", ir.graph.with(&sys).to_string());
}

#[test]
fn variational_system_of_exponential_decay() {
    let mut cx = Ctxt::default();
    let item = quote! {
        fn decay() {
            let k = param(0.5);
            let x = state(2.0);
            der(x) == -k * x;
        }
    };
    let attr = quote!(sensitivities = [k, init(x)]);
    let mut ir = lowered(&mut cx, attr.clone(), item.clone());
    let attributes = daegen_codegen::front::attributes::attributes(&mut cx, attr);
    let s = structure(&mut cx, &mut ir).expect("a structure");
    let sys = daegen_codegen::pipeline::reduction(&mut cx, &mut ir, s).expect("reduced");
    let wrt =
        daegen_codegen::dae::variational::resolve(&mut cx, &attributes.sensitivities, &ir, &sys);
    assert_eq!(wrt.len(), 2);
    let augmented = daegen_codegen::dae::variational::variational_system(&mut ir.graph, &sys, &wrt)
        .expect("a variational system");
    insta::assert_snapshot!("variational", ir.graph.with(&augmented).to_string());
}

#[test]
fn mass_form_of_the_pendulum_is_the_ggl_index_2_form() {
    let (mut ir, _, sys) = reduced(pendulum());
    let form = daegen_codegen::dae::mass_form::mass_form(&mut ir.graph, &sys)
        .expect("no error")
        .expect("a mass-matrix form");
    insta::assert_snapshot!("mass_form", ir.graph.with(&form).to_string());
}

#[test]
fn taylor_tape_and_economic_derivatives_of_the_pendulum_in_its_angle() {
    let mut cx = Ctxt::default();
    let attr = quote!(taylor = 3);
    let mut ir = lowered(
        &mut cx,
        attr.clone(),
        quote! {
            fn swing() {
                let theta = state(0.5);
                der(der(theta)) == -sin(theta);
            }
        },
    );
    let attributes = daegen_codegen::front::attributes::attributes(&mut cx, attr);
    let s = structure(&mut cx, &mut ir).expect("a structure");
    let sys = daegen_codegen::pipeline::reduction(&mut cx, &mut ir, s).expect("reduced");
    let analysis =
        taylor_analysis(&mut ir.graph, &sys, ir.time, &attributes).expect("a Taylor analysis");
    let TaylorAnalysis::Scheme { economic, tape } = &analysis else {
        panic!("`taylor = 3` asks for the economic scheme and the tape");
    };
    insta::assert_snapshot!("taylor_tape", ir.graph.with(tape).to_string());
    insta::assert_snapshot!("economic_derivatives", ir.graph.with(economic).to_string());
}

#[test]
fn sorting_solves_akzo_nobel_one_equation_at_a_time() {
    // y6 from its algebraic equation first, then each rate with y6 in it.
    let (ir, _, sys) = reduced(quote! {
        fn akzo() {
            let k1 = param(18.7);
            let k4 = param(0.42);
            let ks = param(115.83);
            let y1 = state(0.444);
            let y2 = state(0.00123);
            let y4 = state(0.007);
            let y6 = algebraic(0.36);
            let r1 = k1 * y1.powi(4) * sqrt(y2);
            let r5 = k4 * y6 * y6 * sqrt(y2);
            der(y1) == -2.0 * r1;
            der(y2) == -0.5 * r1 - 0.5 * r5;
            der(y4) == r5;
            0.0 == ks * y1 * y4 - y6;
        }
    });
    insta::assert_snapshot!("sorting", ir.graph.with(&sys).to_string());
}

#[test]
fn aliases_and_tearing_leave_newton_one_variable() {
    // A capacitor discharging through a resistor and a diode: `vd` is an
    // alias of `v_anode`, and of the block in `i`, `vr`, `vd` Newton
    // iterates on `i` alone.
    let (ir, _, sys) =
        reduced(model_in(include_str!("../../../tests/structure.rs"), "diode_discharge"));
    insta::assert_snapshot!("tearing", ir.graph.with(&sys).to_string());
}

/// The series RLC circuit of the component tests, from the standard
/// library: the flattened equations under the instances' paths, then
/// Kirchhoff's equations of the connections.
#[test]
fn lower_flattens_components_and_writes_the_connections() {
    let mut cx = Ctxt::default();
    let ir = lowered(
        &mut cx,
        TokenStream::new(),
        model_in(include_str!("../../../tests/models/drives.rs"), "rlc_series"),
    );
    insta::assert_snapshot!("components", ir.to_string());
}

/// A motor's EMF on a rotor joined rigidly to a load: the EMF's shaft
/// angle, the rotor's and the load's angles and rates tied by the
/// connections, one angle and one rate left; and that rate tied to the
/// ideal source across the EMF (`k w = V`, behind the pins' potentials),
/// one angle left, turning at V/k.
#[test]
fn tied_states_leave_one_angle_turning_as_the_source_says() {
    let mut cx = Ctxt::default();
    let mut ir = lowered(
        &mut cx,
        TokenStream::new(),
        quote! {
            fn shaft() {
                let gnd = ground();
                let supply = constant_voltage(1.0);
                let emf = emf(0.1);
                connect(supply.p, emf.p);
                connect(supply.n, emf.n, gnd.p);
                let rotor = inertia(0.01);
                connect(emf.flange, rotor.flange_a);
                let load = inertia(0.02);
                connect(rotor.flange_b, load.flange_a);
            }
        },
    );
    daegen_codegen::dae::tied_states::eliminate_tied_states(&mut cx, &mut ir);
    assert!(cx.is_ok(), "{:?}", cx.messages());
    insta::assert_snapshot!("tied_states", ir.to_string());
}

/// MSL's Cauer low-pass filter of library capacitors: the two loops of
/// capacitors (C1–C2–C3, C3–C4–C5) hide two ties behind the node
/// voltages, which the tied-states pass finds in the over-determined part
/// of the equations and eliminates C2's and C4's voltages by, the other
/// starts being set; five states left, the inductors' and C1, C3, C5's.
#[test]
fn hidden_ties_leave_five_states_of_the_cauer_filter() {
    let mut cx = Ctxt::default();
    let mut ir = lowered(
        &mut cx,
        TokenStream::new(),
        model_in(include_str!("../../../tests/index_reduction_of_parts.rs"), "cauer_low_pass"),
    );
    let found = daegen_codegen::dae::tied_states::eliminate_tied_states(&mut cx, &mut ir);
    assert!(cx.is_ok(), "{:?}", cx.messages());
    let states: Vec<&str> = ir.states.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(states, ["c1.v", "c3.v", "c5.v", "ind1.i", "ind2.i"]);
    // Pantelides' structurally singular subsets, each with the state its
    // tie eliminates; then the model with the dummy derivatives.
    let found: Vec<String> = found.iter().map(|t| t.to_string()).collect();
    insta::assert_snapshot!("over_determined_parts", found.join("\n\n"));
    insta::assert_snapshot!("hidden_ties", ir.to_string());
}

/// A block on a belt that sticks and slips: its equations guarded by the
/// mode, the events' actions; each mode reduced alone, and the joined
/// system reading the boolean.
#[test]
fn modes_are_reduced_alone_and_joined() {
    let mut cx = Ctxt::default();
    let mut ir = lowered(
        &mut cx,
        TokenStream::new(),
        quote! {
            fn belt() {
                let k = param(10.0);
                let x = state(0.0);
                let v = state(0.5);
                let stuck = discrete(true);
                der(x) == v;
                if stuck {
                    der(v) == 0.0;
                } else {
                    der(v) == -k * x + 4.0;
                }
                let slips = event(k * x - 6.0).rising().reinit(stuck, false);
                let sticks = event(v - 0.5).rising().reinit(stuck, true).reinit(v, 0.5);
                let count = discrete(0.0);
                let tick = every(0.1).offset(0.05).reinit(count, pre(count) + 1.0);
            }
        },
    );
    let lowered = ir.to_string();
    let sys = daegen_codegen::dae::modes::reduce_modes(
        &mut cx,
        &mut ir,
        daegen_codegen::pipeline::structure_and_reduction,
    )
    .expect("reduced");
    assert!(cx.is_ok(), "{:?}", cx.messages());
    insta::assert_snapshot!("modes", format!("{lowered}\n{}", ir.graph.with(&sys)));
}

/// An equation that holds in one mode ties no states for good: two rotors
/// whose rates a mode would tie keep both their rates.
#[test]
fn a_mode_ties_no_states_for_good() {
    let mut cx = Ctxt::default();
    let mut ir = lowered(
        &mut cx,
        TokenStream::new(),
        quote! {
            fn clutch() {
                let a = inertia(1.0);
                let b = inertia(1.0);
                let locked = discrete(true);
                if locked {
                    a.w == b.w;
                }
            }
        },
    );
    let before: Vec<String> = ir.states.iter().map(|s| s.name.clone()).collect();
    daegen_codegen::dae::tied_states::eliminate_tied_states(&mut cx, &mut ir);
    assert!(cx.is_ok(), "{:?}", cx.messages());
    let after: Vec<String> = ir.states.iter().map(|s| s.name.clone()).collect();
    assert_eq!(after, before);
    assert!(ir.equations.iter().any(|e| !e.mode.is_empty()), "the mode's equation stays");
}
