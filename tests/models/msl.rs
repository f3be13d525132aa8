// Examples of the Modelica Standard Library 4.0.0, each rewritten with
// daegen's library as a Modelica user connects it (MSL's instance names
// kept, lower case where ours are), shared by tests/msl_examples.rs, which
// compares each with MAP-LIB's reference (tests/msl/), and the bench's
// table of them (`--msl`). Where a rewrite departs from the Modelica
// source, its doc comment says how and why.

/// One of MSL's examples: the name of its reference (tests/msl/`name`.csv),
/// the signals compared (MSL's name, ours), its states, and its run to `t1`.
pub struct MslExample {
    /// The reference's name: MSL's example's.
    pub name: &'static str,
    /// The compared signals: MSL's name, ours.
    pub signals: &'static [(&'static str, &'static str)],
    /// The continuous states of our model.
    pub states: usize,
    /// Its doc comment: what it is, and where the rewrite departs from
    /// MSL's source.
    pub doc: &'static str,
    /// Runs it from 0 to `t1`.
    pub run: fn(f64, &Options) -> Result<Solution, Error>,
}

/// Every example, in the order of the table.
#[allow(dead_code)]
pub fn msl_examples() -> Vec<MslExample> {
    vec![
        MslExample {
            name: "First",
            signals: &[("damper.phi_rel", "damper.phi_rel"), ("damper.w_rel", "damper.w_rel"), ("inertia3.phi", "inertia3.phi"), ("inertia3.w", "inertia3.w")],
            states: <First as Model>::STATES - <First as Model>::INFO.discrete.len(),
            doc: <First as Model>::INFO.doc,
            run: |t1, options| First::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "TwoMasses",
            signals: &[("mass1.T", "mass1.t"), ("mass2.T", "mass2.t")],
            states: <TwoMasses as Model>::STATES - <TwoMasses as Model>::INFO.discrete.len(),
            doc: <TwoMasses as Model>::INFO.doc,
            run: |t1, options| TwoMasses::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "CauerLowPassAnalog",
            signals: &[("C1.v", "cap1.v"), ("C3.v", "cap3.v"), ("C5.v", "cap5.v"), ("L1.i", "ind1.i"), ("L2.i", "ind2.i")],
            states: <CauerLowPassAnalog as Model>::STATES - <CauerLowPassAnalog as Model>::INFO.discrete.len(),
            doc: <CauerLowPassAnalog as Model>::INFO.doc,
            run: |t1, options| CauerLowPassAnalog::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "Oscillator",
            signals: &[("damper1.s_rel", "damper1.s_rel"), ("damper1.v_rel", "damper1.v_rel"), ("mass1.s", "mass1.s"), ("mass1.v", "mass1.v")],
            states: <Oscillator as Model>::STATES - <Oscillator as Model>::INFO.discrete.len(),
            doc: <Oscillator as Model>::INFO.doc,
            run: |t1, options| Oscillator::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "Damper",
            signals: &[("damper1.s_rel", "damper1.s_rel"), ("damper1.v_rel", "damper1.v_rel"), ("damper2.s_rel", "damper2.s_rel"), ("damper2.v_rel", "damper2.v_rel"), ("springDamper3.s_rel", "spring_damper3.s_rel"), ("springDamper3.v_rel", "spring_damper3.v_rel")],
            states: <DamperExample as Model>::STATES - <DamperExample as Model>::INFO.discrete.len(),
            doc: <DamperExample as Model>::INFO.doc,
            run: |t1, options| DamperExample::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "Rectifier",
            signals: &[("Capacitor1.v", "capacitor1.v"), ("Capacitor2.v", "capacitor2.v"), ("Inductor2.i", "inductor2.i"), ("Inductor3.i", "inductor3.i")],
            states: <Rectifier as Model>::STATES - <Rectifier as Model>::INFO.discrete.len(),
            doc: <Rectifier as Model>::INFO.doc,
            run: |t1, options| Rectifier::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "DCPM_Start",
            signals: &[("dcpm.la.i", "dcpm.ia"), ("loadInertia.phi", "load_inertia.phi"), ("loadInertia.w", "load_inertia.w")],
            states: <DcpmStart as Model>::STATES - <DcpmStart as Model>::INFO.discrete.len(),
            doc: <DcpmStart as Model>::INFO.doc,
            run: |t1, options| DcpmStart::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "DCEE_Start",
            signals: &[("dcee.airGapDC.psi_e", "dcee.psi_e"), ("dcee.la.i", "dcee.ia"), ("loadInertia.phi", "load_inertia.phi"), ("loadInertia.w", "load_inertia.w")],
            states: <DceeStart as Model>::STATES - <DceeStart as Model>::INFO.discrete.len(),
            doc: <DceeStart as Model>::INFO.doc,
            run: |t1, options| DceeStart::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "PreLoad",
            signals: &[("friction.v_rel", "friction.v_rel"), ("innerContactA.s_rel", "inner_contact_a.s_rel"), ("innerContactB.s_rel", "inner_contact_b.s_rel"), ("outerContactA.v_rel", "outer_contact_a.v_rel"), ("outerContactB.s_rel", "outer_contact_b.s_rel"), ("outerContactB.v_rel", "outer_contact_b.v_rel")],
            states: <PreLoad as Model>::STATES - <PreLoad as Model>::INFO.discrete.len(),
            doc: <PreLoad as Model>::INFO.doc,
            run: |t1, options| PreLoad::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "InverseModel",
            signals: &[("firstOrder1.y", "first_order1.y"), ("firstOrder2.y", "first_order2.y")],
            states: <InverseModel as Model>::STATES - <InverseModel as Model>::INFO.discrete.len(),
            doc: <InverseModel as Model>::INFO.doc,
            run: |t1, options| InverseModel::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "CoupledClutches",
            signals: &[("J1.phi", "j1.phi"), ("J1.w", "j1.w"), ("clutch1.phi_rel", "clutch1.phi_rel"), ("clutch1.w_rel", "clutch1.w_rel"), ("clutch2.phi_rel", "clutch2.phi_rel"), ("clutch2.w_rel", "clutch2.w_rel"), ("clutch3.phi_rel", "clutch3.phi_rel"), ("clutch3.w_rel", "clutch3.w_rel")],
            states: <CoupledClutches as Model>::STATES - <CoupledClutches as Model>::INFO.discrete.len(),
            doc: <CoupledClutches as Model>::INFO.doc,
            run: |t1, options| CoupledClutches::default().simulate(0.0, t1, options),
        },
        MslExample {
            name: "PID_Controller",
            signals: &[
                ("PI.I.y", "pi.x_i"),
                ("inertia1.phi", "inertia1.phi"),
                ("inertia1.w", "inertia1.w"),
                ("integrator.y", "integrator.y"),
                ("spring.phi_rel", "spring.phi_rel"),
                ("spring.w_rel", "spring.w_rel"),
            ],
            states: <PidControllerExample as Model>::STATES
                - <PidControllerExample as Model>::INFO.discrete.len(),
            doc: <PidControllerExample as Model>::INFO.doc,
            run: |t1, options| PidControllerExample::default().simulate(0.0, t1, options),
        },
    ]
}

/// `Modelica.Mechanics.Rotational.Examples.First`: a motor driving a load
/// through a gear and an elastic shaft, the gear's bearing damped; the
/// torque source's and the gear's supports on the housing, as MSL's
/// `useSupport = true` connects them.
#[dae_model]
fn first() {
    let housing = fixed();
    let sine = sine(amplitude = 10.0, f = 5.0);
    let torque = signal_torque();
    connect(sine.y, torque.u);
    connect(torque.support, housing.flange);
    let inertia1 = inertia(j = 0.1);
    let ideal_gear = ideal_gear(10.0);
    let inertia2 = inertia(j = 2.0);
    init(inertia2.phi, 0.0);
    init(inertia2.w, 0.0);
    let spring = spring(c = 1e4);
    let inertia3 = inertia(j = 2.0);
    init(inertia3.w, 0.0);
    let damper = damper(10.0);
    connect(torque.flange, inertia1.flange_a);
    connect(inertia1.flange_b, ideal_gear.flange_a);
    connect(ideal_gear.flange_b, inertia2.flange_a);
    connect(inertia2.flange_b, spring.flange_a, damper.flange_a);
    connect(spring.flange_b, inertia3.flange_a);
    connect(damper.flange_b, housing.flange);
    connect(ideal_gear.support, housing.flange);
}

/// `Modelica.Thermal.HeatTransfer.Examples.TwoMasses`: two bodies of
/// 15 J/K at 100 °C and 0 °C joined by a conductor of 10 W/K. MSL's
/// parameter `T_final_K`, set by an initial equation and not compared, is
/// left out.
#[dae_model]
fn two_masses() {
    let mass1 = heat_capacitor(c = 15.0, t0 = 373.15);
    init(mass1.t, 373.15);
    let mass2 = heat_capacitor(c = 15.0, t0 = 273.15);
    init(mass2.t, 273.15);
    let conduction = thermal_conductor(10.0);
    let tsensor1 = celsius_sensor();
    let tsensor2 = celsius_sensor();
    connect(mass1.port, conduction.port_a, tsensor1.port);
    connect(mass2.port, conduction.port_b, tsensor2.port);
}

/// `Modelica.Electrical.Analog.Examples.CauerLowPassAnalog`: a fifth-order
/// low-pass filter whose capacitors C1–C2–C3 and C3–C4–C5 form loops,
/// driven by a 1 V step at t = 1 s.
#[dae_model]
fn cauer_low_pass_analog() {
    let l1 = param(1.304);
    let l2 = param(0.8586);
    let c1 = param(1.072);
    // MSL's parameters computed from others are values here.
    let c2 = 1.0 / (1.704992 * 1.704992 * l1);
    let c3 = param(1.682);
    let c4 = 1.0 / (1.179945 * 1.179945 * l2);
    let c5 = param(0.7262);
    let g = ground();
    let v = step_voltage(height = 1.0, start_time = 1.0);
    let r1 = resistor(1.0);
    let r2 = resistor(1.0);
    let cap1 = capacitor(c1);
    init(cap1.v, 0.0);
    let cap2 = capacitor(c2);
    let cap3 = capacitor(c3);
    init(cap3.v, 0.0);
    let cap4 = capacitor(c4);
    let cap5 = capacitor(c5);
    init(cap5.v, 0.0);
    let ind1 = inductor(l1);
    init(ind1.i, 0.0);
    let ind2 = inductor(l2);
    init(ind2.i, 0.0);
    connect(v.p, r1.p);
    connect(r1.n, cap1.p, ind1.p, cap2.p);
    connect(ind1.n, cap2.n, cap3.p, cap4.p, ind2.p);
    connect(ind2.n, cap4.n, cap5.p, r2.p);
    connect(v.n, g.p, cap1.n, cap3.n, cap5.n, r2.n);
}

/// `Modelica.Mechanics.Translational.Examples.Oscillator`: two masses of
/// 1 kg and 1 m length on springs of 10⁴ N/m, one damped, driven at their
/// resonance (15.9155 Hz ≈ 100 rad/s).
#[dae_model]
fn oscillator() {
    let mass1 = mass(m = 1.0, s0 = -0.5, l = 1.0);
    let spring1 = translational_spring(c = 1e4, s_rel0 = 1.0);
    let fixed1 = translational_fixed(1.0);
    let sine1 = sine(f = 15.9155);
    let force1 = signal_force();
    connect(sine1.y, force1.u);
    connect(force1.flange, mass1.flange_a);
    connect(mass1.flange_b, spring1.flange_a);
    connect(spring1.flange_b, fixed1.flange);
    let mass2 = mass(m = 1.0, s0 = -0.5, l = 1.0);
    let spring2 = translational_spring(c = 1e4, s_rel0 = 1.0);
    let damper1 = translational_damper(10.0);
    let fixed2 = translational_fixed(1.0);
    let sine2 = sine(f = 15.9155);
    let force2 = signal_force();
    connect(sine2.y, force2.u);
    connect(force2.flange, mass2.flange_a);
    connect(mass2.flange_b, spring2.flange_a, damper1.flange_a);
    connect(spring2.flange_b, damper1.flange_b, fixed2.flange);
}

/// `Modelica.Mechanics.Translational.Examples.Damper`: three masses
/// moving at 10 m/s into a damper, a damper beside a spring, and a
/// spring-damper.
#[dae_model]
fn damper_example() {
    let mass1 = mass(m = 1.0, s0 = 3.0, v0 = 10.0, l = 1.0);
    let damper1 = translational_damper(25.0);
    let fixed1 = translational_fixed(4.5);
    connect(mass1.flange_b, damper1.flange_a);
    connect(damper1.flange_b, fixed1.flange);
    let mass2 = mass(m = 1.0, s0 = 3.0, v0 = 10.0, l = 1.0);
    let damper2 = translational_damper(25.0);
    let spring2 = translational_spring(c = 1.0, s_rel0 = 1.0);
    let fixed2 = translational_fixed(4.5);
    connect(mass2.flange_b, damper2.flange_a, spring2.flange_a);
    connect(damper2.flange_b, spring2.flange_b, fixed2.flange);
    let mass3 = mass(m = 1.0, s0 = 3.0, v0 = 10.0, l = 1.0);
    let spring_damper3 = translational_spring_damper(c = 1.0, d = 25.0, s_rel0 = 1.0);
    let fixed3 = translational_fixed(4.5);
    connect(mass3.flange_b, spring_damper3.flange_a);
    connect(spring_damper3.flange_b, fixed3.flange);
}

/// `Modelica.Electrical.Analog.Examples.Rectifier`: a B6 diode bridge on
/// a three-phase 400 V, 50 Hz supply behind line inductors, feeding a DC
/// link of two capacitors loaded by 500 A. The three line inductors meet
/// in a star that is not grounded: their currents sum to zero, so the
/// index reduction keeps two of them (MSL fixes the starts of inductors 2
/// and 3). MSL's initial equations on the capacitors' voltages are their
/// fixed starts here; its outputs (`uDC`, `iAC`, `uAC`, `Losses`), not
/// compared, are left out.
#[dae_model]
fn rectifier() {
    let vac = param(400.0);
    let f = param(50.0);
    let lac = param(60e-6);
    let ron = param(1e-3);
    let goff = param(1e-3);
    let vknee = param(2.0);
    let cdc = param(15e-3);
    let idc = param(500.0);
    let amplitude = vac * sqrt(2.0 / 3.0);
    let pi = 3.141592653589793;
    let sine_voltage1 = sine_voltage(amplitude = amplitude, f = f);
    let sine_voltage2 = sine_voltage(amplitude = amplitude, f = f, phase = -2.0 / 3.0 * pi);
    let sine_voltage3 = sine_voltage(amplitude = amplitude, f = f, phase = -4.0 / 3.0 * pi);
    let inductor1 = inductor(lac);
    let inductor2 = inductor(lac);
    init(inductor2.i, 0.0);
    let inductor3 = inductor(lac);
    init(inductor3.i, 0.0);
    let ideal_diode1 = piecewise_diode(ron = ron, goff = goff, v_knee = vknee);
    let ideal_diode2 = piecewise_diode(ron = ron, goff = goff, v_knee = vknee);
    let ideal_diode3 = piecewise_diode(ron = ron, goff = goff, v_knee = vknee);
    let ideal_diode4 = piecewise_diode(ron = ron, goff = goff, v_knee = vknee);
    let ideal_diode5 = piecewise_diode(ron = ron, goff = goff, v_knee = vknee);
    let ideal_diode6 = piecewise_diode(ron = ron, goff = goff, v_knee = vknee);
    let capacitor1 = capacitor(2.0 * cdc);
    init(capacitor1.v, vac * sqrt(2.0) / 2.0);
    let capacitor2 = capacitor(2.0 * cdc);
    init(capacitor2.v, vac * sqrt(2.0) / 2.0);
    let ground1 = ground();
    let signal_current1 = signal_current();
    let constant1 = constant(idc);
    connect(sine_voltage1.n, sine_voltage2.n, sine_voltage3.n);
    connect(sine_voltage1.p, inductor1.p);
    connect(sine_voltage2.p, inductor2.p);
    connect(sine_voltage3.p, inductor3.p);
    connect(ideal_diode1.p, ideal_diode4.n, inductor1.n);
    connect(ideal_diode2.p, ideal_diode5.n, inductor2.n);
    connect(ideal_diode3.p, ideal_diode6.n, inductor3.n);
    connect(ideal_diode1.n, ideal_diode2.n, ideal_diode3.n, capacitor1.p, signal_current1.p);
    connect(ideal_diode4.p, ideal_diode5.p, ideal_diode6.p, capacitor2.n, signal_current1.n);
    connect(capacitor1.n, capacitor2.p, ground1.p);
    connect(constant1.y, signal_current1.u);
}

/// `Modelica.Electrical.Machines.Examples.DCMachines.DCPM_Start`: a DC
/// machine with permanent magnets started by an armature voltage ramp
/// (0 to 100 V from 0.2 s over 0.8 s) driving a 0.15 kg m² load, a load
/// torque of 63.66 N m stepped on at 1.5 s. The machine's data are MSL's
/// `Machines.Utilities.ParameterRecords.DcPermanentMagnetData`, our part's defaults; its losses are zero there
/// as here.
#[dae_model]
fn dcpm_start() {
    let ramp = ramp(height = 100.0, duration = 0.8, start_time = 0.2);
    let signal_voltage = signal_voltage();
    let ground = ground();
    let dcpm = dc_permanent_magnet();
    init(dcpm.phi_mechanical, 0.0);
    init(dcpm.w_mechanical, 0.0);
    init(dcpm.ia, 0.0);
    let load_inertia = inertia(j = 0.15);
    let load_torque_step = step(height = -63.66, start_time = 1.5);
    let load_torque = signal_torque();
    connect(ramp.y, signal_voltage.u);
    connect(signal_voltage.p, dcpm.pin_ap);
    connect(signal_voltage.n, dcpm.pin_an, ground.p);
    connect(dcpm.flange, load_inertia.flange_a);
    connect(load_torque_step.y, load_torque.u);
    connect(load_inertia.flange_b, load_torque.flange);
}

/// `Modelica.Electrical.Machines.Examples.DCMachines.DCEE_Start`: the same
/// start with a separately excited machine, its field on 100 V.
#[dae_model]
fn dcee_start() {
    let ramp = ramp(height = 100.0, duration = 0.8, start_time = 0.2);
    let signal_voltage = signal_voltage();
    let ground = ground();
    let constant_voltage = constant_voltage(100.0);
    let ground_excitation = ground();
    let dcee = dc_electrical_excited();
    init(dcee.phi_mechanical, 0.0);
    init(dcee.w_mechanical, 0.0);
    init(dcee.ia, 0.0);
    init(dcee.ie, 0.0);
    let load_inertia = inertia(j = 0.15);
    let load_torque_step = step(height = -63.66, start_time = 1.5);
    let load_torque = signal_torque();
    connect(ramp.y, signal_voltage.u);
    connect(signal_voltage.p, dcee.pin_ap);
    connect(signal_voltage.n, dcee.pin_an, ground.p);
    connect(constant_voltage.p, dcee.pin_ep);
    connect(constant_voltage.n, dcee.pin_en, ground_excitation.p);
    connect(dcee.flange, load_inertia.flange_a);
    connect(load_torque_step.y, load_torque.u);
    connect(load_inertia.flange_b, load_torque.flange);
}

/// `Modelica.Mechanics.Translational.Examples.PreLoad`: a spool held
/// between two spring plates by elastic contacts with a preloaded spring,
/// in a housing, pushed by a slow 150 N sine; rods set the distances.
#[dae_model]
fn pre_load() {
    let inner_contact_a = elasto_gap(c = 1000e3, d = 250.0, s_rel0 = 0.001);
    let inner_contact_b = elasto_gap(c = 1000e3, d = 250.0, s_rel0 = 0.001);
    let spool = mass(m = 0.150, s0 = 0.01475, l = 0.19);
    init(spool.s, 0.01475);
    init(spool.v, 0.0);
    let fixed_le = translational_fixed(-0.0955);
    let spring_plate_a = mass(m = 10e-3, s0 = -0.093, l = 0.002);
    init(spring_plate_a.s, -0.093);
    init(spring_plate_a.v, 0.0);
    let spring_plate_b = mass(m = 10e-3, s0 = -0.06925, l = 0.002);
    init(spring_plate_b.s, -0.06925);
    init(spring_plate_b.v, 0.0);
    let spring = translational_spring(c = 20e3, s_rel0 = 0.025);
    let outer_contact_a = elasto_gap(c = 1000e3, d = 250.0, s_rel0 = 0.0015);
    let outer_contact_b = elasto_gap(c = 1000e3, d = 250.0, s_rel0 = 0.0015);
    let rod1 = rod(0.007);
    let friction = translational_damper(2500.0);
    let force = signal_force();
    let housing = rod(0.0305);
    let rod3 = rod(0.00575);
    let rod4 = rod(0.00575);
    let rod2 = rod(0.007);
    let sine_force = sine(amplitude = 150.0, f = 0.01);
    connect(outer_contact_a.flange_b, spring_plate_a.flange_a);
    connect(spring_plate_a.flange_b, spring.flange_a, rod1.flange_a);
    connect(spring.flange_b, spring_plate_b.flange_a, rod2.flange_b);
    connect(spring_plate_b.flange_b, outer_contact_b.flange_a);
    connect(outer_contact_b.flange_b, housing.flange_b);
    connect(inner_contact_a.flange_a, rod3.flange_a, friction.flange_b);
    connect(inner_contact_a.flange_b, rod1.flange_b);
    connect(rod2.flange_a, inner_contact_b.flange_a);
    connect(rod4.flange_b, inner_contact_b.flange_b);
    connect(rod3.flange_b, rod4.flange_a, spool.flange_a, force.flange);
    connect(sine_force.y, force.u);
    connect(outer_contact_a.flange_a, housing.flange_a, friction.flange_a, fixed_le.flange);
}

/// `Modelica.Blocks.Examples.InverseModel`: the inverse of a first-order
/// lag, built by holding its output to a filtered sine (inverse-model
/// constraints around it) and feeding the input that needs to a copy of
/// the lag, whose output then follows the sine. MSL's `Continuous.CriticalDamping`
/// of order 1 and cut-off `f` is the first-order lag of time constant
/// 1/(2π f) here; the lags start steady, MSL's `initType = SteadyState`.
#[dae_model]
fn inverse_model() {
    let first_order1 = first_order(k = 1.0, t = 0.3);
    initial(der(first_order1.x) == 0.0);
    let sine = sine(f = 2.0, offset = 1.0, start_time = 0.2);
    let inverse_block_constraints = inverse_block_constraints();
    let first_order2 = first_order(k = 1.0, t = 0.3);
    initial(der(first_order2.x) == 0.0);
    let feedback = feedback();
    let critical_damping = first_order(k = 1.0, t = 1.0 / (2.0 * 3.141592653589793 * 100.0));
    connect(sine.y, critical_damping.u, feedback.u2);
    // The lag held to the filtered sine, its input given to the copy.
    connect(critical_damping.y, inverse_block_constraints.u1);
    connect(first_order1.y, inverse_block_constraints.u2);
    connect(inverse_block_constraints.y2, first_order1.u);
    connect(inverse_block_constraints.y1, first_order2.u);
    connect(first_order2.y, feedback.u1);
}

/// `Modelica.Mechanics.Rotational.Examples.CoupledClutches`: four
/// inertias joined by three clutches, the first (normal force a slow sine)
/// slipping from the start, the others engaged by steps at 0.4 and 0.9 s;
/// a 10 N m, 5 Hz torque on the first inertia. MSL's `mode`,
/// `startForward` and `startBackward` are its friction state machine's,
/// not compared; our clutch's `mode` says whether it is stuck or slips.
#[dae_model]
fn coupled_clutches() {
    let j1 = inertia(j = 1.0, w0 = 10.0);
    init(j1.phi, 0.0);
    init(j1.w, 10.0);
    let torque = signal_torque();
    let clutch1 = clutch(peak = 1.1, fn_max = 20.0);
    let sin1 = sine(amplitude = 10.0, f = 5.0);
    let step1 = step(start_time = 0.4);
    let j2 = inertia(j = 1.0);
    init(j2.phi, 0.0);
    init(j2.w, 0.0);
    let clutch2 = clutch(peak = 1.1, fn_max = 20.0);
    let j3 = inertia(j = 1.0);
    init(j3.phi, 0.0);
    init(j3.w, 0.0);
    let clutch3 = clutch(peak = 1.1, fn_max = 20.0);
    let j4 = inertia(j = 1.0);
    init(j4.phi, 0.0);
    init(j4.w, 0.0);
    let sin2 = sine(amplitude = 1.0, f = 0.2, phase = 1.570796326794897);
    let step2 = step(start_time = 0.9);
    let fixed = fixed();
    // Along the shaft, each clutch with its engagement.
    connect(sin1.y, torque.u);
    connect(fixed.flange, torque.support);
    connect(torque.flange, j1.flange_a);
    connect(j1.flange_b, clutch1.flange_a);
    connect(sin2.y, clutch1.f_normalized);
    connect(clutch1.flange_b, j2.flange_a);
    connect(j2.flange_b, clutch2.flange_a);
    connect(step1.y, clutch2.f_normalized);
    connect(clutch2.flange_b, j3.flange_a);
    connect(j3.flange_b, clutch3.flange_a);
    connect(step2.y, clutch3.f_normalized);
    connect(clutch3.flange_b, j4.flange_a);
}

/// `Modelica.Blocks.Examples.PID_Controller`: a PI speed controller
/// (MSL's `LimPID` with `controllerType = PI`: k = 100, Ti = 0.1, output
/// within ±12, Ni = 0.1) driving an inertia through a torque source, a
/// stiff spring-damper to a second inertia loaded by 10 N m; the speed
/// reference the integral of a point-to-point profile (π/2 rad at most
/// 1 rad/s and 1 rad/s² from 0.5 s). It starts in the steady state MSL's
/// initial equations and `initType = SteadyState` ask for. MSL's `Td`,
/// unused by a PI, and the spring-damper's `StateSelect.prefer` are left
/// out.
#[dae_model]
fn pid_controller_example() {
    let pi = lim_pi(k = 100.0, ti = 0.1, y_max = 12.0, y_min = -12.0, ni = 0.1);
    initial(der(pi.x_i) == 0.0);
    let inertia1 = inertia(j = 1.0);
    init(inertia1.phi, 0.0);
    initial(der(inertia1.w) == 0.0);
    let torque = signal_torque();
    let spring = spring_damper(c = 1e4, d = 100.0);
    initial(spring.w_rel == 0.0);
    initial(der(spring.w_rel) == 0.0);
    let inertia2 = inertia(j = 2.0);
    let kinematic_ptp =
        kinematic_ptp(delta_q = 1.570796326794897, qd_max = 1.0, qdd_max = 1.0, start_time = 0.5);
    let integrator = integrator();
    init(integrator.x, 0.0);
    let speed_sensor = speed_sensor();
    let load_torque = torque_source(10.0);
    connect(spring.flange_b, inertia2.flange_a);
    connect(inertia1.flange_b, spring.flange_a, speed_sensor.flange);
    connect(torque.flange, inertia1.flange_a);
    connect(kinematic_ptp.y, integrator.u);
    connect(load_torque.flange, inertia2.flange_b);
    connect(pi.y, torque.u);
    connect(speed_sensor.w, pi.u_m);
    connect(integrator.y, pi.u_s);
}
