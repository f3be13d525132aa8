//! Modes: `if on { .. } else { .. }` on a discrete boolean, or `if gear
//! == 2 { .. } else if .. { .. }` on a discrete integer. As a statement it
//! selects equations (each mode's equations are analysed alone at compile
//! time); on a boolean, as a value, it picks one of two values.

use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use crate::front::ir::ModeGuard;
use crate::{Id, SymbolId};
use quote::ToTokens;
use std::collections::HashMap;
use syn::{BinOp, Expr, Lit, UnOp};

impl<S: SceneLanguage> Lower<'_, S> {
    /// The condition on a discrete value a condition is: `on`, `!on`,
    /// `gear == 2`, `gear != 2`, or a relation on model variables held in
    /// a discrete boolean (`v < -ve`, see `relations`); `None` for any
    /// other (one on constants, unrolled as written).
    pub(in crate::front) fn mode_condition(&mut self, cond: &Expr) -> Option<ModeGuard> {
        match cond {
            Expr::Binary(b)
                if matches!(b.op, BinOp::Lt(_) | BinOp::Le(_) | BinOp::Gt(_) | BinOp::Ge(_))
                    && self.no_event_depth == 0 =>
            {
                let held = self.relation(cond)?;
                let mode = self.g.as_symbol(held)?;
                Some(ModeGuard { mode, values: vec![1], holds: true, boolean: true })
            }
            Expr::Paren(p) => self.mode_condition(&p.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Not(_)) => {
                self.mode_condition(&u.expr).map(|g| ModeGuard { holds: !g.holds, ..g })
            }
            Expr::Path(_) => {
                let mode = self.discrete_named(cond)?;
                Some(ModeGuard { mode, values: vec![1], holds: true, boolean: true })
            }
            Expr::Binary(b) if matches!(b.op, BinOp::Eq(_) | BinOp::Ne(_)) => {
                let holds = matches!(b.op, BinOp::Eq(_));
                let (mode, value) =
                    match (self.discrete_named(&b.left), self.discrete_named(&b.right)) {
                        (Some(m), None) => (m, whole_number(&b.right)?),
                        (None, Some(m)) => (m, whole_number(&b.left)?),
                        _ => return None,
                    };
                Some(ModeGuard { mode, values: vec![value], holds, boolean: false })
            }
            _ => None,
        }
    }

    /// The discrete value `e` names, if it names one.
    fn discrete_named(&self, e: &Expr) -> Option<SymbolId> {
        let Expr::Path(p) = e else { return None };
        match self.lookup(&p.path.get_ident()?.to_string()) {
            Some(Binding::State(s)) if self.is_discrete(*s) => Some(*s),
            _ => None,
        }
    }

    /// `if on { equations } else { equations }`: each branch's equations
    /// hold in its mode only. Branches hold equations and named values,
    /// no declarations.
    pub(in crate::front) fn mode_if(&mut self, i: &syn::ExprIf) {
        let Some(guard) = self.mode_condition(&i.cond) else { return };
        let otherwise = ModeGuard { holds: !guard.holds, ..guard.clone() };
        self.mode_branch(&i.then_branch.stmts, guard, i);
        match i.else_branch.as_ref().map(|(_, e)| &**e) {
            Some(Expr::Block(b)) => self.mode_branch(&b.block.stmts, otherwise, i),
            Some(Expr::If(inner)) => {
                let stmt = syn::Stmt::Expr(Expr::If(inner.clone()), None);
                self.mode_branch(std::slice::from_ref(&stmt), otherwise, i);
            }
            Some(other) => self.cx.error_at(other, "expected a block after `else`"),
            None => {}
        }
    }

    /// The statements of one branch, their equations marked with `guard`.
    fn mode_branch(&mut self, stmts: &[syn::Stmt], guard: ModeGuard, at: &syn::ExprIf) {
        // A relation a branch compares is held in a discrete boolean of its
        // own, with its events: those are the relation's, not declarations.
        let declared = |l: &Self| {
            let relations = l.relations.len();
            (
                l.states.len() - relations,
                l.algebraics.len(),
                l.params.len(),
                l.events.len() - 2 * relations + l.clocks.len() + l.outputs.len() + l.inputs.len(),
            )
        };
        let (equations_before, declared_before) = (self.equations.len(), declared(self));
        self.scopes.push(HashMap::new());
        self.mode_depth += 1;
        for s in stmts {
            self.stmt(s);
        }
        self.mode_depth -= 1;
        self.scopes.pop();
        if declared(self) != declared_before {
            self.cx.error_at(
                at,
                "a mode selects equations: declare states, variables, parameters, outputs and events before `if`, and write only equations inside",
            );
        }
        let held: Vec<SymbolId> = self.relations.iter().map(|r| r.discrete).collect();
        for equation in &mut self.equations[equations_before..] {
            // A relation's discrete is constant in every mode.
            let rate_of = match self.g.as_symbol(equation.lhs).map(|s| self.g.symbol(s).kind) {
                Some(crate::SymbolKind::Derivative { of, .. }) => Some(of),
                _ => None,
            };
            if rate_of.is_some_and(|of| held.contains(&of)) {
                continue;
            }
            // Inner modes first: the outer guard joins theirs, all to hold.
            equation.mode.insert(0, guard.clone());
        }
    }

    /// `if on { a } else { b }` as a value: `on·a + (1 − on)·b`, exact for
    /// a boolean's 1 and 0 (between events it is one or the other).
    pub(in crate::front) fn mode_value(&mut self, i: &syn::ExprIf) -> Option<Id> {
        let guard = self.mode_condition(&i.cond)?;
        if !guard.boolean {
            self.cx.error_at(
                &i.cond,
                "a value is chosen by a boolean mode (`if on { a } else { b }`); by an integer one, write an equation in each branch: `if gear == 1 { ratio == 3.0; } else { ratio == 1.0; }`",
            );
            return None;
        }
        let (mode, value) = (guard.mode, guard.holds);
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

/// A whole number written as a literal (`2`, `-1`).
fn whole_number(e: &Expr) -> Option<i64> {
    match e {
        Expr::Lit(syn::ExprLit { lit: Lit::Int(i), .. }) => i.base10_parse().ok(),
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => whole_number(&u.expr).map(|v| -v),
        Expr::Paren(p) => whole_number(&p.expr),
        _ => None,
    }
}
