//! # Coming from Modelica
//!
//! A Modelica model written with the Modelica Standard Library (MSL)
//! becomes a daegen model line for line: each instance a `let` of the
//! library part of the same name in snake case, each `connect` the same
//! `connect`, each modifier a named argument. The library's tables
//! ([`super::components`]) name MSL's part beside each of ours; the
//! examples of MSL that run against MAP-LIB's reference results are in the
//! workspace's `tests/models/msl.rs`.
//!
//! | Modelica | daegen |
//! |---|---|
//! | `model M … end M;` | `#[dae_model] fn m() { … }`, the type `M` |
//! | `parameter Real k = 2;` | `let k = param(2.0);` (a field of `M`, set before a run) |
//! | `parameter Real c2 = 1/(k*l1);`, computed from others | a value: `let c2 = 1.0 / (k * l1);` |
//! | `Real x(start = 1);`, differentiated | `let x = state(1.0);` |
//! | `x(start = 1, fixed = true)` | `state(1.0).fixed()`; on a part's state, `init(part.x, 1.0)` |
//! | `Real y;`, not differentiated | `let y = algebraic(0.0);`, its start Newton's first guess |
//! | `der(x) = -x;` | `der(x) == -x;` |
//! | `initial equation der(x) = 0;` | `initial(der(x) == 0.0);` |
//! | `stateSelect = StateSelect.prefer`, `.avoid` | `state(..).prefer()`, `.avoid()` |
//! | `Resistor R1(R = 10);` | `let r1 = resistor(10.0);` or `resistor(r = 10.0)` |
//! | `connect(a.p, b.n);` | `connect(a.p, b.n);`, or several at once: `connect(a.p, b.n, c.p);` |
//! | `useSupport = true`, `connect(gear.support, fixed.flange)` | `connect(gear.support, housing.flange);`; left alone, the support is fixed, MSL's `useSupport = false` |
//! | `if v > 0 then a else b` on variables | `if v > 0.0 { a } else { b }`, switched by events where `v` crosses 0 |
//! | `noEvent(if v > 0 then a else b)` | `no_event(if v > 0.0 { a } else { b })` |
//! | `min`, `max`, `abs`, `sign`, `sqrt`, `exp`, `sin`, … | the same names |
//! | `experiment(StopTime = 1, Tolerance = 1e-6)` | `M::default().simulate(0.0, 1.0, &Options::new().tolerance(1e-6))` |
//! | a result's `inertia3.w` | `sol.at(t, "inertia3.w")` |
//!
//! Names: MSL's instance `springDamper3` is `spring_damper3`; a capital
//! name that meets a parameter's in lower case (MSL's capacitor `C1` of a
//! filter whose capacitance is the parameter `c1`) takes another,
//! `cap1`. A part of your own named exactly like a library part is taken
//! for the library's ([`super::components`]).
//!
//! ## An example: `Modelica.Mechanics.Rotational.Examples.First`
//!
//! MSL's first drive train: a sine torque on a motor inertia, a 10:1 gear
//! whose housing is damped, an elastic shaft to a load. Its Modelica
//! source declares `Torque torque(useSupport = true)`, `IdealGear
//! idealGear(ratio = 10, useSupport = true)`, `Inertia inertia2(J = 2,
//! phi(fixed = true, start = 0), w(fixed = true, start = 0))`,
//! `Spring spring(c = 1e4, phi_rel(fixed = true))`, and so on:
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// MSL's `Rotational.Examples.First`.
//! #[dae_model]
//! fn first() {
//!     let housing = fixed();
//!     let sine = sine(amplitude = 10.0, f = 5.0);
//!     let torque = signal_torque();
//!     connect(sine.y, torque.u);
//!     connect(torque.support, housing.flange);
//!     let inertia1 = inertia(j = 0.1);
//!     let ideal_gear = ideal_gear(10.0);
//!     connect(ideal_gear.support, housing.flange);
//!     let inertia2 = inertia(j = 2.0);
//!     init(inertia2.phi, 0.0);
//!     init(inertia2.w, 0.0);
//!     let spring = spring(c = 1e4);
//!     let inertia3 = inertia(j = 2.0);
//!     init(inertia3.w, 0.0);
//!     let damper = damper(10.0);
//!     connect(torque.flange, inertia1.flange_a);
//!     connect(inertia1.flange_b, ideal_gear.flange_a);
//!     connect(ideal_gear.flange_b, inertia2.flange_a);
//!     connect(inertia2.flange_b, spring.flange_a, damper.flange_a);
//!     connect(spring.flange_b, inertia3.flange_a);
//!     connect(damper.flange_b, housing.flange);
//! }
//!
//! # fn main() -> Result<(), daegen::Error> {
//! let sol = First::default().simulate(0.0, 1.0, &Options::new().tolerance(1e-6))?;
//! // The gear ties the motor's angle to the load side's: the states are
//! // the angles and speeds of inertia2 and inertia3 (and the sine's
//! // relation `t < start_time`, a discrete value).
//! let states = <First as Model>::INFO.states;
//! for name in ["inertia2.phi", "inertia2.w", "inertia3.phi", "inertia3.w"] {
//!     assert!(states.contains(&name), "{states:?}");
//! }
//! assert!(!states.contains(&"inertia1.phi"));
//! let w3 = sol.last("inertia3.w")?;
//! assert!(w3.is_finite());
//! # Ok(())
//! # }
//! ```
//!
//! Its run is inside the tube csv-compare draws around MAP-LIB's reference
//! result for this example, as are the other examples of
//! `tests/models/msl.rs` (electrical, rotational, translational, thermal,
//! blocks and machines); bench/README.md tabulates them.
