//! Relations on model variables, with Modelica's event semantics: a
//! condition `v < -ve` (`<`, `<=`, `>`, `>=`) in an `if` (a value or
//! equations), `min`, `max` and `sign` becomes a discrete boolean, held
//! between events and changed by two events on `p` (`−ve − v` here, the
//! relation being `p > 0`): where `p` rises through zero the relation turns
//! true, where it falls, false. So the branch taken never changes inside a
//! step; each method steps to the crossing and restarts there. The run
//! sets each relation from its value at the start (`start_relations`).
//! Inside `no_event(..)` a relation is the step `heaviside(p)` instead,
//! with no event (for an expression smooth enough at the switch).

use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use crate::front::ir::{Action, Equation, Event, EventDirection, Relation};
use crate::{Func, Id};
use quote::ToTokens;
use syn::spanned::Spanned;
use syn::{BinOp, Expr};

impl<S: SceneLanguage> Lower<'_, S> {
    /// Whether `e` reads a model variable (or a name the lowering does not
    /// know, whose error the relation's path reports), rather than
    /// constants alone (loop indices, `const`s).
    pub(in crate::front) fn mentions_variable(&self, e: &Expr) -> bool {
        match e {
            Expr::Lit(_) => false,
            Expr::Paren(p) => self.mentions_variable(&p.expr),
            Expr::Group(g) => self.mentions_variable(&g.expr),
            Expr::Unary(u) => self.mentions_variable(&u.expr),
            Expr::Binary(b) => self.mentions_variable(&b.left) || self.mentions_variable(&b.right),
            Expr::Cast(c) => self.mentions_variable(&c.expr),
            Expr::Path(p) => match p.path.get_ident().map(|i| self.lookup(&i.to_string())) {
                Some(Some(Binding::Const(_))) => false,
                Some(Some(Binding::Value { id, .. })) => self.g.as_number(*id).is_none(),
                _ => true,
            },
            Expr::Call(c) => {
                let constant_function = matches!(&*c.func, Expr::Path(f) if !f.path.is_ident("time") && !f.path.is_ident("der"));
                !constant_function || c.args.iter().any(|a| self.mentions_variable(a))
            }
            Expr::MethodCall(m) => {
                self.mentions_variable(&m.receiver)
                    || m.args.iter().any(|a| self.mentions_variable(a))
            }
            _ => true,
        }
    }

    /// The relation `cond` is, as the node of its discrete boolean (or,
    /// inside `no_event`, of its step), where it compares model
    /// variables; `None` for any other condition.
    pub(in crate::front) fn relation(&mut self, cond: &Expr) -> Option<Id> {
        let Expr::Binary(b) = cond else { return None };
        let greater = match b.op {
            BinOp::Gt(_) | BinOp::Ge(_) => true,
            BinOp::Lt(_) | BinOp::Le(_) => false,
            _ => return None,
        };
        if !self.mentions_variable(&b.left) && !self.mentions_variable(&b.right) {
            return None;
        }
        let inclusive = matches!(b.op, BinOp::Ge(_) | BinOp::Le(_));
        let (l, r) = (self.value(&b.left), self.value(&b.right));
        let (l, r) = (l?, r?);
        let p = if greater { self.g.sub(l, r) } else { self.g.sub(r, l) };
        let p = self.graph_result(p, cond)?;
        let text = crate::front::names::source_text(&cond.to_token_stream());
        self.relation_of(p, inclusive, &text, cond)
    }

    /// The discrete boolean of the relation `p > 0` (`p >= 0` where
    /// `inclusive`), made once per `p`, with its two events; inside
    /// `no_event`, `heaviside(p)`.
    /// `text` names it: its discrete is `(text)`, its events `(text)` and
    /// `!(text)`.
    pub(in crate::front) fn relation_of(
        &mut self,
        p: Id,
        inclusive: bool,
        text: &str,
        at: &Expr,
    ) -> Option<Id> {
        if self.no_event_depth > 0 {
            let sign = self.g.call(Func::Sign, p);
            let sign = self.graph_result(sign, at)?;
            self.non_smooth_calls.push((sign, at.to_token_stream()));
            let one = self.g.one();
            let r = self.g.add(one, sign).and_then(|s| {
                let half = self.g.rational(1, 2)?;
                self.g.mul(half, s)
            });
            return self.graph_result(r, at);
        }
        if let Some(known) = self.relations.iter().find(|r| r.value == p) {
            return Some(self.g.symbol_node(known.discrete));
        }
        let name = format!("{}({text})", self.prefix);
        let origin = at.to_token_stream();
        let ident = syn::Ident::new("relation", at.span());
        let zero = self.g.zero();
        let discrete = self.declare_state(name.clone(), zero, &ident, &origin, "")?;
        self.discretes.push(discrete);
        match self.g.derivative(discrete, 1) {
            Ok(rate) => self.equations.push(Equation {
                lhs: rate,
                rhs: zero,
                origin: origin.clone(),
                is_constraint: false,
                mode: Vec::new(),
            }),
            Err(err) => self.cx.error_at(at, err),
        }
        let one = self.g.one();
        let turns = |value: Id, direction: EventDirection, name: String| Event {
            name,
            value: p,
            direction,
            terminal: false,
            actions: vec![Action { target: discrete, value, origin: origin.clone() }],
            doc: String::new(),
            origin: origin.clone(),
        };
        let event = self.events.len();
        self.events.push(turns(one, EventDirection::Rising, name.clone()));
        self.events.push(turns(zero, EventDirection::Falling, format!("!{name}")));
        self.relations.push(Relation { value: p, discrete, event, inclusive });
        Some(self.g.symbol_node(discrete))
    }

    /// `if p > 0 { a } else { b }` inside `no_event(..)`: `h a + (1 − h) b`
    /// with `h = heaviside(p)`, no event.
    pub(in crate::front) fn stepped_if_value(&mut self, i: &syn::ExprIf) -> Option<Id> {
        let Some(h) = self.relation(&i.cond) else {
            self.cx.error_at(&i.cond, "inside `no_event`, an `if` on model variables compares two values: `if v > 0.0 { a } else { b }`");
            return None;
        };
        let then = self.branch_value(&i.then_branch);
        let other = match i.else_branch.as_ref().map(|(_, e)| &**e) {
            Some(Expr::Block(b)) => self.branch_value(&b.block),
            Some(other) => self.value(other),
            None => {
                self.cx.error_at(i, "an `if` used as a value needs an `else`");
                None
            }
        };
        let (then, other) = (then?, other?);
        let r = (|| {
            let difference = self.g.sub(then, other)?;
            let switched = self.g.mul(h, difference)?;
            self.g.add(other, switched)
        })();
        self.graph_result(r, &Expr::If(i.clone()))
    }

    /// `min(a, b)`, `max(a, b)` and `sign(x)` on model variables, with the
    /// relations they switch on.
    pub(in crate::front) fn switching_function(
        &mut self,
        name: &str,
        c: &syn::ExprCall,
        e: &Expr,
    ) -> Option<Id> {
        let arity = if name == "sign" { 1 } else { 2 };
        if !self.arity(c, name, arity) {
            return None;
        }
        let text = |k: usize| crate::front::names::source_text(&c.args[k].to_token_stream());
        if name == "sign" {
            let x = self.value(&c.args[0])?;
            let minus_x = self.g.neg(x);
            let minus_x = self.graph_result(minus_x, e)?;
            let positive = self.relation_of(x, false, &format!("{} > 0", text(0)), e)?;
            let negative = self.relation_of(minus_x, false, &format!("{} < 0", text(0)), e)?;
            let r = self.g.sub(positive, negative);
            return self.graph_result(r, e);
        }
        let (a, b) = (self.value(&c.args[0]), self.value(&c.args[1]));
        let (a, b) = (a?, b?);
        // min: a where a < b, i.e. b − a > 0; max: a where a > b.
        let p = if name == "min" { self.g.sub(b, a) } else { self.g.sub(a, b) };
        let p = self.graph_result(p, e)?;
        let relation = match name {
            "min" => format!("{} < {}", text(0), text(1)),
            _ => format!("{} > {}", text(0), text(1)),
        };
        let pick_a = self.relation_of(p, false, &relation, e)?;
        let r = (|| {
            let difference = self.g.sub(a, b)?;
            let switched = self.g.mul(pick_a, difference)?;
            self.g.add(b, switched)
        })();
        self.graph_result(r, e)
    }
}
