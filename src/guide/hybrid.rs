//! # Hybrid models: events that act, modes, clocks and inputs
//!
//! A hybrid model has a continuous part, integrated by any method, and
//! instants where something happens: an event resets a state, a switch
//! changes mode, a controller samples, an input table turns a corner.
//!
//! | statement | meaning |
//! |---|---|
//! | `let bounce = event(h).falling().reinit(der(h), -e * pre(der(h)));` | at the crossing, set a state (or `der(h)` of a second-order `h`, or a discrete value) from the values there |
//! | `pre(x)` | in an action, the value of `x` just before the instant |
//! | `let on = discrete(true);` | a discrete value: constant between instants, set only by actions; `true`/`false` are 1 and 0 |
//! | `if on { v == 0.0; } else { i == 0.0; }`, `if gear == 2 { .. }` | a mode: the equations of the branch that holds |
//! | `if on { p } else { 0.0 }` | a value chosen by a mode |
//! | `let tick = every(0.01).offset(0.0).reinit(u, ..);` | a clock: actions at `offset + k·h` |
//! | `let u = input(0.0);` | a signal supplied at run time: the field `u: Input` |
//!
//! ## Actions
//!
//! `.reinit(target, value)` may be chained, on an event (with `.rising()`,
//! `.falling()`, `.terminal()`) or on a clock. An event that acts and a
//! clock may be written as statements without a name, as Modelica's
//! `when` is: `event(h).falling().reinit(..);`, `every(0.1).reinit(..);`;
//! they are then named by their text (`"event(h)"`, `"every(0.1)"`) in the
//! solution and in `describe()`. The actions of one instant
//! run in the order written, each on the state the ones before it left;
//! `pre(x)` reads the value before the instant. So a sampled PI reads:
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// x' = −2x + 3u under a PI controller sampled every 0.1 s.
//! #[dae_model]
//! fn sampled() {
//!     let h = param(0.1);
//!     let x = state(0.0);
//!     /// The controller's output, held between samples.
//!     let u = discrete(0.0);
//!     let integral = discrete(0.0);
//!     der(x) == -2.0 * x + 3.0 * u;
//!     let sample = every(h)
//!         .reinit(integral, integral + 1.5 * h * (1.0 - x))
//!         .reinit(u, 0.8 * (1.0 - x) + integral);
//! }
//!
//! let sol = Sampled::default().simulate(0.0, 1.0, &Options::new())?;
//! // The instants are stepped to, never over: one jump each, at k·h.
//! assert_eq!(sol.jumps().len(), 11);
//! assert_eq!(sol.jumps()[3].t, 0.30000000000000004);
//! // At t = 0 the controller sees e = 1: integral 0.15, u = 0.8 + 0.15.
//! assert_eq!(sol.at(0.0, "u")?, 0.9500000000000001);
//! assert_eq!(sol.at_left(0.0, "u")?, 0.0);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! A clock's first instant is its offset (0 by default); instants before
//! the start of the run are skipped, one at the start acts before the
//! first step, one at the end acts last (the run's final state is the
//! one after it). Its period and offset are constants or parameters; a run
//! with clocks goes forward in time.
//!
//! At one instant the actions run in rounds (Modelica's event
//! iteration): after a round every event function is evaluated again, and
//! an event whose function crossed zero in its direction because of the
//! actions fires in the next round. A round that fires nothing ends the
//! instant; after [`crate::MAX_EVENT_ITERATIONS`] rounds the run ends in
//! [`crate::Error::EventLoop`], naming the events. A terminal event fired
//! by an action stops the run after the instant.
//!
//! ## The solution at a jump
//!
//! [`crate::Solution::jumps`] lists every instant where actions changed
//! the state, with the state on either side and what acted. With every
//! step stored, such a time appears twice in `times()` (before, after);
//! [`crate::Solution::at`] gives the value after, `at_left` the value
//! before. Nothing is interpolated across a jump, and a discrete value is
//! read, never interpolated, between instants.
//!
//! ## How every method restarts
//!
//! The run integrates from one instant to the next (the next clock
//! instant, an input's breakpoint, or an event its method finds on the
//! step's continuous extension, where it cuts the step) and starts the
//! method afresh from the state after the instant:
//!
//! | method | what a restart resets |
//! |---|---|
//! | DOPRI5, DOP853 | the step (Hairer's starting step again), the error history of the step-size controller, the stiffness test's count |
//! | RADAU5 | the Jacobian, the factorised Newton matrices, the collocation polynomial the next Newton iteration starts from, the step |
//! | RODAS5P | the Jacobian, ∂f/∂t, the factorisation (or GMRES's preconditioner), the step |
//! | Taylor | the jet, the order and step chosen from it |
//! | Auto | its choice of method: each stretch starts with the explicit pair |
//! | fixed-step methods | equal steps of the run's step, fitted to the stretch |
//!
//! A restart allocates the method's work arrays again: once per instant,
//! never per step. `stats()` adds up every stretch; `Auto`'s `switches`
//! counts the hand-overs in all of them.
//!
//! A DAE's state after the actions is made consistent again, as at the
//! start of a run: the values the actions set are kept, the other states
//! are projected onto the constraints and their hidden levels (a pendulum
//! whose horizontal speed an action zeroes loses its vertical speed too);
//! where that cannot be done the run ends in [`crate::Error::Constraint`].
//!
//! A discrete value's column is left out of the Jacobian: it is constant
//! in a stretch, and its row of every Newton matrix stays its own, so it
//! keeps its value exactly. Members of an [`crate::Ensemble`] run apart,
//! each with its own instants. Not hybrid-aware, and refused with a
//! message: batch lanes (`#[dae_model(batch = L)]`) of a model with events
//! or inputs; forward sensitivities across a jump (they would need the
//! jump of the sensitivities, the saltation matrix); the mass-matrix
//! formulation of a DAE with actions, clocks or inputs; the Taylor methods
//! on a model that reads an input.
//!
//! ## Accumulating events
//!
//! A ball with restitution e bounces ever lower: its impacts accumulate at
//! t∞ = t₁ + 2e·v₁/(g(1 − e)), infinitely many in finite time. An event
//! firing again sooner than [`crate::Options::min_event_interval`] (1e-10
//! of the run's length by default) ends the run in
//! [`crate::Error::ZenoEvents`], which extrapolates where the firings
//! accumulate:
//!
//! ```
//! use daegen::prelude::*;
//!
//! #[dae_model]
//! fn ball() {
//!     let e = param(0.5);
//!     let h = state(10.0);
//!     der(der(h)) == -9.81;
//!     let bounce = event(h).falling().reinit(der(h), -e * pre(der(h)));
//! }
//!
//! let t1 = (2.0 * 10.0 / 9.81f64).sqrt();
//! let zeno = t1 + 2.0 * 0.5 * 9.81 * t1 / (9.81 * 0.5);
//! match Ball::default().simulate(0.0, 10.0, &Options::new().tolerance(1e-12)) {
//!     Err(Error::ZenoEvents { accumulation, partial, .. }) => {
//!         assert!((accumulation - zeno).abs() < 1e-9);
//!         assert!(partial.event_times("bounce")?.len() > 30);
//!     }
//!     other => panic!("{other:?}"),
//! }
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! ## Modes
//!
//! `if on { .. } else { .. }` on a discrete boolean (or `!on`, nested for
//! several), or `if gear == 1 { .. } else if gear == 2 { .. } else { .. }`
//! on a discrete integer, selects equations. The macro analyses each mode
//! alone at compile time (sorting, solving, aliases) and joins them into
//! one right-hand side, `Σ [the mode holds]·f_mode`: for a boolean
//! `on·f_on + (1 − on)·f_off`, exact for its 1 and 0; for an integer, the
//! polynomial in it that is 1 at the mode's value and 0 at its others,
//! exact to rounding. An integer mode takes the values it starts at, is
//! compared with, and is set to by actions, which must be whole numbers
//! (`.reinit(gear, 2)`); a boolean is 0 or 1 and may be set by any
//! expression that keeps it so (`.reinit(on, 1.0 - on)`). Each mode must
//! reduce to an explicit ODE in the same states (a sticking contact is
//! written with its constraint differentiated, `der(v) == 0.0`). Beyond
//! 64 modes (four clutches of three booleans make 4096), the modes factor:
//! the discrete values read together in guards form groups (each clutch's
//! own), each group's branches must hold as many equations (Modelica's
//! rule for an `if` on variables), and the k-th equation of every branch
//! is blended into one that holds in every mode, `Σ [the mode holds]·
//! residual`; the model is then analysed once, and the blocks whose
//! coefficients switch with the modes are solved at run time with
//! pivoting. A mode that does not determine its unknowns is a compile
//! error naming the mode. Every mode's expressions are evaluated at each
//! evaluation and summed, so each must stay finite in the states the others
//! visit (a mode dividing by a quantity that is zero while another mode
//! holds needs a guard in its expression). `if on { p } else { 0.0 }` as a
//! value takes a boolean; by an integer, write an equation in each branch.
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A half-wave rectifier: an ideal diode between a sine source behind
//! /// 1 Ω and an RC load.
//! #[dae_model]
//! fn rectifier() {
//!     let t = time();
//!     let v_c = state(1.0);
//!     let v_d = algebraic(0.0);
//!     let i = algebraic(0.0);
//!     let on = discrete(false);
//!     10.0 * sin(6.283185307179586 * t) == i + v_d + v_c;
//!     0.01 * der(v_c) == i - v_c / 100.0;
//!     if on {
//!         v_d == 0.0;
//!     } else {
//!         i == 0.0;
//!     }
//!     let opens = event(v_d).rising().reinit(on, true);
//!     let closes = event(i).falling().reinit(on, false);
//! }
//!
//! let sol = Rectifier::default().simulate(0.0, 1.0, &Options::new())?;
//! assert_eq!(sol.event_times("opens")?.len(), 1);
//! assert_eq!(sol.event_times("closes")?.len(), 1);
//! # Ok::<(), daegen::Error>(())
//! ```
//!
//! The standard library has `ideal_diode()` (this mode in a part),
//! `zero_order_hold(period)`, `sampled_pi(kp, ki, period)` and
//! `sampled_pid(kp, ki, kd, period)` (see [`super::components`]).
//!
//! ## Inputs
//!
//! `let u = input(u0);` makes the field `u: daegen::Input` (the constant
//! `u0` by default), read in the solution like an output. An
//! [`crate::Input`] is a constant, a function of the time, or a table
//! interpolated linearly ([`crate::Input::linear`]) or by Fritsch–Carlson
//! monotone cubics ([`crate::Input::monotone_cubic`]), held constant
//! outside its samples; a run steps to a table's breakpoints, so no step
//! straddles a kink. For co-simulation, set a constant input between
//! communication steps and run each with `simulate_from`. The input's rate
//! enters ∂f/∂t (RODAS5P) and the event rates; the Taylor methods, which
//! need every derivative of it, refuse a model that reads one, and an
//! equation that the index reduction differentiates may not read one.
//!
//! ```
//! use daegen::prelude::*;
//!
//! #[dae_model]
//! fn tank() {
//!     /// Inflow (m³/s).
//!     let q_in = input(0.0);
//!     let volume = state(0.0);
//!     der(volume) == q_in;
//! }
//!
//! let pump = Input::linear(&[0.0, 1.0, 3.0], &[0.0, 2.0, 2.0])?;
//! let tank = Tank { q_in: pump };
//! let sol = tank.simulate(0.0, 4.0, &Options::new().method(Method::Rk4))?;
//! // ∫ q_in = 1 + 4 + 2: exact, the breakpoints being stepped to.
//! assert!((sol.last("volume")? - 7.0).abs() < 1e-12);
//! assert_eq!(sol.at(0.5, "q_in")?, 1.0);
//! # Ok::<(), daegen::Error>(())
//! ```
