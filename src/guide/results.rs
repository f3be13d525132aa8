//! # Getting results out
//!
//! A [`crate::Solution`] answers by name: every state (`"x"`, and
//! `"der(x)"` for a higher-order state), algebraic variable and output;
//! [`crate::Solution::names`] lists them in that order, and
//! [`crate::Model::describe`] prints them with their doc comments.
//!
//! | to get | write |
//! |---|---|
//! | one value at the end, or at any time | `sol.last("x")?`, `sol.at(2.5, "x")?` |
//! | a column at the stored times | `sol.column("x")?` (with `sol.times()`) |
//! | values on your own grid | `sol.sample(&["x", "v"], &grid)?`, a [`crate::Table`] that prints aligned |
//! | a CSV file | `sol.write_csv(File::create("out.csv")?, &sol.names())?` |
//! | a plot (the `plot` feature, on by default) | `daegen::plot::time_series(&sol, &["x"], "x.svg")?`, `phase_portrait(&sol, "x", "v", ..)` |
//! | only some times stored | `Options::output_times(grid)` (SciPy's `t_eval`) |
//! | every step as it is taken, or stop early | `Options::on_step(\|step\| ..)` returning `Flow::Stop` |
//! | a progress bar for long runs | `Options::progress(true)` |
//! | JSON and other formats | the `serde` feature: `Solution` and `Table` serialize |
//!
//! Between the steps each method interpolates at its own order: DOPRI5's
//! continuous extension of order 4, DOP853's of order 7, RADAU5's
//! collocation polynomial, the Taylor polynomial of the step, and for the
//! fixed-step Runge–Kutta methods the cubic Hermite polynomial through
//! both ends of the step and their derivatives.
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A damped oscillator.
//! #[dae_model]
//! fn damped() {
//!     /// Damping ratio.
//!     let zeta = param(0.1);
//!     /// Displacement (m).
//!     let x = state(1.0);
//!     init(der(x), 0.0);
//!     der(der(x)) == -x - 2.0 * zeta * der(x);
//!     /// Energy (J).
//!     let energy = output(0.5 * (x * x + der(x) * der(x)));
//! }
//!
//! let model = Damped::default();
//! assert!(model.describe().contains("zeta = 0.1"));
//! let sol = model.simulate(0.0, 10.0, &Options::new().tolerance(1e-8))?;
//! assert_eq!(sol.names(), ["x", "der(x)", "energy"]);
//!
//! // On a grid, printed as a table.
//! let grid: Vec<f64> = (0..=10).map(f64::from).collect();
//! let table = sol.sample(&["x", "energy"], &grid)?;
//! println!("{table}");
//! assert_eq!(table.column("x").unwrap().len(), 11);
//!
//! // As CSV: a header row, then one row per stored time.
//! let mut csv = Vec::new();
//! sol.write_csv(&mut csv, &["x", "energy"])?;
//! assert!(String::from_utf8(csv).unwrap().starts_with("t,x,energy\n"));
//!
//! // Stored at the grid only, streamed, and stopped once the energy has
//! // fallen to a fifth of its start: constant memory however long the run.
//! let opts = Options::new()
//!     .output_times(grid.clone())
//!     .on_step(|step: &Step| {
//!         let (x, v) = (step.y[0], step.y[1]);
//!         if 0.5 * (x * x + v * v) < 0.1 { Flow::Stop } else { Flow::Continue }
//!     });
//! let sol = model.simulate(0.0, 10.0, &opts)?;
//! let stop = sol.cancelled_at().expect("the energy fell below 0.1");
//! assert!(sol.times().iter().all(|&t| t <= stop));
//! # Ok::<(), daegen::Error>(())
//! ```
