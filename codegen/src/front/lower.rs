//! Lowering: the function body, read as the model language, into a
//! [`ModelIr`]. Names are resolved, `const`s evaluated, `for` loops and
//! constant `if`s unrolled; every mistake is recorded with the user's tokens
//! and lowering goes on, so all mistakes are reported together.

use crate::front::ctxt::Ctxt;
use crate::front::ir::{
    AlgebraicDecl, Equation, Event, EventDirection, Init, ModelIr, Output, Param, StateDecl,
    UserInvariant,
};
use crate::front::names::did_you_mean;

use crate::front::tensor::Tensor;
use crate::mechanics::Scene;
use crate::{Func, Graph, Id, Node, SymbolId, SymbolKind};
use quote::ToTokens;
use std::collections::HashMap;
use syn::{BinOp, Expr, Lit, Pat, Stmt, UnOp};

/// Most loop iterations, over all loops, before unrolling is refused.
const MAX_UNROLLED: usize = 100_000;

/// What a name stands for.
#[derive(Clone)]
pub(crate) enum Binding {
    Param(Id),
    State(SymbolId),
    StateArray(Vec<SymbolId>),
    /// `let m = [a, b, ...];`: constant-indexed values (masses, lengths).
    ValueArray(Vec<Id>),
    Algebraic(Id),
    Time(Id),
    /// A `let` intermediate (possibly `mut`) or an output.
    Value {
        id: Id,
        mutable: bool,
    },
    /// A `const` or a loop index.
    Const(Id),
    /// `let r = rot_z(theta);`: a vector or a matrix.
    Tensor(Tensor),
    /// `let crank = body(m, j, [x, y, theta]);`: a planar rigid body.
    Body(usize),
    /// `let ground = ground();`
    Ground,
    /// A body whose declaration has an error (already reported): its uses
    /// stay quiet.
    BrokenBody,
    /// A value whose definition has an error (already reported): its uses
    /// stay quiet too, so each mistake is reported once.
    Broken,
}

impl Binding {
    pub(crate) fn describe(&self) -> &'static str {
        match self {
            Binding::Param(_) => "a parameter",
            Binding::State(_) => "a state",
            Binding::StateArray(_) => "an array of states",
            Binding::ValueArray(_) => "an array of values",
            Binding::Algebraic(_) => "an algebraic variable",
            Binding::Time(_) => "the time",
            Binding::Value { .. } => "an intermediate value",
            Binding::Const(_) => "a constant",
            Binding::Tensor(_) => "a vector or matrix value",
            Binding::Body(_) => "a body",
            Binding::Ground => "the ground",
            Binding::BrokenBody => "a body",
            Binding::Broken => "a value",
        }
    }
}

const DECLARATIONS: [&str; 11] = [
    "event",
    "body",
    "spatial_body",
    "ground",
    "quaternion_state",
    "param",
    "state",
    "state_array",
    "algebraic",
    "time",
    "output",
];
const FUNCTIONS: [&str; 20] = [
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sinh",
    "cosh",
    "tanh",
    "exp",
    "ln",
    "sqrt",
    "abs",
    "der",
    "init",
    "constraint",
    "invariant",
    "powi",
    "powf",
];

pub(crate) struct Lower<'c> {
    pub(crate) cx: &'c mut Ctxt,
    pub(crate) g: Graph,
    pub(crate) scopes: Vec<HashMap<String, Binding>>,
    pub(crate) time: Option<SymbolId>,
    pub(crate) params: Vec<Param>,
    pub(crate) states: Vec<StateDecl>,
    pub(crate) algebraics: Vec<AlgebraicDecl>,
    pub(crate) outputs: Vec<Output>,
    pub(crate) events: Vec<Event>,
    pub(crate) equations: Vec<Equation>,
    pub(crate) inits: Vec<Init>,
    pub(crate) invariants: Vec<UserInvariant>,
    pub(crate) scene: Scene,
    pub(crate) unrolled: usize,
    pub(crate) non_smooth_calls: Vec<(Id, proc_macro2::TokenStream)>,
    /// Names of whole-number constants: loop indices and integer `const`s
    /// (`front::integers`).
    pub(crate) integer_names: std::collections::HashSet<String>,
}

/// Lowers the body of `item`. Errors go to `cx`; the IR is returned even
/// then (with the parts that could be read) so that a stub can be emitted.
pub fn lower(cx: &mut Ctxt, item: &syn::ItemFn) -> ModelIr {
    lower_with(cx, item, false)
}

/// Lowers `item`; a scene uses the recursive formulation when `recursive`
/// (`#[dae_model(scene = recursive)]`), the global one otherwise.
pub fn lower_with(cx: &mut Ctxt, item: &syn::ItemFn, recursive: bool) -> ModelIr {
    let mut l = Lower {
        cx,
        g: Graph::new(),
        scopes: vec![HashMap::new()],
        time: None,
        params: Vec::new(),
        states: Vec::new(),
        algebraics: Vec::new(),
        outputs: Vec::new(),
        events: Vec::new(),
        equations: Vec::new(),
        inits: Vec::new(),
        invariants: Vec::new(),
        scene: Scene { recursive, ..Scene::default() },
        unrolled: 0,
        non_smooth_calls: Vec::new(),
        integer_names: Default::default(),
    };
    if !item.sig.inputs.is_empty() {
        l.cx.error_at(
            &item.sig.inputs,
            "a model takes no arguments: declare parameters with `let m = param(1.0);`",
        );
    }
    if let syn::ReturnType::Type(_, ty) = &item.sig.output {
        l.cx.error_at(ty, "a model returns nothing: remove the return type");
    }
    for stmt in &item.block.stmts {
        l.stmt(stmt);
    }
    // Without `time()`, the model is autonomous; it still gets a time symbol,
    // under a name no declaration took.
    let time = l.time.or_else(|| {
        let names = std::iter::once("t".to_string()).chain((0..).map(|k| format!("__time{k}")));
        names.into_iter().find_map(|n| l.g.time(&n).ok()).and_then(|id| l.g.as_symbol(id))
    });
    let time = time.unwrap_or(SymbolId(0));
    l.scene_equations(item);
    if l.states.is_empty() && l.cx.is_ok() {
        l.cx.error_at(&item.sig.ident, "the model declares no state: add one with `let x = state(0.0);` and an equation `der(x) == ...;`");
    }
    let mut doc = doc_comment(&item.attrs);
    if !l.scene.summary.is_empty() {
        doc = if doc.is_empty() {
            l.scene.summary.clone()
        } else {
            format!("{doc}\n\n{}", l.scene.summary)
        };
    }
    ModelIr {
        fn_name: item.sig.ident.clone(),
        vis: item.vis.clone(),
        doc,
        graph: l.g,
        time,
        params: l.params,
        states: l.states,
        algebraics: l.algebraics,
        outputs: l.outputs,
        events: l.events,
        equations: l.equations,
        inits: l.inits,
        invariants: l.invariants,
        non_smooth_calls: l.non_smooth_calls,
    }
}

/// The `///` lines of `attrs`, joined.
pub fn doc_comment(attrs: &[syn::Attribute]) -> String {
    let lines: Vec<String> = attrs
        .iter()
        .filter(|a| a.path().is_ident("doc"))
        .filter_map(|a| match &a.meta {
            syn::Meta::NameValue(nv) => match &nv.value {
                Expr::Lit(syn::ExprLit { lit: Lit::Str(s), .. }) => Some(s.value()),
                _ => None,
            },
            _ => None,
        })
        .map(|l| l.strip_prefix(' ').unwrap_or(&l).to_string())
        .collect();
    lines.join("\n")
}

/// `event(g)` and the settings chained after it (`.falling().terminal()`),
/// innermost first.
fn event_call(e: &Expr) -> Option<(&syn::ExprCall, Vec<&syn::ExprMethodCall>)> {
    let mut settings = Vec::new();
    let mut e = e;
    while let Expr::MethodCall(m) = e {
        settings.push(m);
        e = &m.receiver;
    }
    settings.reverse();
    match call_name(e) {
        Some((name, call)) if name == "event" => Some((call, settings)),
        _ => None,
    }
}

fn call_name(e: &Expr) -> Option<(String, &syn::ExprCall)> {
    match e {
        Expr::Call(c) => match &*c.func {
            Expr::Path(p) => p.path.get_ident().map(|i| (i.to_string(), c)),
            _ => None,
        },
        _ => None,
    }
}

impl Lower<'_> {
    pub(crate) fn lookup(&self, name: &str) -> Option<&Binding> {
        self.scopes.iter().rev().find_map(|s| s.get(name))
    }

    pub(crate) fn known_names(&self) -> Vec<String> {
        self.scopes.iter().flat_map(|s| s.keys().cloned()).collect()
    }

    pub(crate) fn in_loop(&self) -> bool {
        self.scopes.len() > 1
    }

    /// Binds `name`, refusing to redeclare a model variable.
    /// Replaces a binding of the innermost scope (a body declared at last).
    pub(crate) fn rebind(&mut self, ident: &syn::Ident, binding: Binding) {
        if let Some(scope) = self.scopes.last_mut() {
            scope.insert(ident.to_string(), binding);
        }
    }

    pub(crate) fn bind(&mut self, ident: &syn::Ident, binding: Binding) {
        let name = ident.to_string();
        if let Some(old) = self.lookup(&name) {
            let is_value = |b: &Binding| matches!(b, Binding::Value { .. } | Binding::Broken);
            // A broken value's error is reported: it redeclares nothing.
            if matches!(binding, Binding::Broken) && !is_value(old) {
                return;
            }
            if !(is_value(old) && is_value(&binding)) {
                let what = old.describe();
                self.cx.error_at(
                    ident,
                    format!("`{name}` is already declared as {what}: choose another name"),
                );
                return;
            }
        }
        if let Some(scope) = self.scopes.last_mut() {
            scope.insert(name, binding);
        }
    }

    pub(crate) fn stmt(&mut self, stmt: &Stmt) {
        match stmt {
            Stmt::Local(local) => self.local(local),
            Stmt::Item(syn::Item::Const(c)) => {
                if let Some(v) = self.constant(&c.expr) {
                    self.bind(&c.ident, Binding::Const(v));
                    let name = c.ident.to_string();
                    if crate::front::integers::is_integer_type(&c.ty) {
                        self.integer_names.insert(name);
                    } else {
                        self.integer_names.remove(&name);
                    }
                }
            }
            Stmt::Expr(e, _) => self.expr_stmt(e),
            Stmt::Item(other) => {
                self.cx.error_at(other, "only `const` items are allowed in a model")
            }
            Stmt::Macro(m) => self.cx.error_at(m, "macros are not part of the model language"),
        }
    }

    pub(crate) fn local(&mut self, local: &syn::Local) {
        let (ident, mutable) = match &local.pat {
            Pat::Ident(p) => (p.ident.clone(), p.mutability.is_some()),
            Pat::Type(t) => match &*t.pat {
                Pat::Ident(p) => (p.ident.clone(), p.mutability.is_some()),
                other => return self.cx.error_at(other, "bind a single name: `let x = ...;`"),
            },
            other => return self.cx.error_at(other, "bind a single name: `let x = ...;`"),
        };
        let Some(init) = &local.init else {
            return self
                .cx
                .error_at(local, format!("`{ident}` needs a value: `let {ident} = ...;`"));
        };
        if let Some((_, else_branch)) = &init.diverge {
            return self
                .cx
                .error_at(else_branch, "`let ... else` is not part of the model language");
        }
        let e = &*init.expr;
        let doc = doc_comment(&local.attrs);
        if let Some((call, settings)) = event_call(e) {
            if self.in_loop() {
                return self.cx.error_at(
                    e,
                    format!("declare `event(...)` outside loops: each iteration would declare `{ident}` again"),
                );
            }
            return self.event(&ident, call, &settings, doc, local);
        }
        // `state(x0).fixed()`: a value consistent initialization keeps.
        let (e, fixed) = match e {
            Expr::MethodCall(m)
                if m.method == "fixed"
                    && m.args.is_empty()
                    && matches!(call_name(&m.receiver), Some((n, _)) if n == "state" || n == "state_array") =>
            {
                (&*m.receiver, true)
            }
            _ => (e, false),
        };
        if let Some((name, call)) = call_name(e) {
            if crate::mechanics::JOINTS.contains(&name.as_str()) {
                if self.already_declared(&ident) {
                    return;
                }
                return self.joint(&name, Some(&ident), call, e);
            }
            if DECLARATIONS.contains(&name.as_str()) {
                if self.in_loop() {
                    return self.cx.error_at(e, format!("declare `{name}(...)` outside loops: each iteration would declare `{ident}` again"));
                }
                if mutable {
                    self.cx.error_at(&local.pat, format!("a {name} cannot be `mut`: remove `mut`"));
                }
                let first = self.states.len();
                self.declaration(&ident, &name, call, doc, local);
                for state in &mut self.states[first..] {
                    state.fixed = fixed;
                }
                return;
            }
        }
        if self.mentions_tensor(e) {
            let Some(t) = self.tensor(e) else {
                return self.bind(&ident, Binding::Broken);
            };
            match (t.as_scalar(), mutable) {
                (Some(id), _) => self.bind(&ident, Binding::Value { id, mutable }),
                (None, false) => self.bind(&ident, Binding::Tensor(t)),
                (None, true) => self.cx.error_at(
                    &local.pat,
                    format!("a {} cannot be `mut`: bind each new value with `let`", t.shape()),
                ),
            }
            return;
        }
        if let (Expr::Array(array), false) = (e, mutable) {
            let values: Vec<Option<Id>> = array.elems.iter().map(|v| self.value(v)).collect();
            match values.into_iter().collect::<Option<Vec<Id>>>() {
                Some(values) => self.bind(&ident, Binding::ValueArray(values)),
                None => self.bind(&ident, Binding::Broken),
            }
            return;
        }
        // `[value; N]`: N copies, as in `state_array([0.0; N])`.
        if let (Expr::Repeat(repeat), false) = (e, mutable) {
            let (Some(value), Some(n)) =
                (self.value(&repeat.expr), self.index_constant(&repeat.len))
            else {
                return;
            };
            self.bind(&ident, Binding::ValueArray(vec![value; n]));
            return;
        }
        match self.value(e) {
            Some(id) => self.bind(&ident, Binding::Value { id, mutable }),
            None => self.bind(&ident, Binding::Broken),
        }
    }

    /// A new state or algebraic symbol `name` and its node; `None` once
    /// the clash with another name is reported at `at`.
    fn new_symbol(
        &mut self,
        name: &str,
        kind: SymbolKind,
        at: &dyn quote::ToTokens,
    ) -> Option<(Id, SymbolId)> {
        let created =
            if kind == SymbolKind::State { self.g.state(name) } else { self.g.algebraic(name) };
        match created {
            Ok(id) => Some((id, self.g.as_symbol(id)?)),
            Err(e) => {
                self.cx.error_at(at, e);
                None
            }
        }
    }

    /// Declares the state `name` (a user's, or a scene's coordinate)
    /// documented by `doc`; `None` once the clash with another name is
    /// reported at `at`.
    pub(crate) fn declare_state(
        &mut self,
        name: String,
        init: Id,
        at: &syn::Ident,
        origin: &proc_macro2::TokenStream,
        doc: &str,
    ) -> Option<SymbolId> {
        let (_, symbol) = self.new_symbol(&name, SymbolKind::State, at)?;
        let (origin, doc) = (origin.clone(), doc.to_string());
        self.states.push(StateDecl { name, symbol, init, origin, fixed: false, doc });
        Some(symbol)
    }

    /// Declares the algebraic variable `name` (a user's, or a joint's
    /// multiplier) documented by `doc`; its node, or `None` once the clash
    /// with another name is reported at `at`.
    pub(crate) fn declare_algebraic(
        &mut self,
        name: String,
        init: Id,
        at: &dyn quote::ToTokens,
        origin: &proc_macro2::TokenStream,
        doc: String,
    ) -> Option<Id> {
        let (id, symbol) = self.new_symbol(&name, SymbolKind::Algebraic, at)?;
        let origin = origin.clone();
        self.algebraics.push(AlgebraicDecl { name, symbol, init, origin, doc });
        Some(id)
    }

    /// Starts `der(state)` at `value` (a body's or a joint's initial
    /// rate); `None` where the state has no derivative to start.
    pub(crate) fn init_rate(
        &mut self,
        state: SymbolId,
        value: Id,
        origin: &proc_macro2::TokenStream,
    ) -> Option<()> {
        let d = self.g.derivative(state, 1).ok()?;
        let target = self.g.as_symbol(d)?;
        self.inits.push(Init { target, value, origin: origin.clone() });
        Some(())
    }

    /// Adds the equations of motion `(lhs, rhs)` the scene gave, or reports
    /// at `origin` why it could not write them.
    pub(crate) fn push_equations_of_motion(
        &mut self,
        equations: crate::Result<Vec<(Id, Id)>>,
        origin: &proc_macro2::TokenStream,
    ) {
        match equations {
            Ok(equations) => {
                for (lhs, rhs) in equations {
                    let origin = origin.clone();
                    let eq = crate::front::ir::Equation { lhs, rhs, origin, is_constraint: false };
                    self.equations.push(eq);
                }
            }
            Err(e) => self.cx.error_at(origin, e),
        }
    }

    /// Reports a second declaration of `ident`'s name.
    pub(crate) fn already_declared(&mut self, ident: &syn::Ident) -> bool {
        let name = ident.to_string();
        let Some(what) = self.lookup(&name).map(Binding::describe) else {
            return false;
        };
        self.cx.error_at(
            ident,
            format!("`{name}` is already declared as {what}: choose another name"),
        );
        true
    }

    /// `let e = event(g).rising().terminal();`
    pub(crate) fn event(
        &mut self,
        ident: &syn::Ident,
        call: &syn::ExprCall,
        settings: &[&syn::ExprMethodCall],
        doc: String,
        local: &syn::Local,
    ) {
        let name = ident.to_string();
        if self.already_declared(ident) {
            return;
        }
        if !self.arity(call, "event", 1) {
            return;
        }
        let (mut direction, mut terminal) = (EventDirection::Any, false);
        for m in settings {
            let setting = m.method.to_string();
            if !m.args.is_empty() {
                self.cx.error_at(&m.args, format!("`.{setting}()` takes no argument"));
                continue;
            }
            let wanted = match setting.as_str() {
                "rising" => EventDirection::Rising,
                "falling" => EventDirection::Falling,
                "terminal" => {
                    terminal = true;
                    continue;
                }
                _ => {
                    self.cx.error_at(
                        &m.method,
                        format!("unknown event setting `.{setting}()`: use `.rising()`, `.falling()` or `.terminal()`"),
                    );
                    continue;
                }
            };
            if direction != EventDirection::Any && direction != wanted {
                self.cx.error_at(
                    &m.method,
                    "an event is `.rising()` or `.falling()`, not both: leave both out to catch every crossing",
                );
            }
            direction = wanted;
        }
        let Some(value) = self.value(&call.args[0]) else {
            return;
        };
        self.events.push(Event {
            name,
            value,
            direction,
            terminal,
            doc,
            origin: local.to_token_stream(),
        });
        self.bind(ident, Binding::Value { id: value, mutable: false });
    }

    pub(crate) fn arity(&mut self, call: &syn::ExprCall, name: &str, n: usize) -> bool {
        if call.args.len() == n {
            return true;
        }
        let args = match n {
            0 => "no argument".to_string(),
            1 => "one argument".to_string(),
            n => format!("{n} arguments"),
        };
        self.cx.error_at(call, format!("`{name}` takes {args}, not {}", call.args.len()));
        false
    }

    pub(crate) fn declaration(
        &mut self,
        ident: &syn::Ident,
        kind: &str,
        call: &syn::ExprCall,
        doc: String,
        local: &syn::Local,
    ) {
        // One match arm per declaration of the language (`param`, `state`, `algebraic`, …):
        // long because the language is, each arm short.
        let name = ident.to_string();
        if self.already_declared(ident) {
            return;
        }
        let origin = local.to_token_stream();
        match kind {
            "body" | "ground" => self.scene_declaration(ident, kind, call, local),
            "spatial_body" => self.spatial_declaration(ident, call, local),
            "param" => {
                if !self.arity(call, "param", 1) {
                    return;
                }
                let v = self.constant(&call.args[0]).unwrap_or_else(|| self.g.zero());
                let default = self.g.as_number(v).map_or(f64::NAN, |n| n.to_f64());
                match self.g.parameter(&name) {
                    Ok(id) => {
                        self.params.push(Param { ident: ident.clone(), default, doc });
                        self.bind(ident, Binding::Param(id));
                    }
                    Err(e) => self.cx.error_at(ident, e),
                }
            }
            "state" => {
                if !self.arity(call, "state", 1) {
                    return;
                }
                // A bad initial value is reported; the state is still
                // declared, so its uses raise no second error.
                let init = self.initial_value(&call.args[0]).unwrap_or_else(|| self.g.zero());
                if let Some(symbol) = self.declare_state(name, init, ident, &origin, &doc) {
                    self.bind(ident, Binding::State(symbol));
                }
            }
            "state_array" | "quaternion_state" => {
                if !self.arity(call, kind, 1) {
                    return;
                }
                let inits: Vec<Option<Id>> = match &call.args[0] {
                    Expr::Array(a) => a.elems.iter().map(|e| self.initial_value(e)).collect(),
                    Expr::Repeat(r) => {
                        let v = self.initial_value(&r.expr);
                        match self.index_constant(&r.len) {
                            Some(n) => vec![v; n],
                            None => return,
                        }
                    }
                    Expr::MethodCall(m) if m.method == "map" => {
                        match self.initial_values_by_index(m) {
                            Some(inits) => inits,
                            None => return,
                        }
                    }
                    other => {
                        return self.cx.error_at(other, "`state_array` takes an array of initial values: `state_array([1.0, 0.0])`, `state_array([0.0; N])` or `state_array((0..N).map(|i| ...))`");
                    }
                };
                if inits.is_empty() {
                    return self
                        .cx
                        .error_at(&call.args[0], "a state array needs at least one element");
                }
                if kind == "quaternion_state" && inits.len() != 4 {
                    return self.cx.error_at(&call.args[0], "a quaternion has four components: `quaternion_state([1.0, 0.0, 0.0, 0.0])` (q0 = cos(θ/2) first)");
                }
                let mut symbols = Vec::new();
                for (i, init) in inits.into_iter().enumerate() {
                    let element = format!("{name}[{i}]");
                    let (Some(init), Ok(id)) = (init, self.g.state(&element)) else {
                        continue;
                    };
                    let symbol = self.g.as_symbol(id).unwrap_or(SymbolId(0));
                    self.states.push(StateDecl {
                        name: element,
                        symbol,
                        init,
                        origin: origin.clone(),
                        fixed: false,
                        doc: doc.clone(),
                    });
                    symbols.push(symbol);
                }
                if kind == "quaternion_state" && symbols.len() == 4 {
                    // |q|² − 1, kept at zero by projection (course notes §4.1.3).
                    let mut terms = Vec::with_capacity(5);
                    for &s in &symbols {
                        let q = self.g.symbol_node(s);
                        match self.g.mul(q, q) {
                            Ok(t) => terms.push(t),
                            Err(e) => return self.cx.error_at(ident, e),
                        }
                    }
                    terms.push(self.g.int(-1));
                    match self.g.sum(&terms) {
                        Ok(value) => {
                            self.invariants.push(UserInvariant { value, origin: origin.clone() })
                        }
                        Err(e) => return self.cx.error_at(ident, e),
                    }
                }
                self.bind(ident, Binding::StateArray(symbols));
            }
            "algebraic" => {
                if !self.arity(call, "algebraic", 1) {
                    return;
                }
                let init = self.initial_value(&call.args[0]).unwrap_or_else(|| self.g.zero());
                if let Some(id) = self.declare_algebraic(name, init, ident, &origin, doc) {
                    self.bind(ident, Binding::Algebraic(id));
                }
            }
            "time" => {
                if !self.arity(call, "time", 0) {
                    return;
                }
                if self.time.is_some() {
                    return self
                        .cx
                        .error_at(local, "the time is already declared: a model has one `time()`");
                }
                match self.g.time(&name) {
                    Ok(id) => {
                        self.time = self.g.as_symbol(id);
                        self.bind(ident, Binding::Time(id));
                    }
                    Err(e) => self.cx.error_at(ident, e),
                }
            }
            _ => {
                // output
                if !self.arity(call, "output", 1) {
                    return;
                }
                let Some(value) = self.value(&call.args[0]) else {
                    return;
                };
                self.outputs.push(Output { name, value, doc, origin });
                self.bind(ident, Binding::Value { id: value, mutable: false });
            }
        }
    }

    /// An initial value or guess: constants and parameters only.
    /// The initial values of `(0..N).map(|i| value)`: `value` with `i`
    /// bound to each index of the range in turn, as a loop binds it.
    fn initial_values_by_index(&mut self, m: &syn::ExprMethodCall) -> Option<Vec<Option<Id>>> {
        let how = "write the initial values as `(0..N).map(|i| 1.0 + 0.1 * (i as f64))`";
        let mut receiver = &*m.receiver;
        while let Expr::Paren(p) = receiver {
            receiver = &p.expr;
        }
        let (Expr::Range(range), [Expr::Closure(closure)]) =
            (receiver, m.args.iter().collect::<Vec<_>>().as_slice())
        else {
            self.cx.error_at(m, how);
            return None;
        };
        let (Some(start), Some(end), [Pat::Ident(var)]) =
            (&range.start, &range.end, closure.inputs.iter().collect::<Vec<_>>().as_slice())
        else {
            self.cx.error_at(m, how);
            return None;
        };
        let (start, end) = (self.index_constant(start)?, self.index_constant(end)?);
        let end = match range.limits {
            syn::RangeLimits::HalfOpen(_) => end,
            syn::RangeLimits::Closed(_) => end + 1,
        };
        let values = (start..end)
            .map(|i| {
                let index = self.g.int(i as i64);
                self.integer_names.insert(var.ident.to_string());
                self.scopes.push(HashMap::from([(var.ident.to_string(), Binding::Const(index))]));
                let value = self.initial_value(&closure.body);
                self.scopes.pop();
                value
            })
            .collect();
        Some(values)
    }

    pub(crate) fn initial_value(&mut self, e: &Expr) -> Option<Id> {
        let v = self.value(e)?;
        let bad = self
            .g
            .free_symbols(v)
            .into_iter()
            .find(|s| self.g.symbol(*s).kind != SymbolKind::Parameter);
        if let Some(s) = bad {
            let name = self.g.symbol(s).name.clone();
            self.cx.error_at(
                e,
                format!("an initial value may use constants and parameters, not `{name}`"),
            );
            return None;
        }
        Some(v)
    }

    /// A compile-time constant (literals, `const`s, loop indices, arithmetic).
    pub(crate) fn constant(&mut self, e: &Expr) -> Option<Id> {
        let v = self.value(e)?;
        if self.g.as_number(v).is_some() {
            return Some(v);
        }
        self.not_constant(e, v);
        None
    }

    /// Says which variable keeps `e` from being a compile-time constant.
    pub(crate) fn not_constant(&mut self, e: &Expr, v: Id) {
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
    pub(crate) fn index_constant(&mut self, e: &Expr) -> Option<usize> {
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

    pub(crate) fn expr_stmt(&mut self, e: &Expr) {
        match e {
            Expr::Binary(b) if matches!(b.op, BinOp::Eq(_)) && (self.mentions_tensor(&b.left) || self.mentions_tensor(&b.right)) => {
                // One equation per component.
                let (lhs, rhs) = (self.tensor(&b.left), self.tensor(&b.right));
                let (Some(lhs), Some(rhs)) = (lhs, rhs) else { return };
                if (lhs.rows, lhs.cols) != (rhs.rows, rhs.cols) {
                    return self.cx.error_at(e, format!("the two sides differ in shape: a {} and a {}", lhs.shape(), rhs.shape()));
                }
                for (&l, &r) in lhs.data.iter().zip(&rhs.data) {
                    self.equations.push(Equation { lhs: l, rhs: r, origin: e.to_token_stream(), is_constraint: false });
                }
            }
            Expr::Binary(b) if matches!(b.op, BinOp::Eq(_)) => {
                let (lhs, rhs) = (self.value(&b.left), self.value(&b.right));
                if let (Some(lhs), Some(rhs)) = (lhs, rhs) {
                    self.equations.push(Equation { lhs, rhs, origin: e.to_token_stream(), is_constraint: false });
                }
            }
            Expr::ForLoop(f) => self.for_loop(f),
            Expr::If(i) => self.const_if(i),
            Expr::Assign(a) if !matches!(&*a.left, Expr::Path(_)) => {
                // `der(x) = f;`: an equation written with Rust's assignment.
                let (lhs, rhs) = (
                    crate::front::names::source_text(&a.left.to_token_stream()),
                    crate::front::names::source_text(&a.right.to_token_stream()),
                );
                self.cx.error_at(
                    a.eq_token,
                    format!("`=` assigns; write an equation with `==`: `{lhs} == {rhs};`"),
                );
            }
            Expr::Assign(a) => {
                let v = self.value(&a.right);
                self.assign(&a.left, v, e);
            }
            Expr::Binary(b) if is_compound_assignment(&b.op) => {
                let current = self.value(&b.left);
                let rhs = self.value(&b.right);
                let combined = match (current, rhs) {
                    (Some(c), Some(r)) => self.arith(&b.op, c, r, e),
                    _ => None,
                };
                self.assign(&b.left, combined, e);
            }
            Expr::Block(b) => {
                self.scopes.push(HashMap::new());
                for s in &b.block.stmts {
                    self.stmt(s);
                }
                self.scopes.pop();
            }
                        _ if event_call(e).is_some() => self.cx.error_at(
                e,
                "an event needs a name to be looked up by: write `let hit = event(...);`",
            ),
            _ => match call_name(e) {
                Some((name, call)) if name == "constraint" => {
                    if self.arity(call, "constraint", 1) {
                        // A vector constraint is one per component.
                        if let Some(phi) = self.tensor(&call.args[0]) {
                            let zero = self.g.zero();
                            for &c in &phi.data {
                                self.equations.push(Equation { lhs: c, rhs: zero, origin: e.to_token_stream(), is_constraint: true });
                            }
                        }
                    }
                }
                Some((name, call)) if crate::mechanics::JOINTS.contains(&name.as_str()) => {
                    self.joint(&name, None, call, e)
                }
                Some((name, call)) if crate::mechanics::LOADS.contains(&name.as_str()) => self.load(&name, call, e),
                Some((name, call)) if name == "invariant" => {
                    if self.arity(call, "invariant", 1) {
                        if let Some(value) = self.tensor(&call.args[0]) {
                            for &v in &value.data {
                                self.invariants.push(UserInvariant { value: v, origin: e.to_token_stream() });
                            }
                        }
                    }
                }
                Some((name, call)) if name == "init" => self.init(call, e),
                Some((name, _)) if DECLARATIONS.contains(&name.as_str()) => {
                    self.cx.error_at(e, format!("`{name}(...)` declares a variable: write `let x = {name}(...);`"))
                }
                _ => self.cx.error_at(
                    e,
                    "a model statement is `let`, an equation `lhs == rhs;`, `constraint(...)`, `init(...)`, `const` or `for`",
                ),
            },
        }
    }

    pub(crate) fn assign(&mut self, target: &Expr, value: Option<Id>, whole: &Expr) {
        let name = match target {
            Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
            _ => None,
        };
        let Some(name) = name else {
            return self.cx.error_at(target, "only `let mut` intermediates can be assigned to");
        };
        match self.lookup(&name).cloned() {
            Some(Binding::Value { mutable: true, .. }) => {
                if let Some(id) = value {
                    // Assign in the scope that declared it, so loops can accumulate.
                    if let Some(scope) = self.scopes.iter_mut().rev().find(|s| s.contains_key(&name)) {
                        scope.insert(name, Binding::Value { id, mutable: true });
                    }
                }
            }
            Some(Binding::Broken) => {}
            Some(Binding::Value { mutable: false, .. }) => {
                self.cx.error_at(whole, format!("`{name}` is not `mut`: declare it with `let mut {name} = ...;` to accumulate into it"))
            }
            Some(b) => {
                let what = b.describe();
                self.cx.error_at(whole, format!("cannot assign to `{name}`, {what}: state its dynamics as an equation, e.g. `der({name}) == ...;`"))
            }
            None => self.unknown_name(target, &name),
        }
    }

    pub(crate) fn init(&mut self, call: &syn::ExprCall, whole: &Expr) {
        if !self.arity(call, "init", 2) {
            return;
        }
        let (target, value) = (self.value(&call.args[0]), self.initial_value(&call.args[1]));
        let (Some(target), Some(value)) = (target, value) else {
            return;
        };
        match self.g.as_symbol(target).map(|s| (s, self.g.symbol(s).kind)) {
            Some((s, SymbolKind::Derivative { .. })) => {
                self.inits.push(Init { target: s, value, origin: whole.to_token_stream() })
            }
            _ => self.cx.error_at(&call.args[0], "`init` sets a derivative of a state: `init(der(x), 0.0)`; set the state itself in `state(...)`"),
        }
    }

    pub(crate) fn for_loop(&mut self, f: &syn::ExprForLoop) {
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

    pub(crate) fn const_if(&mut self, i: &syn::ExprIf) {
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
    fn const_if_value(&mut self, i: &syn::ExprIf) -> Option<Id> {
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
    fn branch_value(&mut self, b: &syn::Block) -> Option<Id> {
        match b.stmts.as_slice() {
            [Stmt::Expr(e, None)] => self.value(e),
            _ => {
                self.cx.error_at(b, "a branch of an `if` used as a value is one expression: `if i == 0 { 1.0 } else { u[i - 1] }`");
                None
            }
        }
    }

    /// A condition on constants (loop indices): `i != j`, `i < N && j > 0`.
    pub(crate) fn condition(&mut self, e: &Expr) -> Option<bool> {
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
                        self.cx.error_at(e, "`if` is only for constants (loop indices), not model variables: the model must be smooth; use `abs`, or split the model");
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

    pub(crate) fn arith(&mut self, op: &BinOp, a: Id, b: Id, at: &Expr) -> Option<Id> {
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
                    Some(b @ (Binding::StateArray(_) | Binding::ValueArray(_))) => {
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
                    Some(Binding::ValueArray(v)) => v,
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
            Expr::Closure(_) => self.unsupported(e, "closures"),
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
            Expr::Field(f) => self.body_coordinate(f, e),
            _ => {
                self.cx.error_at(e, "this expression is not part of the model language");
                None
            }
        }
    }

    pub(crate) fn unsupported(&mut self, e: &Expr, what: &str) -> Option<Id> {
        self.cx.error_at(e, format!("{what} are not part of the model language"));
        None
    }

    pub(crate) fn literal(&mut self, lit: &Lit) -> Option<Id> {
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

    pub(crate) fn call(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<Id> {
        let Some((name, _)) = call_name(e) else {
            self.cx.error_at(&c.func, "call a function by name: `sin(x)`");
            return None;
        };
        if DECLARATIONS.contains(&name.as_str()) {
            self.cx.error_at(e, format!("`{name}(...)` declares a variable and must be the value of a `let`: `let x = {name}(...);`"));
            return None;
        }
        if name == "der" {
            return self.der(c, e);
        }
        if matches!(name.as_str(), "init" | "constraint" | "invariant") {
            self.cx.error_at(e, format!("`{name}(...)` is a statement, not a value"));
            return None;
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

    pub(crate) fn der(&mut self, c: &syn::ExprCall, e: &Expr) -> Option<Id> {
        if !self.arity(c, "der", 1) {
            return None;
        }
        let arg = &c.args[0];
        let inner = self.value(arg)?;
        let symbol = self.g.as_symbol(inner).filter(|&s| {
            matches!(self.g.symbol(s).kind, SymbolKind::State | SymbolKind::Derivative { .. })
        });
        match symbol {
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

    pub(crate) fn method_call(&mut self, m: &syn::ExprMethodCall, e: &Expr) -> Option<Id> {
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

fn is_comparison(op: &BinOp) -> bool {
    matches!(
        op,
        BinOp::Eq(_) | BinOp::Ne(_) | BinOp::Lt(_) | BinOp::Le(_) | BinOp::Gt(_) | BinOp::Ge(_)
    )
}

fn is_compound_assignment(op: &BinOp) -> bool {
    matches!(
        op,
        BinOp::AddAssign(_) | BinOp::SubAssign(_) | BinOp::MulAssign(_) | BinOp::DivAssign(_)
    )
}
