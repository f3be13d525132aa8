//! The main job until the `#[dae_model]` front end lands: course notes
//! Example 1.4, `y' = x*y + x`, `y(0) = 1`, exact solution
//! `y = 2*exp(x²/2) - 1`, solved by the economic Taylor scheme of §1.3.1.
//!
//! The symbolic engine derives `y'' … y⁽ᵖ⁾` by total differentiation, shares
//! their subexpressions, emits the Rust code that computes them, and the
//! scheme integrates to x = 1 with step halving, printing the error against
//! the exact solution and the observed order of convergence.
//!
//! Run: `cargo run --release --example economic_taylor`

use daegen::codegen::{economic_taylor_derivatives, emit_program, Graph, Id, SymbolId, SymbolKind};
use daegen::runtime::taylor_series::taylor_step;
use proc_macro2::Literal;
use quote::quote;

const ORDER: usize = 4;

fn main() -> Result<(), daegen::codegen::Error> {
    let mut g = Graph::new();
    let x = g.time("x")?;
    let y = g.state("y")?;
    let (x, y) = (
        g.as_symbol(x).unwrap_or_else(|| unreachable!()),
        g.as_symbol(y).unwrap_or_else(|| unreachable!()),
    );
    let f = g.parse("x*y + x")?;
    let d = economic_taylor_derivatives(&mut g, x, &[y], &[f], ORDER)?;
    let d: Vec<Id> = d.into_iter().map(|v| v[0]).collect();

    println!("Course notes, Example 1.4: y' = x*y + x, y(0) = 1; exact y = 2*exp(x^2/2) - 1\n");
    println!("Derivatives of the economic Taylor scheme (total derivatives along the ODE):");
    for (k, &dk) in d.iter().enumerate() {
        println!("  y^({}) = {}", k + 1, g.show(dk));
    }

    let program = g.schedule(&d);
    let code = emit_program(
        &g,
        &program,
        &|s| match g.symbol(s).kind {
            SymbolKind::Derivative { order, .. } => {
                let k = Literal::u32_unsuffixed(order);
                quote!(d[#k])
            }
            _ if s == x => quote!(x),
            _ => quote!(y),
        },
        &|i, v| {
            let k = Literal::usize_unsuffixed(i + 1);
            quote!(d[#k] = #v;)
        },
    );
    let function = quote! {
        fn taylor_derivatives(x: f64, y: f64, d: &mut [f64; 5]) { #code }
    };
    let pretty = syn::parse2::<syn::File>(function)
        .map(|f| prettyplease::unparse(&f))
        .unwrap_or_default();
    println!("\nGenerated Rust (d[0] = y, d[k] = y^(k)):\n{pretty}");

    let exact = 2.0 * 0.5f64.exp() - 1.0;
    println!("Integration from x = 0 to 1 (exact y(1) = {exact:.16}):");
    println!("  order  steps  y(1)                 error      observed order");
    for order in 1..=ORDER {
        let mut previous: Option<f64> = None;
        for steps in [10, 20, 40, 80] {
            let value = integrate(&g, &d[..order], x, steps);
            let error = (value - exact).abs();
            let rate = previous.map_or(String::new(), |p| format!("{:.2}", (p / error).log2()));
            println!("  {order:5}  {steps:5}  {value:.16}  {error:.3e}  {rate}");
            previous = Some(error);
        }
    }
    Ok(())
}

/// The economic Taylor scheme with `d.len()` derivatives and `steps` steps on [0, 1].
fn integrate(g: &Graph, d: &[Id], x: SymbolId, steps: usize) -> f64 {
    let h = 1.0 / steps as f64;
    let mut y = [1.0];
    for n in 0..steps {
        let xn = n as f64 * h;
        // known[k] = y^(k) at (x_n, y_n), each D_k reading the lower ones.
        let mut known = vec![y[0]];
        for &dk in d {
            let value = |s: SymbolId| match g.symbol(s).kind {
                SymbolKind::Derivative { order, .. } => known[order as usize],
                _ if s == x => xn,
                _ => known[0],
            };
            let v = g.eval(&[dk], &value)[0];
            known.push(v);
        }
        let mut next = [0.0];
        taylor_step(&y, &known[1..], h, &mut next);
        y = next;
    }
    y[0]
}
