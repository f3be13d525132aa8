//! # Components and connectors
//!
//! A mechatronic model is built from parts of several domains, as in
//! Modelica or ModelingToolkit: each part is written once with its
//! parameters, its connectors and its equations, instantiated by name as
//! often as needed, and joined to others with `connect`, without saying
//! which variable is an input and which an output. The macro flattens
//! the parts into one model and simplifies it at compile time (aliases,
//! states tied by the connections, sorting, tearing), so the generated
//! code is that of the same physics written flat by hand.
//!
//! ## A circuit from the standard library
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// RC charging: a 10 V source through 100 Ω into 1 mF.
//! #[dae_model]
//! fn rc_charging() {
//!     let source = constant_voltage(10.0);
//!     let r1 = resistor(100.0);
//!     let c1 = capacitor(c = 1e-3, v0 = 0.0);
//!     let gnd = ground();
//!     connect(source.p, r1.p);
//!     connect(r1.n, c1.p);
//!     connect(c1.n, source.n, gnd.p);
//! }
//!
//! # fn main() -> Result<(), daegen::Error> {
//! let model = RcCharging { r1_r: 50.0, ..RcCharging::default() };
//! let sol = model.simulate(0.0, 0.2, &Options::new().rtol(1e-9).atol(1e-9))?;
//! let exact = 10.0 * (1.0 - (-0.2f64 / 0.05).exp());
//! assert!((sol.last("c1.v")? - exact).abs() < 1e-6);
//! // Every variable of every part reads by its path.
//! assert!((sol.last("r1.i")? - (10.0 - exact) / 50.0).abs() < 1e-7);
//! assert_eq!(<RcCharging as Model>::INFO.states, ["c1.v"]);
//! # Ok(())
//! # }
//! ```
//!
//! - `let r1 = resistor(100.0);` instantiates a part: its parameters in the
//!   order the part declares them, or by name (`capacitor(c = 1e-3)`),
//!   the rest at their defaults. A wrong name or too many arguments is a
//!   compile error that lists the part's parameters.
//! - Each parameter set to a number is a field of the generated struct,
//!   named by its path with `_` for `.`: `r1.r` is `model.r1_r`,
//!   `motor.emf.k` is `model.motor_emf_k`. A parameter set to an
//!   expression of the enclosing part's parameters (`resistor(r)` in a
//!   motor whose `r` is a parameter) is bound to it and has no field.
//! - Every variable reads by its path in a `Solution`: `r1.v`, `r1.p.i`,
//!   `motor.emf.w`, also when simplification removed it (its value is
//!   then computed from what it was replaced by).
//! - Arrays of parts: `let r = [resistor(1.0); N];` or
//!   `let cells = (0..N).map(|k| heat_capacitor(c = 10.0 * (k as f64 + 1.0)));`,
//!   read as `r[2].p`, `"cells[2].t"`.
//! - `describe()` shows the hierarchy of instances, and
//!   `ModelInfo::components` lists them.
//!
//! ## Connectors and `connect`
//!
//! | declared in a part | kind | potential | flow |
//! |---|---|---|---|
//! | `let p = pin();` | electrical | `v` (V) | `i` (A) |
//! | `let f = flange();` | rotational | `phi` (rad) | `tau` (N m) |
//! | `let f = translational_flange();` | translational | `s` (m) | `f` (N) |
//! | `let port = heat_port();` | thermal | `t` (K) | `q` (W) |
//! | `let u = real_input();`, `let y = real_output();` | signal | the value itself | none |
//!
//! A flow is positive into the part through the connector (Modelica's
//! convention). `connect(a, b, ...)` joins two or more connectors of one
//! kind: their potentials are equal and their flows sum to zero
//! (Kirchhoff's laws; Modelica Language Specification §9.2). Inside a
//! part, its own connectors count with the opposite sign, so a motor's pin
//! `p` joined to its armature's `p` carries the same current out that
//! enters the motor. A connector that nothing connects from outside has
//! zero flow, as in Modelica: an open pin carries no current. A signal
//! has one source (an output, or the part's own input seen from inside);
//! joining two outputs is a compile error, as is joining a pin to a
//! flange.
//!
//! `ground()` is both the scene's world frame and, through its pin
//! `gnd.p`, the electrical ground (`p.v = 0`); a model may declare as
//! many as its drawing has.
//!
//! ## Writing parts
//!
//! A part is a function in the model language under `#[component]`: its
//! parameters (`param`, with defaults), connectors, variables, equations,
//! and parts of its own. It needs no ground and no state; it is checked
//! when it is defined, with errors on its own tokens.
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A permanent-magnet DC motor between the pins `p` and `n`, driving
//! /// the flange `shaft`.
//! #[component]
//! fn dc_motor() {
//!     /// Armature resistance (Ω).
//!     let r = param(1.0);
//!     /// Motor constant (V s/rad).
//!     let k = param(0.05);
//!     /// Rotor inertia (kg m²).
//!     let j = param(1e-4);
//!     let p = pin();
//!     let n = pin();
//!     let shaft = flange();
//!     let armature = resistor(r);
//!     let winding = inductor(0.5e-3);
//!     let emf = emf(k);
//!     let rotor = inertia(j);
//!     connect(p, armature.p);
//!     connect(armature.n, winding.p);
//!     connect(winding.n, emf.p);
//!     connect(emf.n, n);
//!     connect(emf.flange, rotor.flange_a);
//!     connect(rotor.flange_b, shaft);
//! }
//!
//! /// The motor on 12 V with viscous friction at its shaft.
//! #[dae_model]
//! fn run_up() {
//!     let supply = constant_voltage(12.0);
//!     let motor = dc_motor(k = 0.05);
//!     let friction = damper(1e-4);
//!     let housing = fixed();
//!     let gnd = ground();
//!     connect(supply.p, motor.p);
//!     connect(supply.n, motor.n, gnd.p);
//!     connect(motor.shaft, friction.flange_a);
//!     connect(friction.flange_b, housing.flange);
//! }
//!
//! # fn main() -> Result<(), daegen::Error> {
//! let sol = RunUp::default().simulate(0.0, 5.0, &Options::new().rtol(1e-9).atol(1e-9))?;
//! // At rest: k i = b ω and V = R i + k ω, so ω = k V / (R b + k²).
//! let exact = 0.05 * 12.0 / (1.0 * 1e-4 + 0.05 * 0.05);
//! assert!((sol.last("motor.rotor.w")? - exact).abs() < 1e-6);
//! // The EMF's shaft angle, the damper's relative angle and the rotor's
//! // angle are one state: three states remain, as written by hand.
//! assert_eq!(<RunUp as Model>::INFO.states.len(), 3);
//! # Ok(())
//! # }
//! ```
//!
//! A part is an item like any other: it is called by the path it is
//! reachable by (`parts::dc_motor(..)`, or `dc_motor(..)` after a `use`),
//! from another module or another crate. A proc-macro sees only its own
//! item, so `#[component]` expands to a `macro_rules!` that carries the
//! part's definition (with the definitions of the parts it uses, fetched
//! when it is defined); a model that calls parts it does not know expands
//! to a call of their macros, which hand the definitions back to the
//! model's expansion (the tt-call pattern). A crate of parts needs no
//! more than `#[component]` on public functions and a dependency on
//! `daegen` under that name (see the workspace's `parts-example` crate,
//! used from another crate in its tests). A library part's name wins over
//! a part of yours with the same name: call yours by path
//! (`self::resistor(..)`). A name only like a library part's
//! (`conductor_g`, `my_damper`) is yours: it is fetched, never taken for a
//! misspelling, and where you have no such part the compiler says it
//! cannot find it.
//!
//! A state a part declares only to differentiate a connector's potential
//! (an EMF's shaft angle, a damper's relative angle, a speed sensor's
//! angle) is marked `state(0.0).avoid()`: when the connections tie it to
//! other states, it is the one eliminated. Of two tied states the one
//! kept carries the start: set the start value on the part whose state is
//! kept (a scene's coordinate, the first inertia of a rigid shaft), or
//! mark the state whose start you set `state(x0).fixed()`, which a tie
//! never eliminates while another state will do.
//!
//! ## What simplification does with a connected model
//!
//! The connections write many trivial equations (equal potentials,
//! opposite flows); alias elimination removes them. States that the
//! connections tie by an equation linear in them alone (a rotor and the
//! EMF on its shaft, two inertias joined rigidly, the two sides of a
//! gear, an inertia and a fixed flange) are then reduced to one: the tie
//! is solved for one of them, which is replaced with its derivatives
//! everywhere and stays readable. Modelica tools reach the same by index
//! reduction and dummy derivatives; a linear tie with constant
//! coefficients needs neither.
//!
//! A tie may hide behind the connections' potentials and flows: two
//! capacitors in parallel (`c1.v` and `c2.v` both the node's voltage), a
//! loop of capacitors (`c2.v = c1.v − c3.v` in a Cauer filter), a damper
//! behind a gear (its relative angle the load's angle less the rotor's
//! over the ratio), a voltage source across a capacitor (`c.v` the
//! source's `v(t)`). The equations that hide it over-determine the
//! unknowns they read (the over-determined part of the Dulmage–Mendelsohn
//! decomposition, Pantelides' structurally singular subset); where they
//! are linear with coefficients of parameters, their unknowns are
//! eliminated, the relation among the states left is the tie, and one
//! state goes by it: two capacitors in parallel keep one state, the Cauer
//! filter of five library capacitors and two inductors keeps five (as
//! Dymola), a source across a capacitor drives its current by the
//! source's derivative, `c dv/dt`. Which state of a tie goes: an
//! `.avoid()` one, never a `.fixed()` one (or one started with
//! `init(c3.v, 0.0)`) or a `.prefer()` one while another will do, then
//! the later declared. Where the part is linear in its unknowns but the
//! relation it leaves among the states is not (two nonlinear capacitors
//! in parallel, `q/c0 + k q³` each), the relation is a constraint
//! instead: both states stay, the index reduction differentiates it and
//! the run projects onto it, as for a constraint you write. So is a
//! relation the aliases of connected flanges leave among states alone: a
//! rod of your own joining the positions of two masses (`x.s * x.s +
//! y.s * y.s == l * l`, the planar pendulum from parts) keeps both
//! positions and velocities. There a Modelica tool selects states
//! dynamically, since neither position can be solved for along the whole
//! swing (the rod's gradient `(2x, 2y)` loses each part in turn); the
//! projection needs no choice, and holds wherever the gradient is not
//! zero. `describe()` says of each state so kept: "Kept: the connections
//! tie it to `vertical.s` by `horizontal.s^2 + vertical.s^2 - tie_l^2 =
//! 0`, …". What remains is sorted and torn as in [`super::structure`]. A connected model then has as many states as the
//! same physics written flat (a motor driving a slider-crank through a
//! gear keeps the winding's current and the crank's angle and rate).
//!
//! ## Mechanics and components together
//!
//! A named `revolute` or `prismatic` joint has a flange: `pivot.flange`
//! of a revolute is a rotational flange on the second body's angle
//! relative to the first about the joint's axis, whose torque acts on the
//! second body and its reaction on the first; `slide.flange` of a
//! prismatic is a translational flange on the displacement along its
//! axis, its force at the second body's joint point. A motor, a gear or a
//! spring-damper drives the mechanism through it, planar or in space, in
//! in body and in joint coordinates alike. In a planar scene the
//! angle is `θ_b − θ_a`; a spatial scene in body coordinates has no
//! coordinate for it, so the flange's angle is the state `pivot.angle`,
//! the relative rotation since the start integrated from the rates (in
//! joint coordinates it is tied to `pivot.q` and goes). A motor turning a
//! crank in joint coordinates keeps the hand-written model's states: the
//! joint's angle and rate and the winding's current.
//!
//! ```text
//! let pivot = revolute(ground, vec3(0.0, 0.0, 0.0), crank, vec3(-0.5 * r, 0.0, 0.0));
//! let motor = dc_motor();
//! let gear = ideal_gear(10.0);
//! connect(motor.shaft, gear.flange_a);
//! connect(gear.flange_b, pivot.flange);
//! ```
//!
//! ## Mistakes said in the model's terms
//!
//! - A circuit with no ground: "the node voltages of the circuit of
//!   `source`, `r1`, `c1` are fixed only up to a constant: connect a
//!   ground"; the same for springs nothing holds (connect an inertia or a
//!   `fixed()`) and conductors with no temperature fixed. The test is
//!   exact: adding a constant to every potential of the group leaves each
//!   equation unchanged, so the system is singular.
//! - Two ideal voltage sources across the same nodes.
//! - A misspelt part ("unknown part `resistr`; did you mean
//!   `resistor`?"), a wrong parameter name, connectors of different kinds,
//!   a member a part does not have.
//!
//! ## Functions
//!
//! A formula used in several places is a function of the model, a closure
//! bound by `let` and called like the built-in functions; each call is
//! inlined, reading the names the function saw where it was defined:
//!
//! ```
//! use daegen::prelude::*;
//!
//! /// A tank draining through an orifice (Torricelli).
//! #[dae_model]
//! fn draining_tank() {
//!     let cd = param(0.6);
//!     let a = param(1e-3);
//!     let orifice = |dh| cd * a * sqrt(2.0 * 9.81 * dh);
//!     let h = state(2.0);
//!     0.5 * der(h) == -orifice(h);
//!     let flow = output(orifice(h));
//! }
//! # fn main() {}
//! ```
//!
//! ## The standard library
//!
//! Each part as `library.dae` in `daegen-codegen` writes it; parameters in
//! call order, with their defaults; beside each, the part of the Modelica
//! Standard Library (MSL 4.0) it follows, where there is one.
//!
//! **Electrical** (pins `p`, `n`; `v = p.v − n.v`, `i = p.i = −n.i` for
//! the one-ports; two-ports `p1`, `n1`, `p2`, `n2` with `v1`, `i1`, `v2`,
//! `i2`):
//!
//! | part | MSL | equations |
//! |---|---|---|
//! | `ground()` | `Analog.Basic.Ground` | `p.v = 0` |
//! | `resistor(r = 1)` | `Basic.Resistor` | `v = r i` |
//! | `conductor(g = 1)` | `Basic.Conductor` | `i = g v` |
//! | `variable_resistor()`, `variable_conductor()` | `Basic.VariableResistor`, `Basic.VariableConductor` | input `r`: `v = r i`; input `g`: `i = g v` |
//! | `capacitor(c = 1, v0 = 0)` | `Basic.Capacitor` | `c dv/dt = i`, `v` a state |
//! | `inductor(l = 1, i0 = 0)` | `Basic.Inductor` | `l di/dt = v`, `i` a state |
//! | `ideal_transformer(n = 1)` | `Ideal.IdealTransformer` (no magnetization) | `v1 = n v2`, `i2 = −n i1` |
//! | `vcvs(gain = 1)`, `vccs(transconductance = 1)` | `Basic.VCV`, `Basic.VCC` | `v2 = gain v1`, `i2 = transconductance v1`; `i1 = 0` |
//! | `ccvs(transresistance = 1)`, `cccs(gain = 1)` | `Basic.CCV`, `Basic.CCC` | `v2 = transresistance i1`, `i2 = gain i1`; `v1 = 0` |
//! | `constant_voltage(voltage = 1)` | `Sources.ConstantVoltage` | `v = voltage` |
//! | `step_voltage(height = 1, start_time = 0, offset = 0)` | `Sources.StepVoltage` | `v = offset + height H(t − start_time)` |
//! | `sine_voltage(amplitude = 1, f = 1, phase = 0, offset = 0)` | `Sources.SineVoltage` | `v = offset + amplitude sin(2π f t + phase)` |
//! | `signal_voltage()` | `Sources.SignalVoltage` | input `u`: `v = u` |
//! | `constant_current(current = 1)`, `step_current(..)`, `sine_current(..)`, `signal_current()` | `Sources.ConstantCurrent`, … | as the voltages, `i = ..` |
//! | `diode(ids = 1e-6, vt = 0.04)` | `Semiconductors.Diode` (no `R`) | `i = ids (exp(v / vt) − 1)` |
//! | `ideal_diode()` | | discrete `on`: `v = 0` while `on`, `i = 0` while not; `on` set where `v` rises through 0, cleared where `i` falls through 0 |
//! | `piecewise_diode(ron = 1e-5, goff = 1e-5, v_knee = 0)` | `Ideal.IdealDiode` | `v = s (s < 0 ? 1 : ron) + v_knee`, `i = s (s < 0 ? goff : 1) + goff v_knee` |
//! | `ideal_opening_switch(ron = 1e-5, goff = 1e-5)`, `ideal_closing_switch(..)` | `Ideal.IdealOpeningSwitch`, `Ideal.IdealClosingSwitch` | input `control` (MSL's Boolean as 0 or 1): open, `i = goff v`, while `control > 0.5` (closed, for the closing switch), else closed, `v = ron i` |
//! | `emf(k = 1)` | `Basic.EMF` (no support) | flange `flange`: `v = k w`, `w = dφ/dt`, `flange.tau = −k i` |
//! | `ideal_opamp()` | `Ideal.IdealOpAmp3Pin` | pins `in_p`, `in_n`, `out`: `in_p.v = in_n.v`, `in_p.i = in_n.i = 0` |
//! | `voltage_sensor()`, `current_sensor()` | `Sensors.VoltageSensor`, `Sensors.CurrentSensor` | output `v`, `i`: no current, no voltage drop |
//!
//! **Rotational** (flanges `flange_a`, `flange_b`; `phi_rel = flange_b.phi
//! − flange_a.phi`). The gear, the EMF and the torque, angle, speed and
//! acceleration sources have a `support` flange, their housing, which
//! takes the reaction torque: connect it as MSL's `useSupport = true` does
//! (to a housing free to turn, a gear's carrier), or leave it, and it is
//! fixed, as MSL's `useSupport = false`. The translational sources have
//! one too. A part of yours declares one with `flange().support()`
//! (`translational_flange().support()`): where nothing connects it, its
//! angle (position) is zero rather than its torque (force).
//!
//! | part | MSL | equations |
//! |---|---|---|
//! | `inertia(j = 1, phi0 = 0, w0 = 0)` | `Components.Inertia` | `dφ/dt = w`, `j dw/dt = flange_a.tau + flange_b.tau`, both flanges at `φ` |
//! | `spring(c = 1, phi_rel0 = 0)` | `Components.Spring` | `tau = c (phi_rel − phi_rel0)` |
//! | `damper(d = 1)` | `Components.Damper` | `tau = d dphi_rel/dt` |
//! | `spring_damper(c = 1, d = 1, phi_rel0 = 0)` | `Components.SpringDamper` | `tau = c (phi_rel − phi_rel0) + d dphi_rel/dt` |
//! | `clutch(mu = 0.5, peak = 1, cgeo = 1, fn_max = 1)` | `Components.Clutch` (μ constant: MSL's default table) | input `f_normalized`, `fn = fn_max f_normalized`: no torque while `fn ≤ 0`; slipping `tau = ±cgeo fn mu` against `w_rel`; stuck (`mode` 1) `dw_rel/dt = 0` until `\|tau\|` exceeds `peak cgeo fn mu`; sticks where `w_rel` crosses zero |
//! | `brake(mu = 0.5, peak = 1, cgeo = 1, fn_max = 1)` | `Components.Brake` (μ constant) | `flange_a`, `flange_b` on one shaft, `w` against the `support`: as the clutch, braking `±cgeo fn mu` against `w`, stuck (`mode` 1) `dw/dt = 0` while the torque held stays within the peak |
//! | `ideal_gear(ratio = 1)` | `Components.IdealGear` | `flange_a.phi − support.phi = ratio (flange_b.phi − support.phi)`, `flange_b.tau = −ratio flange_a.tau`, `support.tau = −flange_a.tau − flange_b.tau` |
//! | `fixed(phi0 = 0)` | `Components.Fixed` | `flange.phi = phi0` |
//! | `torque_source(tau = 1)`, `signal_torque()` | `Sources.ConstantTorque`, `Sources.Torque` | `flange.tau = −tau`; input `u`: `−u` |
//! | `angle_source()` | `Sources.Position` (`exact = true`) | input `phi_ref`: `flange.phi = phi_ref`, differentiated by the index reduction where the mechanism needs it |
//! | `speed_source(phi0 = 0)`, `acceleration_source(phi0 = 0, w0 = 0)` | `Sources.Speed` (`exact = true`), `Sources.Accelerate` | input `w_ref`: `dφ/dt = w_ref`; input `a_ref`: `d²φ/dt² = a_ref` |
//! | `speed_sensor()`, `angle_sensor()`, `acceleration_sensor()` | `Sensors.SpeedSensor`, `Sensors.AngleSensor`, `Sensors.AccSensor` | output `w = dφ/dt`, `phi`, `a = d²φ/dt²` |
//! | `torque_sensor()`, `power_sensor()` | `Sensors.TorqueSensor`, `Sensors.PowerSensor` | between two flanges: output `tau = flange_a.tau`, `power = flange_a.tau w` |
//! | `relative_angle_sensor()`, `relative_speed_sensor()`, `relative_acceleration_sensor()` | `Sensors.RelAngleSensor`, `Sensors.RelSpeedSensor`, `Sensors.RelAccSensor` | output `phi_rel`, `w_rel`, `a_rel`, no torque |
//!
//! **Machines** (armature pins `pin_ap`, `pin_an`, field pins `pin_ep`,
//! `pin_en`, shaft `flange`; MSL's default losses, which are zero, at the
//! reference temperature, without support; the states `ia`, `ie`,
//! `phi_mechanical`, `w_mechanical`):
//!
//! | part | MSL | equations |
//! |---|---|---|
//! | `dc_permanent_magnet(va_nominal = 100, ia_nominal = 100, w_nominal = 149.23, ra = 0.05, la = 0.0015, jr = 0.15)` | `Machines.BasicMachines.DCMachines.DC_PermanentMagnet` | `la dia/dt = va − ra ia − psi_e w`, `jr dw/dt = psi_e ia + flange.tau`, `psi_e = (va_nominal − ra ia_nominal)/w_nominal` |
//! | `dc_electrical_excited(.., ie_nominal = 1, re = 100, le = 1, sigmae = 0)` | `DCMachines.DC_ElectricalExcited` | `le die/dt = ve − re ie`, `psi_e = le (1 − sigmae) ie`, the armature and torque with `k psi_e`, `k` from the nominal point |
//!
//! **Translational**:
//!
//! | part | MSL | equations |
//! |---|---|---|
//! | `mass(m = 1, s0 = 0, v0 = 0, l = 0)` | `Components.Mass` | `ds/dt = v`, `m dv/dt = flange_a.f + flange_b.f`, `flange_a.s = s − l/2`, `flange_b.s = s + l/2` |
//! | `translational_spring(c = 1, s_rel0 = 0)`, `translational_damper(d = 1)`, `translational_spring_damper(c = 1, d = 1, s_rel0 = 0)` | `Components.Spring`, `Components.Damper`, `Components.SpringDamper` | as the rotational ones with `s`, `v`, `f` |
//! | `rod(l = 0)` | `Components.Rod` | `flange_b.s = flange_a.s + l`, massless |
//! | `elasto_gap(c = 1, d = 1, s_rel0 = 0, n = 1)` | `Components.ElastoGap` | while `s_rel < s_rel0`: `f = −c \|s_rel − s_rel0\|^n + f_d`, the damping `d v_rel` bounded by the spring's force; apart, `f = 0` (continuous, no event) |
//! | `translational_fixed(s0 = 0)` | `Components.Fixed` | `flange.s = s0` |
//! | `force_source(force = 1)`, `signal_force()` | `Sources.ConstantForce`, `Sources.Force` | `flange.f = −force`; input `u`: `−u` |
//! | `position_source()`, `velocity_source(s0 = 0)` | `Sources.Position`, `Sources.Speed` (`exact = true`) | input `s_ref`: `flange.s = s_ref`; input `v_ref`: `ds/dt = v_ref` |
//! | `position_sensor()`, `velocity_sensor()`, `force_sensor()`, `relative_position_sensor()` | `Sensors.PositionSensor`, `Sensors.SpeedSensor`, `Sensors.ForceSensor`, `Sensors.RelPositionSensor` | output `s`, `v`, `f = flange_a.f`, `s_rel` |
//!
//! **Thermal** (ports `port`, or `port_a`/`port_b`; temperatures in K
//! unless named Celsius):
//!
//! | part | MSL | equations |
//! |---|---|---|
//! | `heat_capacitor(c = 1, t0 = 293.15)` | `Components.HeatCapacitor` | `c dT/dt = port.q`, `T` a state |
//! | `thermal_conductor(g = 1)`, `thermal_resistor(r = 1)` | `Components.ThermalConductor`, `Components.ThermalResistor` | `q = g (port_a.t − port_b.t)`; `port_a.t − port_b.t = r q` |
//! | `convection(h_a = 1)`, `signal_convection()` | `Components.Convection` (input `Gc`) | `q = h_a (solid.t − fluid.t)`; input `gc`: `q = gc (solid.t − fluid.t)` |
//! | `body_radiation(gr = 1)` | `Components.BodyRadiation` | `q = gr σ (port_a.t⁴ − port_b.t⁴)`, σ = 5.670374419e-8 |
//! | `fixed_temperature(t = 293.15)`, `fixed_temperature_celsius(t_c = 20)`, `signal_temperature()` | `Sources.FixedTemperature`, `Celsius.FixedTemperature`, `Sources.PrescribedTemperature` | `port.t = t`; `t_c + 273.15`; input `t` |
//! | `heat_flow_source(q = 0)`, `signal_heat_flow()` | `Sources.FixedHeatFlow`, `Sources.PrescribedHeatFlow` | `port.q = −q`; input `u`: `−u` |
//! | `temperature_sensor()`, `celsius_sensor()`, `fahrenheit_sensor()` | `Sensors.TemperatureSensor`, `Celsius.TemperatureSensor`, `Fahrenheit.TemperatureSensor` | output `t = port.t`, `t_c = t − 273.15`, `t_f = 1.8 t_c + 32` |
//! | `heating_resistor(r = 1, t_ref = 293.15, alpha = 0)` | `Analog.Basic.Resistor` (`useHeatPort`) | pins and `heat_port`: `v = r (1 + alpha (T − t_ref)) i`, `heat_port.q = −v i` |
//!
//! **Blocks** (inputs `u`, `u1`, `u2`, or `u_s` set point and `u_m`
//! measurement; output `y`):
//!
//! | part | MSL | equations |
//! |---|---|---|
//! | `constant(k = 1)`, `step(height = 1, start_time = 0, offset = 0)`, `ramp(height = 1, duration = 1, start_time = 0, offset = 0)`, `sine(amplitude = 1, f = 1, phase = 0, offset = 0, start_time = 0)` | `Sources.Constant`, `Sources.Step`, `Sources.Ramp`, `Sources.Sine` | sources; the sine is `offset` before `start_time`, `offset + amplitude sin(2π f (t − start_time) + phase)` from it |
//! | `pulse(amplitude = 1, width = 50, period = 1, offset = 0, start_time = 0)` | `Sources.Pulse` | `offset + amplitude` for `width` % of each period from `start_time`, else `offset`; switched by two clocks |
//! | `inverse_block_constraints()` | `Math.InverseBlockConstraints` | `u1 = u2`, `y1 = y2`: around a block, its output held to `u1`'s signal and its input given to `y1`'s block, solved backwards by the index reduction |
//! | `gain(k = 1)`, `add(k1 = 1, k2 = 1)`, `feedback()` | `Math.Gain`, `Math.Add`, `Math.Feedback` | `y = k u`, `y = k1 u1 + k2 u2`, `y = u1 − u2` |
//! | `integrator(k = 1, y0 = 0)` | `Continuous.Integrator` | `dy/dt = k u` |
//! | `derivative(k = 1, t = 0.01, x0 = 0)` | `Continuous.Derivative` | `y = k (u − x)/t`, `t dx/dt = u − x` |
//! | `first_order(k = 1, t = 1, y0 = 0)` | `Continuous.FirstOrder` | `t dy/dt + y = k u` |
//! | `limiter(u_max = 1, u_min = −1)` | `Nonlinear.Limiter` | `y = max(u_min, min(u_max, u))`, switched by events at the limits |
//! | `rate_limiter(rising = 1, falling = −1, td = 0.001, y0 = 0)` | `Nonlinear.SlewRateLimiter` | `dy/dt = max(falling, min(rising, (u − y)/td))`, switched by events at the limits |
//! | `dead_zone(u_max = 1, u_min = −1)` | `Nonlinear.DeadZone` | `y = 0` inside, `u − u_max` above, `u − u_min` below |
//! | `saturation(y_max = 1, y_min = −1, eps = 1e-3)` | | `y = u` within the limits, corners rounded over `eps` (`\|y − clamp(u)\| ≤ eps/2`): smooth, for the Taylor methods |
//! | `pi_controller(kp = 1, ki = 1)` | `Continuous.PI` (as gains) | `y = kp e + x`, `dx/dt = ki e`, `e = u_s − u_m` |
//! | `pid_controller(kp = 1, ki = 1, kd = 0, td = 1e-3)` | `Continuous.PID` (as gains) | plus `kd (e − d)/td`, `td dd/dt = e − d` |
//! | `limited_pi(kp, ki, y_max = 1, y_min = −1, k_aw = 1, eps = 1e-3)`, `limited_pid(kp, ki, kd, td, y_max, y_min, k_aw, eps)` | `Continuous.LimPID` (as gains) | `y = sat(v)`, `dx/dt = ki e + k_aw (y − v)` (back-calculation anti-windup) |
//! | `lim_pi(k = 1, ti = 0.5, y_max = 1, y_min = −1, ni = 0.9, xi_start = 0)` | `Continuous.LimPID` (`controllerType = PI`) | `v = k (e + x_i)`, `y = max(y_min, min(y_max, v))` (events at the limits), `ti dx_i/dt = e + (y − v)/(k ni)`; MSL's `initType`: `init(pi.x_i, xi_start)` (InitialState), `initial(der(pi.x_i) == 0.0)` (SteadyState), `initial(pi.y == y_start)` (InitialOutput) |
//! | `kinematic_ptp(delta_q = 1, qd_max = 1, qdd_max = 1, start_time = 0)` | `Sources.KinematicPTP` (one axis) | the acceleration of a move by `delta_q`: `±qdd_max` speeding up and slowing down, 0 between, switched at instants every method steps to |
//! | `zero_order_hold(period = 0.01)` | `Discrete.ZeroOrderHold` | `y` = `u` at the instants `k·period`, held between |
//! | `sampled_pi(kp = 1, ki = 1, period = 0.01)` | | at each instant `x ← x + ki·period·e`, then `y ← kp e + x`; held between |
//! | `sampled_pid(kp = 1, ki = 1, kd = 0, period = 0.01)` | | plus `kd (e − e_prev)/period`, `e_prev ← e` |
//!
//! Sources switching in time (`step_voltage`, `step`, `ramp`) use the
//! step function `heaviside(x)` (0 below zero, 1 above) of the time
//! alone: every method steps to the switch exactly, as to an event known
//! in advance. Parts switching on a variable (`limiter`, `dead_zone`,
//! `piecewise_diode`, the switches) hold each relation between events and
//! switch where it crosses, as Modelica does. A model whose states do not
//! bound its steps (a circuit of sources, resistors and diodes alone)
//! needs `Options::max_step` shorter than the time between two crossings,
//! which one long step could pass over unseen.
