//! Constants and unrolling: `const`s evaluated, whole-number indices,
//! `for` loops and constant `if`s unrolled.

use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use super::syntax::is_comparison;

use crate::{Id, SymbolKind};
use std::collections::HashMap;
use syn::{BinOp, Expr, Lit, Pat, Stmt, UnOp};

/// Most loop iterations, over all loops, before unrolling is refused.
pub(super) const MAX_UNROLLED: usize = 100_000;

impl<S: SceneLanguage> Lower<'_, S> {
    /// A compile-time constant (literals, `const`s, loop indices, arithmetic).
    pub(in crate::front) fn constant(&mut self, e: &Expr) -> Option<Id> {
        let v = self.value(e)?;
        if self.g.as_number(v).is_some() {
            return Some(v);
        }
        self.not_constant(e, v);
        None
    }

    /// Says which variable keeps `e` from being a compile-time constant.
    pub(in crate::front) fn not_constant(&mut self, e: &Expr, v: Id) {
        let culprit = self.g.free_symbols(v).into_iter().next().map(|s| {
            let kind = match self.g.symbol(s).kind {
                SymbolKind::Parameter => "a parameter, known only at run time",
                SymbolKind::Time => "the time",
                _ => "a variable of the model",
            };
            format!("`{}` is {kind}", self.g.symbol(s).name)
        });
        let culprit = culprit.unwrap_or_else(|| "it is not a number".to_string());
        self.cx.error_at(e, format!("this must be a constant, but {culprit}: use literals, `const N: usize = 3;` and loop indices"));
    }

    /// A non-negative whole constant (loop bound, array index or length).
    pub(in crate::front) fn index_constant(&mut self, e: &Expr) -> Option<usize> {
        let v = self.value(e)?;
        match self.g.as_number(v).and_then(|n| n.as_integer()).and_then(|n| usize::try_from(n).ok())
        {
            Some(n) => Some(n),
            None => {
                if self.g.as_number(v).is_some() {
                    self.cx.error_at(e, "this must be a whole number ≥ 0");
                } else {
                    self.not_constant(e, v);
                }
                None
            }
        }
    }

    pub(in crate::front) fn for_loop(&mut self, f: &syn::ExprForLoop) {
        let Pat::Ident(var) = &*f.pat else {
            return self.cx.error_at(&f.pat, "loop over one index: `for i in 0..N`");
        };
        let Expr::Range(range) = &*f.expr else {
            return self.cx.error_at(&f.expr, "loop over a constant range: `for i in 0..N`");
        };
        let (Some(start), Some(end)) = (&range.start, &range.end) else {
            return self.cx.error_at(range, "the range needs both bounds: `0..N`");
        };
        let (Some(start), Some(end)) = (self.index_constant(start), self.index_constant(end))
        else {
            return;
        };
        let end = match range.limits {
            syn::RangeLimits::HalfOpen(_) => end,
            syn::RangeLimits::Closed(_) => end + 1,
        };
        let count = end.saturating_sub(start);
        self.unrolled += count;
        if self.unrolled > MAX_UNROLLED {
            return self
                .cx
                .error_at(&f.expr, format!("loops unroll to more than {MAX_UNROLLED} iterations"));
        }
        for i in start..end {
            let index = self.g.int(i as i64);
            self.integer_names.insert(var.ident.to_string());
            let mut scope = HashMap::new();
            scope.insert(var.ident.to_string(), Binding::Const(index));
            self.scopes.push(scope);
            for s in &f.body.stmts {
                self.stmt(s);
            }
            self.scopes.pop();
        }
    }

    pub(in crate::front) fn const_if(&mut self, i: &syn::ExprIf) {
        let Some(taken) = self.condition(&i.cond) else {
            return;
        };
        let branch: Option<Vec<Stmt>> = if taken {
            Some(i.then_branch.stmts.clone())
        } else {
            match &i.else_branch {
                Some((_, e)) => match &**e {
                    Expr::Block(b) => Some(b.block.stmts.clone()),
                    Expr::If(inner) => {
                        self.const_if(inner);
                        None
                    }
                    other => {
                        self.cx.error_at(other, "expected a block after `else`");
                        None
                    }
                },
                None => None,
            }
        };
        if let Some(stmts) = branch {
            self.scopes.push(HashMap::new());
            for s in &stmts {
                self.stmt(s);
            }
            self.scopes.pop();
        }
    }

    /// `if i == 0 { 1.0 } else { u[i - 1] }`, a condition on constants as a
    /// value: the value of the branch taken.
    pub(in crate::front) fn const_if_value(&mut self, i: &syn::ExprIf) -> Option<Id> {
        let taken = self.condition(&i.cond)?;
        if taken {
            return self.branch_value(&i.then_branch);
        }
        match i.else_branch.as_ref().map(|(_, e)| &**e) {
            Some(Expr::Block(b)) => self.branch_value(&b.block),
            Some(Expr::If(inner)) => self.const_if_value(inner),
            Some(other) => self.value(other),
            None => {
                self.cx.error_at(i, "an `if` used as a value needs an `else`: `if i == 0 { 1.0 } else { u[i - 1] }`");
                None
            }
        }
    }

    /// The value of a branch of an `if` used as a value: one expression.
    pub(in crate::front) fn branch_value(&mut self, b: &syn::Block) -> Option<Id> {
        match b.stmts.as_slice() {
            [Stmt::Expr(e, None)] => self.value(e),
            _ => {
                self.cx.error_at(b, "a branch of an `if` used as a value is one expression: `if i == 0 { 1.0 } else { u[i - 1] }`");
                None
            }
        }
    }

    /// A condition on constants (loop indices): `i != j`, `i < N && j > 0`.
    pub(in crate::front) fn condition(&mut self, e: &Expr) -> Option<bool> {
        match e {
            Expr::Paren(p) => self.condition(&p.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Not(_)) => self.condition(&u.expr).map(|b| !b),
            Expr::Lit(syn::ExprLit { lit: Lit::Bool(b), .. }) => Some(b.value),
            Expr::Binary(b) if matches!(b.op, BinOp::And(_) | BinOp::Or(_)) => {
                let (l, r) = (self.condition(&b.left)?, self.condition(&b.right)?);
                Some(if matches!(b.op, BinOp::And(_)) { l && r } else { l || r })
            }
            Expr::Binary(b) if is_comparison(&b.op) => {
                let (l, r) = (self.value(&b.left)?, self.value(&b.right)?);
                match (self.g.as_number(l), self.g.as_number(r)) {
                    (Some(l), Some(r)) => {
                        let (l, r) = (l.to_f64(), r.to_f64());
                        Some(match b.op {
                            BinOp::Eq(_) => l == r,
                            BinOp::Ne(_) => l != r,
                            BinOp::Lt(_) => l < r,
                            BinOp::Le(_) => l <= r,
                            BinOp::Gt(_) => l > r,
                            _ => l >= r,
                        })
                    }
                    _ => {
                        self.cx.error_at(e, "`if` on model variables compares them with `<`, `<=`, `>` or `>=` (a relation, switched by events where it crosses); `==` and `!=` compare constants (loop indices) or a discrete value");
                        None
                    }
                }
            }
            other => {
                self.cx
                    .error_at(other, "`if` is only for conditions on constants, such as `i != j`");
                None
            }
        }
    }
}
