//! Lowering: the function body, read as the model language, into a
//! [`ModelIr`]. Names are resolved, `const`s evaluated, `for` loops and
//! constant `if`s unrolled; every mistake is recorded with the user's tokens
//! and lowering goes on, so all mistakes are reported together.
//!
//! One file per concern: the state and its scopes (`scopes`),
//! statements, declarations, constants and unrolling, expressions, Rust's
//! integer semantics (`integers`), and the shapes of syntax they ask about
//! (`syntax`).

mod constants;
mod declarations;
mod expressions;
mod functions;
mod hybrid;
mod instances;
pub(crate) mod integers;
mod modes;
mod relations;
mod scene;
mod scopes;
mod statements;
mod syntax;

pub(crate) use scene::SceneLanguage;
pub(crate) use scopes::{Binding, Lower};
pub(crate) use syntax::doc_comment;

use crate::front::components::definitions::Definitions;
use crate::front::ctxt::Ctxt;
use crate::front::ir::{InstanceSummary, ModelIr};

use crate::{Graph, SymbolId};
use std::collections::HashMap;

/// Lowers `item`; a scene uses joint coordinates when `recursive`
/// (`#[dae_model(scene = recursive)]`), body coordinates otherwise.
/// Errors go to `cx`; the IR is returned even then (with the parts that
/// could be read) so that a stub can be emitted.
pub(crate) fn lower_with<S: SceneLanguage>(
    cx: &mut Ctxt,
    item: &syn::ItemFn,
    recursive: bool,
    parts: Definitions,
) -> ModelIr {
    let mut l = new_lower::<S>(cx, recursive, parts);
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
    let written = l.equations.len();
    l.connection_equations();
    l.connection_diagnostics(written);
    S::equations(&mut l, item);
    // A circuit of parts may have none (sources and resistors): Modelica
    // runs it, its variables algebraic functions of the time.
    if l.states.is_empty() && l.instances.is_empty() && l.cx.is_ok() {
        l.cx.error_at(&item.sig.ident, "the model declares no state: add one with `let x = state(0.0);` and an equation `der(x) == ...;`");
    }
    let mut doc = doc_comment(&item.attrs);
    if !l.scene.summary().is_empty() {
        doc = if doc.is_empty() {
            l.scene.summary().to_string()
        } else {
            format!("{doc}\n\n{}", l.scene.summary())
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
        clocks: l.clocks,
        inputs: l.inputs,
        discretes: l.discretes,
        pre: l.pre,
        equations: l.equations,
        inits: l.inits,
        initial_equations: l.initial_equations,
        fixed_starts: l.fixed_starts,
        relations: l.relations,
        invariants: l.invariants,
        non_smooth_calls: l.non_smooth_calls,
        instances: l
            .instances
            .iter()
            .map(|i| InstanceSummary { path: i.path.clone(), part: i.part.clone() })
            .collect(),
        missing_parts: l.missing_parts,
        depends_on: l.scene.files(),
        body_coordinates: recursive_or_not(recursive, l.scene.has_spatial_bodies()),
    }
}

/// Whether a scene in space keeps its bodies' coordinates (the global
/// formulation).
fn recursive_or_not(recursive: bool, spatial: bool) -> bool {
    spatial && !recursive
}

/// An empty lowering, the user's `parts` callable.
fn new_lower<S: SceneLanguage>(cx: &mut Ctxt, recursive: bool, parts: Definitions) -> Lower<'_, S> {
    Lower::<S> {
        cx,
        g: Graph::new(),
        scopes: vec![HashMap::new()],
        time: None,
        params: Vec::new(),
        states: Vec::new(),
        algebraics: Vec::new(),
        outputs: Vec::new(),
        events: Vec::new(),
        clocks: Vec::new(),
        inputs: Vec::new(),
        discretes: Vec::new(),
        pre: Vec::new(),
        in_action: false,
        mode_depth: 0,
        equations: Vec::new(),
        inits: Vec::new(),
        initial_equations: Vec::new(),
        fixed_starts: Vec::new(),
        relations: Vec::new(),
        no_event_depth: 0,
        invariants: Vec::new(),
        scene: S::new(recursive),
        unrolled: 0,
        non_smooth_calls: Vec::new(),
        integer_names: Default::default(),
        parts: std::rc::Rc::new(parts),
        library: std::rc::Rc::new(Definitions::standard_library()),
        missing_parts: Vec::new(),
        prefix: String::new(),
        field_prefix: String::new(),
        instance: None,
        overrides: HashMap::new(),
        instances: Vec::new(),
        connectors: Vec::new(),
        connections: Vec::new(),
        lazy_connectors: HashMap::new(),
        time_implicit: false,
        function_depth: 0,
    }
}

/// Lowers one instance of the component `definition` (its `parts`
/// callable) with its defaults and reports what is wrong in it, with the
/// user's tokens; `#[component]` checks a body so. The parts its body
/// calls that no definition provides are returned (the user's
/// components, to fetch first).
pub(crate) fn check_component<S: SceneLanguage>(
    cx: &mut Ctxt,
    definition: std::rc::Rc<crate::front::components::definitions::Definition>,
) -> Vec<syn::Path> {
    let mut l = new_lower::<S>(cx, false, Definitions::default());
    l.parts = definition.parts.clone();
    l.check_part(&definition);
    l.missing_parts
}
