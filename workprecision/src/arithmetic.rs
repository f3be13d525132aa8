//! How much arithmetic generated code does: its floating-point operations
//! counted in its tokens, so that methods can be compared by the work a
//! solve needs as well as by its time (a method can win by doing less, or
//! by doing the same faster; the two call for different work).
//!
//! Counted: the binary operators `+ - * /`, each fused multiply-add
//! (`mul_add(a, b, c)`, a function or a method) and each elementary
//! function (`sqrt`, `exp`, `ln`, `sin`, …) as one operation. Index
//! arithmetic (inside `[…]`) and unary minus are not operations; a loop
//! `for _ in a..b { … }` counts its body b − a times; a function defined
//! in the code counts its body at each call, not where it is defined.

use proc_macro2::{Delimiter, Group, TokenStream, TokenTree};
use std::collections::HashMap;
use std::str::FromStr;

/// Methods and functions counted as one operation each.
const FUNCTIONS: [&str; 17] = [
    "mul_add", "sqrt", "cbrt", "exp", "ln", "sin", "cos", "tan", "sinh", "cosh", "tanh", "asin",
    "acos", "atan", "atan2", "powf", "powi",
];

/// Keywords after which `-`, `*` and `&` are unary (`&mut *r`, `return -x`).
const KEYWORDS: [&str; 8] = ["return", "in", "mut", "let", "if", "while", "match", "else"];

/// The operations of one call of `function` (its first definition in
/// `code`), or None when the code does not parse or has no such function.
pub fn function_operations(code: &str, function: &str) -> Option<u64> {
    let body = function_body(code, function)?;
    Some(Counter::new(&body).count(&body))
}

/// The operations of one call of the generated `taylor_jet_unrolled` at
/// `order` (its `match` arm), or None when the code has no unrolled jet
/// of that order.
pub fn taylor_jet_operations(code: &str, order: usize) -> Option<u64> {
    let body = function_body(code, "taylor_jet_unrolled")?;
    let arm = find_arm(&body, order)?;
    Some(Counter::new(&arm).count(&arm))
}

/// The body of the first `fn name` in `code`, searched through every group.
fn function_body(code: &str, name: &str) -> Option<Vec<TokenTree>> {
    let tokens: Vec<TokenTree> = TokenStream::from_str(code).ok()?.into_iter().collect();
    let mut functions = HashMap::new();
    collect_functions(&tokens, &mut functions);
    Some(functions.get(name)?.stream().into_iter().collect())
}

/// The block of the `match` arm `order => { … }`, searched through every
/// group.
fn find_arm(tokens: &[TokenTree], order: usize) -> Option<Vec<TokenTree>> {
    let literal = order.to_string();
    for (i, t) in tokens.iter().enumerate() {
        match (t, tokens.get(i + 1), tokens.get(i + 2), tokens.get(i + 3)) {
            (
                TokenTree::Literal(l),
                Some(TokenTree::Punct(eq)),
                Some(TokenTree::Punct(gt)),
                Some(TokenTree::Group(g)),
            ) if l.to_string() == literal
                && eq.as_char() == '='
                && gt.as_char() == '>'
                && g.delimiter() == Delimiter::Brace =>
            {
                return Some(g.stream().into_iter().collect());
            }
            (TokenTree::Group(g), ..) => {
                let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                if let Some(arm) = find_arm(&inner, order) {
                    return Some(arm);
                }
            }
            _ => {}
        }
    }
    None
}

/// Counts operations, knowing the functions defined in the code.
struct Counter {
    /// Each function defined in the code and its body.
    functions: HashMap<String, Group>,
}

impl Counter {
    fn new(tokens: &[TokenTree]) -> Counter {
        let mut functions = HashMap::new();
        collect_functions(tokens, &mut functions);
        Counter { functions }
    }

    /// The operations of `tokens` run once.
    fn count(&self, tokens: &[TokenTree]) -> u64 {
        let mut total = 0;
        let mut i = 0;
        while i < tokens.len() {
            let previous = i.checked_sub(1).map(|j| &tokens[j]);
            match &tokens[i] {
                TokenTree::Ident(f) if f == "fn" => {
                    // A definition: counted where it is called. Skip its
                    // name, signature and body.
                    while i < tokens.len()
                        && !matches!(&tokens[i], TokenTree::Group(g) if g.delimiter() == Delimiter::Brace)
                    {
                        i += 1;
                    }
                }
                TokenTree::Ident(f) if f == "for" => {
                    let (trips, body, next) = loop_parts(tokens, i);
                    total += trips * self.count(&body);
                    i = next;
                    continue;
                }
                TokenTree::Ident(name) => {
                    let called = matches!(tokens.get(i + 1), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis);
                    let name = name.to_string();
                    if called && FUNCTIONS.contains(&name.as_str()) {
                        total += 1;
                    } else if called && !matches!(previous, Some(TokenTree::Ident(f)) if f == "fn")
                    {
                        if let Some(body) = self.functions.get(&name) {
                            let body: Vec<TokenTree> = body.stream().into_iter().collect();
                            total += self.count(&body);
                        }
                    }
                }
                TokenTree::Punct(p) => {
                    let next_is = |c: char| matches!(tokens.get(i + 1), Some(TokenTree::Punct(q)) if q.as_char() == c);
                    let binary = matches!(
                        previous,
                        Some(TokenTree::Ident(_) | TokenTree::Literal(_) | TokenTree::Group(_))
                    ) && !matches!(previous, Some(TokenTree::Ident(k)) if KEYWORDS.iter().any(|w| k == w));
                    match p.as_char() {
                        // `->` and `=>` are not operators; `-` after an
                        // operator is a negation.
                        '-' if next_is('>') => {}
                        '+' | '-' | '*' | '/' if binary => total += 1,
                        _ => {}
                    }
                }
                TokenTree::Group(g) if g.delimiter() != Delimiter::Bracket => {
                    let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                    total += self.count(&inner);
                }
                _ => {}
            }
            i += 1;
        }
        total
    }
}

/// Every `fn name … { body }` in `tokens` and its groups.
fn collect_functions(tokens: &[TokenTree], functions: &mut HashMap<String, Group>) {
    for (i, t) in tokens.iter().enumerate() {
        match t {
            TokenTree::Ident(f) if f == "fn" => {
                if let Some(TokenTree::Ident(name)) = tokens.get(i + 1) {
                    let body = tokens[i + 2..].iter().find_map(|t| match t {
                        TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => Some(g.clone()),
                        _ => None,
                    });
                    if let Some(body) = body {
                        functions.entry(name.to_string()).or_insert(body);
                    }
                }
            }
            TokenTree::Group(g) => {
                let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                collect_functions(&inner, functions);
            }
            _ => {}
        }
    }
}

/// The trip count of the loop `for … in a..b { body }` starting at
/// `tokens[at]` (1 when its range is not two integer literals), its body,
/// and the position after it.
fn loop_parts(tokens: &[TokenTree], at: usize) -> (u64, Vec<TokenTree>, usize) {
    let body = tokens.iter().enumerate().skip(at).find_map(|(j, t)| match t {
        TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => Some((j, g)),
        _ => None,
    });
    let Some((open, body)) = body else {
        return (1, Vec::new(), tokens.len());
    };
    let header: Vec<String> = tokens[at..open].iter().map(|t| t.to_string()).collect();
    let trips = header
        .iter()
        .position(|t| t == "in")
        .and_then(|j| match &header[j + 1..] {
            [a, dot, dot2, b] if dot == "." && dot2 == "." => {
                Some(b.parse::<u64>().ok()?.saturating_sub(a.parse::<u64>().ok()?))
            }
            _ => None,
        })
        .unwrap_or(1);
    (trips, body.stream().into_iter().collect(), open + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operators_fused_multiply_adds_and_functions_count_once_each() {
        let code = "fn rhs(y: &[f64], dy: &mut [f64]) -> f64 {
            let a = y[0] * y[1] + -y[2];
            dy[0] = (a - 1.0) / a.sqrt();
            dy[1] = ::m::mul_add(a, a, 2.0 * a);
            a.mul_add(a, a)
        }";
        // *, +, (unary minus no), -, /, sqrt, mul_add, *, mul_add.
        assert_eq!(function_operations(code, "rhs"), Some(8));
    }

    #[test]
    fn index_arithmetic_arrows_and_dereferences_are_not_counted() {
        let code = "fn f(r: &mut [f64; 8], k: usize) -> f64 { let r = &mut *r; r[1 + 2 * k] = r[k - 1]; 0.0 }";
        assert_eq!(function_operations(code, "f"), Some(0));
    }

    #[test]
    fn loops_count_their_body_per_trip_and_functions_per_call() {
        let code = "fn taylor_jet_unrolled(order: usize, out: &mut [f64]) -> bool {
            match order {
                3 => {
                    fn order_1(r: &mut [f64; 4]) { r[0] = r[1] * r[2]; }
                    fn shared(r: &mut [f64; 4], k: usize) { r[k] = r[k] + r[k] + 1.0; }
                    order_1(r);
                    for lane in 0..4 { r[lane] = r[lane] * 2.0; }
                    shared(r, 1);
                    shared(r, 2);
                    true
                }
                5 => { out[0] = out[1] * out[2] * out[3]; true }
                _ => false,
            }
        }";
        // 1 (order_1) + 4·1 (loop) + 2·2 (shared).
        assert_eq!(taylor_jet_operations(code, 3), Some(9));
        assert_eq!(taylor_jet_operations(code, 5), Some(2));
        assert_eq!(taylor_jet_operations(code, 4), None);
    }
}
