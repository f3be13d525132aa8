//! Shapes of the user's syntax the lowering asks about: a call by name, an
//! event with its settings, kinds of operators.

use syn::{BinOp, Expr, Lit};

/// The functions of the language, for suggestions.
pub(super) const FUNCTIONS: [&str; 27] = [
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sinh",
    "cosh",
    "tanh",
    "exp",
    "ln",
    "sqrt",
    "abs",
    "heaviside",
    "min",
    "max",
    "sign",
    "no_event",
    "der",
    "pre",
    "init",
    "initial",
    "constraint",
    "invariant",
    "powi",
    "powf",
];

/// `event(g)` or `every(h)` and the settings chained after it
/// (`.falling().terminal()`, `.reinit(..)`), innermost first; `true` for a
/// clock.
pub(super) fn trigger_call(e: &Expr) -> Option<(&syn::ExprCall, Vec<&syn::ExprMethodCall>, bool)> {
    let mut settings = Vec::new();
    let mut e = e;
    while let Expr::MethodCall(m) = e {
        settings.push(m);
        e = &m.receiver;
    }
    settings.reverse();
    match call_name(e) {
        Some((name, call)) if name == "event" => Some((call, settings, false)),
        Some((name, call)) if name == "every" => Some((call, settings, true)),
        _ => None,
    }
}

pub(super) fn call_name(e: &Expr) -> Option<(String, &syn::ExprCall)> {
    match e {
        Expr::Call(c) => match &*c.func {
            Expr::Path(p) => p.path.get_ident().map(|i| (i.to_string(), c)),
            _ => None,
        },
        _ => None,
    }
}

pub(super) fn is_comparison(op: &BinOp) -> bool {
    matches!(
        op,
        BinOp::Eq(_) | BinOp::Ne(_) | BinOp::Lt(_) | BinOp::Le(_) | BinOp::Gt(_) | BinOp::Ge(_)
    )
}

pub(super) fn is_compound_assignment(op: &BinOp) -> bool {
    matches!(
        op,
        BinOp::AddAssign(_) | BinOp::SubAssign(_) | BinOp::MulAssign(_) | BinOp::DivAssign(_)
    )
}

/// The `///` lines of `attrs`, joined.
pub(crate) fn doc_comment(attrs: &[syn::Attribute]) -> String {
    let lines: Vec<String> = attrs
        .iter()
        .filter(|a| a.path().is_ident("doc"))
        .filter_map(|a| match &a.meta {
            syn::Meta::NameValue(nv) => match &nv.value {
                Expr::Lit(syn::ExprLit { lit: Lit::Str(s), .. }) => Some(s.value()),
                _ => None,
            },
            _ => None,
        })
        .map(|l| l.strip_prefix(' ').unwrap_or(&l).to_string())
        .collect();
    lines.join("\n")
}
