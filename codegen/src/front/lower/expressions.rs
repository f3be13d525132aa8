//! Expressions: names, literals, arithmetic, calls and `der`, lowered into
//! the graph.

use super::declarations::Declaration;
use super::instances::Member;
use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use super::syntax::{call_name, FUNCTIONS};
use crate::front::names::did_you_mean;

use crate::{Func, Graph, Id, Node, SymbolKind};
use quote::ToTokens;
use syn::{BinOp, Expr, Lit, Stmt, UnOp};

impl<S: SceneLanguage> Lower<'_, S> {
    pub(crate) fn unknown_name(&mut self, at: impl ToTokens, name: &str) {
        let known = self.known_names();
        let mut candidates: Vec<&str> = known.iter().map(String::as_str).collect();
        candidates.extend(FUNCTIONS);
        match did_you_mean(name, candidates.into_iter()) {
            Some(s) => self.cx.error_at(at, format!("unknown name `{name}`; did you mean `{s}`?")),
            None => self.cx.error_at(at, format!("unknown name `{name}`: declare it with `let {name} = param(..)`, `state(..)` or a value")),
        }
    }

    pub(crate) fn graph_result(&mut self, r: crate::Result<Id>, at: &Expr) -> Option<Id> {
        match r {
            Ok(id) => Some(id),
            Err(e) => {
                self.cx.error_at(at, e);
                None
            }
        }
    }

    pub(in crate::front) fn arith(&mut self, op: &BinOp, a: Id, b: Id, at: &Expr) -> Option<Id> {
        let r = match op {
            BinOp::Add(_) | BinOp::AddAssign(_) => self.g.add(a, b),
            BinOp::Sub(_) | BinOp::SubAssign(_) => self.g.sub(a, b),
            BinOp::Mul(_) | BinOp::MulAssign(_) => self.g.mul(a, b),
            BinOp::Div(_) | BinOp::DivAssign(_) => self.g.div(a, b),
            BinOp::Rem(_) => {
                // Neighbours on a periodic grid: `u[(i + 1) % N]`.
                let whole = |g: &Graph, x: Id| g.as_number(x).and_then(|n| n.as_integer());
                return match (whole(&self.g, a), whole(&self.g, b)) {
                    (Some(x), Some(m)) if m > 0 => Some(self.g.int(x.rem_euclid(m))),
                    _ => {
                        self.cx.error_at(at, "`%` takes whole-number constants such as loop indices, the right one positive: `u[(i + 1) % N]`");
                        None
                    }
                };
            }
            _ => {
                self.cx.error_at(op, format!("operator `{}` is not part of the model language: use + - * / and `powi`, `powf` (and `%` on loop indices)", op.to_token_stream()));
                return None;
            }
        };
        self.graph_result(r, at)
    }

    /// An expression of the model language.
    pub(crate) fn value(&mut self, e: &Expr) -> Option<Id> {
        match e {
            Expr::Lit(l) => self.literal(&l.lit),
            Expr::Paren(p) => self.value(&p.expr),
            Expr::Group(g) => self.value(&g.expr),
            Expr::Cast(c) => self.value(&c.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                let a = self.value(&u.expr)?;
                let r = self.g.neg(a);
                self.graph_result(r, e)
            }
            Expr::Binary(b) if matches!(b.op, BinOp::Eq(_)) => {
                self.cx.error_at(
                    e,
                    "`==` states an equation and must be a whole statement: `lhs == rhs;`",
                );
                None
            }
            Expr::Binary(b) => {
                let (l, r) = (self.value(&b.left), self.value(&b.right));
                if matches!(b.op, BinOp::Div(_)) && self.is_integer_expr(e) {
                    return self.integer_division(l?, r?, e);
                }
                self.arith(&b.op, l?, r?, e)
            }
            Expr::Path(p) => {
                let Some(ident) = p.path.get_ident() else {
                    self.cx.error_at(p, "use a plain name here");
                    return None;
                };
                let name = ident.to_string();
                match self.lookup(&name).cloned() {
                    Some(
                        Binding::Param(id)
                        | Binding::Algebraic(id)
                        | Binding::Time(id)
                        | Binding::Const(id),
                    ) => Some(id),
                    Some(Binding::Value { id, .. }) => Some(id),
                    Some(Binding::State(s)) => Some(self.g.symbol_node(s)),
                    Some(Binding::BrokenBody | Binding::Broken) => None,
                    Some(
                        b @ (Binding::Connector(_)
                        | Binding::Instance(_)
                        | Binding::InstanceArray(_)),
                    ) => self.member_value(b, e),
                    Some(Binding::Function(_)) => {
                        self.cx
                            .error_at(e, format!("`{name}` is a function: call it, `{name}(..)`"));
                        None
                    }
                    Some(Binding::Clock) => {
                        self.cx.error_at(e, format!("`{name}` is a clock, which has no value: read the discrete values its actions set"));
                        None
                    }
                    Some(b @ (Binding::Body(_) | Binding::Ground)) => {
                        let what = b.describe();
                        self.cx.error_at(e, format!("`{name}` is {what}: use `position({name}, p)` for a point of it, or its coordinates `{name}.x`… in the solution"));
                        None
                    }
                    Some(Binding::Tensor(t)) => match t.as_scalar() {
                        Some(id) => Some(id),
                        None => {
                            let shape = t.shape();
                            self.cx.error_at(e, format!("`{name}` is a {shape}: take a component (`{name}[0]`) or use `dot`/`norm`"));
                            None
                        }
                    },
                    Some(
                        b @ (Binding::StateArray(_)
                        | Binding::ValueArray(_)
                        | Binding::AlgebraicArray(_)),
                    ) => {
                        let what = b.describe();
                        self.cx.error_at(e, format!("`{name}` is {what}: index it, `{name}[0]`"));
                        None
                    }
                    None => {
                        self.unknown_name(e, &name);
                        None
                    }
                }
            }
            Expr::Index(ix) if self.mentions_tensor(&ix.expr) => self.scalar_of(e),
            Expr::Index(_) | Expr::Field(_) if self.is_member_path(e) => match self.member(e) {
                Member::Found(b) => self.member_value(b, e),
                _ => None,
            },
            Expr::Index(ix) => {
                let Expr::Path(p) = &*ix.expr else {
                    self.cx.error_at(&ix.expr, "only arrays declared in the model can be indexed");
                    return None;
                };
                let name = p.path.get_ident().map(|i| i.to_string()).unwrap_or_default();
                let elements = match self.lookup(&name).cloned() {
                    Some(Binding::StateArray(s)) => {
                        s.into_iter().map(|s| self.g.symbol_node(s)).collect()
                    }
                    Some(Binding::ValueArray(v) | Binding::AlgebraicArray(v)) => v,
                    Some(Binding::Broken) => return None,
                    Some(b) => {
                        let what = b.describe();
                        self.cx.error_at(&ix.expr, format!("`{name}` is {what}, not an array"));
                        return None;
                    }
                    None => {
                        self.unknown_name(&ix.expr, &name);
                        return None;
                    }
                };
                let i = self.index_constant(&ix.index)?;
                match elements.get(i) {
                    Some(&id) => Some(id),
                    None => {
                        self.cx.error_at(
                            &ix.index,
                            format!(
                                "index {i} is out of bounds: `{name}` has {} elements",
                                elements.len()
                            ),
                        );
                        None
                    }
                }
            }
            // A tensor function's value (dot, norm, or an error for a vector);
            // scalar functions of tensor components go the ordinary way.
            Expr::Call(_) if crate::front::tensor::is_tensor_call(e) => self.scalar_of(e),
            Expr::Call(c) => self.call(c, e),
            Expr::MethodCall(m) => self.method_call(m, e),
            Expr::Closure(_) => {
                self.cx.error_at(e, "a closure is a function of the model: bind it, `let f = |x| ...;`, and call it, `f(x)`");
                None
            }
            Expr::If(i) if self.no_event_depth > 0 && self.mentions_variable(&i.cond) => {
                self.stepped_if_value(i)
            }
            Expr::If(i) if self.mode_condition(&i.cond).is_some() => self.mode_value(i),
            Expr::If(i) => self.const_if_value(i),
            Expr::Match(_) => self.unsupported(e, "`match`"),
            // `{ expr }`, as rustfmt writes a long closure's body.
            Expr::Block(b) if matches!(b.block.stmts.as_slice(), [Stmt::Expr(_, None)]) => {
                self.branch_value(&b.block)
            }
            Expr::Block(_) => self.unsupported(e, "blocks as values"),
            Expr::Assign(_) => self.unsupported(e, "assignments inside expressions"),
            Expr::Macro(_) => self.unsupported(e, "macros"),
            Expr::Reference(_) => self.unsupported(e, "references"),
            Expr::Field(f) => S::body_coordinate(self, f, e),
            _ => {
                self.cx.error_at(e, "this expression is not part of the model language");
                None
            }
        }
    }

    pub(in crate::front) fn unsupported(&mut self, e: &Expr, what: &str) -> Option<Id> {
        self.cx.error_at(e, format!("{what} are not part of the model language"));
        None
    }

    pub(in crate::front) fn literal(&mut self, lit: &Lit) -> Option<Id> {
        let parsed = match lit {
            Lit::Int(i) => i.base10_parse::<f64>(),
            Lit::Float(f) => f.base10_parse::<f64>(),
            Lit::Str(s) => {
                let v = s.value();
                let fix = if v.trim().parse::<f64>().is_ok() {
                    format!("write the number without quotes: `{}`", v.trim())
                } else {
                    "write a number such as `1.0`".to_string()
                };
                self.cx.error_at(lit, format!("a string is not a number: {fix}"));
                return None;
            }
            // A mode's new value in an action: true is 1, false 0.
            Lit::Bool(b) if self.in_action => return Some(self.g.int(i64::from(b.value))),
            Lit::Bool(b) => {
                let v = if b.value { "1.0" } else { "0.0" };
                self.cx.error_at(
                    lit,
                    format!(
                        "`{}` is not a number: the model language has only numbers (`{v}`)",
                        b.value
                    ),
                );
                return None;
            }
            other => {
                self.cx.error_at(other, "expected a number such as `1.0` or `2`");
                return None;
            }
        };
        match parsed {
            Ok(v) if v.is_finite() => self.g.float(v).ok(),
            Ok(_) => {
                self.cx.error_at(
                    lit,
                    format!(
                        "`{}` is not a finite f64: write a number below 1.8e308",
                        lit.to_token_stream()
                    ),
                );
                None
            }
            Err(err) => {
                self.cx.push(err);
                None
            }
        }
    }

    pub(in crate::front) fn call(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<Id> {
        let Some((name, _)) = call_name(e) else {
            self.cx.error_at(&c.func, "call a function by name: `sin(x)`");
            return None;
        };
        if Declaration::from_name(&name).is_some() {
            self.cx.error_at(e, format!("`{name}(...)` declares a variable and must be the value of a `let`: `let x = {name}(...);`"));
            return None;
        }
        if name == "der" {
            return self.der(c, e);
        }
        if name == "pre" {
            return self.pre(c, e);
        }
        if let Some(Binding::Function(function)) = self.lookup(&name).cloned() {
            return self.call_function(&name, &function, c);
        }
        if matches!(name.as_str(), "init" | "constraint" | "invariant") {
            self.cx.error_at(e, format!("`{name}(...)` is a statement, not a value"));
            return None;
        }
        if matches!(name.as_str(), "min" | "max" | "sign") {
            return self.switching_function(&name, c, e);
        }
        if name == "no_event" {
            if !self.arity(c, "no_event", 1) {
                return None;
            }
            self.no_event_depth += 1;
            let v = self.value(&c.args[0]);
            self.no_event_depth -= 1;
            return v;
        }
        if name == "heaviside" {
            // 0 below zero, 1 above, ½ at zero: (1 + sign x) / 2.
            if !self.arity(c, "heaviside", 1) {
                return None;
            }
            let x = self.value(&c.args[0])?;
            let sign = self.g.call(Func::Sign, x);
            let sign = self.graph_result(sign, e)?;
            self.non_smooth_calls.push((sign, e.to_token_stream()));
            let one = self.g.one();
            let r = self.g.add(one, sign).and_then(|s| {
                let half = self.g.rational(1, 2)?;
                self.g.mul(half, s)
            });
            return self.graph_result(r, e);
        }
        let func = Func::ALL.iter().copied().find(|f| f.name() == name && *f != Func::Sign);
        let arity = match name.as_str() {
            "atan2" => 2,
            _ if func.is_some() || name == "sqrt" => 1,
            _ => {
                let suggestion = did_you_mean(&name, FUNCTIONS.into_iter());
                match suggestion {
                    Some(s) => self.cx.error_at(&c.func, format!("unknown function `{name}`; did you mean `{s}`?")),
                    None => self.cx.error_at(&c.func, format!("unknown function `{name}`: the model language has sin cos tan asin acos atan atan2 sinh cosh tanh exp ln sqrt abs, and `powi`/`powf` methods")),
                }
                return None;
            }
        };
        if !self.arity(c, &name, arity) {
            return None;
        }
        let args: Vec<Option<Id>> = c.args.iter().map(|a| self.value(a)).collect();
        let args: Vec<Id> = args.into_iter().collect::<Option<_>>()?;
        let r = match (name.as_str(), func) {
            ("atan2", _) => self.g.atan2(args[0], args[1]),
            ("sqrt", _) => self.g.sqrt(args[0]),
            (_, Some(f)) => self.g.call(f, args[0]),
            _ => return None,
        };
        if let (Ok(id), Some(Func::Abs)) = (&r, func) {
            self.non_smooth_calls.push((*id, e.to_token_stream()));
        }
        self.graph_result(r, e)
    }

    /// An algebraic variable the model differentiates (`der(w_rel)`, as
    /// Modelica allows of any variable) becomes a state the structure may
    /// eliminate (`.avoid()`): where a tie determines it, it goes, its
    /// derivative the tie's; otherwise its defining equation is a
    /// constraint on it that index reduction differentiates.
    fn promote_differentiated_algebraic(&mut self, value: Id) {
        let Some(s) = self.g.as_symbol(value) else { return };
        let Some(k) = self.algebraics.iter().position(|a| a.symbol == s) else { return };
        let a = self.algebraics.remove(k);
        self.g.promote_to_state(s);
        self.states.push(crate::front::ir::StateDecl {
            name: a.name,
            symbol: s,
            init: a.init,
            origin: a.origin,
            fixed: false,
            doc: a.doc,
            avoid: true,
            prefer: false,
        });
    }

    pub(in crate::front) fn der(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<Id> {
        if !self.arity(c, "der", 1) {
            return None;
        }
        let arg = &c.args[0];
        let inner = self.value(arg)?;
        self.promote_differentiated_algebraic(inner);
        let symbol = self.g.as_symbol(inner).filter(|&s| {
            matches!(self.g.symbol(s).kind, SymbolKind::State | SymbolKind::Derivative { .. })
        });
        match symbol {
            Some(s) if self.is_discrete(s) => {
                self.cx.error_at(
                    e,
                    format!("`{}` is a discrete value, which changes only at events: set it with `.reinit(..)` on an event or a clock", arg.to_token_stream()),
                );
                None
            }
            Some(s) => {
                let r = self.g.derivative(s, 1);
                self.graph_result(r, e)
            }
            None => {
                let what = match self.g.node(inner) {
                    Node::Number(_) => "a constant".to_string(),
                    Node::Symbol(s) => match self.g.symbol(*s).kind {
                        SymbolKind::Parameter => "a parameter (constant during a run)".to_string(),
                        SymbolKind::Time => "the time (its derivative is 1)".to_string(),
                        SymbolKind::Algebraic => "an algebraic variable".to_string(),
                        _ => "not a state".to_string(),
                    },
                    _ => "an expression".to_string(),
                };
                self.cx.error_at(
                    arg,
                    format!(
                        "`der` takes a state, and `{}` is {what}: declare it with `state(..)`",
                        arg.to_token_stream()
                    ),
                );
                None
            }
        }
    }

    pub(in crate::front) fn method_call(
        &mut self,
        m: &syn::ExprMethodCall,
        e: &Expr,
    ) -> Option<Id> {
        let method = m.method.to_string();
        match method.as_str() {
            "powi" | "powf" if m.args.len() == 1 => {
                let base = self.value(&m.receiver);
                let exponent = if method == "powi" {
                    let v = self.constant(&m.args[0])?;
                    if self.g.as_number(v).and_then(|n| n.as_integer()).is_none() {
                        self.cx.error_at(
                            &m.args[0],
                            "`powi` takes a whole number; use `powf` for others",
                        );
                        return None;
                    }
                    v
                } else {
                    self.value(&m.args[0])?
                };
                let r = self.g.pow(base?, exponent);
                self.graph_result(r, e)
            }
            "powi" | "powf" => {
                self.cx.error_at(e, format!("`{method}` takes one argument"));
                None
            }
            other if FUNCTIONS.contains(&other) || other == "sqrt" => {
                let receiver = m.receiver.to_token_stream();
                self.cx.error_at(
                    &m.method,
                    format!("write `{other}({receiver})`: the only methods are `powi` and `powf`"),
                );
                None
            }
            other => {
                self.cx.error_at(
                    &m.method,
                    format!("unknown method `{other}`: the only methods are `powi` and `powf`"),
                );
                None
            }
        }
    }
}
