//! Modes: `if on { .. } else { .. }` on a discrete boolean. As a
//! statement it selects equations (each mode's equations are analysed
//! alone at compile time); as a value it picks one of two values.

use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use crate::{Id, SymbolId};
use quote::ToTokens;
use std::collections::HashMap;
use syn::{Expr, UnOp};

impl<S: SceneLanguage> Lower<'_, S> {
    /// The discrete value a condition tests and the value that makes it
    /// hold: `on` (true) or `!on` (false); `None` for any other condition
    /// (one on constants, unrolled as written).
    pub(in crate::front) fn mode_condition(&self, cond: &Expr) -> Option<(SymbolId, bool)> {
        match cond {
            Expr::Paren(p) => self.mode_condition(&p.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Not(_)) => {
                self.mode_condition(&u.expr).map(|(s, value)| (s, !value))
            }
            Expr::Path(p) => {
                let name = p.path.get_ident()?.to_string();
                match self.lookup(&name) {
                    Some(Binding::State(s)) if self.is_discrete(*s) => Some((*s, true)),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// `if on { equations } else { equations }`: each branch's equations
    /// hold in its mode only. Branches hold equations and named values,
    /// no declarations.
    pub(in crate::front) fn mode_if(&mut self, i: &syn::ExprIf) {
        let Some((mode, value)) = self.mode_condition(&i.cond) else { return };
        self.mode_branch(&i.then_branch.stmts, (mode, value), i);
        match i.else_branch.as_ref().map(|(_, e)| &**e) {
            Some(Expr::Block(b)) => self.mode_branch(&b.block.stmts, (mode, !value), i),
            Some(Expr::If(inner)) => {
                let stmt = syn::Stmt::Expr(Expr::If(inner.clone()), None);
                self.mode_branch(std::slice::from_ref(&stmt), (mode, !value), i);
            }
            Some(other) => self.cx.error_at(other, "expected a block after `else`"),
            None => {}
        }
    }

    /// The statements of one branch, their equations marked with `guard`.
    fn mode_branch(&mut self, stmts: &[syn::Stmt], guard: (SymbolId, bool), at: &syn::ExprIf) {
        let before = (
            self.equations.len(),
            self.states.len(),
            self.algebraics.len(),
            self.params.len(),
            self.events.len() + self.clocks.len() + self.outputs.len() + self.inputs.len(),
        );
        self.scopes.push(HashMap::new());
        self.mode_depth += 1;
        for s in stmts {
            self.stmt(s);
        }
        self.mode_depth -= 1;
        self.scopes.pop();
        let after = (
            self.states.len(),
            self.algebraics.len(),
            self.params.len(),
            self.events.len() + self.clocks.len() + self.outputs.len() + self.inputs.len(),
        );
        if after != (before.1, before.2, before.3, before.4) {
            self.cx.error_at(
                at,
                "a mode selects equations: declare states, variables, parameters, outputs and events before `if`, and write only equations inside",
            );
        }
        for equation in &mut self.equations[before.0..] {
            // Inner modes first: the outer guard joins theirs.
            if !equation.mode.iter().any(|&(s, _)| s == guard.0) {
                equation.mode.insert(0, guard);
            }
        }
    }

    /// `if on { a } else { b }` as a value: `on·a + (1 − on)·b`, exact for
    /// a boolean's 1 and 0 (between events it is one or the other).
    pub(in crate::front) fn mode_value(&mut self, i: &syn::ExprIf) -> Option<Id> {
        let (mode, value) = self.mode_condition(&i.cond)?;
        let then = self.branch_value(&i.then_branch);
        let other = match i.else_branch.as_ref().map(|(_, e)| &**e) {
            Some(Expr::Block(b)) => self.branch_value(&b.block),
            Some(other) => self.value(other),
            None => {
                self.cx.error_at(
                    i,
                    format!(
                        "an `if` used as a value needs an `else`: `if {} {{ p }} else {{ 0.0 }}`",
                        i.cond.to_token_stream()
                    ),
                );
                None
            }
        };
        let (then, other) = (then?, other?);
        let (on_value, off_value) = if value { (then, other) } else { (other, then) };
        let on = self.g.symbol_node(mode);
        let r = (|| {
            let difference = self.g.sub(on_value, off_value)?;
            let switched = self.g.mul(on, difference)?;
            self.g.add(off_value, switched)
        })();
        self.graph_result(r, &Expr::If(i.clone()))
    }
}
