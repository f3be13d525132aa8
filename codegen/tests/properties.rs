//! Property tests over random expressions, each checked against an oracle
//! that does not use the graph: a plain recursive `f64` evaluation of the
//! expression as written, and forward-mode dual numbers for derivatives.

use daegen_codegen::{emit_program, Func, Graph, Id, Number, Program, SymbolId};
use proc_macro2::{Literal, TokenStream};
use proptest::prelude::*;
use quote::quote;

mod support;

const NAMES: [&str; 4] = ["x", "y", "z", "t"];

/// An expression as written, before the graph simplifies it.
#[derive(Clone, Debug)]
enum R {
    Var(usize),
    Int(i64),
    Frac(i64, i64),
    Float(f64),
    Add(Box<R>, Box<R>),
    Sub(Box<R>, Box<R>),
    Mul(Box<R>, Box<R>),
    Div(Box<R>, Box<R>),
    Neg(Box<R>),
    Powi(Box<R>, i64),
    PowHalf(Box<R>, i64),
    Powf(Box<R>, Box<R>),
    Call(Func, Box<R>),
    Atan2(Box<R>, Box<R>),
}

fn recipe() -> impl Strategy<Value = R> {
    let leaf = prop_oneof![
        4 => (0usize..4).prop_map(R::Var),
        1 => (-3i64..=3).prop_map(R::Int),
        1 => ((-5i64..=5), (1i64..=4)).prop_map(|(p, q)| R::Frac(p, q)),
        1 => (-2.5f64..2.5).prop_map(R::Float),
    ];
    // Every function but `sign`, which only appears as the derivative of `abs`.
    let funcs = prop::sample::select(
        Func::ALL.iter().copied().filter(|&f| f != Func::Sign).collect::<Vec<_>>(),
    );
    leaf.prop_recursive(5, 48, 3, move |inner| {
        let b = |r: R| Box::new(r);
        prop_oneof![
            3 => (inner.clone(), inner.clone()).prop_map(move |(a, c)| R::Add(b(a), b(c))),
            2 => (inner.clone(), inner.clone()).prop_map(move |(a, c)| R::Sub(b(a), b(c))),
            3 => (inner.clone(), inner.clone()).prop_map(move |(a, c)| R::Mul(b(a), b(c))),
            2 => (inner.clone(), inner.clone()).prop_map(move |(a, c)| R::Div(b(a), b(c))),
            1 => inner.clone().prop_map(move |a| R::Neg(b(a))),
            2 => (inner.clone(), -3i64..=4).prop_map(move |(a, n)| R::Powi(b(a), n)),
            1 => (inner.clone(), prop::sample::select(vec![-3i64, -1, 1, 3, 5])).prop_map(move |(a, k)| R::PowHalf(b(a), k)),
            1 => (inner.clone(), inner.clone()).prop_map(move |(a, c)| R::Powf(b(a), b(c))),
            2 => (funcs.clone(), inner.clone()).prop_map(move |(f, a)| R::Call(f, b(a))),
            1 => (inner.clone(), inner.clone()).prop_map(move |(a, c)| R::Atan2(b(a), b(c))),
        ]
    })
}

fn graph() -> (Graph, Vec<SymbolId>) {
    let mut g = Graph::new();
    let mut syms = Vec::new();
    for (i, n) in NAMES.iter().enumerate() {
        let id = if i == 3 { g.time(n) } else { g.state(n) }.unwrap();
        syms.push(g.as_symbol(id).unwrap());
    }
    (g, syms)
}

/// Builds the recipe; `None` when constant folding refuses it (non-finite).
fn build(g: &mut Graph, s: &[SymbolId], r: &R) -> Option<Id> {
    let mut b = |r: &R| build(g, s, r);
    Some(match r {
        R::Var(i) => g.symbol_node(s[*i]),
        R::Int(n) => g.int(*n),
        R::Frac(p, q) => g.rational(*p, *q).ok()?,
        R::Float(v) => g.float(*v).ok()?,
        R::Add(a, c) => {
            let (a, c) = (b(a)?, b(c)?);
            g.add(a, c).ok()?
        }
        R::Sub(a, c) => {
            let (a, c) = (b(a)?, b(c)?);
            g.sub(a, c).ok()?
        }
        R::Mul(a, c) => {
            let (a, c) = (b(a)?, b(c)?);
            g.mul(a, c).ok()?
        }
        R::Div(a, c) => {
            let (a, c) = (b(a)?, b(c)?);
            g.div(a, c).ok()?
        }
        R::Neg(a) => {
            let a = b(a)?;
            g.neg(a).ok()?
        }
        R::Powi(a, n) => {
            let a = b(a)?;
            g.powi(a, *n).ok()?
        }
        R::PowHalf(a, k) => {
            let a = b(a)?;
            let e = g.rational(*k, 2).ok()?;
            g.pow(a, e).ok()?
        }
        R::Powf(a, c) => {
            let (a, c) = (b(a)?, b(c)?);
            g.pow(a, c).ok()?
        }
        R::Call(f, a) => {
            let a = b(a)?;
            g.call(*f, a).ok()?
        }
        R::Atan2(a, c) => {
            let (a, c) = (b(a)?, b(c)?);
            g.atan2(a, c).ok()?
        }
    })
}

/// A value with its derivative along one direction. [`dual`] also reports
/// the largest magnitude met on the way, or the largest amplification of a
/// rounding error by a function (the scale that rounding errors are
/// relative to: its condition, to first order).
#[derive(Clone, Copy, Debug)]
struct Dual {
    v: f64,
    d: f64,
}

fn dual(r: &R, point: &[f64; 4], direction: usize, scale: &mut f64) -> Dual {
    let mut e = |r: &R| dual(r, point, direction, scale);
    let out = match r {
        R::Var(i) => Dual { v: point[*i], d: if *i == direction { 1.0 } else { 0.0 } },
        R::Int(n) => Dual { v: *n as f64, d: 0.0 },
        R::Frac(p, q) => Dual { v: *p as f64 / *q as f64, d: 0.0 },
        R::Float(v) => Dual { v: *v, d: 0.0 },
        R::Add(a, c) => {
            let (a, c) = (e(a), e(c));
            Dual { v: a.v + c.v, d: a.d + c.d }
        }
        R::Sub(a, c) => {
            let (a, c) = (e(a), e(c));
            Dual { v: a.v - c.v, d: a.d - c.d }
        }
        R::Mul(a, c) => {
            let (a, c) = (e(a), e(c));
            Dual { v: a.v * c.v, d: a.d * c.v + a.v * c.d }
        }
        R::Div(a, c) => {
            let (a, c) = (e(a), e(c));
            Dual { v: a.v / c.v, d: (a.d * c.v - a.v * c.d) / (c.v * c.v) }
        }
        R::Neg(a) => {
            let a = e(a);
            Dual { v: -a.v, d: -a.d }
        }
        R::Powi(a, n) => {
            let a = e(a);
            let n = *n as i32;
            Dual {
                v: a.v.powi(n),
                d: if a.d == 0.0 { 0.0 } else { n as f64 * a.v.powi(n - 1) * a.d },
            }
        }
        R::PowHalf(a, k) => {
            let a = e(a);
            let p = *k as f64 / 2.0;
            Dual {
                v: a.v.powf(p),
                // At a zero base a half power below 1 has no derivative (the
                // chain rule's u'/(2√u) is 0/0 even where u ≡ 0 nearby):
                // such points are rejected rather than compared.
                d: if a.v == 0.0 && p < 1.0 {
                    f64::NAN
                } else if a.d == 0.0 {
                    0.0
                } else {
                    p * a.v.powf(p - 1.0) * a.d
                },
            }
        }
        R::Powf(a, c) => {
            let (a, c) = (e(a), e(c));
            // Integer-valued constant exponents are powi in the graph, defined for a < 0.
            let v =
                if c.d == 0.0 && c.v.fract() == 0.0 { a.v.powi(c.v as i32) } else { a.v.powf(c.v) };
            // As for half powers: at a zero base an exponent below 1 has no
            // derivative (the chain rule's c·u^(c−1)·u' is ∞·0 even where
            // u ≡ 0 nearby, as for 0^z/t): such points are rejected.
            let da = if a.v == 0.0 && c.v < 1.0 && c.v != 0.0 {
                f64::NAN
            } else if a.d == 0.0 {
                0.0
            } else {
                c.v * a.v.powf(c.v - 1.0) * a.d
            };
            let dc = if c.d == 0.0 { 0.0 } else { v * a.v.ln() * c.d };
            Dual { v, d: da + dc }
        }
        R::Call(f, a) => {
            let a = e(a);
            let v = f.apply(a.v);
            let fp = match f {
                Func::Sin => a.v.cos(),
                Func::Cos => -a.v.sin(),
                Func::Tan => 1.0 + v * v,
                Func::Asin => 1.0 / (1.0 - a.v * a.v).sqrt(),
                Func::Acos => -1.0 / (1.0 - a.v * a.v).sqrt(),
                Func::Atan => 1.0 / (1.0 + a.v * a.v),
                Func::Sinh => a.v.cosh(),
                Func::Cosh => a.v.sinh(),
                Func::Tanh => 1.0 - v * v,
                Func::Exp => v,
                Func::Ln => 1.0 / a.v,
                Func::Abs => daegen_codegen::sign(a.v),
                Func::Sign => 0.0,
            };
            // A function amplifies the rounding of its argument: a relative
            // error ε in `a` moves f(a) by ε·|a f'(a)| and f'(a)·a' by about
            // ε·|a|·|f''(a) a'| (bounded here by |f'| + |f|, exact for sin,
            // cos and exp). sin(−1/(3x⁴)) at x = −0.0044 has |a| ≈ 8.6e8:
            // two codes rounding `a` differently disagree in the seventh
            // digit, and such points are ill-conditioned, not wrong.
            let amplification = a.v.abs() * (fp.abs() + a.d.abs() * (fp.abs() + v.abs()));
            *scale = scale.max(amplification);
            Dual { v, d: if a.d == 0.0 { 0.0 } else { fp * a.d } }
        }
        R::Atan2(a, c) => {
            let (y, x) = (e(a), e(c));
            let d = if y.d == 0.0 && x.d == 0.0 {
                0.0
            } else {
                (x.v * y.d - y.v * x.d) / (x.v * x.v + y.v * y.v)
            };
            Dual { v: y.v.atan2(x.v), d }
        }
    };
    // Real arithmetic has no signed zero; IEEE's -0.0 would flip atan2 by 2π.
    let out = Dual { v: if out.v == 0.0 { 0.0 } else { out.v }, d: out.d };
    // Values are only promised where no intermediate is infinite or NaN (where
    // `inf^(-3/2)` happens to give 0, say): an infinite scale marks the point unusable.
    *scale = scale.max(out.v.abs()).max(out.d.abs());
    if out.v.is_nan() || out.d.is_nan() {
        *scale = f64::INFINITY;
    }
    out
}

/// The only derivative that may be refused: a constant base `c <= 0` raised
/// to a variable exponent has none (`ln(c)` is not real).
fn derivative_or_skip(d: daegen_codegen::Result<Id>) -> Result<Option<Id>, TestCaseError> {
    match d {
        Ok(d) => Ok(Some(d)),
        Err(daegen_codegen::Error::NotFinite { reason, .. })
            if reason.contains("positive base") =>
        {
            Ok(None)
        }
        Err(e) => Err(TestCaseError::fail(format!("differentiation failed: {e}"))),
    }
}

fn point() -> impl Strategy<Value = [f64; 4]> {
    [-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0, 0.0f64..3.0]
}

fn close(got: f64, want: f64, scale: f64, rel: f64) -> bool {
    (got - want).abs() <= rel * scale.max(1.0)
}

/// Well-conditioned cases only: the oracle and the graph round differently,
/// and near a pole that difference is amplified without bound.
fn usable(value: f64, scale: f64) -> bool {
    value.is_finite() && scale < 1e6
}

proptest! {
    // Points where the written expression is undefined are rejected (a few
    // percent); failures found are kept in properties.proptest-regressions.
    #![proptest_config(support::config(2000, Some("tests/properties.proptest-regressions")))]

    #[test]
    fn simplification_never_changes_a_finite_value(r in recipe(), at in point()) {
        let (mut g, s) = graph();
        let Some(e) = build(&mut g, &s, &r) else { return Ok(()) };
        let mut scale = 0.0;
        let want = dual(&r, &at, 0, &mut scale).v;
        prop_assume!(usable(want, scale));
        let got = g.eval(&[e], &|sym| at[sym.index()])[0];
        prop_assert!(close(got, want, scale, 1e-9), "{r:?} built {} = {got}, written = {want}", g.show(e));
    }

    #[test]
    fn derivatives_agree_with_dual_numbers(r in recipe(), at in point(), direction in 0usize..4) {
        let (mut g, s) = graph();
        let Some(e) = build(&mut g, &s, &r) else { return Ok(()) };
        let mut scale = 0.0;
        let want = dual(&r, &at, direction, &mut scale);
        prop_assume!(usable(want.v, scale) && usable(want.d, scale));
        let Some(d) = derivative_or_skip(g.partial(e, s[direction]))? else { return Ok(()) };
        let got = g.eval(&[d], &|sym| at[sym.index()])[0];
        prop_assert!(close(got, want.d, scale, 1e-8),
            "d/d{} of {} is {} = {got}, dual numbers say {}", NAMES[direction], g.show(e), g.show(d), want.d);
    }

    #[test]
    fn total_derivative_is_the_chain_rule(r in recipe(), fx in recipe(), fy in recipe(), at in point()) {
        let (mut g, s) = graph();
        let (Some(e), Some(fx), Some(fy)) = (build(&mut g, &s, &r), build(&mut g, &s, &fx), build(&mut g, &s, &fy)) else { return Ok(()) };
        let mut field = daegen_codegen::VectorField::new();
        let one = g.one();
        field.set(s[0], fx);
        field.set(s[1], fy);
        field.set(s[3], one);
        let Some(total) = derivative_or_skip(g.total_derivative(e, &mut field))? else { return Ok(()) };
        // ∂e/∂t + ∂e/∂x fx + ∂e/∂y fy, by partial derivatives.
        let (Some(dt), Some(dx), Some(dy)) = (
            derivative_or_skip(g.partial(e, s[3]))?,
            derivative_or_skip(g.partial(e, s[0]))?,
            derivative_or_skip(g.partial(e, s[1]))?,
        ) else { return Ok(()) };
        let chain = g.parse("0").unwrap();
        let (a, b) = (g.mul(dx, fx).unwrap(), g.mul(dy, fy).unwrap());
        let chain = g.sum(&[chain, dt, a, b]).unwrap();
        let v = g.eval(&[total, chain, e, fx, fy], &|sym| at[sym.index()]);
        prop_assume!(v[2..].iter().all(|x| x.is_finite()), "the field and e must be defined at the point");
        let scale = v[1].abs().max(1.0);
        prop_assume!(v[1].is_finite() && scale < 1e6);
        prop_assert!(close(v[0], v[1], scale, 1e-9), "total {} = {}, chain rule {}", g.show(total), v[0], v[1]);
    }

    #[test]
    fn display_reads_back_to_the_same_node(r in recipe()) {
        let (mut g, s) = graph();
        let Some(e) = build(&mut g, &s, &r) else { return Ok(()) };
        let text = g.show(e).to_string();
        let back = g.parse(&text);
        prop_assert_eq!(back.clone(), Ok(e), "`{}` read back as `{}`", text, back.map(|b| g.show(b).to_string()).unwrap_or_default());
    }

    #[test]
    fn scheduled_and_emitted_code_computes_the_same_values(r in recipe(), q in recipe(), at in point()) {
        scheduled_and_emitted_agree(&r, &q, &at)?;
    }
}

/// The graph, its schedule and the emitted Rust evaluate `r`, `q` and their
/// partial derivatives in x and y alike: the schedule bit for bit, the
/// emitted code to rounding wherever the expressions are well-conditioned.
fn scheduled_and_emitted_agree(r: &R, q: &R, at: &[f64; 4]) -> Result<(), TestCaseError> {
    let (mut g, s) = graph();
    let (Some(e), Some(f)) = (build(&mut g, &s, r), build(&mut g, &s, q)) else {
        return Ok(());
    };
    let (Some(de), Some(df)) =
        (derivative_or_skip(g.partial(e, s[0]))?, derivative_or_skip(g.partial(f, s[1]))?)
    else {
        return Ok(());
    };
    let outputs = [e, f, de, df];
    let direct = g.eval(&outputs, &|sym| at[sym.index()]);
    let program = g.schedule(&outputs);
    let scheduled = program.evaluate(&g, &|sym| at[sym.index()]).map_err(TestCaseError::fail)?;
    let code = emit_to_out(&g, &program);
    let emitted = interpret(&code, at).map_err(TestCaseError::fail)?;
    // The condition of each expression as written, from the oracle.
    let mut condition = [0.0f64; 2];
    let written = [dual(r, at, 0, &mut condition[0]), dual(q, at, 1, &mut condition[1])];
    for k in 0..outputs.len() {
        // Same operations in the same order: bit-identical (or both NaN).
        prop_assert!(
            direct[k].to_bits() == scheduled[k].to_bits()
                || (direct[k].is_nan() && scheduled[k].is_nan()),
            "output {k}: graph {} vs program {}",
            direct[k],
            scheduled[k]
        );
        // Emission reorders (division instead of x^-1, sqrt forms): rounding
        // only, compared where the written expression is well-conditioned.
        let want = if k < 2 { written[k].v } else { written[k - 2].d };
        let scale = direct[k].abs().max(1.0);
        if direct[k].is_finite() && scale < 1e6 && usable(want, condition[k % 2]) {
            prop_assert!(
                close(emitted[k], direct[k], scale, 1e-9),
                "output {k} of {}: emitted code gives {} where the graph gives {}\n{}",
                g.show(outputs[k]),
                emitted[k],
                direct[k],
                code
            );
        }
    }
    Ok(())
}

/// Found by CI: sin(−1/(3x⁴)) near x = −0.0044 takes sin of −8.6e8, where
/// the graph's and the emitted code's roundings of the argument differ by
/// about 1e-7 in the sine. Ill-conditioned, so not compared; the bit-for-bit
/// schedule check still runs.
#[test]
fn an_ill_conditioned_point_is_not_compared_to_rounding() {
    let x = Box::new(R::Var(0));
    let r = R::Call(
        Func::Sin,
        Box::new(R::Div(
            Box::new(R::Int(-1)),
            Box::new(R::Mul(Box::new(R::Int(3)), Box::new(R::Powi(x, 4)))),
        )),
    );
    let at = [-0.004438441918562186, 0.5, 0.25, 1.0];
    let mut condition = 0.0;
    let value = dual(&r, &at, 0, &mut condition).v;
    assert!(value.is_finite() && !usable(value, condition), "condition {condition:e}");
    scheduled_and_emitted_agree(&r, &R::Var(1), &at).unwrap();
}

proptest! {
    #![proptest_config(support::config(300, None))]

    /// The same model always expands to the same code: two fresh graphs, the
    /// same construction, byte-identical output.
    #[test]
    fn emission_is_deterministic(r in recipe(), q in recipe()) {
        let emit_once = || {
            let (mut g, s) = graph();
            let (e, f) = (build(&mut g, &s, &r)?, build(&mut g, &s, &q)?);
            let j = g.jacobian(&[e, f], &s).ok()?;
            let mut outputs = vec![e, f];
            outputs.extend(j.expressions());
            let program = g.schedule(&outputs);
            let code = emit_to_out(&g, &program);
            Some(code.to_string())
        };
        prop_assert_eq!(emit_once(), emit_once());
    }
}

#[test]
fn shared_square_roots_are_defined_before_use() {
    // r^(-3/2) in f and r^(-5/2) in its Jacobian share a sqrt(r) that is
    // created while scheduling, after both powers.
    let (mut g, s) = graph();
    let f = g.parse("x*(x^2 + y^2)^(-3/2)").unwrap();
    let d = g.partial(f, s[0]).unwrap();
    let program = g.schedule(&[f, d]);
    let at = [0.3, -1.2, 0.0, 0.0];
    let code = emit_to_out(&g, &program);
    let emitted = interpret(&code, &at).unwrap_or_else(|e| panic!("{e}\n{code}"));
    let direct = g.eval(&[f, d], &|sym| at[sym.index()]);
    for k in 0..2 {
        assert!((emitted[k] - direct[k]).abs() < 1e-14 * direct[k].abs(), "{code}");
    }
    assert_eq!(
        code.to_string().matches("sqrt").count(),
        1,
        "one square root for both powers:\n{code}"
    );
}

#[test]
fn partial_derivatives_are_memoised_per_node_and_symbol() {
    let (mut g, s) = graph();
    let e = g.parse("sin(x*y)^2 + exp(x*y)").unwrap();
    let d1 = g.partial(e, s[0]).unwrap();
    let before = g.len();
    let d2 = g.partial(e, s[0]).unwrap();
    assert_eq!(d1, d2);
    assert_eq!(g.len(), before, "a repeated derivative must not build new nodes");
    let _ = Number::ONE;
}

/// The program's statements with the symbols by their names and output
/// `i` written as `out[i] = …;`.
fn emit_to_out(g: &Graph, program: &Program) -> TokenStream {
    emit_program(
        g,
        program,
        &|sym| {
            let n = quote::format_ident!("{}", NAMES[sym.index()]);
            quote!(#n)
        },
        &|i, v| {
            let i = Literal::usize_unsuffixed(i);
            quote!(out[#i] = #v;)
        },
    )
}

/// Interprets the emitted statements (`let t = ...;` and `out[i] = ...;`) with
/// `syn`, independently of the graph: checks precedence and parentheses.
fn interpret(code: &TokenStream, at: &[f64; 4]) -> Result<Vec<f64>, String> {
    let block: syn::Block = syn::parse2(quote!({ #code }))
        .map_err(|e| format!("emitted code does not parse: {e}\n{code}"))?;
    let mut env: Vec<(String, f64)> =
        NAMES.iter().zip(at).map(|(n, v)| (n.to_string(), *v)).collect();
    let mut out = vec![f64::NAN; 4];
    for stmt in &block.stmts {
        match stmt {
            syn::Stmt::Local(l) => {
                let syn::Pat::Ident(name) = &l.pat else {
                    return Err("let without a name".into());
                };
                let init = l.init.as_ref().ok_or("let without a value")?;
                let v = eval_expr(&init.expr, &env)?;
                env.push((name.ident.to_string(), v));
            }
            syn::Stmt::Expr(syn::Expr::Assign(a), _) => {
                let syn::Expr::Index(ix) = &*a.left else {
                    return Err("assignment to a non-index".into());
                };
                let k = eval_expr(&ix.index, &env)? as usize;
                out[k] = eval_expr(&a.right, &env)?;
            }
            other => return Err(format!("unexpected statement {}", quote!(#other))),
        }
    }
    Ok(out)
}

fn eval_expr(e: &syn::Expr, env: &[(String, f64)]) -> Result<f64, String> {
    use syn::{BinOp, Expr, Lit, UnOp};
    let ev = |e: &Expr| eval_expr(e, env);
    Ok(match e {
        Expr::Lit(l) => match &l.lit {
            Lit::Float(f) => f.base10_parse::<f64>().map_err(|e| e.to_string())?,
            Lit::Int(i) => i.base10_parse::<f64>().map_err(|e| e.to_string())?,
            other => return Err(format!("literal {}", quote!(#other))),
        },
        Expr::Path(p) => {
            let name = p.path.get_ident().ok_or("path")?.to_string();
            env.iter()
                .rev()
                .find(|(n, _)| *n == name)
                .map(|(_, v)| *v)
                .ok_or(format!("unbound `{name}`"))?
        }
        Expr::Paren(p) => ev(&p.expr)?,
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => -ev(&u.expr)?,
        Expr::Binary(b) => {
            let (l, r) = (ev(&b.left)?, ev(&b.right)?);
            match b.op {
                BinOp::Add(_) => l + r,
                BinOp::Sub(_) => l - r,
                BinOp::Mul(_) => l * r,
                BinOp::Div(_) => l / r,
                BinOp::Gt(_) => (l > r) as u8 as f64,
                BinOp::Lt(_) => (l < r) as u8 as f64,
                _ => return Err("operator".into()),
            }
        }
        Expr::If(i) => {
            let c = ev(&i.cond)?;
            let branch = if c != 0.0 { Some(&i.then_branch) } else { None };
            match (branch, &i.else_branch) {
                (Some(b), _) => match b.stmts.first() {
                    Some(syn::Stmt::Expr(e, None)) => ev(e)?,
                    _ => return Err("if body".into()),
                },
                (None, Some((_, e))) => ev(e)?,
                (None, None) => return Err("if without else".into()),
            }
        }
        Expr::Block(b) => match b.block.stmts.first() {
            Some(syn::Stmt::Expr(e, None)) => ev(e)?,
            _ => return Err("block".into()),
        },
        Expr::MethodCall(m) => {
            let x = ev(&m.receiver)?;
            let args: Vec<f64> = m.args.iter().map(ev).collect::<Result<_, _>>()?;
            match (m.method.to_string().as_str(), args.as_slice()) {
                ("powi", [n]) => x.powi(*n as i32),
                ("powf", [e]) => x.powf(*e),
                ("sqrt", []) => x.sqrt(),
                ("atan2", [o]) => x.atan2(*o),
                (name, []) => match Func::ALL.iter().find(|f| f.name() == name) {
                    Some(f) => f.apply(x),
                    None => return Err(format!("method {name}")),
                },
                (name, _) => return Err(format!("method {name} with arguments")),
            }
        }
        other => return Err(format!("unsupported expression {}", quote!(#other))),
    })
}
