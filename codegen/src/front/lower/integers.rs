//! Rust's integer semantics for index arithmetic: which expressions of a
//! model are whole-number typed (integer literals, loop indices, the index
//! of `state_array((0..N).map(|k| ..))`, integer `const`s, and `+ − * / %`
//! and casts to integer types of them), so that `k / 2` divides as Rust
//! does, truncating, and not as the real numbers do.

use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use crate::Id;
use syn::{BinOp, Expr, Lit, Type};

/// Whether `ty` is one of Rust's integer types.
pub(crate) fn is_integer_type(ty: &Type) -> bool {
    let Type::Path(p) = ty else { return false };
    p.path.get_ident().is_some_and(|i| {
        matches!(
            i.to_string().as_str(),
            "usize" | "isize" | "u8" | "u16" | "u32" | "u64" | "i8" | "i16" | "i32" | "i64"
        )
    })
}

impl<S: SceneLanguage> Lower<'_, S> {
    /// Whether `e` is whole-number typed in Rust.
    pub(in crate::front) fn is_integer_expr(&self, e: &Expr) -> bool {
        match e {
            Expr::Lit(l) => match &l.lit {
                Lit::Int(i) => !matches!(i.suffix(), "f32" | "f64"),
                _ => false,
            },
            Expr::Paren(p) => self.is_integer_expr(&p.expr),
            Expr::Group(g) => self.is_integer_expr(&g.expr),
            Expr::Cast(c) => is_integer_type(&c.ty),
            Expr::Unary(u) => self.is_integer_expr(&u.expr),
            Expr::Binary(b) => {
                matches!(
                    b.op,
                    BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Div(_) | BinOp::Rem(_)
                ) && self.is_integer_expr(&b.left)
                    && self.is_integer_expr(&b.right)
            }
            Expr::Path(p) => p.path.get_ident().is_some_and(|ident| {
                let name = ident.to_string();
                self.integer_names.contains(&name)
                    && matches!(self.lookup(&name), Some(Binding::Const(_)))
            }),
            _ => false,
        }
    }

    /// `a / b` for whole numbers, truncated towards zero as Rust's integer
    /// division is; `None` (and an error at `at`) for a zero divisor, and
    /// for numbers written as integers that do not divide (`1 / 3`, which
    /// Rust makes 0: a real number was meant).
    pub(in crate::front) fn integer_division(&mut self, a: Id, b: Id, at: &Expr) -> Option<Id> {
        let whole = |x: Id| self.g.as_number(x).and_then(|n| n.as_integer());
        match (whole(a), whole(b)) {
            (Some(_), Some(0)) => {
                self.cx.error_at(at, "division by zero in an index expression");
                None
            }
            (Some(x), Some(y)) if x % y != 0 && literals_only(at) => {
                self.cx.error_at(
                    at,
                    format!("`{x} / {y}` divides whole numbers, which Rust truncates to {}: write `{x}.0 / {y}.0` for the real quotient", x / y),
                );
                None
            }
            (Some(x), Some(y)) => Some(self.g.int(x / y)),
            // Not constants after all (an error reported elsewhere): divide.
            _ => {
                let r = self.g.div(a, b);
                self.graph_result(r, at)
            }
        }
    }
}

/// Whether `e` is built of number literals alone (no index, no constant).
fn literals_only(e: &Expr) -> bool {
    match e {
        Expr::Lit(_) => true,
        Expr::Paren(p) => literals_only(&p.expr),
        Expr::Group(g) => literals_only(&g.expr),
        Expr::Cast(c) => literals_only(&c.expr),
        Expr::Unary(u) => literals_only(&u.expr),
        Expr::Binary(b) => literals_only(&b.left) && literals_only(&b.right),
        _ => false,
    }
}
