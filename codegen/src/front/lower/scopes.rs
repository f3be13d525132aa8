//! The lowering's state and its scopes: what each name stands for, and
//! the struct every concern of the lowering is a method of.

use crate::front::ctxt::Ctxt;
use crate::front::ir::{
    AlgebraicDecl, Equation, Event, Init, Output, Param, StateDecl, UserInvariant,
};

use crate::front::components::definitions::Definitions;
use crate::front::components::{Connection, Connector, Instance};
use crate::front::tensor::Tensor;
use crate::{Graph, Id, SymbolId};
use std::collections::HashMap;

/// What a name stands for.
#[derive(Clone)]
pub(crate) enum Binding {
    Param(Id),
    State(SymbolId),
    StateArray(Vec<SymbolId>),
    /// `let m = [a, b, ...];`: constant-indexed values (masses, lengths).
    ValueArray(Vec<Id>),
    Algebraic(Id),
    /// `let i = algebraic_array([..]);`
    AlgebraicArray(Vec<Id>),
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
    /// `let r1 = resistor(100.0);`: an instance of a component.
    Instance(usize),
    /// `let r = [resistor(1.0); N];`: instances, `r[k]`.
    InstanceArray(Vec<usize>),
    /// `let p = pin();`: a connector.
    Connector(usize),
    /// `let f = |x| ...;`: a function of the model.
    Function(std::rc::Rc<Function>),
    /// `every(h)`: a clock, which acts but has no value.
    Clock,
}

/// A function of the model: its closure and the scopes it captured
/// (`lower::functions` calls it).
pub(crate) struct Function {
    pub(in crate::front) closure: syn::ExprClosure,
    pub(in crate::front) captured: Vec<HashMap<String, Binding>>,
}

impl Binding {
    pub(crate) fn describe(&self) -> &'static str {
        match self {
            Binding::Param(_) => "a parameter",
            Binding::State(_) => "a state",
            Binding::StateArray(_) => "an array of states",
            Binding::ValueArray(_) => "an array of values",
            Binding::Algebraic(_) => "an algebraic variable",
            Binding::AlgebraicArray(_) => "an array of algebraic variables",
            Binding::Time(_) => "the time",
            Binding::Value { .. } => "an intermediate value",
            Binding::Const(_) => "a constant",
            Binding::Tensor(_) => "a vector or matrix value",
            Binding::Body(_) => "a body",
            Binding::Ground => "the ground",
            Binding::BrokenBody => "a body",
            Binding::Broken => "a value",
            Binding::Instance(_) => "an instance of a component",
            Binding::InstanceArray(_) => "an array of instances",
            Binding::Connector(_) => "a connector",
            Binding::Function(_) => "a function",
            Binding::Clock => "a clock",
        }
    }
}

pub(crate) struct Lower<'c, S> {
    pub(crate) cx: &'c mut Ctxt,
    pub(crate) g: Graph,
    pub(in crate::front) scopes: Vec<HashMap<String, Binding>>,
    pub(in crate::front) time: Option<SymbolId>,
    pub(crate) params: Vec<Param>,
    pub(crate) states: Vec<StateDecl>,
    pub(crate) algebraics: Vec<AlgebraicDecl>,
    pub(crate) outputs: Vec<Output>,
    pub(crate) events: Vec<Event>,
    pub(crate) clocks: Vec<crate::front::ir::Clock>,
    pub(crate) inputs: Vec<crate::front::ir::InputDecl>,
    /// States declared `discrete(v0)`.
    pub(crate) discretes: Vec<SymbolId>,
    /// `pre(x)` symbols made so far, with x's.
    pub(crate) pre: Vec<(SymbolId, SymbolId)>,
    /// Lowering an action's value, where `pre(x)` reads the value before
    /// the instant.
    pub(in crate::front) in_action: bool,
    /// How deep `if on { .. }` of modes are nested here.
    pub(in crate::front) mode_depth: usize,
    pub(crate) equations: Vec<Equation>,
    pub(crate) inits: Vec<Init>,
    pub(crate) initial_equations: Vec<crate::front::ir::InitialEquation>,
    pub(crate) fixed_starts: Vec<(crate::SymbolId, proc_macro2::TokenStream)>,
    pub(crate) relations: Vec<crate::front::ir::Relation>,
    /// How deep `no_event(..)` calls are nested here.
    pub(in crate::front) no_event_depth: usize,
    pub(crate) invariants: Vec<UserInvariant>,
    pub(crate) scene: S,
    pub(in crate::front) unrolled: usize,
    pub(in crate::front) non_smooth_calls: Vec<(Id, proc_macro2::TokenStream)>,
    /// Names of whole-number constants: loop indices and integer `const`s
    /// (`front::lower::integers`).
    pub(in crate::front) integer_names: std::collections::HashSet<String>,
    /// The user's parts a call may instantiate at this level, by path.
    pub(in crate::front) parts: std::rc::Rc<Definitions>,
    /// The standard library.
    pub(in crate::front) library: std::rc::Rc<Definitions>,
    /// Parts called that nothing here defines: the user's components the
    /// expansion fetches before lowering again.
    pub(crate) missing_parts: Vec<syn::Path>,
    /// The path of the instance being lowered and a dot (`motor.emf.`);
    /// empty at the model's level.
    pub(crate) prefix: String,
    /// The same for parameter fields (`motor_emf_`).
    pub(in crate::front) field_prefix: String,
    /// The instance being lowered.
    pub(in crate::front) instance: Option<usize>,
    /// The parameters its call set, by name.
    pub(in crate::front) overrides: HashMap<String, Id>,
    /// Every instance, in the order declared (parents first).
    pub(crate) instances: Vec<Instance>,
    /// Every connector.
    pub(crate) connectors: Vec<Connector>,
    /// Every `connect`.
    pub(crate) connections: Vec<Connection>,
    /// How deep calls of the model's functions are nested.
    pub(in crate::front) function_depth: usize,
    /// The time was declared by a component's `time()`, not the model's.
    pub(in crate::front) time_implicit: bool,
    /// Connectors made on first use (a ground's pin, a joint's flange), by path.
    pub(in crate::front) lazy_connectors: HashMap<String, usize>,
}

impl<S> Lower<'_, S> {
    pub(crate) fn lookup(&self, name: &str) -> Option<&Binding> {
        self.scopes.iter().rev().find_map(|s| s.get(name))
    }

    pub(in crate::front) fn known_names(&self) -> Vec<String> {
        self.scopes.iter().flat_map(|s| s.keys().cloned()).collect()
    }

    pub(in crate::front) fn in_loop(&self) -> bool {
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
}
