//! Declarations: `param`, `state`, `state_array`, `algebraic`, `time`,
//! `output`, `event`, and the scene's bodies, each checked and bound to
//! its name.

use super::hybrid::Trigger;
use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use crate::front::ir::{
    AlgebraicDecl, Event, EventDirection, Init, Output, Param, StateDecl, UserInvariant,
};

use crate::{Id, SymbolId, SymbolKind};
use quote::ToTokens;
use std::collections::HashMap;
use syn::{Expr, Pat};

/// The declarations of the model language: `let x = state(1.0);` and the
/// like, each a call by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Declaration {
    /// `event(g)`, with its settings chained after it.
    Event,
    /// `body(m, j, [x, y, theta])`: a planar rigid body.
    Body,
    /// `spatial_body(..)`: a rigid body in space.
    SpatialBody,
    /// `ground()`: the scene's fixed frame.
    Ground,
    /// `quaternion_state([1, 0, 0, 0])`: four states kept on the unit sphere.
    QuaternionState,
    /// `param(value)`.
    Param,
    /// `state(x0)`.
    State,
    /// `state_array([..])`.
    StateArray,
    /// `algebraic(z0)`.
    Algebraic,
    /// `algebraic_array([..])`.
    AlgebraicArray,
    /// `time()`.
    Time,
    /// `output(value)`.
    Output,
    /// `output_array([..])`.
    OutputArray,
    /// `discrete(v0)`.
    Discrete,
    /// `input(u0)`.
    Input,
}

impl Declaration {
    /// Every declaration, in the order the language reference lists them.
    pub(crate) const ALL: [Declaration; 15] = [
        Declaration::Event,
        Declaration::Body,
        Declaration::SpatialBody,
        Declaration::Ground,
        Declaration::QuaternionState,
        Declaration::Param,
        Declaration::State,
        Declaration::StateArray,
        Declaration::Algebraic,
        Declaration::AlgebraicArray,
        Declaration::Time,
        Declaration::Output,
        Declaration::OutputArray,
        Declaration::Discrete,
        Declaration::Input,
    ];

    /// The function the user calls.
    pub(in crate::front) fn name(self) -> &'static str {
        match self {
            Declaration::Event => "event",
            Declaration::Body => "body",
            Declaration::SpatialBody => "spatial_body",
            Declaration::Ground => "ground",
            Declaration::QuaternionState => "quaternion_state",
            Declaration::Param => "param",
            Declaration::State => "state",
            Declaration::StateArray => "state_array",
            Declaration::Algebraic => "algebraic",
            Declaration::AlgebraicArray => "algebraic_array",
            Declaration::Time => "time",
            Declaration::Output => "output",
            Declaration::OutputArray => "output_array",
            Declaration::Discrete => "discrete",
            Declaration::Input => "input",
        }
    }

    /// The declaration a call of `name` makes, if it makes one.
    pub(in crate::front) fn from_name(name: &str) -> Option<Declaration> {
        Declaration::ALL.into_iter().find(|d| d.name() == name)
    }
}

impl<S: SceneLanguage> Lower<'_, S> {
    /// A new state or algebraic symbol `name` and its node; `None` once
    /// the clash with another name is reported at `at`.
    pub(in crate::front) fn new_symbol(
        &mut self,
        name: &str,
        kind: SymbolKind,
        at: &dyn quote::ToTokens,
    ) -> Option<(Id, SymbolId)> {
        let created =
            if kind == SymbolKind::State { self.g.state(name) } else { self.g.algebraic(name) };
        match created {
            Ok(id) => Some((id, self.g.as_symbol(id)?)),
            Err(e) => {
                self.cx.error_at(at, e);
                None
            }
        }
    }

    /// Declares the state `name` (a user's, or a scene's coordinate)
    /// documented by `doc`; `None` once the clash with another name is
    /// reported at `at`.
    pub(crate) fn declare_state(
        &mut self,
        name: String,
        init: Id,
        at: &syn::Ident,
        origin: &proc_macro2::TokenStream,
        doc: &str,
    ) -> Option<SymbolId> {
        let (_, symbol) = self.new_symbol(&name, SymbolKind::State, at)?;
        let (origin, doc) = (origin.clone(), doc.to_string());
        self.states.push(StateDecl {
            name,
            symbol,
            init,
            origin,
            fixed: false,
            doc,
            avoid: false,
            prefer: false,
        });
        Some(symbol)
    }

    /// Declares the algebraic variable `name` (a user's, or a joint's
    /// multiplier) documented by `doc`; its node, or `None` once the clash
    /// with another name is reported at `at`.
    pub(crate) fn declare_algebraic(
        &mut self,
        name: String,
        init: Id,
        at: &dyn quote::ToTokens,
        origin: &proc_macro2::TokenStream,
        doc: String,
    ) -> Option<Id> {
        let (id, symbol) = self.new_symbol(&name, SymbolKind::Algebraic, at)?;
        let origin = origin.clone();
        self.algebraics.push(AlgebraicDecl { name, symbol, init, origin, doc });
        Some(id)
    }

    /// Starts `der(state)` at `value` (a body's or a joint's initial
    /// rate); `None` where the state has no derivative to start.
    pub(crate) fn init_rate(
        &mut self,
        state: SymbolId,
        value: Id,
        origin: &proc_macro2::TokenStream,
    ) -> Option<()> {
        let d = self.g.derivative(state, 1).ok()?;
        let target = self.g.as_symbol(d)?;
        self.inits.push(Init { target, value, origin: origin.clone() });
        Some(())
    }

    /// Adds the equations of motion `(lhs, rhs)` the scene gave, or reports
    /// at `origin` why it could not write them.
    pub(crate) fn push_equations_of_motion(
        &mut self,
        equations: crate::Result<Vec<(Id, Id)>>,
        origin: &proc_macro2::TokenStream,
    ) {
        match equations {
            Ok(equations) => {
                for (lhs, rhs) in equations {
                    let origin = origin.clone();
                    let eq = crate::front::ir::Equation {
                        lhs,
                        rhs,
                        origin,
                        is_constraint: false,
                        mode: Vec::new(),
                    };
                    self.equations.push(eq);
                }
            }
            Err(e) => self.cx.error_at(origin, e),
        }
    }

    /// Reports a second declaration of `ident`'s name.
    pub(in crate::front) fn already_declared(&mut self, ident: &syn::Ident) -> bool {
        let name = ident.to_string();
        let Some(what) = self.lookup(&name).map(Binding::describe) else {
            return false;
        };
        self.cx.error_at(
            ident,
            format!("`{name}` is already declared as {what}: choose another name"),
        );
        true
    }

    /// `let e = event(g).rising().terminal();`
    /// Unnamed (`event(h).falling().reinit(..);` as a statement), it is
    /// named by its source text.
    pub(in crate::front) fn event(&mut self, trigger: Trigger<'_>) {
        let Some(name) = self.trigger_declared(&trigger, "event") else {
            return;
        };
        let Trigger { ident, call, settings, doc, origin } = trigger;
        let (mut direction, mut terminal) = (EventDirection::Any, false);
        let mut actions = Vec::new();
        for m in settings {
            let setting = m.method.to_string();
            if setting == "reinit" {
                actions.extend(self.action(m));
                continue;
            }
            if !m.args.is_empty() {
                self.cx.error_at(&m.args, format!("`.{setting}()` takes no argument"));
                continue;
            }
            let wanted = match setting.as_str() {
                "rising" => EventDirection::Rising,
                "falling" => EventDirection::Falling,
                "terminal" => {
                    terminal = true;
                    continue;
                }
                _ => {
                    self.cx.error_at(
                        &m.method,
                        format!("unknown event setting `.{setting}()`: use `.rising()`, `.falling()`, `.terminal()` or `.reinit(x, value)`"),
                    );
                    continue;
                }
            };
            if direction != EventDirection::Any && direction != wanted {
                self.cx.error_at(
                    &m.method,
                    "an event is `.rising()` or `.falling()`, not both: leave both out to catch every crossing",
                );
            }
            direction = wanted;
        }
        let Some(value) = self.value(&call.args[0]) else {
            return;
        };
        self.events.push(Event {
            name,
            value,
            direction,
            terminal,
            actions,
            doc,
            origin: origin.to_token_stream(),
        });
        if let Some(ident) = ident {
            self.bind(ident, Binding::Value { id: value, mutable: false });
        }
    }

    pub(crate) fn arity(&mut self, call: &syn::ExprCall, name: &str, n: usize) -> bool {
        if call.args.len() == n {
            return true;
        }
        let args = match n {
            0 => "no argument".to_string(),
            1 => "one argument".to_string(),
            n => format!("{n} arguments"),
        };
        self.cx.error_at(call, format!("`{name}` takes {args}, not {}", call.args.len()));
        false
    }

    pub(in crate::front) fn declaration(
        &mut self,
        ident: &syn::Ident,
        kind: Declaration,
        call: &syn::ExprCall,
        doc: String,
        local: &syn::Local,
    ) {
        // One match arm per declaration of the language (`param`, `state`, `algebraic`, …):
        // long because the language is, each arm short.
        let name = format!("{}{ident}", self.prefix);
        if self.already_declared(ident) {
            return;
        }
        let origin = local.to_token_stream();
        let in_component = self.instance.is_some();
        match kind {
            Declaration::Body | Declaration::SpatialBody | Declaration::QuaternionState
                if in_component =>
            {
                self.cx.error_at(local, format!("a component declares no `{}`: bodies and joints belong to the model, which connects the component to them through flanges", kind.name()));
            }
            Declaration::Body | Declaration::Ground => {
                S::body(self, ident, kind.name(), call, local)
            }
            Declaration::SpatialBody => S::spatial_body(self, ident, call, local),
            Declaration::Param => {
                if !self.arity(call, "param", 1) {
                    return;
                }
                // An instance's argument replaces the default: a number
                // makes the instance's own parameter, an expression of
                // the enclosing parameters binds it.
                let given = self.overrides.get(&ident.to_string()).copied();
                if let Some(v) = given.filter(|&v| self.g.as_number(v).is_none()) {
                    return self.bind(ident, Binding::Value { id: v, mutable: false });
                }
                let v = match given {
                    Some(v) => v,
                    None => self.constant(&call.args[0]).unwrap_or_else(|| self.g.zero()),
                };
                let default = self.g.as_number(v).map_or(f64::NAN, |n| n.to_f64());
                let field = format!("{}{ident}", self.field_prefix);
                if let Some(other) = self.params.iter().find(|p| p.ident == field) {
                    let message = format!("the parameter `{name}` would be the field `{field}`, which `{}` already is: rename an instance", other.path);
                    return self.cx.error_at(ident, message);
                }
                match self.g.parameter(&field) {
                    Ok(id) => {
                        let field = syn::Ident::new(&field, ident.span());
                        self.params.push(Param { ident: field, default, doc, path: name });
                        self.bind(ident, Binding::Param(id));
                    }
                    Err(e) => self.cx.error_at(ident, e),
                }
            }
            Declaration::State => {
                if !self.arity(call, "state", 1) {
                    return;
                }
                // A bad initial value is reported; the state is still
                // declared, so its uses raise no second error.
                let init = self.initial_value(&call.args[0]).unwrap_or_else(|| self.g.zero());
                if let Some(symbol) = self.declare_state(name, init, ident, &origin, &doc) {
                    self.bind(ident, Binding::State(symbol));
                }
            }
            Declaration::StateArray | Declaration::QuaternionState => {
                if !self.arity(call, kind.name(), 1) {
                    return;
                }
                let Some(inits) = self.array_values(&call.args[0], kind) else { return };
                if inits.is_empty() {
                    return self.cx.error_at(&call.args[0], "an array needs at least one element");
                }
                if kind == Declaration::QuaternionState && inits.len() != 4 {
                    return self.cx.error_at(&call.args[0], "a quaternion has four components: `quaternion_state([1.0, 0.0, 0.0, 0.0])` (q0 = cos(θ/2) first)");
                }
                let mut symbols = Vec::new();
                for (i, init) in inits.into_iter().enumerate() {
                    let element = format!("{name}[{i}]");
                    let (Some(init), Ok(id)) = (init, self.g.state(&element)) else {
                        continue;
                    };
                    let symbol = self.g.as_symbol(id).unwrap_or(SymbolId(0));
                    self.states.push(StateDecl {
                        name: element,
                        symbol,
                        init,
                        origin: origin.clone(),
                        fixed: false,
                        doc: doc.clone(),
                        avoid: false,
                        prefer: false,
                    });
                    symbols.push(symbol);
                }
                if kind == Declaration::QuaternionState && symbols.len() == 4 {
                    // |q|² − 1, kept at zero by projection (course notes §4.1.3).
                    let mut terms = Vec::with_capacity(5);
                    for &s in &symbols {
                        let q = self.g.symbol_node(s);
                        match self.g.mul(q, q) {
                            Ok(t) => terms.push(t),
                            Err(e) => return self.cx.error_at(ident, e),
                        }
                    }
                    terms.push(self.g.int(-1));
                    match self.g.sum(&terms) {
                        Ok(value) => {
                            self.invariants.push(UserInvariant { value, origin: origin.clone() })
                        }
                        Err(e) => return self.cx.error_at(ident, e),
                    }
                }
                self.bind(ident, Binding::StateArray(symbols));
            }
            Declaration::Algebraic => {
                if !self.arity(call, "algebraic", 1) {
                    return;
                }
                let init = self.initial_value(&call.args[0]).unwrap_or_else(|| self.g.zero());
                if let Some(id) = self.declare_algebraic(name, init, ident, &origin, doc) {
                    self.bind(ident, Binding::Algebraic(id));
                }
            }
            Declaration::AlgebraicArray => {
                if !self.arity(call, "algebraic_array", 1) {
                    return;
                }
                let Some(guesses) = self.array_values(&call.args[0], kind) else { return };
                if guesses.is_empty() {
                    return self.cx.error_at(&call.args[0], "an array needs at least one element");
                }
                let mut elements = Vec::with_capacity(guesses.len());
                for (i, guess) in guesses.into_iter().enumerate() {
                    let guess = guess.unwrap_or_else(|| self.g.zero());
                    let element = format!("{name}[{i}]");
                    match self.declare_algebraic(element, guess, ident, &origin, doc.clone()) {
                        Some(id) => elements.push(id),
                        None => return,
                    }
                }
                self.bind(ident, Binding::AlgebraicArray(elements));
            }
            Declaration::Time => {
                if !self.arity(call, "time", 0) {
                    return;
                }
                // A component reads the model's time, declared or not.
                if let Some(time) = self.time.filter(|_| in_component || self.time_implicit) {
                    self.time_implicit &= in_component;
                    let id = self.g.symbol_node(time);
                    return self.bind(ident, Binding::Time(id));
                }
                if in_component {
                    let names =
                        std::iter::once("t".to_string()).chain((0..).map(|k| format!("__time{k}")));
                    let created = names.into_iter().find_map(|n| self.g.time(&n).ok());
                    if let Some(id) = created {
                        self.time = self.g.as_symbol(id);
                        self.time_implicit = true;
                        self.bind(ident, Binding::Time(id));
                    }
                    return;
                }
                if self.time.is_some() {
                    return self
                        .cx
                        .error_at(local, "the time is already declared: a model has one `time()`");
                }
                match self.g.time(&name) {
                    Ok(id) => {
                        self.time = self.g.as_symbol(id);
                        self.bind(ident, Binding::Time(id));
                    }
                    Err(e) => self.cx.error_at(ident, e),
                }
            }
            // Met first, with its settings, by the statement; here without.
            Declaration::Event => {
                self.event(Trigger { ident: Some(ident), call, settings: &[], doc, origin: local })
            }
            Declaration::Discrete => self.discrete(ident, call, doc, local),
            Declaration::Input => self.input(ident, call, doc, local),
            Declaration::Output => {
                if !self.arity(call, "output", 1) {
                    return;
                }
                let Some(value) = self.value(&call.args[0]) else {
                    return;
                };
                let declared = self.instance.is_none();
                self.outputs.push(Output { name, value, doc, origin, declared });
                self.bind(ident, Binding::Value { id: value, mutable: false });
            }
            Declaration::OutputArray => {
                if !self.arity(call, "output_array", 1) {
                    return;
                }
                let Some(values) = self.array_values(&call.args[0], kind) else { return };
                if values.is_empty() {
                    return self.cx.error_at(&call.args[0], "an array needs at least one element");
                }
                let Some(values) = values.into_iter().collect::<Option<Vec<Id>>>() else {
                    return self.bind(ident, Binding::Broken);
                };
                for (i, &value) in values.iter().enumerate() {
                    let (name, doc, origin) = (format!("{name}[{i}]"), doc.clone(), origin.clone());
                    let declared = self.instance.is_none();
                    self.outputs.push(Output { name, value, doc, origin, declared });
                }
                self.bind(ident, Binding::ValueArray(values));
            }
        }
    }

    /// The elements of an array declaration's argument: `[a, b]`,
    /// `[a; N]` or `(0..N).map(|i| ..)`, each an initial value (constants
    /// and parameters) but for `output_array`'s, which may read anything;
    /// `None` once the shape is reported.
    fn array_values(&mut self, argument: &Expr, kind: Declaration) -> Option<Vec<Option<Id>>> {
        let any_value = kind == Declaration::OutputArray;
        let element = |this: &mut Self, e: &Expr| match any_value {
            true => this.value(e),
            false => this.initial_value(e),
        };
        match argument {
            Expr::Array(a) => Some(a.elems.iter().map(|e| element(self, e)).collect()),
            Expr::Repeat(r) => {
                let v = element(self, &r.expr);
                self.index_constant(&r.len).map(|n| vec![v; n])
            }
            Expr::MethodCall(m) if m.method == "map" => self.values_by_index(m, any_value),
            other => {
                let name = kind.name();
                let what = if any_value { "values" } else { "initial values" };
                self.cx.error_at(other, format!("`{name}` takes an array of {what}: `{name}([1.0, 0.0])`, `{name}([0.0; N])` or `{name}((0..N).map(|i| ...))`"));
                None
            }
        }
    }

    /// An initial value or guess: constants and parameters only.
    /// The initial values of `(0..N).map(|i| value)`: `value` with `i`
    /// bound to each index of the range in turn, as a loop binds it.
    pub(in crate::front) fn values_by_index(
        &mut self,
        m: &syn::ExprMethodCall,
        any_value: bool,
    ) -> Option<Vec<Option<Id>>> {
        let how = "write the initial values as `(0..N).map(|i| 1.0 + 0.1 * (i as f64))`";
        let mut receiver = &*m.receiver;
        while let Expr::Paren(p) = receiver {
            receiver = &p.expr;
        }
        let (Expr::Range(range), [Expr::Closure(closure)]) =
            (receiver, m.args.iter().collect::<Vec<_>>().as_slice())
        else {
            self.cx.error_at(m, how);
            return None;
        };
        let (Some(start), Some(end), [Pat::Ident(var)]) =
            (&range.start, &range.end, closure.inputs.iter().collect::<Vec<_>>().as_slice())
        else {
            self.cx.error_at(m, how);
            return None;
        };
        let (start, end) = (self.index_constant(start)?, self.index_constant(end)?);
        let end = match range.limits {
            syn::RangeLimits::HalfOpen(_) => end,
            syn::RangeLimits::Closed(_) => end + 1,
        };
        let values = (start..end)
            .map(|i| {
                let index = self.g.int(i as i64);
                self.integer_names.insert(var.ident.to_string());
                self.scopes.push(HashMap::from([(var.ident.to_string(), Binding::Const(index))]));
                let value = match any_value {
                    true => self.value(&closure.body),
                    false => self.initial_value(&closure.body),
                };
                self.scopes.pop();
                value
            })
            .collect();
        Some(values)
    }

    pub(crate) fn initial_value(&mut self, e: &Expr) -> Option<Id> {
        let v = self.value(e)?;
        let bad = self
            .g
            .free_symbols(v)
            .into_iter()
            .find(|s| self.g.symbol(*s).kind != SymbolKind::Parameter);
        if let Some(s) = bad {
            let name = self.g.symbol(s).name.clone();
            self.cx.error_at(
                e,
                format!("an initial value may use constants and parameters, not `{name}`"),
            );
            return None;
        }
        Some(v)
    }
}
