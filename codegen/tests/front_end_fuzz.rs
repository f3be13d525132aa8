//! The front end under random input, fed to `expand_dae_model` directly (no
//! macro): random token soups from the language's vocabulary, random
//! well-formed ODE models, and random planar and spatial scenes. Whatever
//! comes in, the expansion must return (within a time limit) without
//! panicking, and what it returns must parse as Rust: either the model or
//! compile errors with a stub. Crashes found are kept as regression cases
//! below. `PROPTEST_CASES=20000 cargo test -p daegen-codegen --test
//! front_end_fuzz --release` runs a longer campaign.

use proc_macro2::TokenStream;
use proptest::prelude::*;
use std::str::FromStr;
use std::sync::mpsc;
use std::time::Duration;

mod support;

/// Expands `attr` and `body` (the statements of `fn m() { ... }`) on another
/// thread: `Err` if it panicked or took longer than the limit, else the
/// expansion as text. Input that does not lex is `Ok(None)`.
fn expand(attr: &str, body: &str) -> Result<Option<String>, String> {
    let (Ok(attr), Ok(item)) =
        (TokenStream::from_str(attr), TokenStream::from_str(&format!("fn m() {{ {body} }}")))
    else {
        return Ok(None);
    };
    // proc_macro2 token streams are not Send: hand over text.
    let (attr, item) = (attr.to_string(), item.to_string());
    let (tx, rx) = mpsc::channel();
    let worker = std::thread::spawn(move || {
        let attr = TokenStream::from_str(&attr).unwrap_or_default();
        let item = TokenStream::from_str(&item).unwrap_or_default();
        let out = daegen_codegen::expand_dae_model(attr, item).to_string();
        let _ = tx.send(out);
    });
    match rx.recv_timeout(Duration::from_secs(20)) {
        Ok(out) => {
            let _ = worker.join();
            Ok(Some(out))
        }
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!("no answer in 20 s for: {body}")),
        Err(mpsc::RecvTimeoutError::Disconnected) => Err(format!("panicked on: {body}")),
    }
}

/// The expansion parses as a Rust file (the model, or errors and a stub).
fn well_formed(out: &str) -> Result<(), String> {
    let tokens = TokenStream::from_str(out).map_err(|e| format!("{e}: {out:.300}"))?;
    syn::parse2::<syn::File>(tokens).map(|_| ()).map_err(|e| format!("{e}: {out:.300}"))
}

const VOCABULARY: &[&str] = &[
    "let",
    "x",
    "y",
    "v",
    "b",
    "g",
    "=",
    "==",
    ";",
    ",",
    "(",
    ")",
    "[",
    "]",
    ".",
    "+",
    "-",
    "*",
    "/",
    "0.0",
    "1.0",
    "2",
    "-1.0",
    "1e308",
    "state",
    "param",
    "algebraic",
    "der",
    "time",
    "output",
    "event",
    "constraint",
    "invariant",
    "init",
    "sin",
    "cos",
    "sqrt",
    "ln",
    "exp",
    "powi",
    "powf",
    "abs",
    "atan2",
    "vec3",
    "mat3",
    "cross",
    "dot",
    "rot_z",
    "quat_to_rot",
    "ground",
    "body",
    "spatial_body",
    "revolute",
    "spherical",
    "fixed",
    "distance",
    "prismatic",
    "gravity",
    "force",
    "torque",
    "spring",
    "position",
    "orientation",
    "for",
    "in",
    "0..3",
    "const",
    "N",
    ":",
    "usize",
    "state_array",
    "quaternion_state",
    "theta",
    "q0",
    "{",
    "}",
    "if",
    "fixed()",
];

fn soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(VOCABULARY), 0..60).prop_map(|w| w.join(" "))
}

/// A random smooth expression in x0..x{n-1}, the parameter k and time t.
fn expression(n: usize) -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        (0..n).prop_map(|i| format!("x{i}")),
        Just("k".to_string()),
        Just("t".to_string()),
        (-3i32..4).prop_map(|c| format!("{c}.0")),
        (0.1f64..3.0).prop_map(|c| format!("{c:.3}")),
    ];
    leaf.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} + {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} - {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} * {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} / {b})")),
            (
                inner.clone(),
                prop::sample::select(&["sin", "cos", "exp", "sqrt", "ln", "tanh", "atan"][..])
            )
                .prop_map(|(a, f)| format!("{f}({a})")),
            (inner.clone(), -3i32..4).prop_map(|(a, p)| format!("({a}).powi({p})")),
            (inner.clone(), prop::sample::select(&["-1.5", "0.5", "1.5", "2.5"][..]))
                .prop_map(|(a, p)| format!("({a}).powf({p})")),
            (inner.clone(), inner).prop_map(|(a, b)| format!("atan2({a}, {b})")),
        ]
    })
}

/// A random ODE (some states second order), sometimes with a constraint.
fn ode() -> impl Strategy<Value = String> {
    (1usize..4).prop_flat_map(|n| {
        (
            prop::collection::vec(expression(n), n),
            prop::collection::vec(any::<bool>(), n),
            prop::option::of(expression(n)),
        )
            .prop_map(move |(rhs, second, constraint)| {
                let mut s = String::from("let k = param(0.7); let t = time();");
                for i in 0..n {
                    s.push_str(&format!("let x{i} = state({}.5);", i));
                }
                for (i, (e, two)) in rhs.iter().zip(&second).enumerate() {
                    if *two {
                        s.push_str(&format!("der(der(x{i})) == {e};"));
                    } else {
                        s.push_str(&format!("der(x{i}) == {e};"));
                    }
                }
                if let Some(c) = constraint {
                    s.push_str(&format!("let l = algebraic(0.0); constraint({c});"));
                }
                s
            })
    })
}

/// A random scene: bodies and joints between random frames, and whether to
/// use joint coordinates (planar scenes only).
fn scene() -> impl Strategy<Value = (bool, String)> {
    (any::<bool>(), any::<bool>(), 1usize..4, prop::collection::vec((0usize..5, 0usize..5, 0usize..5, -2i32..3), 1..6))
        .prop_map(|(recursive, spatial, bodies, joints)| {
            let mut s = String::from("let ground = ground(); gravity(vec3(0.0, -9.81, -1.0));");
            for b in 0..bodies {
                if spatial {
                    s.push_str(&format!(
                        "let b{b} = spatial_body(1.0, vec3(0.1, 0.2, 0.3), [{b}.0, 0.5, 0.0], [1.0, 0.0, 0.0, 0.0]);"
                    ));
                } else {
                    s.push_str(&format!("let b{b} = body(1.0, 0.1, [{b}.0, 0.5, 0.3]);"));
                }
            }
            let frame = |i: usize| {
                if i == 0 || i > bodies {
                    "ground".to_string()
                } else {
                    format!("b{}", i - 1)
                }
            };
            let kinds = if spatial {
                ["spherical", "revolute", "prismatic", "fixed", "distance"]
            } else {
                ["revolute", "revolute", "prismatic", "fixed", "distance"]
            };
            for (a, b, kind, offset) in joints {
                // The second frame a body, mostly not the first one.
                let b = 1 + b % bodies;
                let (fa, fb) = (frame(a), frame(b));
                let p = format!("vec3({offset}.0, 0.5, 0.0)");
                let q = format!("vec3(0.0, {offset}.0, 0.0)");
                let stmt = match kinds[kind] {
                    "distance" => format!("distance({fa}, {p}, {fb}, {q}, 1.5);"),
                    "prismatic" => format!("prismatic({fa}, {p}, {fb}, {q}, vec3(1.0, 0.0, 0.0));"),
                    "revolute" if spatial => format!("revolute({fa}, {p}, {fb}, {q}, vec3(0.0, 0.0, 1.0));"),
                    k => format!("{k}({fa}, {p}, {fb}, {q});"),
                };
                s.push_str(&stmt);
            }
            s.push_str("spring(ground, vec3(0.0, 0.0, 0.0), b0, vec3(0.1, 0.0, 0.0), 10.0, 1.0, 0.1);");
            (recursive && !spatial, s)
        })
}

proptest! {
    #![proptest_config(support::config(96, None))]

    #[test]
    fn token_soups_never_panic(body in soup(), taylor in any::<bool>()) {
        let attr = if taylor { "taylor = 2" } else { "" };
        if let Some(out) = expand(attr, &body).map_err(TestCaseError::fail)? {
            well_formed(&out).map_err(TestCaseError::fail)?;
        }
    }

    #[test]
    fn random_odes_expand_or_explain(body in ode(), taylor in any::<bool>()) {
        let attr = if taylor { "taylor = 3" } else { "" };
        if let Some(out) = expand(attr, &body).map_err(TestCaseError::fail)? {
            well_formed(&out).map_err(TestCaseError::fail)?;
        }
    }

    #[test]
    fn random_scenes_expand_or_explain((recursive, body) in scene()) {
        let attr = if recursive { "scene = recursive" } else { "" };
        if let Some(out) = expand(attr, &body).map_err(TestCaseError::fail)? {
            well_formed(&out).map_err(TestCaseError::fail)?;
        }
    }
}

/// How deep the generators reach: a campaign is only as good as the share
/// of cases that get past the parser.
#[test]
fn the_generators_reach_past_the_parser() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::default();
    let expanded = |body: &str, attr: &str| -> bool {
        matches!(expand(attr, body), Ok(Some(out)) if !out.contains("compile_error"))
    };
    let odes =
        (0..60).filter(|_| expanded(&ode().new_tree(&mut runner).unwrap().current(), "")).count();
    let scenes = (0..60)
        .filter(|_| {
            let (recursive, body) = scene().new_tree(&mut runner).unwrap().current();
            expanded(&body, if recursive { "scene = recursive" } else { "" })
        })
        .count();
    // Measured over 300 each: about 42 % and 22 %.
    assert!(odes >= 12 && scenes >= 6, "of 60 each: {odes} ODEs, {scenes} scenes");
}
