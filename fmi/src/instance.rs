//! One FMU instance, the same for FMI 2.0 and 3.0: the model, its time and
//! state, what the importer set, and what each call of either version does
//! with them. The version layers (`fmi2`, `fmi3`) check the call order of
//! their state machine and translate pointers and statuses; everything an
//! instance computes is here.
//!
//! **Model Exchange** hands the importer the generated right-hand side. A
//! DAE goes out in the form the run API integrates: its index-reduced
//! ODE in the model's states (the constraints differentiated until the
//! algebraic variables solve), which drifts from the constraints as any
//! integrator steps it. After each completed integrator step the instance
//! measures the constraints' residual; above the tolerance it asks for an
//! event, and in event mode projects the state back onto the constraints
//! and their hidden levels (`valuesOfContinuousStatesChanged`), so the
//! importer's solution stays on the constraint manifold as daegen's own
//! does. Event functions are the importer's event indicators; an event
//! acts when its function crossed zero in its direction since the last
//! point the importer completed, with the run API's rounds of actions.
//! Clocks are time events (`nextEventTime`).
//!
//! **Co-Simulation** steps with daegen's own methods: each `doStep` is a
//! run of the method `solver.method` (`Auto` by default) at the tolerance
//! `solver.tolerance` (the experiment's, else 1e-6) from the instance's
//! state, with the inputs held at the values set, events and clocks acting
//! inside it.

use crate::variables::{fmi_variables, Role, Variable, DEFAULT_METHOD, DEFAULT_TOLERANCE};
use daegen_runtime::instants::{self, ClockInstants};
use daegen_runtime::{Input, Method, Model, Options};

/// Which interface an instance was made for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interface {
    /// The importer integrates the model's right-hand side.
    ModelExchange,
    /// The instance integrates itself between communication points.
    CoSimulation,
}

/// Where an instance is in FMI's state machine (the states both versions
/// share; configuration and clock modes are not offered).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Made; start values and parameters may be set.
    Instantiated,
    /// Between entering and leaving initialization.
    Initialization,
    /// Model Exchange's event mode.
    Event,
    /// Model Exchange's continuous-time mode.
    Continuous,
    /// Co-simulation between steps (FMI 2.0's StepComplete, 3.0's Step
    /// mode).
    Step,
    /// After a step that failed.
    StepFailed,
    /// After `Terminate`.
    Terminated,
}

impl Phase {
    /// The phase's name in FMI's state machine.
    pub fn name(self) -> &'static str {
        match self {
            Phase::Instantiated => "Instantiated",
            Phase::Initialization => "Initialization Mode",
            Phase::Event => "Event Mode",
            Phase::Continuous => "Continuous-Time Mode",
            Phase::Step => "Step Mode",
            Phase::StepFailed => "Step Failed",
            Phase::Terminated => "Terminated",
        }
    }

    fn code(self) -> f64 {
        match self {
            Phase::Instantiated => 0.0,
            Phase::Initialization => 1.0,
            Phase::Event => 2.0,
            Phase::Continuous => 3.0,
            Phase::Step => 4.0,
            Phase::StepFailed => 5.0,
            Phase::Terminated => 6.0,
        }
    }

    fn of_code(code: f64) -> Option<Phase> {
        [
            Phase::Instantiated,
            Phase::Initialization,
            Phase::Event,
            Phase::Continuous,
            Phase::Step,
            Phase::StepFailed,
            Phase::Terminated,
        ]
        .into_iter()
        .find(|p| p.code() == code)
    }
}

/// The status a call returns, in FMI's order of severity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// Done.
    Ok,
    /// Done, with something to say.
    Warning,
    /// Not done; the importer may go back (a step it may retry shorter).
    Discard,
    /// Not done; the instance is left as it was.
    Error,
    /// The instance cannot go on.
    Fatal,
}

/// A call the instance did not carry out, and why, for the importer's
/// log.
#[derive(Clone, Debug, PartialEq)]
pub struct Refusal {
    /// The status the call returns.
    pub status: Status,
    /// What went wrong and how to fix it.
    pub message: String,
}

/// The result of a call: done, or refused with the reason.
pub type Outcome<T = ()> = Result<T, Refusal>;

/// An error refusal with `message`.
pub fn refuse(message: impl Into<String>) -> Refusal {
    Refusal { status: Status::Error, message: message.into() }
}

/// What an event-mode update found, as both versions report it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventUpdate {
    /// The continuous states changed (an action, or a projection).
    pub values_changed: bool,
    /// A terminal event acted.
    pub terminate: bool,
    /// The next time event (a clock instant), if any.
    pub next_event_time: Option<f64>,
}

/// What a co-simulation step did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepDone {
    /// A terminal event ended the simulation inside the step.
    pub terminate: bool,
    /// The time the step reached (the end of the step, or the terminal
    /// event).
    pub reached: f64,
}

/// The methods co-simulation steps with, by the names `solver.method`
/// takes: the run API's adaptive methods.
pub const METHODS: [(&str, Method); 6] = [
    ("Auto", Method::Auto),
    ("Taylor", Method::Taylor),
    ("Dopri5", Method::Dopri5),
    ("Dop853", Method::Dop853),
    ("Radau5", Method::Radau5),
    ("Rodas5P", Method::Rodas5P),
];

/// Marks a serialized state of this layout.
const SNAPSHOT_MAGIC: f64 = 4.0626e7;

/// One instance of model `M`.
pub struct Instance<M: Model> {
    /// The interface it was made for.
    pub interface: Interface,
    /// Where it is in the state machine.
    pub phase: Phase,
    model: M,
    vars: Vec<Variable>,
    t: f64,
    y: Vec<f64>,
    /// Positions in `y` of the continuous states (FMI's `x`), without the
    /// discrete values.
    continuous: Vec<usize>,
    /// States whose start value the importer set.
    set_states: Vec<bool>,
    inputs: Vec<f64>,
    /// The event functions at the last point the importer completed.
    known_indicators: Vec<f64>,
    scratch: Vec<f64>,
    experiment_tolerance: Option<f64>,
    stop_time: Option<f64>,
    method: usize,
    solver_tolerance: f64,
    clocks: Option<ClockInstants>,
    /// The clocks due at this time or before have acted.
    acted_until: f64,
    /// A terminal event ended the simulation.
    ended: bool,
    /// The constraints drifted beyond the tolerance: project at the next
    /// event update.
    drifted: bool,
}

impl<M: Model + Clone + Default + Send + Sync + 'static> Instance<M> {
    /// A new instance with the model's defaults, or why the model cannot be
    /// one for `interface`.
    pub fn new(interface: Interface) -> Result<Instance<M>, String> {
        if M::LANES > 1 {
            return Err(format!(
                "{} is a batch of {} members: export the single model",
                M::INFO.name,
                M::LANES
            ));
        }
        if interface == Interface::ModelExchange && !M::MASS.is_identity() {
            return Err(format!(
                "{} is integrated in mass-matrix form, which Model Exchange cannot hand over: use Co-Simulation",
                M::INFO.name
            ));
        }
        let model = M::default();
        let vars = fmi_variables(&model);
        let continuous =
            (0..M::STATES).filter(|&i| !M::INFO.discrete.contains(&M::INFO.states[i])).collect();
        let mut y = vec![0.0; M::STATES];
        model.initial_state(&mut y);
        let inputs = vars
            .iter()
            .filter(|v| matches!(v.role, Role::Input(_)))
            .map(|v| v.start.unwrap_or(0.0))
            .collect();
        let method = METHODS.iter().position(|(n, _)| *n == DEFAULT_METHOD).unwrap_or(0);
        Ok(Instance {
            interface,
            phase: Phase::Instantiated,
            model,
            vars,
            t: 0.0,
            y,
            continuous,
            set_states: vec![false; M::STATES],
            inputs,
            known_indicators: vec![0.0; M::INFO.events.len()],
            scratch: vec![0.0; M::STATES.max(M::INFO.events.len())],
            experiment_tolerance: None,
            stop_time: None,
            method,
            solver_tolerance: 0.0,
            clocks: None,
            acted_until: f64::NEG_INFINITY,
            ended: false,
            drifted: false,
        })
    }

    /// Back to the state right after instantiation.
    pub fn reset(&mut self) {
        if let Ok(fresh) = Instance::new(self.interface) {
            *self = fresh;
        }
    }

    /// The number of continuous states the importer integrates.
    pub fn continuous_states(&self) -> usize {
        self.continuous.len()
    }

    /// The number of event indicators.
    pub fn event_indicators(&self) -> usize {
        M::INFO.events.len()
    }

    /// The instance's time.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The variable with value reference `vr`.
    pub fn variable(&self, vr: u32) -> Outcome<&Variable> {
        self.vars.get(vr as usize).ok_or_else(|| {
            refuse(format!(
                "{} has no variable with value reference {vr} (they run from 0 to {})",
                M::INFO.name,
                self.vars.len() - 1
            ))
        })
    }

    /// Refuses a call unless the instance is in one of `allowed`.
    pub fn allow_in(&self, allowed: &[Phase]) -> Outcome {
        if allowed.contains(&self.phase) {
            return Ok(());
        }
        let names: Vec<&str> = allowed.iter().map(|p| p.name()).collect();
        Err(refuse(format!(
            "not allowed in {}; allowed in {}",
            self.phase.name(),
            names.join(", ")
        )))
    }

    /// Refuses a call that Model Exchange alone makes.
    pub fn require_interface(&self, interface: Interface) -> Outcome {
        if self.interface == interface {
            return Ok(());
        }
        Err(refuse(format!(
            "belongs to {}; this instance was made for {}",
            interface_name(interface),
            interface_name(self.interface)
        )))
    }

    // ----- Initialization -----

    /// Enters initialization with the experiment's tolerance, start and
    /// stop time.
    pub fn enter_initialization(
        &mut self,
        tolerance: Option<f64>,
        start: f64,
        stop: Option<f64>,
    ) -> Outcome {
        if !start.is_finite() {
            return Err(refuse(format!("the start time {start} is not finite")));
        }
        if let Some(stop) = stop.filter(|&s| s < start || s.is_nan()) {
            return Err(refuse(format!("the stop time {stop} is before the start time {start}")));
        }
        if let Some(tol) = tolerance.filter(|&t| t <= 0.0 || !t.is_finite()) {
            return Err(refuse(format!("the tolerance {tol} is not positive and finite")));
        }
        self.setup(tolerance, start, stop);
        self.phase = Phase::Initialization;
        Ok(())
    }

    /// Records the experiment (FMI 2.0's `SetupExperiment`) without
    /// entering initialization.
    pub fn setup(&mut self, tolerance: Option<f64>, start: f64, stop: Option<f64>) {
        self.experiment_tolerance = tolerance;
        self.stop_time = stop;
        self.t = start;
    }

    /// Leaves initialization: the start state made consistent, the
    /// parameters checked; event mode (Model Exchange) or step mode
    /// (Co-Simulation) next.
    pub fn exit_initialization(&mut self) -> Outcome {
        self.start_state();
        for k in 0..M::INFO.parameters.len() {
            let v = self.model.parameter(k);
            if !v.is_finite() {
                return Err(refuse(format!(
                    "the parameter `{}` is {v}: give it a finite value",
                    M::INFO.parameters[k]
                )));
            }
        }
        if let Some(divisor) = self.model.degenerate_parameters() {
            return Err(refuse(format!("the parameters make {divisor} zero or not finite")));
        }
        if let Err(e) = instants::consistent_state(&self.model, self.t, &mut self.y) {
            return Err(refuse(format!("the start state is not consistent: {e}")));
        }
        if let Err(e) = self.model.rhs(self.t, &self.y, &mut self.scratch[..M::STATES]) {
            return Err(refuse(format!("the model cannot be evaluated at the start: {e}")));
        }
        let horizon = self.stop_time.unwrap_or(self.t);
        self.clocks = match ClockInstants::of(&self.model, self.t, horizon) {
            Ok(c) => Some(c).filter(|_| !M::INFO.clocks.is_empty()),
            Err(e) => return Err(refuse(e.to_string())),
        };
        self.model.events(self.t, &self.y, &mut self.known_indicators);
        self.phase = match self.interface {
            Interface::ModelExchange => Phase::Event,
            Interface::CoSimulation => Phase::Step,
        };
        Ok(())
    }

    /// The start state from the parameters, with the start values the
    /// importer set.
    fn start_state(&mut self) {
        let mut y0 = vec![0.0; M::STATES];
        self.model.initial_state(&mut y0);
        for ((y, start), set) in self.y.iter_mut().zip(y0).zip(&self.set_states) {
            if !set {
                *y = start;
            }
        }
    }

    // ----- Values -----

    /// The value of real variable `vr`.
    pub fn get_real(&mut self, vr: u32) -> Outcome<f64> {
        let role = self.variable(vr)?.role;
        if matches!(self.phase, Phase::Instantiated | Phase::Initialization) {
            self.start_state();
        }
        let (t, y) = (self.t, &self.y);
        Ok(match role {
            Role::Time => t,
            Role::State(i) => y[i],
            Role::Derivative(i) => {
                let dy = &mut self.scratch[..M::STATES];
                if let Err(e) = self.model.rhs(t, y, dy) {
                    return Err(refuse(format!("the rates cannot be evaluated at t = {t}: {e}")));
                }
                dy[i]
            }
            Role::Parameter(k) => self.model.parameter(k),
            Role::Input(k) => self.inputs[k],
            Role::Output(k) => self.model.output(k, t, y),
            Role::EventFunction(k) => {
                let g = &mut self.scratch[..M::INFO.events.len()];
                self.model.events(t, y, g);
                g[k]
            }
            Role::SolverTolerance => self.solver_tolerance,
            Role::SolverMethod => {
                return Err(refuse(format!(
                    "`{}` is a string: read it with GetString",
                    self.vars[vr as usize].name
                )))
            }
        })
    }

    /// Sets real variable `vr` to `value`.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Outcome {
        let var = self.variable(vr)?;
        let (role, name) = (var.role, var.name.clone());
        if !value.is_finite() {
            return Err(refuse(format!("`{name}` was set to {value}, which is not finite")));
        }
        let starting = matches!(self.phase, Phase::Instantiated | Phase::Initialization);
        let calculated =
            || refuse(format!("`{name}` is calculated by the model; it cannot be set"));
        match role {
            Role::State(i) if starting => {
                self.y[i] = value;
                self.set_states[i] = true;
            }
            Role::State(_) => {
                return Err(refuse(format!(
                    "`{name}` is a state: its start value is set before initialization ends; afterwards Model Exchange sets the states with SetContinuousStates"
                )))
            }
            Role::Parameter(k) => {
                if !(starting || matches!(self.phase, Phase::Event | Phase::Step)) {
                    return Err(refuse(format!(
                        "`{name}` is a tunable parameter, set before initialization ends, in event mode or between steps; not in {}",
                        self.phase.name()
                    )));
                }
                self.model.set_parameter(k, value);
            }
            Role::Input(k) => {
                self.inputs[k] = value;
                self.model.set_input(k, Input::constant(value));
            }
            Role::SolverTolerance if starting => {
                if value < 0.0 {
                    return Err(refuse(format!(
                        "`{name}` = {value}: give a positive tolerance (or 0 for the experiment's)"
                    )));
                }
                self.solver_tolerance = value;
            }
            Role::SolverTolerance => {
                return Err(refuse(format!("`{name}` is fixed: set it before initialization ends")))
            }
            Role::SolverMethod => {
                return Err(refuse(format!("`{name}` is a string: set it with SetString")))
            }
            Role::Time | Role::Derivative(_) | Role::Output(_) | Role::EventFunction(_) => {
                return Err(calculated())
            }
        }
        Ok(())
    }

    /// The value of string variable `vr` (`solver.method`).
    pub fn get_string(&self, vr: u32) -> Outcome<&'static str> {
        let var = self.variable(vr)?;
        match var.role {
            Role::SolverMethod => Ok(METHODS[self.method].0),
            _ => Err(refuse(format!("`{}` is a real: read it with GetReal", var.name))),
        }
    }

    /// Sets string variable `vr` (`solver.method`) to `value`.
    pub fn set_string(&mut self, vr: u32, value: &str) -> Outcome {
        let var = self.variable(vr)?;
        match var.role {
            Role::SolverMethod => {
                if !matches!(self.phase, Phase::Instantiated | Phase::Initialization) {
                    return Err(refuse(format!(
                        "`{}` is fixed: set it before initialization ends",
                        var.name
                    )));
                }
                match METHODS.iter().position(|(n, _)| n.eq_ignore_ascii_case(value)) {
                    Some(k) => {
                        self.method = k;
                        Ok(())
                    }
                    None => {
                        let names: Vec<&str> = METHODS.iter().map(|(n, _)| *n).collect();
                        Err(refuse(format!(
                            "`{}` = \"{value}\" is not a method; use one of {}",
                            var.name,
                            names.join(", ")
                        )))
                    }
                }
            }
            _ => Err(refuse(format!("`{}` is a real: set it with SetReal", var.name))),
        }
    }

    // ----- Model Exchange -----

    /// Sets the time.
    pub fn set_time(&mut self, t: f64) -> Outcome {
        if !t.is_finite() {
            return Err(refuse(format!("the time {t} is not finite")));
        }
        self.t = t;
        Ok(())
    }

    /// Sets the continuous states.
    pub fn set_continuous_states(&mut self, x: &[f64]) -> Outcome {
        self.check_length("continuous states", x.len(), self.continuous.len())?;
        if let Some(k) = x.iter().position(|v| !v.is_finite()) {
            return Err(refuse(format!(
                "the state `{}` was set to {}, which is not finite",
                M::INFO.states[self.continuous[k]],
                x[k]
            )));
        }
        for (k, &i) in self.continuous.iter().enumerate() {
            self.y[i] = x[k];
        }
        Ok(())
    }

    /// Writes the continuous states.
    pub fn get_continuous_states(&mut self, x: &mut [f64]) -> Outcome {
        self.check_length("continuous states", x.len(), self.continuous.len())?;
        if matches!(self.phase, Phase::Instantiated | Phase::Initialization) {
            self.start_state();
        }
        for (k, &i) in self.continuous.iter().enumerate() {
            x[k] = self.y[i];
        }
        Ok(())
    }

    /// Writes the nominal magnitude of each continuous state: 1.
    pub fn nominals(&self, x: &mut [f64]) -> Outcome {
        self.check_length("continuous states", x.len(), self.continuous.len())?;
        x.fill(1.0);
        Ok(())
    }

    /// Writes the rates of the continuous states.
    pub fn derivatives(&mut self, dx: &mut [f64]) -> Outcome {
        self.check_length("derivatives", dx.len(), self.continuous.len())?;
        let dy = &mut self.scratch[..M::STATES];
        if let Err(e) = self.model.rhs(self.t, &self.y, dy) {
            return Err(Refusal {
                status: Status::Discard,
                message: format!("the rates cannot be evaluated at t = {}: {e}", self.t),
            });
        }
        for (k, &i) in self.continuous.iter().enumerate() {
            dx[k] = dy[i];
            if !dx[k].is_finite() {
                return Err(Refusal {
                    status: Status::Discard,
                    message: format!(
                        "the rate of `{}` is {} at t = {}",
                        M::INFO.states[i],
                        dx[k],
                        self.t
                    ),
                });
            }
        }
        Ok(())
    }

    /// Writes the event indicators: the event functions.
    pub fn indicators(&mut self, g: &mut [f64]) -> Outcome {
        self.check_length("event indicators", g.len(), M::INFO.events.len())?;
        if matches!(self.phase, Phase::Instantiated | Phase::Initialization) {
            self.start_state();
        }
        self.model.events(self.t, &self.y, g);
        Ok(())
    }

    /// A step of the importer's integrator ended at the current point:
    /// whether to enter event mode (the constraints drifted beyond the
    /// tolerance), and whether to stop.
    pub fn completed_integrator_step(&mut self) -> (bool, bool) {
        let m = M::INFO.events.len();
        let g = &mut self.scratch[..m];
        self.model.events(self.t, &self.y, g);
        // Past a crossing the importer is about to report, the point
        // before it is what the event update compares with.
        let crossing = (0..m)
            .any(|k| instants::fires(M::INFO.events[k].direction, self.known_indicators[k], g[k]));
        if !crossing {
            self.known_indicators.copy_from_slice(g);
        }
        if !M::CONSTRAINTS.is_empty() {
            let drift = instants::constraint_residual(&self.model, self.t, &self.y);
            if drift > self.drift_limit() || drift.is_nan() {
                self.drifted = true;
            }
        }
        (self.drifted, self.ended)
    }

    /// How far a DAE's state may drift from its constraints before it is
    /// projected: the tolerance relative to the state's size.
    fn drift_limit(&self) -> f64 {
        let size = self.y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        self.experiment_tolerance.unwrap_or(DEFAULT_TOLERANCE) * size
    }

    /// The event update at the current time: the events whose functions
    /// crossed zero in their direction since the last completed point and
    /// the clocks due act (with the rounds they start), and a drifted DAE
    /// is projected.
    pub fn update_discrete_states(&mut self) -> Outcome<EventUpdate> {
        let (t, m) = (self.t, M::INFO.events.len());
        let mut g = vec![0.0; m];
        self.model.events(t, &self.y, &mut g);
        let mut due: Vec<usize> = (0..m)
            .filter(|&k| {
                instants::fires(M::INFO.events[k].direction, self.known_indicators[k], g[k])
            })
            .collect();
        if let Some(clocks) = &self.clocks {
            if t > self.acted_until {
                due.extend(clocks.due(t));
            }
        }
        let before = self.y.clone();
        let mut terminate = false;
        if !due.is_empty() {
            let fired = instants::act(&self.model, t, &mut self.y, &due)
                .map_err(|e| refuse(format!("the event update at t = {t} failed: {e}")))?;
            terminate = fired.iter().any(|&k| k < m && M::INFO.events[k].terminal);
        }
        if self.clocks.is_some() {
            self.acted_until = t;
        }
        if self.drifted {
            instants::project(&self.model, t, &mut self.y)
                .map_err(|e| refuse(format!("at t = {t} the state drifted from {e}")))?;
            self.drifted = false;
        }
        self.model.events(t, &self.y, &mut self.known_indicators);
        self.ended |= terminate;
        let values_changed = self.continuous.iter().any(|&i| self.y[i] != before[i]);
        // The next time event: a clock's instant, or a breakpoint of an
        // input or of a switch in the time alone (a step source), which
        // the importer's integrator should not step across.
        let next_clock = self.clocks.as_ref().and_then(|c| c.next_after(t));
        let next_breakpoint =
            self.model.input_breakpoints().into_iter().filter(|&b| b > t).min_by(f64::total_cmp);
        let next_event_time = match (next_clock, next_breakpoint) {
            (Some(c), Some(b)) => Some(c.min(b)),
            (c, b) => c.or(b),
        };
        Ok(EventUpdate { values_changed, terminate, next_event_time })
    }

    // ----- Co-Simulation -----

    /// Integrates from the communication point `t` over `h` with the
    /// instance's method and tolerance.
    pub fn do_step(&mut self, t: f64, h: f64) -> Outcome<StepDone> {
        let resolution = 1e-12 * self.t.abs().max(1.0);
        if (t - self.t).abs() > resolution || t.is_nan() {
            return Err(refuse(format!(
                "the communication point {t} is not the instance's time {}: step from where the last step ended",
                self.t
            )));
        }
        if h <= 0.0 || !h.is_finite() {
            return Err(refuse(format!("the communication step {h} is not positive and finite")));
        }
        if self.ended {
            return Err(refuse(format!("a terminal event ended the simulation at t = {}", self.t)));
        }
        let t1 = self.t + h;
        let tolerance = if self.solver_tolerance > 0.0 {
            self.solver_tolerance
        } else {
            self.experiment_tolerance.unwrap_or(DEFAULT_TOLERANCE)
        };
        let options = Options::new()
            .method(METHODS[self.method].1)
            .rtol(tolerance)
            .atol(tolerance * 1e-3)
            .dense_output(false)
            .continues(self.acted_until >= self.t);
        match daegen_runtime::simulate_from(&self.model, self.t, &self.y, t1, &options) {
            Ok(solution) => {
                let reached = solution.final_time();
                self.y.copy_from_slice(solution.final_state());
                self.ended = reached < t1;
                self.t = if self.ended { reached } else { t1 };
                self.acted_until = self.t;
                Ok(StepDone { terminate: self.ended, reached: self.t })
            }
            Err(e) => {
                self.phase = Phase::StepFailed;
                Err(refuse(format!(
                    "the step from t = {} to {t1} with {} failed: {e}",
                    self.t, METHODS[self.method].0
                )))
            }
        }
    }

    /// Whether a terminal event ended the simulation.
    pub fn ended(&self) -> bool {
        self.ended
    }

    // ----- Directional derivatives -----

    /// `sensitivity = ∂unknowns/∂knowns · seed`: exact from the generated
    /// Jacobian for the rates with respect to the states, by central
    /// differences for the rest (outputs, inputs, parameters).
    pub fn directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        sensitivity: &mut [f64],
    ) -> Outcome {
        self.check_length("seed values", seed.len(), knowns.len())?;
        self.check_length("sensitivities", sensitivity.len(), unknowns.len())?;
        let mut known_roles = Vec::with_capacity(knowns.len());
        for &vr in knowns {
            let var = self.variable(vr)?;
            match var.role {
                Role::State(i) if self.continuous.contains(&i) => {}
                Role::Input(_) | Role::Parameter(_) => {}
                _ => {
                    return Err(refuse(format!(
                        "`{}` is not a known of a directional derivative (a continuous state, an input or a parameter)",
                        var.name
                    )))
                }
            }
            known_roles.push(var.role);
        }
        let mut unknown_roles = Vec::with_capacity(unknowns.len());
        for &vr in unknowns {
            let var = self.variable(vr)?;
            if matches!(var.role, Role::SolverMethod | Role::SolverTolerance | Role::Time) {
                return Err(refuse(format!(
                    "`{}` is not an unknown of a directional derivative",
                    var.name
                )));
            }
            unknown_roles.push(var.role);
        }
        let states_only = known_roles.iter().all(|r| matches!(r, Role::State(_)));
        let symbolic = states_only && M::JACOBIAN.is_symbolic();
        let mut jacobian = Vec::new();
        if symbolic {
            jacobian = vec![0.0; M::JACOBIAN.pattern().len()];
            if let Err(e) = self.model.jacobian(self.t, &self.y, &mut jacobian) {
                return Err(refuse(format!("the Jacobian cannot be evaluated: {e}")));
            }
        }
        let mut by_difference = Vec::new();
        for (u, role) in unknown_roles.iter().enumerate() {
            sensitivity[u] = match *role {
                Role::State(i) if states_only => known_roles
                    .iter()
                    .zip(seed)
                    .filter(|(r, _)| **r == Role::State(i))
                    .map(|(_, s)| s)
                    .sum(),
                Role::Derivative(i) if symbolic => M::JACOBIAN
                    .pattern()
                    .iter()
                    .zip(&jacobian)
                    .filter(|((r, _), _)| *r == i)
                    .map(|(&(_, c), v)| {
                        let s: f64 = known_roles
                            .iter()
                            .zip(seed)
                            .filter(|(r, _)| **r == Role::State(c))
                            .map(|(_, s)| s)
                            .sum();
                        v * s
                    })
                    .sum(),
                _ => {
                    by_difference.push(u);
                    0.0
                }
            };
        }
        if by_difference.is_empty() {
            return Ok(());
        }
        let size = known_roles.iter().map(|&r| self.known_value(r).abs()).fold(1.0f64, f64::max);
        let reach = seed.iter().fold(0.0f64, |m, s| m.max(s.abs()));
        if reach == 0.0 {
            return Ok(());
        }
        let eps = 6e-6 * size / reach;
        let saved = (self.y.clone(), self.model.clone(), self.inputs.clone());
        let mut plus = vec![0.0; by_difference.len()];
        let mut minus = vec![0.0; by_difference.len()];
        for (sign, values) in [(1.0, &mut plus), (-1.0, &mut minus)] {
            for (r, s) in known_roles.iter().zip(seed) {
                let v = self.known_value(*r) + sign * eps * s;
                self.set_known(*r, v);
            }
            for (k, &u) in by_difference.iter().enumerate() {
                values[k] = self.get_real(unknowns[u])?;
            }
            (self.y, self.model, self.inputs) = (saved.0.clone(), saved.1.clone(), saved.2.clone());
        }
        for (k, &u) in by_difference.iter().enumerate() {
            sensitivity[u] = (plus[k] - minus[k]) / (2.0 * eps);
        }
        Ok(())
    }

    fn known_value(&self, role: Role) -> f64 {
        match role {
            Role::State(i) => self.y[i],
            Role::Input(k) => self.inputs[k],
            Role::Parameter(k) => self.model.parameter(k),
            _ => 0.0,
        }
    }

    fn set_known(&mut self, role: Role, value: f64) {
        match role {
            Role::State(i) => self.y[i] = value,
            Role::Input(k) => {
                self.inputs[k] = value;
                self.model.set_input(k, Input::constant(value));
            }
            Role::Parameter(k) => self.model.set_parameter(k, value),
            _ => {}
        }
    }

    // ----- FMU state -----

    /// Everything that makes this instance's state, as numbers: what
    /// `GetFMUState` keeps and `SerializeFMUState` writes.
    pub fn snapshot(&self) -> Vec<f64> {
        let mut out = vec![SNAPSHOT_MAGIC, M::STATES as f64, self.phase.code(), self.t];
        out.extend_from_slice(&self.y);
        out.extend(self.set_states.iter().map(|&s| if s { 1.0 } else { 0.0 }));
        out.push(M::INFO.parameters.len() as f64);
        out.extend((0..M::INFO.parameters.len()).map(|k| self.model.parameter(k)));
        out.push(self.inputs.len() as f64);
        out.extend_from_slice(&self.inputs);
        out.push(self.known_indicators.len() as f64);
        out.extend_from_slice(&self.known_indicators);
        out.extend([
            self.experiment_tolerance.unwrap_or(-1.0),
            self.stop_time.unwrap_or(f64::NAN),
            self.method as f64,
            self.solver_tolerance,
            self.acted_until,
            if self.ended { 1.0 } else { 0.0 },
            if self.drifted { 1.0 } else { 0.0 },
        ]);
        out
    }

    /// Restores a [`Instance::snapshot`] of an instance of the same model.
    pub fn restore(&mut self, snapshot: &[f64]) -> Outcome {
        let bad = || refuse(format!("the FMU state is not one of {}", M::INFO.name));
        let mut it = snapshot.iter().copied();
        let mut next = || it.next().ok_or_else(bad);
        if next()? != SNAPSHOT_MAGIC || next()? != M::STATES as f64 {
            return Err(bad());
        }
        let phase = Phase::of_code(next()?).ok_or_else(bad)?;
        let t = next()?;
        let mut y = vec![0.0; M::STATES];
        for v in &mut y {
            *v = next()?;
        }
        let mut set_states = vec![false; M::STATES];
        for s in &mut set_states {
            *s = next()? == 1.0;
        }
        if next()? != M::INFO.parameters.len() as f64 {
            return Err(bad());
        }
        let mut parameters = vec![0.0; M::INFO.parameters.len()];
        for p in &mut parameters {
            *p = next()?;
        }
        if next()? != self.inputs.len() as f64 {
            return Err(bad());
        }
        let mut inputs = vec![0.0; self.inputs.len()];
        for v in &mut inputs {
            *v = next()?;
        }
        if next()? != self.known_indicators.len() as f64 {
            return Err(bad());
        }
        let mut known = vec![0.0; self.known_indicators.len()];
        for v in &mut known {
            *v = next()?;
        }
        let tolerance = next()?;
        let stop = next()?;
        let method = next()? as usize;
        if method >= METHODS.len() {
            return Err(bad());
        }
        let solver_tolerance = next()?;
        let acted_until = next()?;
        let ended = next()? == 1.0;
        let drifted = next()? == 1.0;
        // Complete: apply.
        self.phase = phase;
        self.t = t;
        self.y = y;
        self.set_states = set_states;
        for (k, p) in parameters.into_iter().enumerate() {
            self.model.set_parameter(k, p);
        }
        for (k, v) in inputs.iter().enumerate() {
            self.model.set_input(k, Input::constant(*v));
        }
        self.inputs = inputs;
        self.known_indicators = known;
        self.experiment_tolerance = Some(tolerance).filter(|&t| t > 0.0);
        self.stop_time = Some(stop).filter(|s| !s.is_nan());
        self.method = method;
        self.solver_tolerance = solver_tolerance;
        self.acted_until = acted_until;
        self.ended = ended;
        self.drifted = drifted;
        if self.clocks.is_none() && !M::INFO.clocks.is_empty() {
            self.clocks = ClockInstants::of(&self.model, t, self.stop_time.unwrap_or(t)).ok();
        }
        Ok(())
    }

    fn check_length(&self, what: &str, given: usize, expected: usize) -> Outcome {
        if given == expected {
            return Ok(());
        }
        Err(refuse(format!("{given} {what} given; {} has {expected}", M::INFO.name)))
    }
}

fn interface_name(interface: Interface) -> &'static str {
    match interface {
        Interface::ModelExchange => "Model Exchange",
        Interface::CoSimulation => "Co-Simulation",
    }
}
