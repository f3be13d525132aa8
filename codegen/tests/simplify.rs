//! The smart constructors: canonical forms, value-preserving identities and
//! refused constant folds.

use daegen_codegen::{Error, Func, Graph, Id};

fn graph() -> Graph {
    let mut g = Graph::new();
    for s in ["x", "y", "z"] {
        g.state(s).unwrap();
    }
    g.parameter("m").unwrap();
    g.time("t").unwrap();
    g
}

fn p(g: &mut Graph, s: &str) -> Id {
    g.parse(s).unwrap_or_else(|e| panic!("{s}: {e}"))
}

/// `a` and `b` build the same node.
fn same(a: &str, b: &str) {
    let mut g = graph();
    let (ia, ib) = (p(&mut g, a), p(&mut g, b));
    assert_eq!(ia, ib, "`{a}` built `{}`, `{b}` built `{}`", g.show(ia), g.show(ib));
}

fn shows(src: &str, expected: &str) {
    let mut g = graph();
    let id = p(&mut g, src);
    assert_eq!(g.show(id).to_string(), expected, "from `{src}`");
}

#[test]
fn neutral_elements_vanish() {
    same("x + 0", "x");
    same("x * 1", "x");
    same("x * 0", "0");
    same("x - x", "0");
    same("x / x", "1");
    same("x^1", "x");
    same("x^0", "1");
    same("1^x", "1");
    same("--x", "x");
}

#[test]
fn equal_expressions_get_equal_ids_whatever_the_order() {
    same("x*y", "y*x");
    same("(x + y) + z", "x + (y + z)");
    same("x*(y*z)", "(z*x)*y");
    same("sin(x + y)", "sin(y + x)");
    same("x - y", "-y + x");
    same("x/y/z", "x/(y*z)");
}

#[test]
fn like_terms_and_powers_are_collected() {
    same("2*x + 3*x", "5*x");
    same("x + x", "2*x");
    same("x*y - y*x/2", "x*y/2");
    same("x*x", "x^2");
    same("x^2 * x^-3", "1/x");
    same("x^(1/2) * x^(1/2)", "x");
    same("sqrt(x) * x", "x^(3/2)");
    same("(x^(1/2))^2", "x");
    same("(x^3)^2", "x^6");
    same("(2*x*y)^2", "4*x^2*y^2");
    same("x*(x*y)^-1", "1/y");
    same("2*(x + y) - 2*x", "2*y");
    same("x + y - (x + y)", "0");
    same("3*(x - y) + 0", "3*(x - y)");
    shows("3*(x - y)", "3*(x - y)");
    shows("-(x + y)", "-(x + y)");
    same("x^m * x", "x^(m + 1)");
    same("(x - y)^2", "(y - x)^2");
    same("(x - y)^-4", "(y - x)^-4");
}

#[test]
fn fractional_powers_do_not_compose_unsafely() {
    // ((-1)^2)^(1/2) is 1, while (-1)^(2/2) would be -1: must stay nested.
    let mut g = graph();
    let nested = p(&mut g, "(x^2)^(1/2)");
    let x = p(&mut g, "x");
    assert_ne!(nested, x);
    assert_eq!(g.eval_named(nested, &[("x", -3.0)]), 3.0);
    // sqrt(x*y) is not sqrt(x)*sqrt(y) for negative x, y.
    let a = p(&mut g, "sqrt(x*y)");
    let b = p(&mut g, "sqrt(x)*sqrt(y)");
    assert_ne!(a, b);
}

#[test]
fn constants_fold_exactly() {
    same("1/2 + 1/3", "5/6");
    same("(1/2)^-3", "8");
    same("sqrt(9/4)", "3/2");
    same("2^(1/2)*2^(1/2)", "2");
    same("0.5*x", "x/2");
    same("3.0", "3");
    same("exp(0) + cos(0) + ln(1)", "2");
    shows("1/6 - 1/4", "-1/12");
    let mut g = graph();
    let s2 = p(&mut g, "sqrt(2)");
    assert_eq!(g.show(s2).to_string(), "2^(1/2)");
    assert_eq!(g.eval_named(s2, &[]), 2f64.sqrt());
    let folded = p(&mut g, "2.5^0.5");
    assert_eq!(g.eval_named(folded, &[]), 2.5f64.sqrt());
}

#[test]
fn folding_to_a_non_finite_value_is_an_error_naming_the_expression() {
    let cases = [
        ("1/0", "0^(-1)", "division by zero"),
        ("x + 1/(1 - 1)", "0^(-1)", "division by zero"),
        ("ln(0)", "ln(0)", "positive argument"),
        ("ln(-2)", "ln(-2)", "positive argument"),
        ("sqrt(-1)", "sqrt(-1)", "not a real number"),
        ("asin(2)", "asin(2)", "[-1, 1]"),
        ("exp(1000)", "exp(1000)", "overflows"),
        ("1e300 * 1e300", "* ", "overflows"),
    ];
    for (src, named, reason) in cases {
        let mut g = graph();
        match g.parse(src) {
            Err(Error::NotFinite { expression, reason: why }) => {
                assert!(expression.contains(named.trim()), "{src}: message names `{expression}`");
                assert!(why.contains(reason), "{src}: reason `{why}`");
            }
            other => panic!("{src}: expected a non-finite error, got {other:?}"),
        }
    }
}

#[test]
fn display_is_readable_and_reads_back() {
    shows("x*y + x", "x + x*y");
    shows("x - 1", "x - 1");
    shows("1 - x", "1 - x");
    shows("-x - y", "-x - y");
    shows("3*x/(2*y)", "3*x/(2*y)");
    shows("x^(1/2)", "x^(1/2)");
    shows("1/sqrt(x)", "1/x^(1/2)");
    shows("x/(y+z)^2", "x/(y + z)^2");
    shows("atan2(y, x)", "atan2(y, x)");
    shows("sin(x)^2", "sin(x)^2");
    shows("x^m", "x^m");
    shows("0.1*x", "0.1*x");
    for src in [
        "x + x*y",
        "3*x/(2*y)",
        "1/x^(1/2)",
        "x/(y + z)^2",
        "-x*sin(y)^(-3/2)",
        "x^(m + 1)",
        "1.5e-30*x",
    ] {
        let mut g = graph();
        let id = p(&mut g, src);
        let text = g.show(id).to_string();
        assert_eq!(p(&mut g, &text), id, "`{src}` shows as `{text}`, which reads back differently");
    }
}

#[test]
fn non_smooth_functions_are_flagged_upwards() {
    let mut g = graph();
    let smooth = p(&mut g, "sin(x)*exp(y) + sqrt(x)");
    let rough = p(&mut g, "sin(x) + abs(y)");
    assert!(g.is_smooth(smooth));
    assert!(!g.is_smooth(rough));
    let d = g.partial(rough, g.symbol_named("y").unwrap()).unwrap();
    assert_eq!(g.show(d).to_string(), "sign(y)");
    assert!(!g.is_smooth(d));
}

#[test]
fn symbols_keep_their_kind() {
    let mut g = graph();
    assert!(matches!(g.parameter("x"), Err(Error::NameTaken { .. })));
    let x = g.symbol_named("x").unwrap();
    let d2 = g.derivative(x, 2).unwrap();
    assert_eq!(g.show(d2).to_string(), "der(der(x))");
    let d1 = g.derivative(x, 1).unwrap();
    let d1_sym = g.as_symbol(d1).unwrap();
    assert_eq!(g.derivative(d1_sym, 1).unwrap(), d2);
    let e = p(&mut g, "x*y");
    let named = g.intermediate("e", e).unwrap();
    let f = g.call(Func::Sin, named).unwrap();
    assert_eq!(g.show(f).to_string(), "sin(e)");
    let v = g.eval_named(f, &[("x", 2.0), ("y", 0.25)]);
    assert_eq!(v, 0.5f64.sin());
}
