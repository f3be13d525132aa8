//! Functions of the model: `let orifice = |dp| cd * a * sqrt(2.0 * dp / rho);`
//! written once and called like the built-in ones, `orifice(p1 - p2)`.
//! A call is inlined: the body is lowered with the parameters bound to the
//! arguments' values, in the scopes the function was defined in (it reads
//! the names it saw there, as a Rust closure captures them).

use super::scene::SceneLanguage;
use super::scopes::{Binding, Function, Lower};
use crate::Id;
use std::collections::HashMap;
use std::rc::Rc;
use syn::{Expr, Pat, Stmt};

/// Calls of functions nested deeper than this are refused: a function
/// that calls itself.
const MAX_DEPTH: usize = 64;

impl<S: SceneLanguage> Lower<'_, S> {
    /// `let f = |x, y| body;`: binds the function `f`.
    pub(in crate::front) fn function(&mut self, ident: &syn::Ident, closure: &syn::ExprClosure) {
        for input in &closure.inputs {
            let plain = match input {
                Pat::Ident(_) => true,
                Pat::Type(t) => matches!(&*t.pat, Pat::Ident(_)),
                _ => false,
            };
            if !plain {
                return self.cx.error_at(input, "a function's parameter is one name: `|dp| ...`");
            }
        }
        let function = Function { closure: closure.clone(), captured: self.scopes.clone() };
        self.bind(ident, Binding::Function(Rc::new(function)));
    }

    /// `f(args)` of a function of the model: its body's value.
    pub(in crate::front) fn call_function(
        &mut self,
        name: &str,
        function: &Function,
        c: &syn::ExprCall,
    ) -> Option<Id> {
        let inputs: Vec<String> = function
            .closure
            .inputs
            .iter()
            .filter_map(|p| match p {
                Pat::Ident(i) => Some(i.ident.to_string()),
                Pat::Type(t) => match &*t.pat {
                    Pat::Ident(i) => Some(i.ident.to_string()),
                    _ => None,
                },
                _ => None,
            })
            .collect();
        if !self.arity(c, name, inputs.len()) {
            return None;
        }
        if self.function_depth >= MAX_DEPTH {
            self.cx.error_at(
                c,
                format!(
                    "`{name}` calls itself: a function of the model is inlined, and cannot recurse"
                ),
            );
            return None;
        }
        let args: Vec<Option<Id>> = c.args.iter().map(|a| self.value(a)).collect();
        let args: Vec<Id> = args.into_iter().collect::<Option<_>>()?;
        let mut frame: HashMap<String, Binding> = HashMap::new();
        for (input, value) in inputs.into_iter().zip(args) {
            frame.insert(input, Binding::Value { id: value, mutable: false });
        }
        let mut scopes = function.captured.clone();
        scopes.push(frame);
        let saved = std::mem::replace(&mut self.scopes, scopes);
        self.function_depth += 1;
        let value = self.function_body(&function.closure.body);
        self.function_depth -= 1;
        self.scopes = saved;
        value
    }

    /// A function's body: an expression, or a block of `let` values ending
    /// in one.
    fn function_body(&mut self, body: &Expr) -> Option<Id> {
        let Expr::Block(b) = body else { return self.value(body) };
        let Some((last, lets)) = b.block.stmts.split_last() else {
            self.cx.error_at(body, "a function's body ends in its value");
            return None;
        };
        self.scopes.push(HashMap::new());
        for stmt in lets {
            match stmt {
                Stmt::Local(l) => {
                    let (Pat::Ident(p), Some(init)) = (&l.pat, &l.init) else {
                        self.cx.error_at(l, "in a function, bind a single name: `let x = ...;`");
                        continue;
                    };
                    let value = self.value(&init.expr);
                    let binding = match value {
                        Some(id) => Binding::Value { id, mutable: false },
                        None => Binding::Broken,
                    };
                    if let Some(scope) = self.scopes.last_mut() {
                        scope.insert(p.ident.to_string(), binding);
                    }
                }
                other => self.cx.error_at(other, "a function's body has `let` values and ends in its value; declare states, equations and parts in the model"),
            }
        }
        let value = match last {
            Stmt::Expr(e, None) => self.value(e),
            other => {
                self.cx.error_at(other, "a function's body ends in its value, without `;`");
                None
            }
        };
        self.scopes.pop();
        value
    }
}
