//! The hash-consed arena: every distinct node is stored once, children before
//! parents, and looked up by structure so equal expressions get equal ids.

use crate::error::{Error, Result};
use crate::expr::node::{Id, Node, Symbol, SymbolId, SymbolKind};
use crate::expr::number::Number;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// The multiply-rotate hash of rustc (FxHash): hash-consing does millions of
/// look-ups of small keys, where SipHash's DoS resistance buys nothing.
#[derive(Default)]
pub struct FxHasher(u64);

impl Hasher for FxHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut buf = [0u8; 8];
            buf[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(buf));
        }
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_u32(&mut self, v: u32) {
        self.write_u64(v as u64)
    }
    fn write_u8(&mut self, v: u8) {
        self.write_u64(v as u64)
    }
    fn write_usize(&mut self, v: usize) {
        self.write_u64(v as u64)
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

/// A `HashMap` with a fast non-cryptographic hash. Never iterated where order
/// could leak into output.
pub type FxHashMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// The expression DAG: an arena of canonical nodes and a symbol table.
///
/// Nodes are only created by the smart constructors (`sum`, `product`, `pow`,
/// `call`, ... in `build.rs`), which fold constants and apply value-preserving
/// identities, so structurally equal expressions are the same [`Id`].
#[derive(Clone, Default)]
pub struct Graph {
    nodes: Vec<Node>,
    smooth: Vec<bool>,
    interned: FxHashMap<Node, Id>,
    symbols: Vec<Symbol>,
    symbol_nodes: Vec<Id>,
    symbol_names: HashMap<String, SymbolId>,
    derivatives: FxHashMap<(SymbolId, u32), SymbolId>,
    /// Partial derivatives already taken, per symbol: node -> derivative.
    pub(crate) partials: FxHashMap<SymbolId, FxHashMap<Id, Id>>,
    /// Discrete values that switch blended equations between their
    /// branches: a coefficient that reads one may vanish in some mode, so
    /// no symbolic solve divides by it.
    switching: Vec<SymbolId>,
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Graph {
        Graph::default()
    }

    /// Number of nodes in the arena (including ones no expression uses any more).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// `true` when no node was created yet.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The arena's invariants, for the checks between passes: every node
    /// reads only nodes made before it and is the one hash-consing finds
    /// for itself; every symbol's node is that symbol, every symbol a node
    /// names exists, a derivative's symbol and an intermediate's definition
    /// exist.
    pub fn verify(&self) -> std::result::Result<(), String> {
        if self.smooth.len() != self.nodes.len() {
            return Err(format!(
                "{} nodes but {} smoothness flags",
                self.nodes.len(),
                self.smooth.len()
            ));
        }
        for (i, node) in self.nodes.iter().enumerate() {
            if let Some(c) = node.children().iter().find(|c| c.index() >= i) {
                return Err(format!("node {i} reads node {} made after it", c.index()));
            }
            if let Node::Symbol(s) = node {
                if s.index() >= self.symbols.len() {
                    return Err(format!(
                        "node {i} names symbol {}, which does not exist",
                        s.index()
                    ));
                }
            }
            if self.interned.get(node).map(|id| id.index()) != Some(i) {
                return Err(format!("node {i} is not the one hash-consing finds for itself"));
            }
        }
        for (k, symbol) in self.symbols.iter().enumerate() {
            let node = self.symbol_nodes.get(k).map(|&id| self.node(id));
            if !matches!(node, Some(Node::Symbol(s)) if s.index() == k) {
                return Err(format!("symbol `{}` has no node of its own", symbol.name));
            }
            match symbol.kind {
                SymbolKind::Derivative { of, .. } if of.index() >= self.symbols.len() => {
                    return Err(format!(
                        "`{}` is the derivative of a symbol that does not exist",
                        symbol.name
                    ));
                }
                SymbolKind::Intermediate { definition }
                    if definition.index() >= self.nodes.len() =>
                {
                    return Err(format!("`{}` stands for a node that does not exist", symbol.name));
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The node behind an id.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id.index()]
    }

    /// The operands a value depends on: the children, or for an intermediate
    /// symbol its definition.
    pub fn operands(&self, id: Id) -> &[Id] {
        self.operands_of(self.node(id))
    }

    /// The constant value, if the node is a number.
    pub fn as_number(&self, id: Id) -> Option<Number> {
        match self.node(id) {
            Node::Number(n) => Some(*n),
            _ => None,
        }
    }

    /// The symbol, if the node is one.
    pub fn as_symbol(&self, id: Id) -> Option<SymbolId> {
        match self.node(id) {
            Node::Symbol(s) => Some(*s),
            _ => None,
        }
    }

    /// `true` when the expression contains no non-smooth function (`abs`,
    /// `sign`), so methods that need continuous derivatives may use it.
    pub fn is_smooth(&self, id: Id) -> bool {
        self.smooth[id.index()]
    }

    /// The node for `node`, created if it does not exist yet.
    ///
    /// # Panics
    /// If the arena exceeds 2^32 nodes (hundreds of gigabytes of memory).
    /// The id of `node` if the graph already holds it (nothing is created).
    pub(crate) fn lookup(&self, node: &Node) -> Option<Id> {
        self.interned.get(node).copied()
    }

    pub(crate) fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.interned.get(&node) {
            return id;
        }
        let smooth = match &node {
            Node::Call(f, _) if !f.is_smooth() => false,
            _ => self.operands_of(&node).iter().all(|c| self.smooth[c.index()]),
        };
        let id = Id(u32::try_from(self.nodes.len()).expect("expression graph exceeds 2^32 nodes"));
        self.nodes.push(node.clone());
        self.smooth.push(smooth);
        self.interned.insert(node, id);
        id
    }

    fn operands_of<'a>(&'a self, node: &'a Node) -> &'a [Id] {
        match node {
            Node::Symbol(s) => match &self.symbols[s.index()].kind {
                SymbolKind::Intermediate { definition } => std::slice::from_ref(definition),
                _ => &[],
            },
            node => node.children(),
        }
    }

    /// The constant `n`.
    pub fn num(&mut self, n: Number) -> Id {
        self.intern(Node::Number(n))
    }

    /// The integer constant `n`.
    pub fn int(&mut self, n: i64) -> Id {
        self.num(Number::integer(n))
    }

    /// The constant `0`.
    pub fn zero(&mut self) -> Id {
        self.int(0)
    }

    /// The constant `1`.
    pub fn one(&mut self) -> Id {
        self.int(1)
    }

    /// The constant `v`: exact when `v` is a small dyadic fraction (`0.5`, `3.0`).
    pub fn float(&mut self, v: f64) -> Result<Id> {
        match Number::from_f64(v) {
            Some(n) => Ok(self.num(n)),
            None => Err(Error::NotFinite {
                expression: format!("{v}"),
                reason: "a constant must be finite",
            }),
        }
    }

    /// The exact constant `num/den`.
    pub fn rational(&mut self, num: i64, den: i64) -> Result<Id> {
        match crate::Rational::new(num, den) {
            Some(r) => Ok(self.num(Number::Rational(r))),
            None => Err(Error::NotFinite {
                expression: format!("{num}/{den}"),
                reason: "division by zero",
            }),
        }
    }

    /// A symbol's name and kind.
    pub fn symbol(&self, s: SymbolId) -> &Symbol {
        &self.symbols[s.index()]
    }

    /// Makes the algebraic variable `s` a state: a model differentiates
    /// it (`der(w_rel)`), so the integrator carries it, and the structure
    /// eliminates it again where a tie determines it.
    pub fn promote_to_state(&mut self, s: SymbolId) {
        let symbol = &mut self.symbols[s.index()];
        if symbol.kind == SymbolKind::Algebraic {
            symbol.kind = SymbolKind::State;
        }
    }

    /// Marks `s` as switching blended equations (see [`Graph::reads_switching`]).
    pub fn mark_switching(&mut self, s: SymbolId) {
        if !self.switching.contains(&s) {
            self.switching.push(s);
        }
    }

    /// Whether `e` reads a discrete value that switches blended equations:
    /// it may vanish in some mode, so a solve must not divide by it.
    pub fn reads_switching(&self, e: Id) -> bool {
        !self.switching.is_empty()
            && self.free_symbols(e).iter().any(|s| self.switching.contains(s))
    }

    /// The node standing for a symbol.
    pub fn symbol_node(&self, s: SymbolId) -> Id {
        self.symbol_nodes[s.index()]
    }

    /// All symbols, in creation order.
    pub fn symbols(&self) -> impl Iterator<Item = (SymbolId, &Symbol)> {
        self.symbols.iter().enumerate().map(|(i, s)| (SymbolId(i as u32), s))
    }

    /// The symbol with this name, if any.
    pub fn symbol_named(&self, name: &str) -> Option<SymbolId> {
        self.symbol_names.get(name).copied()
    }

    /// The symbol `name` of `kind`, created on first use. Asking again with the
    /// same kind returns the same symbol; another kind is an error.
    pub fn add_symbol(&mut self, name: &str, kind: SymbolKind) -> Result<Id> {
        if let Some(&s) = self.symbol_names.get(name) {
            if self.symbols[s.index()].kind == kind {
                return Ok(self.symbol_node(s));
            }
            return Err(Error::NameTaken { name: name.to_string() });
        }
        let s = SymbolId(self.symbols.len() as u32);
        self.symbols.push(Symbol { name: name.to_string(), kind });
        self.symbol_names.insert(name.to_string(), s);
        let id = self.intern(Node::Symbol(s));
        self.symbol_nodes.push(id);
        Ok(id)
    }

    /// A differential variable.
    pub fn state(&mut self, name: &str) -> Result<Id> {
        self.add_symbol(name, SymbolKind::State)
    }

    /// New differential variables `names`, as symbols: for tests and tools
    /// that build a graph by hand.
    pub fn state_symbols(&mut self, names: &[&str]) -> Result<Vec<SymbolId>> {
        names
            .iter()
            .map(|n| {
                let id = self.state(n)?;
                self.as_symbol(id).ok_or_else(|| crate::Error::Unsupported {
                    message: format!("`{n}` is not a symbol"),
                })
            })
            .collect()
    }

    /// An algebraic variable.
    pub fn algebraic(&mut self, name: &str) -> Result<Id> {
        self.add_symbol(name, SymbolKind::Algebraic)
    }

    /// A runtime parameter.
    pub fn parameter(&mut self, name: &str) -> Result<Id> {
        self.add_symbol(name, SymbolKind::Parameter)
    }

    /// The independent variable.
    pub fn time(&mut self, name: &str) -> Result<Id> {
        self.add_symbol(name, SymbolKind::Time)
    }

    /// A signal supplied at run time.
    pub fn input(&mut self, name: &str) -> Result<Id> {
        self.add_symbol(name, SymbolKind::Input { rate_of: None })
    }

    /// The rate of the input `of`, named `rate(u)`.
    pub fn input_rate(&mut self, of: SymbolId) -> Result<Id> {
        let name = format!("rate({})", self.symbol(of).name);
        self.add_symbol(&name, SymbolKind::Input { rate_of: Some(of) })
    }

    /// A named intermediate standing for `definition`.
    pub fn intermediate(&mut self, name: &str, definition: Id) -> Result<Id> {
        self.add_symbol(name, SymbolKind::Intermediate { definition })
    }

    /// The symbol for the `order`-th time derivative of `of`, named
    /// `der(x)`, `der(der(x))`, ...; `order` 0 is `of` itself. Derivatives of
    /// derivatives are flattened (`der` of `der(x)` is `der(der(x))`).
    pub fn derivative(&mut self, of: SymbolId, order: u32) -> Result<Id> {
        let (base, order) = match self.symbols[of.index()].kind {
            SymbolKind::Derivative { of: base, order: k } => (base, k + order),
            _ => (of, order),
        };
        if order == 0 {
            return Ok(self.symbol_node(base));
        }
        if let Some(&s) = self.derivatives.get(&(base, order)) {
            return Ok(self.symbol_node(s));
        }
        let base_name = &self.symbols[base.index()].name;
        let name =
            format!("{}{}{}", "der(".repeat(order as usize), base_name, ")".repeat(order as usize));
        let id = self.add_symbol(&name, SymbolKind::Derivative { of: base, order })?;
        if let Node::Symbol(s) = self.node(id) {
            self.derivatives.insert((base, order), *s);
        }
        Ok(id)
    }

    /// The symbol of `der^order(of)` if the graph has made it (`of` not a
    /// derivative itself).
    pub fn existing_derivative(&self, of: SymbolId, order: u32) -> Option<SymbolId> {
        self.derivatives.get(&(of, order)).copied()
    }

    /// Every node reachable from `roots` (through intermediate definitions),
    /// each once, in ascending id order: children before parents.
    pub fn reachable(&self, roots: &[Id]) -> Vec<Id> {
        self.reachable_until(roots, |_| false)
    }

    /// Like [`Graph::reachable`], but does not enter (or list) nodes for which
    /// `stop` holds.
    pub(crate) fn reachable_until(&self, roots: &[Id], stop: impl Fn(Id) -> bool) -> Vec<Id> {
        // A set, not an arena-sized bitmap: Jacobians call this once per entry,
        // each visiting a small part of a large graph.
        let mut seen: std::collections::HashSet<Id, BuildHasherDefault<FxHasher>> =
            Default::default();
        let mut stack: Vec<Id> = Vec::new();
        for &r in roots {
            if !stop(r) && seen.insert(r) {
                stack.push(r);
            }
        }
        while let Some(id) = stack.pop() {
            for &c in self.operands(id) {
                if !stop(c) && seen.insert(c) {
                    stack.push(c);
                }
            }
        }
        let mut out: Vec<Id> = seen.into_iter().collect();
        out.sort_unstable();
        out
    }

    /// The symbols an expression depends on (through intermediates), sorted.
    pub fn free_symbols(&self, id: Id) -> Vec<SymbolId> {
        self.reachable(&[id])
            .into_iter()
            .filter_map(|n| match self.node(n) {
                Node::Symbol(s)
                    if !matches!(self.symbols[s.index()].kind, SymbolKind::Intermediate { .. }) =>
                {
                    Some(*s)
                }
                _ => None,
            })
            .collect()
    }
}
