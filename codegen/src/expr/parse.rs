//! Reads the text syntax of [`crate::Graph::show`] back into the graph, so
//! tests can state expected expressions as text: `y + x*der(y) + 1`.
//!
//! Grammar (usual precedence, `^` right-associative and binding tighter than
//! unary minus): numbers (`2`, `0.5`, `1e-3`), symbol names, `der(x)`,
//! function calls `sin(x)`, `sqrt(x)`, `atan2(y, x)`, `+ - * / ^`, parentheses.
//! Symbols must exist already (`der` creates derivative symbols on demand).

use crate::error::{Error, Result};
use crate::expr::graph::Graph;
use crate::expr::node::{Func, Id};

const MAX_NESTING: usize = 200;

/// A graph operation on two operands.
type BinaryOp = fn(&mut Graph, Id, Id) -> Result<Id>;

struct Parser<'a, 'g> {
    src: &'a str,
    pos: usize,
    depth: usize,
    g: &'g mut Graph,
}

impl Graph {
    /// Builds the expression written in the text syntax.
    pub fn parse(&mut self, src: &str) -> Result<Id> {
        let mut p = Parser { src, pos: 0, depth: 0, g: self };
        let e = p.expr()?;
        p.skip_ws();
        if p.pos < src.len() {
            return Err(p.error("unexpected input after the expression"));
        }
        Ok(e)
    }
}

impl Parser<'_, '_> {
    fn error(&self, message: &str) -> Error {
        Error::Parse { position: self.pos, message: message.to_string() }
    }

    fn skip_ws(&mut self) {
        while self.src[self.pos..].starts_with(char::is_whitespace) {
            self.pos += 1;
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_ws();
        self.src[self.pos..].chars().next()
    }

    fn eat(&mut self, c: char) -> bool {
        if self.peek() == Some(c) {
            self.pos += c.len_utf8();
            true
        } else {
            false
        }
    }

    fn expect(&mut self, c: char) -> Result<()> {
        if self.eat(c) {
            Ok(())
        } else {
            Err(self.error(&format!("expected `{c}`")))
        }
    }

    fn nested<T>(&mut self, f: impl FnOnce(&mut Self) -> Result<T>) -> Result<T> {
        self.depth += 1;
        if self.depth > MAX_NESTING {
            return Err(self.error("expression nested too deeply"));
        }
        let r = f(self);
        self.depth -= 1;
        r
    }

    fn expr(&mut self) -> Result<Id> {
        self.nested(|p| p.left_associative([('+', Graph::add), ('-', Graph::sub)], Self::term))
    }

    fn term(&mut self) -> Result<Id> {
        self.left_associative([('*', Graph::mul), ('/', Graph::div)], Self::unary)
    }

    /// `operand (op operand)*` for the two operators `ops`, from the left.
    fn left_associative(
        &mut self,
        ops: [(char, BinaryOp); 2],
        operand: fn(&mut Self) -> Result<Id>,
    ) -> Result<Id> {
        let mut acc = operand(self)?;
        loop {
            let Some(&(_, op)) = ops.iter().find(|(c, _)| self.eat(*c)) else {
                return Ok(acc);
            };
            let rhs = operand(self)?;
            acc = op(self.g, acc, rhs)?;
        }
    }

    fn unary(&mut self) -> Result<Id> {
        if self.eat('-') {
            let a = self.nested(|p| p.unary())?;
            return self.g.neg(a);
        }
        self.power()
    }

    fn power(&mut self) -> Result<Id> {
        let base = self.atom()?;
        if self.eat('^') {
            let e = self.nested(|p| p.unary())?;
            return self.g.pow(base, e);
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Id> {
        match self.peek() {
            Some('(') => {
                self.pos += 1;
                let e = self.expr()?;
                self.expect(')')?;
                Ok(e)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_alphabetic() || c == '_' => self.name(),
            _ => Err(self.error("expected a number, a name or `(`")),
        }
    }

    fn number(&mut self) -> Result<Id> {
        let start = self.pos;
        let bytes = self.src.as_bytes();
        let mut end = start;
        while end < bytes.len() && (bytes[end].is_ascii_digit() || bytes[end] == b'.') {
            end += 1;
        }
        if end < bytes.len() && (bytes[end] == b'e' || bytes[end] == b'E') {
            let mut k = end + 1;
            if k < bytes.len() && (bytes[k] == b'+' || bytes[k] == b'-') {
                k += 1;
            }
            if k < bytes.len() && bytes[k].is_ascii_digit() {
                end = k;
                while end < bytes.len() && bytes[end].is_ascii_digit() {
                    end += 1;
                }
            }
        }
        let literal = &self.src[start..end];
        self.pos = end;
        if let Ok(n) = literal.parse::<i64>() {
            return Ok(self.g.int(n));
        }
        match literal.parse::<f64>() {
            Ok(v) => self.g.float(v),
            Err(_) => Err(Error::Parse {
                position: start,
                message: format!("`{literal}` is not a number"),
            }),
        }
    }

    fn name(&mut self) -> Result<Id> {
        let start = self.pos;
        let len = self.src[start..]
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(self.src.len() - start);
        let name = &self.src[start..start + len];
        self.pos += len;
        if !self.eat('(') {
            return match self.g.symbol_named(name) {
                Some(s) => Ok(self.g.symbol_node(s)),
                None => Err(Error::Parse {
                    position: start,
                    message: format!("unknown symbol `{name}`"),
                }),
            };
        }
        let args = self.nested(|p| {
            let mut args = vec![p.expr()?];
            while p.eat(',') {
                args.push(p.expr()?);
            }
            p.expect(')')?;
            Ok(args)
        })?;
        let arity = |n: usize| {
            if args.len() == n {
                Ok(())
            } else {
                Err(Error::Parse {
                    position: start,
                    message: format!("`{name}` takes {n} argument(s)"),
                })
            }
        };
        match name {
            "der" => {
                arity(1)?;
                match self.g.as_symbol(args[0]) {
                    Some(s) => self.g.derivative(s, 1),
                    None => Err(Error::Parse {
                        position: start,
                        message: "`der` takes a symbol".into(),
                    }),
                }
            }
            "sqrt" => {
                arity(1)?;
                self.g.sqrt(args[0])
            }
            "atan2" => {
                arity(2)?;
                self.g.atan2(args[0], args[1])
            }
            _ => match Func::ALL.iter().find(|f| f.name() == name) {
                Some(&f) => {
                    arity(1)?;
                    self.g.call(f, args[0])
                }
                None => Err(Error::Parse {
                    position: start,
                    message: format!("unknown function `{name}`"),
                }),
            },
        }
    }
}
