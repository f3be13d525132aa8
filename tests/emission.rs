//! Snapshots of emitted code for small models, formatted with prettyplease.
//! Every change to emission shows up here as a diff to review like code.

use daegen_codegen::{
    economic_taylor_derivatives, emit_program, token_count, Graph, Id, SymbolId, SymbolKind,
};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// Symbols read as `y[i]` (states, by creation order), `p[i]` (parameters),
/// `t` (time), `d[k][i]` (k-th derivative of state i).
fn layout(g: &Graph) -> impl Fn(SymbolId) -> TokenStream + '_ {
    move |s| {
        let index_among = |kind: fn(&SymbolKind) -> bool, s: SymbolId| {
            let i =
                g.symbols().filter(|(_, sym)| kind(&sym.kind)).position(|(id, _)| id == s).unwrap();
            Literal::usize_unsuffixed(i)
        };
        match g.symbol(s).kind {
            SymbolKind::State => {
                let i = index_among(|k| matches!(k, SymbolKind::State), s);
                quote!(y[#i])
            }
            SymbolKind::Parameter => {
                let i = index_among(|k| matches!(k, SymbolKind::Parameter), s);
                quote!(p[#i])
            }
            SymbolKind::Derivative { of, order } => {
                let i = index_among(|k| matches!(k, SymbolKind::State), of);
                let k = Literal::u32_unsuffixed(order);
                quote!(d[#k][#i])
            }
            _ => {
                let n = format_ident!("{}", g.symbol(s).name);
                quote!(#n)
            }
        }
    }
}

/// `fn name(<signature>) { <program for outputs, written to targets> }`, pretty-printed.
fn emit(
    g: &mut Graph,
    name: &str,
    signature: TokenStream,
    outputs: &[(Id, TokenStream)],
) -> String {
    let ids: Vec<Id> = outputs.iter().map(|o| o.0).collect();
    let program = g.schedule(&ids);
    let g = &*g;
    let body = emit_program(g, &program, &layout(g), &|i, v| {
        let target = &outputs[i].1;
        quote!(#target = #v;)
    });
    let name = format_ident!("{}", name);
    let tokens = quote! { pub fn #name(#signature) { #body } };
    let file: syn::File = syn::parse2(tokens).expect("emitted code parses");
    let code = prettyplease::unparse(&file);
    format!(
        "// {} tokens, {} temporaries\n{code}",
        token_count(&quote!(#body)),
        program.temps.len()
    )
}

fn indexed(array: &str, i: usize) -> TokenStream {
    let a = format_ident!("{}", array);
    let i = Literal::usize_unsuffixed(i);
    quote!(#a[#i])
}

fn states(g: &mut Graph, names: &[&str]) -> Vec<SymbolId> {
    g.state_symbols(names).unwrap()
}

/// Right-hand side and sparse Jacobian in one program: shared subexpressions once.
fn rhs_and_jacobian(g: &mut Graph, s: &[SymbolId], f: &[&str]) -> String {
    let f: Vec<Id> = f.iter().map(|e| g.parse(e).unwrap()).collect();
    let j = g.jacobian(&f, s).unwrap();
    let mut outputs: Vec<(Id, TokenStream)> =
        f.iter().enumerate().map(|(i, &e)| (e, indexed("dy", i))).collect();
    outputs.extend(j.entries.iter().enumerate().map(|(k, &(_, _, e))| (e, indexed("jac", k))));
    let (n, nnz) = (Literal::usize_unsuffixed(f.len()), Literal::usize_unsuffixed(j.entries.len()));
    let np = Literal::usize_unsuffixed(
        g.symbols().filter(|(_, s)| s.kind == SymbolKind::Parameter).count(),
    );
    let pattern: Vec<String> = j.entries.iter().map(|(r, c, _)| format!("({r},{c})")).collect();
    let signature =
        quote!(y: &[f64; #n], p: &[f64; #np], dy: &mut [f64; #n], jac: &mut [f64; #nnz]);
    format!(
        "// jacobian pattern {}\n{}",
        pattern.join(" "),
        emit(g, "rhs_and_jacobian", signature, &outputs)
    )
}

#[test]
fn lorenz_right_hand_side_and_jacobian() {
    let mut g = Graph::new();
    for p in ["sigma", "rho", "beta"] {
        g.parameter(p).unwrap();
    }
    let s = states(&mut g, &["x", "y", "z"]);
    insta::assert_snapshot!(rhs_and_jacobian(
        &mut g,
        &s,
        &["sigma*(y - x)", "x*(rho - z) - y", "x*y - beta*z"]
    ));
}

#[test]
fn kepler_right_hand_side_and_jacobian() {
    let mut g = Graph::new();
    g.parameter("mu").unwrap();
    let s = states(&mut g, &["q1", "q2", "p1", "p2"]);
    let f = ["p1", "p2", "-mu*q1*(q1^2 + q2^2)^(-3/2)", "-mu*q2*(q1^2 + q2^2)^(-3/2)"];
    insta::assert_snapshot!(rhs_and_jacobian(&mut g, &s, &f));
}

#[test]
fn example_1_4_economic_taylor_derivatives() {
    let mut g = Graph::new();
    let x = g.time("x").unwrap();
    let x = g.as_symbol(x).unwrap();
    let y = states(&mut g, &["y"]);
    let f = g.parse("x*y + x").unwrap();
    let d = economic_taylor_derivatives(&mut g, x, &y, &[f], 4).unwrap();
    let outputs: Vec<(Id, TokenStream)> = d
        .iter()
        .enumerate()
        .map(|(k, dk)| {
            let k = Literal::usize_unsuffixed(k + 1);
            (dk[0], quote!(out[#k][0]))
        })
        .collect();
    let signature = quote!(x: f64, y: &[f64; 1], d: &[[f64; 1]; 5], out: &mut [[f64; 1]; 5]);
    insta::assert_snapshot!(emit(&mut g, "taylor_derivatives", signature, &outputs));
}

#[test]
fn elementary_functions_and_powers() {
    let mut g = Graph::new();
    g.parameter("a").unwrap();
    let s = states(&mut g, &["u", "v", "w"]);
    let r = g.parse("u^2 + v^2").unwrap();
    let r = g.intermediate("r", r).unwrap();
    let _ = r;
    let exprs = [
        "atan2(v, u) + abs(w)",
        "tan(u*v)",
        "u^5 - v^4 + w^(5/2)",
        "1/r^(1/2) + sqrt(r)",
        "u^a + 2^w",
        "u/3 + v/(3*w) + 0.1*w",
        "exp(-u)*ln(v) + asin(w/2)",
        "sinh(u) - cosh(v) + tanh(w)",
    ];
    let mut outputs = Vec::new();
    for (i, e) in exprs.iter().enumerate() {
        let id = g.parse(e).unwrap();
        outputs.push((id, indexed("out", i)));
    }
    // Derivatives bring sign(), 1 + tan², (1 - x²)^(-1/2) and u^(a - 1).
    for (i, e) in [(0, s[2]), (1, s[0]), (4, s[0]), (6, s[2])] {
        let d = g.partial(outputs[i].0, e).unwrap();
        let k = outputs.len();
        outputs.push((d, indexed("out", k)));
    }
    let n = Literal::usize_unsuffixed(outputs.len());
    let signature = quote!(y: &[f64; 3], p: &[f64; 1], out: &mut [f64; #n]);
    insta::assert_snapshot!(emit(&mut g, "elementary", signature, &outputs));
}
