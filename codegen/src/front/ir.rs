//! The model as the front end understood it: declarations and equations over
//! one expression graph, each with the user's tokens for error messages.

use crate::{Graph, Id, SymbolId};
use proc_macro2::TokenStream;

/// `let u = input(u0);`: a signal the caller supplies at run time, the
/// field `u: daegen::Input` (`u0` by default).
pub struct InputDecl {
    /// The field name.
    pub ident: syn::Ident,
    /// Its value by default.
    pub default: f64,
    /// Its doc comment.
    pub doc: String,
    /// Its symbol, and its rate's.
    pub symbol: SymbolId,
    /// The rate's symbol (`rate(u)`).
    pub rate: SymbolId,
}

/// `let name = param(default);`
pub struct Param {
    /// The field name.
    pub ident: syn::Ident,
    /// Its default value.
    pub default: f64,
    /// Its doc comment.
    pub doc: String,
    /// Its path in the hierarchy of instances (`r1.r`); the field's name
    /// at the model's level.
    pub path: String,
}

/// One scalar state (`state(x0)` or an element of `state_array`).
pub struct StateDecl {
    /// `x` or `q[2]`.
    pub name: String,
    /// Its symbol.
    pub symbol: SymbolId,
    /// Initial value (constants and parameters).
    pub init: Id,
    /// The declaration, for errors.
    pub origin: TokenStream,
    /// `state(x0).fixed()`: consistent initialization keeps the value.
    pub fixed: bool,
    /// Its doc comment (for a scene's coordinates, what they are).
    pub doc: String,
    /// `state(x0).avoid()`: when an equation ties it to other states, it
    /// is the one eliminated.
    pub avoid: bool,
    /// `state(x0).prefer()`: when an equation ties it to other states, it
    /// is kept while another can go.
    pub prefer: bool,
}

/// `let z = algebraic(guess);`
#[derive(Clone)]
pub struct AlgebraicDecl {
    /// Its name.
    pub name: String,
    /// Its symbol.
    pub symbol: SymbolId,
    /// Its initial guess (constants and parameters).
    pub init: Id,
    /// The declaration, for errors.
    pub origin: TokenStream,
    /// Its doc comment (for a joint's reactions, what they are).
    pub doc: String,
}

/// `let e = output(value);`
pub struct Output {
    /// Its name.
    pub name: String,
    /// Its value.
    pub value: Id,
    /// Its doc comment.
    pub doc: String,
    /// The declaration, for errors.
    pub origin: TokenStream,
    /// Declared by `output(..)` at the model's own level: an output of
    /// the model (of its FMU). The others (a part's outputs, variables
    /// the structure eliminated, a scene's coordinates) are values read
    /// by name.
    pub declared: bool,
}

/// Which sign changes of an event function fire it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventDirection {
    /// Both.
    Any,
    /// From negative to positive (`.rising()`).
    Rising,
    /// From positive to negative (`.falling()`).
    Falling,
}

/// `let e = event(g).falling().terminal();`
pub struct Event {
    /// Its name.
    pub name: String,
    /// The function whose zeros are the event.
    pub value: Id,
    /// Which crossings count.
    pub direction: EventDirection,
    /// Whether the run stops at the first one.
    pub terminal: bool,
    /// What it does where it fires, in order (`.reinit(..)`).
    pub actions: Vec<Action>,
    /// Its doc comment.
    pub doc: String,
    /// The declaration, for errors.
    pub origin: TokenStream,
}

/// `.reinit(target, value)` on an event or a clock: where it fires, the
/// state or discrete value `target` takes `value`, computed from the values
/// at that instant as the actions before it left them (`pre(x)` reads the
/// value just before the instant).
pub struct Action {
    /// A state, a derivative kept as a state (`der(h)`), or a discrete value.
    pub target: SymbolId,
    /// Its new value.
    pub value: Id,
    /// The `.reinit(..)`, for errors.
    pub origin: TokenStream,
}

/// `let tick = every(h).offset(t0).reinit(u, ..);`: actions at the
/// instants `offset + k·period`.
pub struct Clock {
    /// Its name.
    pub name: String,
    /// The time between two instants (constants and parameters).
    pub period: Id,
    /// The first instant of the grid (constants and parameters).
    pub offset: Id,
    /// What it does at each instant, in order.
    pub actions: Vec<Action>,
    /// Its doc comment.
    pub doc: String,
    /// The declaration, for errors.
    pub origin: TokenStream,
}

/// `lhs == rhs;` or `constraint(phi);` (as `phi == 0`).
#[derive(Clone)]
pub struct Equation {
    /// Left side.
    pub lhs: Id,
    /// Right side.
    pub rhs: Id,
    /// The statement, for errors.
    pub origin: TokenStream,
    /// Written as `constraint(..)`.
    pub is_constraint: bool,
    /// Written inside `if on { .. } else { .. }` or `if gear == 2 { .. }`:
    /// what the discrete values must be for the equation to hold, all of
    /// it (empty: always).
    pub mode: Vec<ModeGuard>,
}

/// A condition on a discrete value selecting equations: its value is one
/// of `values` (`holds`), or none of them (`!holds`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModeGuard {
    /// The discrete value.
    pub mode: SymbolId,
    /// The values tested.
    pub values: Vec<i64>,
    /// Whether the value is among them.
    pub holds: bool,
    /// Written as a boolean (`if on`, `if !on`): the value is 0 or 1.
    pub boolean: bool,
}

impl ModeGuard {
    /// Whether the guard holds where its discrete value is `value`.
    pub fn holds_at(&self, value: i64) -> bool {
        self.values.contains(&value) == self.holds
    }
}

/// `invariant(e);` (or the unit norm of a `quaternion_state`): a function of
/// the states that the dynamics keep constant at zero and that the runtime
/// projects onto after each step, without differentiating it.
pub struct UserInvariant {
    /// Its value, zero on the solution.
    pub value: Id,
    /// The statement, for errors and messages.
    pub origin: TokenStream,
}

/// `initial(lhs == rhs);`: an equation that holds at the start only
/// (Modelica's `initial equation`).
pub struct InitialEquation {
    /// Its left-hand side.
    pub lhs: Id,
    /// Its right-hand side.
    pub rhs: Id,
    /// The statement, for errors.
    pub origin: TokenStream,
}

/// A relation on model variables, `p > 0` (`p >= 0` where `inclusive`),
/// held in a discrete boolean between events.
pub struct Relation {
    /// `p`.
    pub value: Id,
    /// The discrete boolean that holds it.
    pub discrete: SymbolId,
    /// The event where it turns true; the next one turns it false.
    pub event: usize,
    /// `>=` or `<=`: true where `p` is zero at the start.
    pub inclusive: bool,
}

/// `init(der(x), v);`
pub struct Init {
    /// The derivative symbol `der^k(x)`.
    pub target: SymbolId,
    /// The value (constants and parameters).
    pub value: Id,
    /// The statement, for errors.
    pub origin: TokenStream,
}

/// Everything `lower` found.
pub struct ModelIr {
    /// The function's name.
    pub fn_name: syn::Ident,
    /// Its visibility, given to the generated type.
    pub vis: syn::Visibility,
    /// Its doc comment.
    pub doc: String,
    /// The expressions.
    pub graph: Graph,
    /// The independent variable (declared with `time()`, or implicit).
    pub time: SymbolId,
    /// Parameters in declaration order.
    pub params: Vec<Param>,
    /// Scalar states in declaration order.
    pub states: Vec<StateDecl>,
    /// Algebraic variables.
    pub algebraics: Vec<AlgebraicDecl>,
    /// Outputs.
    pub outputs: Vec<Output>,
    /// Events.
    pub events: Vec<Event>,
    /// Clocks (`every(h)`).
    pub clocks: Vec<Clock>,
    /// Inputs (`input(u0)`), in declaration order.
    pub inputs: Vec<InputDecl>,
    /// States that are discrete values (`discrete(v0)`): constant between
    /// events, changed only by actions.
    pub discretes: Vec<SymbolId>,
    /// `pre(x)` as read by actions: its symbol, and x's.
    pub pre: Vec<(SymbolId, SymbolId)>,
    /// Equations and constraints in order.
    pub equations: Vec<Equation>,
    /// Initial values of derivatives.
    pub inits: Vec<Init>,
    /// Equations that hold at the start only.
    pub initial_equations: Vec<InitialEquation>,
    /// The states whose starts `init(part.x, v)` set, with the statement.
    pub fixed_starts: Vec<(SymbolId, TokenStream)>,
    /// The relations on model variables, each held in a discrete boolean.
    pub relations: Vec<Relation>,
    /// Invariants to project onto (`invariant(e)`, quaternion norms).
    pub invariants: Vec<UserInvariant>,
    /// Calls of non-smooth functions (`abs`) and their tokens, for errors
    /// found after lowering (the Taylor methods refuse them).
    pub non_smooth_calls: Vec<(Id, proc_macro2::TokenStream)>,
    /// The instances of components, parents first.
    pub instances: Vec<InstanceSummary>,
    /// Parts the model calls that no definition provided: the user's
    /// components, which the expansion fetches and lowers again with.
    pub missing_parts: Vec<syn::Path>,
    /// Files the model was built from (a robot's URDF): the build depends on
    /// them, so a change to one expands the model again.
    pub depends_on: Vec<std::path::PathBuf>,
    /// A scene in space in body coordinates (body coordinates),
    /// whose generated code grows fast with its joints.
    pub body_coordinates: bool,
}

/// An instance of a component, for the hierarchy `describe()` shows.
pub struct InstanceSummary {
    /// Its path: `motor.emf`.
    pub path: String,
    /// The part: `emf`.
    pub part: String,
}

/// The model as its tests read it: one declaration or statement a line,
/// in the order written, expressions in the graph's text syntax.
impl std::fmt::Display for ModelIr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let g = &self.graph;
        let name = |s: SymbolId| g.symbol(s).name.clone();
        writeln!(f, "model {}", self.fn_name)?;
        writeln!(f, "time {}", name(self.time))?;
        for p in &self.params {
            writeln!(f, "param {} = {}", p.ident, p.default)?;
        }
        for i in &self.inputs {
            writeln!(f, "input {} = {}", i.ident, i.default)?;
        }
        for s in &self.states {
            let fixed = if s.fixed { " fixed" } else { "" };
            writeln!(f, "state {} = {}{fixed}", s.name, g.show(s.init))?;
        }
        for a in &self.algebraics {
            writeln!(f, "algebraic {} = {}", a.name, g.show(a.init))?;
        }
        for e in &self.equations {
            let mode: String = e
                .mode
                .iter()
                .map(|m| match (m.boolean, m.holds, m.values.as_slice()) {
                    (true, holds, _) => {
                        format!(" if {}{}", if holds { "" } else { "!" }, name(m.mode))
                    }
                    (false, true, [v]) => format!(" if {} == {v}", name(m.mode)),
                    (false, false, [v]) => format!(" if {} != {v}", name(m.mode)),
                    (false, holds, values) => {
                        let not = if holds { "" } else { "not " };
                        format!(" if {} {not}in {values:?}", name(m.mode))
                    }
                })
                .collect();
            match e.is_constraint {
                true => writeln!(f, "constraint {} == {}{mode}", g.show(e.lhs), g.show(e.rhs))?,
                false => writeln!(f, "equation {} == {}{mode}", g.show(e.lhs), g.show(e.rhs))?,
            }
        }
        for i in &self.inits {
            writeln!(f, "init {} = {}", name(i.target), g.show(i.value))?;
        }
        for e in &self.initial_equations {
            writeln!(f, "initial {} == {}", g.show(e.lhs), g.show(e.rhs))?;
        }
        for i in &self.invariants {
            writeln!(f, "invariant {}", g.show(i.value))?;
        }
        for o in &self.outputs {
            writeln!(f, "output {} = {}", o.name, g.show(o.value))?;
        }
        for e in &self.events {
            let direction = match e.direction {
                EventDirection::Any => "",
                EventDirection::Rising => " rising",
                EventDirection::Falling => " falling",
            };
            let terminal = if e.terminal { " terminal" } else { "" };
            writeln!(f, "event {} = {}{direction}{terminal}", e.name, g.show(e.value))?;
            show_actions(f, g, &e.actions)?;
        }
        for c in &self.clocks {
            writeln!(f, "clock {} every {} from {}", c.name, g.show(c.period), g.show(c.offset))?;
            show_actions(f, g, &c.actions)?;
        }
        for &d in &self.discretes {
            writeln!(f, "discrete {}", name(d))?;
        }
        Ok(())
    }
}

/// An event's or a clock's actions, one a line under it.
fn show_actions(
    f: &mut std::fmt::Formatter<'_>,
    g: &Graph,
    actions: &[Action],
) -> std::fmt::Result {
    for a in actions {
        writeln!(f, "  reinit {} = {}", g.symbol(a.target).name, g.show(a.value))?;
    }
    Ok(())
}
