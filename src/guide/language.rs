//! # The model language
//!
//! A model is a Rust function with no arguments under `#[dae_model]`; its
//! body is a small language the macro reads (it is never run as Rust). The
//! macro generates a struct named after the function in UpperCamelCase,
//! with one `pub f64` field per parameter and a `Default` with the values
//! written.
//!
//! | statement | meaning |
//! |---|---|
//! | `let k = param(2.0);` | a parameter: a field of the struct, constant during a run |
//! | `let x = state(1.0);` | a state with its initial value (constants and parameters) |
//! | `let q = state_array([1.0, 0.0]);`, `state_array([0.0; N])`, `state_array((0..N).map(|i| ...))` | an array of states, `q[i]`; initial values by index with `map` |
//! | `der(x) == f;`, `der(der(x)) == a;` | an equation; second derivatives are reduced to first order (`init(der(x), v0)` sets the initial rate); `der(w)` of an algebraic `w` makes it a state the structure eliminates where its equation ties it to others |
//! | `state(x0).fixed()`, `.avoid()`, `.prefer()` | the start kept by initialization; the state eliminated, or kept, when connections tie it to others (Modelica's `fixed = true`, `StateSelect.avoid`, `.prefer`) |
//! | `init(c1.v, 0.0);` | a part's state started at a value, kept (Modelica's `C1(v(start = 0, fixed = true))`) |
//! | `initial(der(w) == 0.0);` | an equation that holds at the start only (Modelica's `initial equation`): it decides the start of a state it reads whose start is not fixed, solved by Newton's method before the first step (a steady start: `initial(der(x) == 0.0)` for each state); the values chosen are in `Solution::initial_corrections()`; an equation that can move no start, or more equations than the starts they can move, is a compile error |
//! | `lhs == rhs;` | any equation, in any order, also implicit in the derivatives (solved symbolically; see [`super::structure`]) |
//! | `let y = algebraic(0.0);` and `constraint(g);` | a DAE: see [`super::daes`] |
//! | `let i = algebraic_array([0.0; N]);` | an array of algebraic variables, `i[k]`: see [`super::structure`] |
//! | `let e = output(expr);` | a value computed from the solution, only when asked for |
//! | `let p = output_array((0..N).map(\|k\| expr));` | an array of outputs, read as `"p[k]"` |
//! | `let hit = event(g).falling().terminal();` | a zero crossing of `g`, located to machine precision |
//! | `event(h).falling().reinit(der(h), -e * pre(der(h)))` | an action at an event: a state set from the values there (`pre(x)`: just before): see [`super::hybrid`] |
//! | `let on = discrete(true);`, `if on { .. } else { .. }` | a value that changes only at events; a mode selecting equations |
//! | `let i = if v < -ve { a } else if v > ve { b } else { c };`, `if x > 1.0 { eqs } else { eqs }`, `min(a, b)`, `max(a, b)`, `sign(x)` | relations on model variables, with Modelica's event semantics: each relation is held in a discrete boolean `(v < -ve)` between events, and two events on it (named `(v < -ve)` where it turns true, `!(v < -ve)` where it turns false) switch it where it crosses; the run sets it from its value at the start; every method steps to the crossing and restarts there. `no_event(expr)` evaluates the relations in `expr` as steps without events, for an expression smooth enough at the switch |
//! | `heaviside(t - t0)`, a library step, ramp or pulse | a switch in the time alone: every method steps to `t0` exactly and restarts there |
//! | `let tick = every(0.01).reinit(u, expr);` | a clock: actions at each sample instant |
//! | `let u = input(0.0);` | a signal the caller supplies at run time (a function, a table) |
//! | `let t = time();` | the independent variable |
//! | `const N: usize = 3; for i in 0..N { ... }` | loops over constants, unrolled into equations; where the cells' equations differ only in the states they read, the generated right-hand side and Jacobian loop over a table of indices again (a 2048-state grid compiles in seconds); `if` on indices, `u[(i + 1) % N]` for a periodic neighbour, and `k / 2` truncating as in Rust (indices are integers; `1 / 3` of two literals is refused: write `1.0 / 3.0`) |
//! | `let r = rot_z(theta); let p = r * vec3(1.0, 0.0, 0.0);` | vectors and 3 × 3 matrices: see [`super::mechanisms`] |
//! | `let r1 = resistor(100.0);`, `r1.v`, `r1.p.i`, `let r = [resistor(1.0); N];` | an instance of a part (the standard library's or your `#[component]`), its variables by path: see [`super::components`] |
//! | `let p = pin();` (in a part), `connect(a.p, b.n);` | connectors, and equal potentials with flows summing to zero |
//! | `let f = \|dh\| cd * sqrt(dh);`, `f(h)` | a function of the model, inlined where it is called |
//!
//! Functions: `sin cos tan asin acos atan atan2 sinh cosh tanh exp ln sqrt
//! abs heaviside min max sign no_event`, `x.powi(n)`, `x.powf(a)`. The Taylor
//! methods need a smooth right-hand side between events (`abs` and
//! `heaviside` are refused there, with their span). Mistakes are compile
//! errors on the tokens at fault, with the fix: an unknown name suggests the
//! nearest declared one, `ln(0.0)` is refused as it is written.
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// Two coupled oscillators, a damping parameter and an output.
//! #[dae_model]
//! fn coupled() {
//!     let c = param(0.1);
//!     const N: usize = 2;
//!     let x = state_array([1.0, 0.0]);
//!     for i in 0..N {
//!         init(der(x[i]), 0.0);
//!     }
//!     der(der(x[0])) == -x[0] + 0.5 * (x[1] - x[0]) - c * der(x[0]);
//!     der(der(x[1])) == -x[1] + 0.5 * (x[0] - x[1]) - c * der(x[1]);
//!     /// Distance between the two.
//!     let gap = output(x[1] - x[0]);
//! }
//!
//! let sol = Coupled { c: 0.0 }.simulate(0.0, 10.0, &Options::new().tolerance(1e-10))?;
//! // Without damping, x0 − x1 oscillates at √2: x1 − x0 = −cos(√2 t).
//! assert!((sol.last("gap")? + (10.0 * 2f64.sqrt()).cos()).abs() < 1e-8);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! An event stops a run (`terminal`), acts (see [`super::hybrid`]) or is
//! only recorded; the solution lists the crossings:
//!
//! ```
//! use daegen::prelude::*;
//!
//! #[dae_model]
//! fn drop() {
//!     let h = state(1.0);
//!     der(der(h)) == -9.81;
//!     let ground = event(h).falling().terminal();
//! }
//!
//! let sol = Drop::default().simulate(0.0, 10.0, &Options::new())?;
//! let t = sol.event_times("ground")?[0];
//! assert!((t - (2.0f64 / 9.81).sqrt()).abs() < 1e-12);
//! # Ok::<(), daegen::Error>(())
//! ```
