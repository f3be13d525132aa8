//! Expansion speed and expression swell on two models the issue names:
//! N-body gravity (N = 10 bodies in 3D, 60 states) and a 100-link planar
//! chain (200 positions and 200 velocities; stiff springs between links,
//! plus the rigid-link constraint Jacobian Φ_q of the same chain).
//!
//! For each: time to build f, to differentiate the full sparse Jacobian, to
//! schedule f and J together and to emit them (median of 7 runs), DAG sizes
//! of f, of J, and of both, and the emitted token count.
//!
//! Run: `cargo bench -p daegen-codegen --bench expansion` (flags after `--`).

use daegen_codegen::{emit_program, token_count, Graph, Id, SymbolId};
use quote::quote;
use std::time::{Duration, Instant};

struct Model {
    g: Graph,
    states: Vec<SymbolId>,
    f: Vec<Id>,
}

fn sym(g: &mut Graph, id: Id) -> SymbolId {
    g.as_symbol(id).expect("a symbol")
}

/// r_i'' = Σ_{j≠i} m_j (r_j - r_i) |r_j - r_i|^(-3)
fn n_body(n: usize) -> Model {
    let mut g = Graph::new();
    let masses: Vec<Id> = (0..n).map(|i| g.parameter(&format!("m{i}")).unwrap()).collect();
    let pos: Vec<[Id; 3]> =
        (0..n).map(|i| ["x", "y", "z"].map(|c| g.state(&format!("{c}{i}")).unwrap())).collect();
    let vel: Vec<[Id; 3]> =
        (0..n).map(|i| ["u", "v", "w"].map(|c| g.state(&format!("{c}{i}")).unwrap())).collect();
    let mut f = Vec::new();
    for v in &vel {
        f.extend_from_slice(v);
    }
    let m32 = g.rational(-3, 2).unwrap();
    for i in 0..n {
        let mut acc = [Vec::new(), Vec::new(), Vec::new()];
        for j in (0..n).filter(|&j| j != i) {
            let d: Vec<Id> = (0..3).map(|c| g.sub(pos[j][c], pos[i][c]).unwrap()).collect();
            let squares: Vec<Id> = d.iter().map(|&dc| g.powi(dc, 2).unwrap()).collect();
            let r2 = g.sum(&squares).unwrap();
            let inv_r3 = g.pow(r2, m32).unwrap();
            for c in 0..3 {
                acc[c].push(g.product(&[masses[j], d[c], inv_r3]).unwrap());
            }
        }
        for terms in &acc {
            f.push(g.sum(terms).unwrap());
        }
    }
    let mut states = Vec::new();
    for p in pos.iter().chain(&vel) {
        for &s in p {
            states.push(sym(&mut g, s));
        }
    }
    // f was pushed as velocities then accelerations; states as positions then velocities.
    Model { g, states, f }
}

/// Point masses k = 1..n hanging from the origin, joined by springs of
/// stiffness k_s and rest length l: m a_k = T_{k+1} - T_k + m g,
/// T_k = k_s (|d_k| - l) d_k / |d_k|, d_k = p_k - p_{k-1}.
fn spring_chain(n: usize) -> Model {
    let mut g = Graph::new();
    let (ks, l, m, grav) = ["ks", "l", "m", "g"].map(|p| g.parameter(p).unwrap()).into();
    let x: Vec<Id> = (0..n).map(|k| g.state(&format!("x{k}")).unwrap()).collect();
    let y: Vec<Id> = (0..n).map(|k| g.state(&format!("y{k}")).unwrap()).collect();
    let u: Vec<Id> = (0..n).map(|k| g.state(&format!("u{k}")).unwrap()).collect();
    let v: Vec<Id> = (0..n).map(|k| g.state(&format!("v{k}")).unwrap()).collect();
    // Tension of link k (between mass k-1, or the origin, and mass k).
    let mut tension = Vec::new();
    for k in 0..n {
        let (dx, dy, len2) = link(&mut g, &x, &y, k);
        let len = g.sqrt(len2).unwrap();
        let stretch = g.sub(len, l).unwrap();
        let inv = g.powi(len, -1).unwrap();
        let scale = g.product(&[ks, stretch, inv]).unwrap();
        tension.push([g.mul(scale, dx).unwrap(), g.mul(scale, dy).unwrap()]);
    }
    let mut f: Vec<Id> = u.iter().chain(&v).copied().collect();
    let inv_m = g.powi(m, -1).unwrap();
    let mut ax = Vec::new();
    let mut ay = Vec::new();
    for k in 0..n {
        let mut fx = g.neg(tension[k][0]).unwrap();
        let mut fy = g.neg(tension[k][1]).unwrap();
        if k + 1 < n {
            fx = g.add(fx, tension[k + 1][0]).unwrap();
            fy = g.add(fy, tension[k + 1][1]).unwrap();
        }
        ax.push(g.mul(fx, inv_m).unwrap());
        let fy_m = g.mul(fy, inv_m).unwrap();
        ay.push(g.sub(fy_m, grav).unwrap());
    }
    f.extend(ax);
    f.extend(ay);
    let states = x.iter().chain(&y).chain(&u).chain(&v).map(|&s| sym(&mut g, s)).collect();
    Model { g, states, f }
}

/// Φ_k = |p_k - p_{k-1}|² - l² for a rigid chain: its Jacobian Φ_q.
fn chain_constraints(n: usize) -> Model {
    let mut g = Graph::new();
    let l = g.parameter("l").unwrap();
    let x: Vec<Id> = (0..n).map(|k| g.state(&format!("x{k}")).unwrap()).collect();
    let y: Vec<Id> = (0..n).map(|k| g.state(&format!("y{k}")).unwrap()).collect();
    let l2 = g.powi(l, 2).unwrap();
    let f = (0..n)
        .map(|k| {
            let (_, _, s) = link(&mut g, &x, &y, k);
            g.sub(s, l2).unwrap()
        })
        .collect();
    let states = x.iter().chain(&y).map(|&s| sym(&mut g, s)).collect();
    Model { g, states, f }
}

/// Link k of a planar chain hanging from the origin: `(dx, dy, dx² + dy²)`
/// between point k-1 (the origin for k = 0) and point k.
fn link(g: &mut Graph, x: &[Id], y: &[Id], k: usize) -> (Id, Id, Id) {
    let zero = g.zero();
    let (px, py) = if k == 0 { (zero, zero) } else { (x[k - 1], y[k - 1]) };
    let dx = g.sub(x[k], px).unwrap();
    let dy = g.sub(y[k], py).unwrap();
    let dx2 = g.powi(dx, 2).unwrap();
    let dy2 = g.powi(dy, 2).unwrap();
    (dx, dy, g.add(dx2, dy2).unwrap())
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn ms(d: Duration) -> String {
    format!("{:.2} ms", d.as_secs_f64() * 1e3)
}

fn report(name: &str, build: fn() -> Model) {
    const RUNS: usize = 7;
    let (mut t_build, mut t_jac, mut t_sched, mut t_emit, mut t_total) =
        (vec![], vec![], vec![], vec![], vec![]);
    let mut sizes = (0, 0, 0, 0, 0, 0, 0);
    for _ in 0..RUNS {
        let start = Instant::now();
        let mut m = build();
        let built = Instant::now();
        let j = m.g.jacobian(&m.f, &m.states).unwrap();
        let differentiated = Instant::now();
        let mut outputs = m.f.clone();
        outputs.extend(j.expressions());
        let program = m.g.schedule(&outputs);
        let scheduled = Instant::now();
        let code = emit_program(
            &m.g,
            &program,
            &|s| {
                let i = proc_macro2::Literal::usize_unsuffixed(s.index());
                quote!(y[#i])
            },
            &|i, v| {
                let i = proc_macro2::Literal::usize_unsuffixed(i);
                quote!(out[#i] = #v;)
            },
        );
        let emitted = Instant::now();
        t_build.push(built - start);
        t_jac.push(differentiated - built);
        t_sched.push(scheduled - differentiated);
        t_emit.push(emitted - scheduled);
        t_total.push(emitted - start);
        let size_f = m.g.dag_size(&m.f);
        let size_j = m.g.dag_size(&j.expressions());
        let size_both = m.g.dag_size(&outputs);
        sizes = (
            m.states.len(),
            j.entries.len(),
            size_f,
            size_j,
            size_both,
            program.temps.len(),
            token_count(&code),
        );
    }
    let (n, nnz, size_f, size_j, size_both, temps, tokens) = sizes;
    println!("## {name}");
    println!("states {n}, Jacobian non-zeros {nnz}");
    println!(
        "time (median of {RUNS}): build f {}, Jacobian {}, schedule {}, emit {}, total {}",
        ms(median(t_build)),
        ms(median(t_jac)),
        ms(median(t_sched)),
        ms(median(t_emit)),
        ms(median(t_total))
    );
    println!(
        "DAG nodes: f {size_f}, J {size_j} ({:.2}x f), f and J together {size_both} ({:.2}x f)",
        size_j as f64 / size_f as f64,
        size_both as f64 / size_f as f64
    );
    println!("emitted: {temps} temporaries, {tokens} tokens\n");
}

include!("../../tests/models/n_body.rs");

/// `quoted! { tokens }`: the tokens as a `TokenStream`, `#name` interpolated.
macro_rules! quoted {
    ($($tokens:tt)*) => {
        quote::quote! { $($tokens)* }
    };
}

/// Full `#[dae_model]` expansions: parse, lower, reduce, differentiate,
/// schedule and emit a whole model (median of 7).
fn report_models() {
    use daegen_codegen::expand_dae_model;
    use quote::quote;
    let n_body = |n: usize| {
        let n_lit = proc_macro2::Literal::usize_unsuffixed(n);
        gravitating_bodies!(@then quoted {} fn n_body(spatial) {
            const N: usize = #n_lit;
            let g = param(1.0);
            let m = [1.0; N];
            let x = state_array([0.0; N]);
            let y = state_array([0.0; N]);
            let z = state_array([0.0; N]);
            let u = state_array([0.0; N]);
            let v = state_array([0.0; N]);
            let w = state_array([0.0; N]);
        })
    };
    let chain = quote! {
        /// 30 masses on a line, joined by nonlinear springs: 30 equations, 60 states.
        fn chain() {
            const N: usize = 30;
            let k = param(1.0);
            let c = param(0.1);
            let q = state_array([0.0; N]);
            for i in 0..N {
                let mut f = -k * q[i] - c * q[i].powi(3);
                if i > 0 { f += k * (q[i - 1] - q[i]) + c * (q[i - 1] - q[i]).powi(3); }
                if i + 1 < N { f += k * (q[i + 1] - q[i]) + c * (q[i + 1] - q[i]).powi(3); }
                der(der(q[i])) == f;
            }
            init(der(q[0]), 1.0);
        }
    };
    let kepler = quote! {
        fn kepler() {
            let q1 = state(0.1);
            let q2 = state(0.0);
            let p1 = state(0.0);
            let p2 = state(4.358898943540674);
            let r3 = (q1 * q1 + q2 * q2).powf(-1.5);
            der(q1) == p1;
            der(q2) == p2;
            der(p1) == -q1 * r3;
            der(p2) == -q2 * r3;
        }
    };
    let none = proc_macro2::TokenStream::new();
    let models = [
        ("3-body, 3D (18 states)", none.clone(), n_body(3)),
        ("10-body, 3D (60 states)", none.clone(), n_body(10)),
        ("30-equation spring chain (60 states)", none, chain),
        (
            "Kepler with the Taylor tape and order 19 unrolled",
            quote!(taylor = 1, unroll = [19]),
            kepler,
        ),
        (
            "6-body, 3D (36 states) with the Taylor tape and orders 12, 15, 19 unrolled",
            quote!(taylor = 1, unroll = [12, 15, 19]),
            n_body(6),
        ),
    ];
    println!("## #[dae_model] expansion (f, Jacobian, ∂f/∂t, outputs; Taylor code when asked)");
    for (name, attr, item) in models {
        let mut times = Vec::new();
        let mut tokens = 0;
        for _ in 0..7 {
            let start = Instant::now();
            let out = expand_dae_model(attr.clone(), item.clone());
            times.push(start.elapsed());
            tokens = token_count(&out);
        }
        println!("{name}: {} , {tokens} tokens of generated code", ms(median(times)));
    }
}

/// Flags: `--models-only` runs only the `#[dae_model]` expansions;
/// `--histogram` lists, by kind, the nodes the Jacobian adds to f (where swell
/// would show).
fn main() {
    let flag = |f: &str| std::env::args().any(|a| a == f);
    if flag("--histogram") {
        histogram(&mut n_body(10));
        histogram(&mut spring_chain(100));
        return;
    }
    if !flag("--models-only") {
        report("N-body, N = 10 (3D, 60 states)", || n_body(10));
        report("100-link spring chain (400 states)", || spring_chain(100));
        report("100-link rigid chain, constraint Jacobian Φ_q", || chain_constraints(100));
    }
    report_models();
}
/// Nodes of the Jacobian that f does not have, by kind and coefficient.
fn histogram(m: &mut Model) {
    let j = m.g.jacobian(&m.f, &m.states).unwrap();
    let in_f: std::collections::BTreeSet<Id> = m.g.reachable(&m.f).into_iter().collect();
    let mut kinds: std::collections::BTreeMap<String, usize> = Default::default();
    for id in m.g.reachable(&j.expressions()) {
        if in_f.contains(&id) {
            continue;
        }
        let k = match m.g.node(id) {
            daegen_codegen::Node::Mul(f) => {
                let c = f
                    .iter()
                    .find_map(|&x| m.g.as_number(x))
                    .map(|n| n.to_string())
                    .unwrap_or("1".into());
                format!("Mul(c={c}, {} factors)", f.len())
            }
            daegen_codegen::Node::Add(t) => format!("Add({} terms)", t.len()),
            daegen_codegen::Node::Pow(_) => "Pow".into(),
            other => format!("{other:?}").chars().take(12).collect(),
        };
        *kinds.entry(k).or_default() += 1;
    }
    for (k, v) in kinds {
        println!("  {v:5}  {k}");
    }
}
