//! # Equations in any order
//!
//! Write the equations as the physics reads them: Kirchhoff before Ohm, a
//! definition after its use, one `let` per element. The macro finds the
//! order itself, as a Modelica compiler or ModelingToolkit's
//! `structural_simplify` does, at compile time:
//!
//! 1. **Aliases** go first. An equation `a == b`, `a == -b`, `a + b == 0`
//!    or `a == c` (`c` a constant or an expression of the parameters),
//!    with `a` an algebraic variable, removes `a` and the equation (of two
//!    algebraic variables the one declared later goes); `a` stays
//!    readable by name, with its alias's value.
//! 2. **Matching and sorting.** Each equation is matched to the unknown
//!    it determines (a highest derivative or an algebraic variable), and
//!    the equations are sorted into blocks, each after the blocks whose
//!    unknowns it reads (the block-lower-triangular form, Tarjan's
//!    algorithm).
//! 3. **Block by block.** A block of one equation linear in its unknown
//!    is solved symbolically, and its solution is substituted into every
//!    equation after it, which may then use that unknown in any way
//!    (squared, under a root). A linear block of several equations is
//!    solved symbolically when its coefficients allow (Cramer's rule up
//!    to three unknowns, elimination with constant pivots beyond), else by
//!    an LU factorization at run time. Nonlinear algebraic equations are
//!    solved by Newton's method with their generated Jacobian, warm-started
//!    from the last solution, part by part: a grid's independent cells
//!    each by an iteration of their own.
//! 4. **Tearing.** Newton iterates on as few variables as it can: while
//!    some equation of the block determines one variable explicitly (its
//!    coefficient reading only variables already known), that variable
//!    is computed from it; when none does, the variable that appears in
//!    most equations is torn (Cellier & Kofman's heuristic). A part of
//!    more than 200 tearing variables is a compile error (its Jacobian
//!    lives on the stack).
//!
//! The chemical Akzo Nobel problem of the IVP test set, as its authors
//! write it, with its algebraic equation last and `y6` squared in two
//! rates: `y6` is solved first from `0 == ks * y1 * y4 - y6` and every
//! method integrates the five concentrations.
//!
//! ```
//! use daegen::prelude::*;
//!
//! #[dae_model]
//! fn akzo_nobel() {
//!     let k1 = param(18.7);
//!     let k2 = param(0.58);
//!     let k3 = param(0.09);
//!     let k4 = param(0.42);
//!     let kbig = param(34.4);
//!     let kla = param(3.3);
//!     let ks = param(115.83);
//!     let po2 = param(0.9);
//!     let hen = param(737.0);
//!     let y1 = state(0.444);
//!     let y2 = state(0.00123);
//!     let y3 = state(0.0);
//!     let y4 = state(0.007);
//!     let y5 = state(0.0);
//!     let y6 = algebraic(0.36);
//!     let r1 = k1 * y1.powi(4) * sqrt(y2);
//!     let r2 = k2 * y3 * y4;
//!     let r3 = k2 / kbig * y1 * y5;
//!     let r4 = k3 * y1 * y4 * y4;
//!     let r5 = k4 * y6 * y6 * sqrt(y2);
//!     let f_in = kla * (po2 / hen - y2);
//!     der(y1) == -2.0 * r1 + r2 - r3 - r4;
//!     der(y2) == -0.5 * r1 - r4 - 0.5 * r5 + f_in;
//!     der(y3) == r1 - r2 + r3;
//!     der(y4) == -r2 + r3 - 2.0 * r4;
//!     der(y5) == r2 - r3 + r5;
//!     0.0 == ks * y1 * y4 - y6;
//! }
//!
//! let opts = Options::new().method(Method::Radau5).rtol(1e-8).atol(1e-12);
//! let sol = AkzoNobel::default().simulate(0.0, 180.0, &opts)?;
//! // The test set's reference at t = 180.
//! assert!((sol.last("y1")? / 0.1150794920661702 - 1.0).abs() < 1e-5);
//! assert!((sol.last("y6")? / 0.4873531310307455e-2 - 1.0).abs() < 1e-5);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! ## Arrays of unknowns and outputs
//!
//! `algebraic_array([guess; N])` declares N algebraic variables `i[0]` …
//! `i[N-1]` (guesses as for `state_array`: a list, `[v; N]` or
//! `(0..N).map(|k| ...)`), and `output_array((0..N).map(|k| expr))` N
//! outputs `name[k]`; a ladder, a grid or a chain is a loop. An RC ladder
//! with its resistor currents as unknowns, and a capacitor discharging
//! through a diode, whose block in `i`, `vr` and `va` Newton solves on
//! `i` alone:
//!
//! ```
//! use daegen::prelude::*;
//!
//! #[dae_model]
//! fn rc_ladder() {
//!     const N: usize = 10;
//!     let r = param(1.0);
//!     let c = param(1.0);
//!     let v = state_array([1.0; N]);
//!     let i = algebraic_array([0.0; N]);
//!     for k in 0..N - 1 {
//!         c * der(v[k]) == i[k] - i[k + 1];
//!     }
//!     c * der(v[N - 1]) == i[N - 1];
//!     r * i[0] == -v[0];
//!     for k in 1..N {
//!         r * i[k] == v[k - 1] - v[k];
//!     }
//!     /// The voltage across each resistor.
//!     let drop = output_array((0..N).map(|k| r * i[k]));
//! }
//!
//! #[dae_model]
//! fn diode_discharge() {
//!     let r = param(10.0);
//!     let is = param(1e-9);
//!     let vt = param(0.025);
//!     let v = state(1.0);
//!     let i = algebraic(0.0);
//!     let vr = algebraic(0.0);
//!     let va = algebraic(0.0);
//!     let vd = algebraic(0.0);
//!     der(v) == -i;
//!     v == vr + vd;
//!     vd == va;
//!     vr == r * i;
//!     i == is * (exp(va / vt) - 1.0);
//! }
//!
//! let sol = RcLadder::default().simulate(0.0, 1.0, &Options::new())?;
//! assert_eq!(sol.last("drop[3]")?, sol.last("i[3]")?);
//! let text = DiodeDischarge::default().describe();
//! assert!(text.contains("structure: 1 alias removed, 1 equation solved one at a time, 1 block"));
//! assert!(text.contains("block of 3 equations: nonlinear, Newton on 1 tearing variable"));
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! `describe()` lists what the sorting found, and `Model::INFO.structure`
//! (a [`crate::StructureInfo`]) holds it: the aliases removed, the
//! equations solved one at a time, and each block with its size and how
//! it is solved ([`crate::BlockSolution`]: symbolically, by an LU of so
//! many unknowns, or by Newton on so many tearing variables).
//!
//! ## Structural mistakes
//!
//! A system that does not match is a compile error on the equations or
//! declarations at fault, naming the part of it that is over- or
//! under-determined (the Dulmage–Mendelsohn decomposition):
//!
//! ```text
//! error: these 3 equations determine only 2 unknowns, `i1`, `i2`:
//!        `2.0 * i1 == v`, `3.0 * i2 == v`, `i1 * i2 == v * v / 6.0`;
//!        remove one of them or add an unknown they determine
//! error: nothing determines `i3`: `i1 == 2.0 * i2 + 3.0 * i3` is left
//!        for 2 unknowns, `i2`, `i3`; add an equation
//! ```
//!
//! Not yet: an equation nonlinear in a highest derivative (`der(x) *
//! der(x) == x`) is refused, as Newton blocks hold algebraic variables only.
