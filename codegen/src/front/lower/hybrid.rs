//! What makes a model hybrid: `.reinit(target, value)` on an event or a
//! clock, clocks (`every(h)`), discrete values (`discrete(v0)`), `pre(x)`,
//! and inputs from outside (`input(u0)`).

use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use crate::front::ir::{Action, Clock, Equation, InputDecl, Output};
use crate::{Id, SymbolId, SymbolKind};
use quote::ToTokens;
use syn::{Expr, Lit};

/// The declaration of an event or a clock, as the statement writes it.
pub(in crate::front) struct Trigger<'a> {
    /// Its `let` name; `None` for one written as a statement.
    pub ident: Option<&'a syn::Ident>,
    /// `event(g)` or `every(h)`.
    pub call: &'a syn::ExprCall,
    /// The settings after the call: `.rising()`, `.reinit(x, v)`, …
    pub settings: &'a [&'a syn::ExprMethodCall],
    /// Its doc comment.
    pub doc: String,
    /// The tokens its errors point at.
    pub origin: &'a dyn ToTokens,
}

impl<S: SceneLanguage> Lower<'_, S> {
    /// `.reinit(target, value)` on an event or a clock.
    pub(in crate::front) fn action(&mut self, m: &syn::ExprMethodCall) -> Option<Action> {
        if m.args.len() != 2 {
            self.cx.error_at(
                m,
                "`.reinit` takes what it sets and its new value: `.reinit(der(h), -e * pre(der(h)))`",
            );
            return None;
        }
        let target_expr = &m.args[0];
        let target = self.value(target_expr)?;
        let Some(symbol) = self.state_symbol(target) else {
            self.cx.error_at(
                target_expr,
                format!(
                    "`.reinit` sets a state, a derivative kept as a state (`der(h)` of a second-order `h`) or a discrete value, and `{}` is none of them",
                    target_expr.to_token_stream()
                ),
            );
            return None;
        };
        self.in_action = true;
        let value = self.value(&m.args[1]);
        self.in_action = false;
        // The `reinit(..)` alone, not the event before it.
        let mut origin = m.method.to_token_stream();
        origin.extend(m.args.to_token_stream());
        Some(Action { target: symbol, value: value?, origin })
    }

    /// The state or derivative `id` stands for, if it is one.
    fn state_symbol(&self, id: Id) -> Option<SymbolId> {
        self.g.as_symbol(id).filter(|&s| {
            matches!(self.g.symbol(s).kind, SymbolKind::State | SymbolKind::Derivative { .. })
        })
    }

    /// Whether `s` was declared `discrete(..)`.
    pub(in crate::front) fn is_discrete(&self, s: SymbolId) -> bool {
        self.discretes.contains(&s)
    }

    /// `pre(x)`: in an action, the value of `x` just before the instant;
    /// elsewhere, for a discrete value, the value itself (it changes only
    /// at events).
    pub(in crate::front) fn pre(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<Id> {
        if !self.arity(c, "pre", 1) {
            return None;
        }
        let arg = &c.args[0];
        let inner = self.value(arg)?;
        let Some(symbol) = self.state_symbol(inner) else {
            self.cx.error_at(
                arg,
                format!(
                    "`pre` takes a state or a discrete value, and `{}` is neither",
                    arg.to_token_stream()
                ),
            );
            return None;
        };
        if !self.in_action {
            if self.is_discrete(symbol) {
                return Some(inner);
            }
            self.cx.error_at(
                e,
                format!(
                    "`{}` is the value just before an event: read it in an action, `.reinit(..)`",
                    e.to_token_stream()
                ),
            );
            return None;
        }
        if let Some(&(p, _)) = self.pre.iter().find(|(_, of)| *of == symbol) {
            return Some(self.g.symbol_node(p));
        }
        let name = format!("pre({})", self.g.symbol(symbol).name);
        let id = match self.g.algebraic(&name) {
            Ok(id) => id,
            Err(err) => {
                self.cx.error_at(e, err);
                return None;
            }
        };
        let p = self.g.as_symbol(id)?;
        self.pre.push((p, symbol));
        Some(id)
    }

    /// `let u = discrete(v0);`: a state whose derivative is zero, changed
    /// only by actions. `v0` is a number, `true`/`false` (1 and 0), or an
    /// expression of the parameters.
    pub(in crate::front) fn discrete(
        &mut self,
        ident: &syn::Ident,
        call: &syn::ExprCall,
        doc: String,
        local: &syn::Local,
    ) {
        if !self.arity(call, "discrete", 1) {
            return;
        }
        let name = format!("{}{ident}", self.prefix);
        let init = match &call.args[0] {
            Expr::Lit(syn::ExprLit { lit: Lit::Bool(b), .. }) => self.g.int(i64::from(b.value)),
            other => self.initial_value(other).unwrap_or_else(|| self.g.zero()),
        };
        let origin = local.to_token_stream();
        let Some(symbol) = self.declare_state(name, init, ident, &origin, &doc) else {
            return;
        };
        self.discretes.push(symbol);
        self.bind(ident, Binding::State(symbol));
        match self.g.derivative(symbol, 1) {
            Ok(rate) => {
                let zero = self.g.zero();
                self.equations.push(Equation {
                    lhs: rate,
                    rhs: zero,
                    origin,
                    is_constraint: false,
                    mode: Vec::new(),
                });
            }
            Err(err) => self.cx.error_at(ident, err),
        }
    }

    /// The name of the event or clock `trigger` declares with `function`,
    /// or `None` where it declares none: its name taken, or its arguments
    /// wrong (both said).
    pub(in crate::front) fn trigger_declared(
        &mut self,
        trigger: &Trigger<'_>,
        function: &str,
    ) -> Option<String> {
        let name = self.trigger_name(trigger.ident, trigger.call);
        let taken = trigger.ident.is_some_and(|i| self.already_declared(i));
        (!taken && self.arity(trigger.call, function, 1)).then_some(name)
    }

    /// The name of an event or a clock: its `let` name, or for one written
    /// as a statement its source text (`every(0.1)`, then `every(0.1)#2`).
    fn trigger_name(&self, ident: Option<&syn::Ident>, call: &syn::ExprCall) -> String {
        if let Some(ident) = ident {
            return format!("{}{ident}", self.prefix);
        }
        let text =
            format!("{}{}", self.prefix, crate::front::names::source_text(&call.to_token_stream()));
        let taken = |n: &str| {
            self.events.iter().any(|e| e.name == n) || self.clocks.iter().any(|c| c.name == n)
        };
        (1..)
            .map(|k| if k == 1 { text.clone() } else { format!("{text}#{k}") })
            .find(|n| !taken(n))
            .unwrap_or(text)
    }

    /// `every(h)` or `event(g)` with settings, written as a statement: a
    /// clock, or an event that acts, named by its text; an event that
    /// does not act needs a name to be read by.
    pub(in crate::front) fn unnamed_trigger(
        &mut self,
        e: &Expr,
        call: &syn::ExprCall,
        settings: &[&syn::ExprMethodCall],
        clock: bool,
    ) {
        if clock {
            return self.clock(Trigger {
                ident: None,
                call,
                settings,
                doc: String::new(),
                origin: e,
            });
        }
        if settings.iter().any(|m| m.method == "reinit") {
            return self.event(Trigger {
                ident: None,
                call,
                settings,
                doc: String::new(),
                origin: e,
            });
        }
        self.cx
            .error_at(e, "an event needs a name to be looked up by: write `let hit = event(...);`")
    }

    /// `let tick = every(h).offset(t0).reinit(u, ..);`, or as a statement.
    pub(in crate::front) fn clock(&mut self, trigger: Trigger<'_>) {
        let Some(name) = self.trigger_declared(&trigger, "every") else {
            return;
        };
        let Trigger { ident, call, settings, doc, origin } = trigger;
        let period = self.initial_value(&call.args[0]);
        if let Some(p) = period.and_then(|p| self.g.as_number(p)) {
            if p.to_f64() <= 0.0 || !p.to_f64().is_finite() {
                self.cx.error_at(&call.args[0], "a clock's period is positive: `every(0.01)`");
            }
        }
        let mut offset = self.g.zero();
        let mut actions = Vec::new();
        for m in settings {
            match m.method.to_string().as_str() {
                "offset" if m.args.len() == 1 => {
                    if let Some(o) = self.initial_value(&m.args[0]) {
                        offset = o;
                    }
                }
                "offset" => self.cx.error_at(m, "`.offset` takes the first instant: `.offset(0.5)`"),
                "reinit" => actions.extend(self.action(m)),
                other => self.cx.error_at(
                    &m.method,
                    format!("unknown clock setting `.{other}()`: use `.offset(t0)` and `.reinit(u, value)`"),
                ),
            }
        }
        if actions.is_empty() && settings.iter().all(|m| m.method != "reinit") {
            self.cx.error_at(
                origin,
                format!(
                    "the clock `{name}` does nothing: give it actions, `every(h).reinit(u, value)`"
                ),
            );
        }
        let Some(period) = period else { return };
        let origin = origin.to_token_stream();
        self.clocks.push(Clock { name, period, offset, actions, doc, origin });
        if let Some(ident) = ident {
            self.bind(ident, Binding::Clock);
        }
    }

    /// `let u = input(u0);`: a signal the caller supplies at run time, a
    /// field `u: daegen::Input` of the model (the constant `u0` by
    /// default), read like an output.
    pub(in crate::front) fn input(
        &mut self,
        ident: &syn::Ident,
        call: &syn::ExprCall,
        doc: String,
        local: &syn::Local,
    ) {
        if !self.arity(call, "input", 1) {
            return;
        }
        if self.instance.is_some() {
            return self.cx.error_at(local, "a component declares no `input`: give it a `real_input()` connector, and the model an input connected to it");
        }
        let value = self.constant(&call.args[0]);
        let default = value.and_then(|v| self.g.as_number(v)).map(|n| n.to_f64());
        let Some(default) = default else {
            return self
                .cx
                .error_at(&call.args[0], "an input's value by default is a number: `input(0.0)`");
        };
        let name = ident.to_string();
        let (id, rate) = match self.g.input(&name).and_then(|id| {
            let s = self.g.as_symbol(id).unwrap_or(SymbolId(0));
            Ok((id, self.g.input_rate(s)?))
        }) {
            Ok(pair) => pair,
            Err(err) => return self.cx.error_at(ident, err),
        };
        let (Some(symbol), Some(rate)) = (self.g.as_symbol(id), self.g.as_symbol(rate)) else {
            return;
        };
        let field = syn::Ident::new(&name, ident.span());
        self.inputs.push(InputDecl { ident: field, default, doc: doc.clone(), symbol, rate });
        let origin = local.to_token_stream();
        self.outputs.push(Output { name, value: id, doc, origin, declared: false });
        self.bind(ident, Binding::Value { id, mutable: false });
    }
}
