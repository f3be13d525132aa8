//! # Functional Mock-up Units: a model in the tools engineers already use
//!
//! Any `#[dae_model]` becomes an FMU (FMI 3.0 and 2.0, each with Model
//! Exchange and Co-Simulation) that FMPy, Simulink, Dymola, OpenModelica,
//! a hardware-in-the-loop rig or the Rust `fmi` crate can load. The crate
//! `daegen-fmi` (folder `fmi/`) provides the exported C functions and the
//! packaging command.
//!
//! ## One crate, one command
//!
//! An FMU is a C library, so the model lives in a crate of its own of type
//! `cdylib`:
//!
//! ```toml
//! [package]
//! name = "tank"
//!
//! [lib]
//! crate-type = ["cdylib"]
//!
//! [dependencies]
//! daegen = { path = "../daegen", default-features = false }
//! daegen-fmi = { path = "../daegen/fmi" }
//! ```
//!
//! ```text
//! // src/lib.rs
//! use daegen::prelude::*;
//!
//! /// A tank drained through an orifice, filled by an inflow from outside.
//! #[dae_model]
//! pub fn tank() {
//!     /// Outflow coefficient.
//!     let k = param(0.5);
//!     /// Inflow (m³/s).
//!     let q = input(0.2);
//!     /// Level (m).
//!     let h = state(1.0);
//!     der(h) == q - k * sqrt(h);
//!     /// Outflow (m³/s).
//!     let outflow = output(k * sqrt(h));
//! }
//!
//! daegen_fmi::export_fmu!(Tank);
//! ```
//!
//! Install the packaging command once, then run it in the crate:
//!
//! ```text
//! cargo install --path ../daegen/fmi      # installs cargo-fmu
//! cargo fmu --release
//! ```
//!
//! It builds the crate's `cdylib` targets (every other argument goes to
//! `cargo build`: `-p`, `--example`, `--target`, …) and writes, for each,
//! `target/fmu/tank.fmu` (FMI 3.0) and `target/fmu/tank_fmi2.fmu`
//! (FMI 2.0), or into `--out DIR`. `target/` is cargo's target
//! directory: with `CARGO_TARGET_DIR` set (or `build.target-dir` in a
//! cargo configuration), the archives go to `fmu/` under that folder
//! instead; the command's last line says where they went. An FMU archive holds one
//! `modelDescription.xml`, hence one version each; both hold the same
//! library, which exports every function of both standards. The model
//! identifier, and the library's name in `binaries/<platform>/`, is the
//! crate's name. The archives are stored zip files with fixed dates: the
//! same library makes the same bytes.
//!
//! ## What the description says
//!
//! `modelDescription.xml` comes from what the macro knows, with each doc
//! comment's first paragraph as the description. The value references
//! are the same in both versions:
//!
//! | value references | variables | causality, variability |
//! |---|---|---|
//! | 0 | `time` | independent |
//! | 1 … n | the states (`x`, `der(x)` of a second-order `x`, `motor.rotor.w`) | local, continuous; a discrete value discrete |
//! | next | each rate not itself a state: `der(x)`, `der(x,2)` | local, calculated, `derivative` of its state |
//! | next | the parameters, with this build's defaults as start values | parameter, tunable |
//! | next | the inputs (`input(..)`) | input, continuous |
//! | next | the values read by name: the model's own outputs (`let e = output(..)` at its level, causality output), then every other (a part's outputs, variables the structure eliminated, a scene's coordinates: local), then the algebraic variables (`lambda`, `motor.emf.i`: local) | output / local, calculated |
//! | next | the event functions, by the event's name | local; FMI 3.0's `EventIndicator`s |
//! | last two | `solver.method` (string), `solver.tolerance` | parameter, fixed |
//!
//! A name FMI's structured naming does not accept (an unnamed event,
//! `event(h)`) is quoted: `'event(h)'`. The model structure lists each
//! derivative's dependencies from the generated Jacobian's pattern (no
//! list, "depends on everything", where the Jacobian is differenced or
//! inputs and discrete values enter), the outputs, and the initial
//! unknowns; a DAE's states start as `approx`, since initialization may
//! move them onto the constraints. The GUID (FMI 2.0) or instantiation
//! token (3.0) is a hash of the description: it changes when the model
//! does, and an instance refuses a token that is not its own.
//!
//! ## Model Exchange
//!
//! The importer integrates; the FMU hands it the generated right-hand
//! side, the event functions as event indicators, and directional
//! derivatives from the symbolic Jacobian (∂ rates/∂ states exactly;
//! with respect to inputs and parameters, and of outputs, by central
//! differences).
//!
//! - **A DAE** goes out in its index-reduced form: the states the run API
//!   integrates, with the algebraic variables solved from the
//!   constraints differentiated to the level where they solve. Any
//!   integrator drifts off the original constraints; after each completed
//!   integrator step the FMU measures them and, past the tolerance (the
//!   experiment's, else 1e-6, relative to the state's size), asks for an
//!   event, in which it projects the state back onto the constraints and
//!   their hidden levels (`valuesOfContinuousStatesChanged`), as a native
//!   run projects after each step. Initialization makes the start
//!   consistent the same way.
//! - **Events** act when their function crossed zero in their direction
//!   since the last point the importer completed: `.rising()` and
//!   `.falling()` keep their meaning although FMI's indicators are
//!   undirected. Their actions run in the rounds of a native run;
//!   a terminal event sets `terminateSimulation`.
//! - **Clocks** are time events: `nextEventTime` is the next instant,
//!   and each instant acts once.
//! - **Inputs** hold the value the importer sets.
//! - A model in mass-matrix form only cannot go out as Model Exchange
//!   (instantiation says so); Co-Simulation runs it.
//!
//! ## Co-Simulation
//!
//! `doStep` integrates with daegen's own methods: a run of
//! `solver.method` (`Auto` by default; `Taylor`, `Dopri5`, `Dop853`,
//! `Radau5`, `Rodas5P`) at `solver.tolerance` (0, the default, means the
//! experiment's tolerance, else 1e-6; the absolute tolerance is 1e-3 of
//! it), from the instance's state over the communication step, inputs
//! held, events and clocks acting inside the step (an instant at a
//! communication point acts at the end of the step that reaches it, once).
//! A terminal event ends the step early: FMI 3.0 says
//! `terminateSimulation` with the time in `lastSuccessfulTime`; FMI 2.0
//! returns `fmi2Discard`, with `fmi2Terminated` and
//! `fmi2LastSuccessfulTime` to ask. A step that fails (a stiff problem
//! for an explicit method, an accumulation of events) returns `Error`
//! with the run's message, and the instance keeps its state before the
//! step. Both interfaces get and set the FMU state and serialize it.
//!
//! ## Misuse
//!
//! Every exported function checks its arguments and the call order of
//! its standard's state machine. A null pointer, an unknown value
//! reference, a call in the wrong state, a wrong array size, a value that
//! is not finite or an FMU state of another model returns `Error` and
//! logs what was wrong through the importer's callback:
//!
//! ```text
//! fmi3GetContinuousStateDerivatives: not allowed in Instantiated; allowed in
//!     Initialization Mode, Event Mode, Continuous-Time Mode, Terminated
//! fmi3SetFloat64: VanDerPol has no variable with value reference 999 (they run from 0 to 7)
//! ```
//!
//! Instances and FMU states are handles looked up on every call, so a
//! freed or foreign pointer is refused, not dereferenced. Instances are
//! independent: several in one process, each on its own thread; one
//! instance called from two threads at once refuses the second call. A
//! panic inside becomes `Fatal`, never an unwind across the boundary.
//!
//! Not offered (each function exists and returns `Error` with a message,
//! since importers load every symbol): scheduled execution, clock
//! variables (clocks are time events), structural parameters, adjoint
//! derivatives, output derivatives and input interpolation in
//! Co-Simulation, Co-Simulation's event mode and intermediate updates,
//! and variables of types other than Float64 and String.
//!
//! ## Using the FMU
//!
//! With FMPy (`python3 -m pip install fmpy`):
//!
//! ```text
//! fmpy validate target/fmu/tank.fmu
//! python3 -c "
//! from fmpy import simulate_fmu
//! me = simulate_fmu('target/fmu/tank.fmu', fmi_type='ModelExchange', stop_time=10, relative_tolerance=1e-9)
//! cs = simulate_fmu('target/fmu/tank.fmu', fmi_type='CoSimulation', stop_time=10,
//!                   start_values={'solver.method': 'Radau5', 'solver.tolerance': 1e-10})
//! print(me['h'][-1], cs['h'][-1])"
//! ```
//!
//! The tests of `daegen-fmi` export Van der Pol's oscillator, the
//! pendulum DAE, a slider-crank scene, a PI speed drive of library parts,
//! a bouncing ball, a sampled controller and a tank with an input; FMPy
//! validates each and runs it in both interfaces and both versions
//! against the native run (FMPy from an environment the tests make under
//! `target/python-peers/`), and an importer of the tests' own unpacks the
//! archives and calls the C functions by the standards' names.
