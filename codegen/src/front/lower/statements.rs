//! Statements: `let`, equations `lhs == rhs;`, `constraint(..)`,
//! `init(..)`, assignments, and where each goes.

use super::declarations::Declaration;
use super::hybrid::Trigger;
use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use super::syntax::{call_name, doc_comment, is_compound_assignment, trigger_call};
use crate::front::components::connectors::ConnectorKind;
use crate::front::ir::{Equation, Init, UserInvariant};

use crate::{Id, SymbolKind};
use quote::ToTokens;
use std::collections::HashMap;
use syn::{BinOp, Expr, Pat, Stmt};

/// The name `let` binds: `x` of `let x` or `let x: f64`.
fn bound_name(pat: &Pat) -> Option<&syn::Ident> {
    match pat {
        Pat::Ident(p) => Some(&p.ident),
        Pat::Type(t) => bound_name(&t.pat),
        _ => None,
    }
}

/// A declaration inside a mode's branch.
const IN_MODE: &str = "a mode selects equations: declare states, variables, parameters, outputs and events before `if`, and write only equations inside";

impl<S: SceneLanguage> Lower<'_, S> {
    pub(in crate::front) fn stmt(&mut self, stmt: &Stmt) {
        match stmt {
            Stmt::Local(local) => {
                self.local(local);
                // A declaration whose value was refused (here, or where a
                // name it reads was) still declares its name, so that its
                // uses further down stay quiet: one mistake, one message.
                // (Only once a mistake is reported: a model without one
                // binds every name it declares.)
                if let (Some(ident), false) = (bound_name(&local.pat), self.cx.is_ok()) {
                    let name = ident.to_string();
                    if !self.scopes.last().is_some_and(|s| s.contains_key(&name)) {
                        self.bind(ident, Binding::Broken);
                    }
                }
            }
            Stmt::Item(syn::Item::Const(c)) => {
                if let Some(v) = self.constant(&c.expr) {
                    self.bind(&c.ident, Binding::Const(v));
                    let name = c.ident.to_string();
                    if crate::front::lower::integers::is_integer_type(&c.ty) {
                        self.integer_names.insert(name);
                    } else {
                        self.integer_names.remove(&name);
                    }
                }
            }
            Stmt::Expr(e, _) => self.expr_stmt(e),
            Stmt::Item(other) => {
                self.cx.error_at(other, "only `const` items are allowed in a model")
            }
            Stmt::Macro(m) => self.cx.error_at(m, "macros are not part of the model language"),
        }
    }

    /// Lowers statements a scene wrote for the user (a robot's bodies and
    /// joints), as if they stood where `at` does.
    pub(crate) fn generated_statements(&mut self, statements: &[Stmt]) {
        for s in statements {
            self.stmt(s);
        }
    }

    pub(in crate::front) fn local(&mut self, local: &syn::Local) {
        let (ident, mutable) = match &local.pat {
            Pat::Ident(p) => (p.ident.clone(), p.mutability.is_some()),
            Pat::Type(t) => match &*t.pat {
                Pat::Ident(p) => (p.ident.clone(), p.mutability.is_some()),
                other => return self.cx.error_at(other, "bind a single name: `let x = ...;`"),
            },
            other => return self.cx.error_at(other, "bind a single name: `let x = ...;`"),
        };
        let Some(init) = &local.init else {
            return self
                .cx
                .error_at(local, format!("`{ident}` needs a value: `let {ident} = ...;`"));
        };
        if let Some((_, else_branch)) = &init.diverge {
            return self
                .cx
                .error_at(else_branch, "`let ... else` is not part of the model language");
        }
        let e = &*init.expr;
        let doc = doc_comment(&local.attrs);
        if let Some((call, settings, clock)) = trigger_call(e) {
            let what = if clock { "every" } else { "event" };
            if self.mode_depth > 0 {
                self.bind(&ident, Binding::Broken);
                return self.cx.error_at(e, IN_MODE);
            }
            if self.in_loop() {
                return self.cx.error_at(
                    e,
                    format!("declare `{what}(...)` outside loops: each iteration would declare `{ident}` again"),
                );
            }
            let trigger =
                Trigger { ident: Some(&ident), call, settings: &settings, doc, origin: local };
            if clock {
                return self.clock(trigger);
            }
            return self.event(trigger);
        }
        // `state(x0).fixed()`: a value consistent initialization keeps;
        // `state(x0).avoid()`: the state eliminated when tied to others;
        // `state(x0).prefer()`: the state kept.
        // `flange().support()`: a support flange, at rest where unconnected.
        let (mut e, mut fixed, mut avoid, mut prefer, mut support) =
            (e, false, false, false, false);
        while let Expr::MethodCall(m) = e {
            let is_state = |r: &Expr| {
                let mut r = r;
                while let Expr::MethodCall(inner) = r {
                    r = &inner.receiver;
                }
                matches!(call_name(r), Some((n, _)) if n == "state" || n == "state_array")
            };
            let is_connector = |r: &Expr| matches!(call_name(r), Some((n, _)) if ConnectorKind::from_name(&n).is_some_and(|k| !k.is_signal()));
            match m.method.to_string().as_str() {
                "fixed" if m.args.is_empty() && is_state(&m.receiver) => fixed = true,
                "avoid" if m.args.is_empty() && is_state(&m.receiver) => avoid = true,
                "prefer" if m.args.is_empty() && is_state(&m.receiver) => prefer = true,
                "support" if m.args.is_empty() && is_connector(&m.receiver) => support = true,
                _ => break,
            }
            e = &m.receiver;
        }
        if let (Expr::Closure(closure), false) = (e, mutable) {
            if self.already_declared(&ident) {
                return;
            }
            return self.function(&ident, closure);
        }
        if let Some((name, call)) = call_name(e) {
            if let Some(kind) = ConnectorKind::from_name(&name) {
                return self.connector(&ident, kind, call, local, (doc, support));
            }
        }
        if self.instance_statement(&ident, e) {
            return;
        }
        if let Some((name, call)) = call_name(e) {
            if S::is_joint(&name) && self.instance.is_some() {
                return self.cx.error_at(e, format!("a component declares no `{name}`: bodies and joints belong to the model, which connects the component to them through flanges"));
            }
            if S::is_joint(&name) {
                if self.already_declared(&ident) {
                    return;
                }
                return S::joint(self, &name, Some(&ident), call, e);
            }
            if let Some(declaration) = Declaration::from_name(&name) {
                if self.mode_depth > 0 {
                    self.bind(&ident, Binding::Broken);
                    return self.cx.error_at(e, IN_MODE);
                }
                if self.in_loop() {
                    return self.cx.error_at(e, format!("declare `{name}(...)` outside loops: each iteration would declare `{ident}` again"));
                }
                if mutable {
                    self.cx.error_at(&local.pat, format!("a {name} cannot be `mut`: remove `mut`"));
                }
                let first = self.states.len();
                self.declaration(&ident, declaration, call, doc, local);
                for state in &mut self.states[first..] {
                    state.fixed = fixed;
                    state.avoid = avoid;
                    state.prefer = prefer;
                }
                return;
            }
        }
        if self.mentions_tensor(e) {
            let Some(t) = self.tensor(e) else {
                return self.bind(&ident, Binding::Broken);
            };
            match (t.as_scalar(), mutable) {
                (Some(id), _) => self.bind(&ident, Binding::Value { id, mutable }),
                (None, false) => self.bind(&ident, Binding::Tensor(t)),
                (None, true) => self.cx.error_at(
                    &local.pat,
                    format!("a {} cannot be `mut`: bind each new value with `let`", t.shape()),
                ),
            }
            return;
        }
        if let (Expr::Array(array), false) = (e, mutable) {
            let values: Vec<Option<Id>> = array.elems.iter().map(|v| self.value(v)).collect();
            match values.into_iter().collect::<Option<Vec<Id>>>() {
                Some(values) => self.bind(&ident, Binding::ValueArray(values)),
                None => self.bind(&ident, Binding::Broken),
            }
            return;
        }
        // `[value; N]`: N copies, as in `state_array([0.0; N])`.
        if let (Expr::Repeat(repeat), false) = (e, mutable) {
            let (Some(value), Some(n)) =
                (self.value(&repeat.expr), self.index_constant(&repeat.len))
            else {
                return;
            };
            self.bind(&ident, Binding::ValueArray(vec![value; n]));
            return;
        }
        match self.value(e) {
            Some(id) => self.bind(&ident, Binding::Value { id, mutable }),
            None => self.bind(&ident, Binding::Broken),
        }
    }

    pub(in crate::front) fn expr_stmt(&mut self, e: &Expr) {
        // `urdf("arm.urdf").floating();`
        if let Expr::MethodCall(m) = e {
            if let Some((name, call)) = call_name(&m.receiver).filter(|(n, _)| S::is_robot(n)) {
                if m.method != "floating" || !m.args.is_empty() {
                    return self.cx.error_at(
                        &m.method,
                        format!("`{name}(..)` takes `.floating()` (a free base), nothing else"),
                    );
                }
                return S::robot(self, call, e, true);
            }
        }
        if let Some((call, settings, clock)) = trigger_call(e) {
            if self.mode_depth > 0 {
                return self.cx.error_at(e, IN_MODE);
            }
            if self.in_loop() {
                let what = if clock { "every" } else { "event" };
                return self.cx.error_at(
                    e,
                    format!(
                        "write `{what}(...)` outside loops: each iteration would make it again"
                    ),
                );
            }
            return self.unnamed_trigger(e, call, &settings, clock);
        }
        match e {
            Expr::Binary(b) if matches!(b.op, BinOp::Eq(_)) && (self.mentions_tensor(&b.left) || self.mentions_tensor(&b.right)) => {
                // One equation per component.
                let (lhs, rhs) = (self.tensor(&b.left), self.tensor(&b.right));
                let (Some(lhs), Some(rhs)) = (lhs, rhs) else { return };
                if (lhs.rows, lhs.cols) != (rhs.rows, rhs.cols) {
                    return self.cx.error_at(e, format!("the two sides differ in shape: a {} and a {}", lhs.shape(), rhs.shape()));
                }
                for (&l, &r) in lhs.data.iter().zip(&rhs.data) {
                    self.equations.push(Equation { lhs: l, rhs: r, origin: e.to_token_stream(), is_constraint: false, mode: Vec::new() });
                }
            }
            Expr::Binary(b) if matches!(b.op, BinOp::Eq(_)) => {
                let (lhs, rhs) = (self.value(&b.left), self.value(&b.right));
                if let (Some(lhs), Some(rhs)) = (lhs, rhs) {
                    self.equations.push(Equation { lhs, rhs, origin: e.to_token_stream(), is_constraint: false, mode: Vec::new() });
                }
            }
            Expr::ForLoop(f) => self.for_loop(f),
            Expr::If(i) if self.mode_condition(&i.cond).is_some() => self.mode_if(i),
            Expr::If(i) => self.const_if(i),
            Expr::Assign(a) if !matches!(&*a.left, Expr::Path(_)) => {
                // `der(x) = f;`: an equation written with Rust's assignment.
                let (lhs, rhs) = (
                    crate::front::names::source_text(&a.left.to_token_stream()),
                    crate::front::names::source_text(&a.right.to_token_stream()),
                );
                self.cx.error_at(
                    a.eq_token,
                    format!("`=` assigns; write an equation with `==`: `{lhs} == {rhs};`"),
                );
            }
            Expr::Assign(a) => {
                let v = self.value(&a.right);
                self.assign(&a.left, v, e);
            }
            Expr::Binary(b) if is_compound_assignment(&b.op) => {
                let current = self.value(&b.left);
                let rhs = self.value(&b.right);
                let combined = match (current, rhs) {
                    (Some(c), Some(r)) => self.arith(&b.op, c, r, e),
                    _ => None,
                };
                self.assign(&b.left, combined, e);
            }
            Expr::Block(b) => {
                self.scopes.push(HashMap::new());
                for s in &b.block.stmts {
                    self.stmt(s);
                }
                self.scopes.pop();
            }
            _ => match call_name(e) {
                Some((name, call)) if name == "constraint" => {
                    if self.arity(call, "constraint", 1) {
                        // A vector constraint is one per component.
                        if let Some(phi) = self.tensor(&call.args[0]) {
                            let zero = self.g.zero();
                            for &c in &phi.data {
                                self.equations.push(Equation { lhs: c, rhs: zero, origin: e.to_token_stream(), is_constraint: true, mode: Vec::new() });
                            }
                        }
                    }
                }
                Some((name, call)) if S::is_joint(&name) => {
                    S::joint(self, &name, None, call, e)
                }
                Some((name, call)) if S::is_load(&name) => S::load(self, &name, call, e),
                Some((name, call)) if S::is_robot(&name) => S::robot(self, call, e, false),
                Some((name, call)) if name == "invariant" => {
                    if self.arity(call, "invariant", 1) {
                        if let Some(value) = self.tensor(&call.args[0]) {
                            for &v in &value.data {
                                self.invariants.push(UserInvariant { value: v, origin: e.to_token_stream() });
                            }
                        }
                    }
                }
                Some((name, call)) if name == "init" => self.init(call, e),
                Some((name, call)) if name == "initial" => self.initial_equation(call, e),
                Some((name, call)) if name == "connect" => self.connect(call, e),
                Some((name, _)) if Declaration::from_name(&name).is_some() => {
                    self.cx.error_at(e, format!("`{name}(...)` declares a variable: write `let x = {name}(...);`"))
                }
                _ => self.cx.error_at(
                    e,
                    "a model statement is `let`, an equation `lhs == rhs;`, `constraint(...)`, `init(...)`, `connect(...)`, `const` or `for`",
                ),
            },
        }
    }

    pub(in crate::front) fn assign(&mut self, target: &Expr, value: Option<Id>, whole: &Expr) {
        let name = match target {
            Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
            _ => None,
        };
        let Some(name) = name else {
            return self.cx.error_at(target, "only `let mut` intermediates can be assigned to");
        };
        match self.lookup(&name).cloned() {
            Some(Binding::Value { mutable: true, .. }) => {
                if let Some(id) = value {
                    // Assign in the scope that declared it, so loops can accumulate.
                    if let Some(scope) = self.scopes.iter_mut().rev().find(|s| s.contains_key(&name)) {
                        scope.insert(name, Binding::Value { id, mutable: true });
                    }
                }
            }
            Some(Binding::Broken) => {}
            Some(Binding::Value { mutable: false, .. }) => {
                self.cx.error_at(whole, format!("`{name}` is not `mut`: declare it with `let mut {name} = ...;` to accumulate into it"))
            }
            Some(b) => {
                let what = b.describe();
                self.cx.error_at(whole, format!("cannot assign to `{name}`, {what}: state its dynamics as an equation, e.g. `der({name}) == ...;`"))
            }
            None => self.unknown_name(target, &name),
        }
    }

    /// `initial(lhs == rhs);`: an equation for the start alone.
    fn initial_equation(&mut self, call: &syn::ExprCall, whole: &Expr) {
        if !self.arity(call, "initial", 1) {
            return;
        }
        let Expr::Binary(b) = &call.args[0] else {
            return self.cx.error_at(
                &call.args[0],
                "`initial` takes an equation that holds at the start: `initial(der(w) == 0.0);`",
            );
        };
        if !matches!(b.op, BinOp::Eq(_)) {
            return self.cx.error_at(
                &call.args[0],
                "`initial` takes an equation that holds at the start: `initial(der(w) == 0.0);`",
            );
        }
        let (lhs, rhs) = (self.value(&b.left), self.value(&b.right));
        if let (Some(lhs), Some(rhs)) = (lhs, rhs) {
            self.initial_equations.push(crate::front::ir::InitialEquation {
                lhs,
                rhs,
                origin: whole.to_token_stream(),
            });
        }
    }

    pub(in crate::front) fn init(&mut self, call: &syn::ExprCall, whole: &Expr) {
        if !self.arity(call, "init", 2) {
            return;
        }
        if S::joint_init(self, &call.args[0], &call.args[1], whole) {
            return;
        }
        let (target, value) = (self.value(&call.args[0]), self.initial_value(&call.args[1]));
        let (Some(target), Some(value)) = (target, value) else {
            return;
        };
        match self.g.as_symbol(target).map(|s| (s, self.g.symbol(s).kind)) {
            Some((s, SymbolKind::Derivative { .. })) => {
                self.inits.push(Init { target: s, value, origin: whole.to_token_stream() })
            }
            // A part's state (`init(c1.v, 1.0)`), as Modelica's modifier
            // `C1(v(start = 1, fixed = true))`: the start the run keeps,
            // so a tie keeps the state while another will do.
            Some((s, SymbolKind::State)) if self.states.iter().any(|d| d.symbol == s) => {
                if let Some(decl) = self.states.iter_mut().find(|d| d.symbol == s) {
                    decl.init = value;
                    decl.fixed = true;
                    self.fixed_starts.push((s, whole.to_token_stream()));
                }
            }
            _ => self.cx.error_at(&call.args[0], "`init` sets a state's start, `init(c1.v, 1.0)`, or a derivative's, `init(der(x), 0.0)`"),
        }
    }
}
