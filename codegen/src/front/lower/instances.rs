//! Instances of components: `let r1 = resistor(100.0);` lowered into the
//! model under the path `r1`, arrays of them, connectors declared in a
//! component's body, members read by path (`r1.p.v`, `cells[2].t`), and
//! `connect(a, b, ...)`.

use super::scene::SceneLanguage;
use super::scopes::{Binding, Lower};
use crate::front::components::connectors::ConnectorKind;
use crate::front::components::definitions::{path_text, Definition};
use crate::front::components::{Connection, Connector, Instance};
use crate::front::names::did_you_mean;
use crate::Id;
use quote::ToTokens;
use std::collections::HashMap;
use std::rc::Rc;
use syn::Expr;

/// What a path such as `r1.p.v` names.
pub(in crate::front) enum Member {
    /// It does not start at an instance or a connector: the caller reads
    /// it its own way (a body's coordinate, a plain name).
    Elsewhere,
    /// What it names.
    Found(Binding),
    /// A mistake, reported.
    Reported,
}

/// The saved state of the level an instance's body is lowered from.
struct Level {
    scopes: Vec<HashMap<String, Binding>>,
    prefix: String,
    field_prefix: String,
    instance: Option<usize>,
    overrides: HashMap<String, Id>,
    parts: Rc<crate::front::components::definitions::Definitions>,
    integer_names: std::collections::HashSet<String>,
}

impl<S: SceneLanguage> Lower<'_, S> {
    /// The part a call of `path` instantiates: the user's parts known
    /// here, then the standard library. A path no one defines is
    /// recorded as missing (a user's component the expansion fetches),
    /// and `None` returned.
    pub(in crate::front) fn part(&mut self, e: &Expr) -> Option<Option<Rc<Definition>>> {
        let Expr::Call(c) = e else { return None };
        let Expr::Path(f) = &*c.func else { return None };
        let path = path_text(&f.path);
        if let Some(d) = self.parts.get(&path) {
            return Some(Some(d));
        }
        let single = f.path.get_ident().map(|i| i.to_string());
        // `ground()` declares the scene's frame, whose pin `p` is the
        // library's electrical ground when a circuit uses it.
        if single.as_deref().and_then(super::declarations::Declaration::from_name).is_some() {
            return None;
        }
        // `fixed` and `spring` are also a scene's joint and load, with
        // bodies and points for arguments: four or more.
        let scene_call = single.as_deref().is_some_and(|n| S::is_joint(n) || S::is_load(n));
        if scene_call && c.args.len() >= 4 {
            return None;
        }
        if let Some(d) = single.as_deref().and_then(|n| self.library.get(n)) {
            return Some(Some(d));
        }
        let known_function = single
            .as_deref()
            .is_some_and(|n| self.is_known_function(n) || self.lookup(n).is_some());
        if known_function {
            return None;
        }
        // A misspelt function is a mistake here, not a component to fetch
        // from elsewhere. A name like a library part's may be the user's
        // own part (`conductor` beside `inductor`): it is fetched, and
        // where no part of that name exists the compiler says so.
        if let Some(name) = single.as_deref() {
            if did_you_mean(name, super::syntax::FUNCTIONS.into_iter()).is_some() {
                return None;
            }
        }
        if !self.missing_parts.iter().any(|p| path_text(p) == path) {
            self.missing_parts.push(f.path.clone());
        }
        Some(None)
    }

    /// `let r1 = part(args);`, `let r = [part(args); N];` or
    /// `let r = (0..N).map(|k| part(args));`: `true` when `e` is one of
    /// these (handled, or reported).
    pub(in crate::front) fn instance_statement(&mut self, ident: &syn::Ident, e: &Expr) -> bool {
        if let Some(definition) = self.part(e) {
            if self.in_loop() {
                self.cx.error_at(e, format!("declare parts outside loops: each iteration would declare `{ident}` again; an array of parts is `let {ident} = [part(..); N];` or `(0..N).map(|k| part(..))`"));
                return true;
            }
            if self.already_declared(ident) {
                return true;
            }
            let name = ident.to_string();
            match definition.and_then(|d| self.instance(&name, &d, e)) {
                Some(k) => self.bind(ident, Binding::Instance(k)),
                None => self.bind(ident, Binding::Broken),
            }
            return true;
        }
        let Some(array) = self.instance_array(e) else { return false };
        if self.already_declared(ident) {
            return true;
        }
        let Some((count, element)) = array else {
            self.bind(ident, Binding::Broken);
            return true;
        };
        let mut members = Vec::with_capacity(count);
        for k in 0..count {
            let (call, index) = element(k);
            let Some(Some(definition)) = self.part(call) else { return true };
            self.scopes.push(index.into_iter().collect());
            let instance = self.instance(&format!("{ident}[{k}]"), &definition, call);
            self.scopes.pop();
            match instance {
                Some(i) => members.push(i),
                None => {
                    self.bind(ident, Binding::Broken);
                    return true;
                }
            }
        }
        self.bind(ident, Binding::InstanceArray(members));
        true
    }

    /// `[part(..); N]` or `(0..N).map(|k| part(..))`: the count, and for
    /// each element its call and the loop variable's binding; `Some(None)`
    /// once a mistake in it is reported, `None` for another shape.
    #[allow(clippy::type_complexity)]
    fn instance_array<'e>(
        &mut self,
        e: &'e Expr,
    ) -> Option<Option<(usize, Box<dyn Fn(usize) -> (&'e Expr, Option<(String, Binding)>) + 'e>)>>
    {
        match e {
            Expr::Repeat(r) if self.part_call(&r.expr) => {
                let Some(n) = self.index_constant(&r.len) else { return Some(None) };
                Some(Some((n, Box::new(move |_| (&*r.expr, None)))))
            }
            Expr::MethodCall(m) if m.method == "map" && m.args.len() == 1 => {
                let Expr::Closure(closure) = &m.args[0] else { return None };
                if !self.part_call(&closure.body) {
                    return None;
                }
                let mut receiver = &*m.receiver;
                while let Expr::Paren(p) = receiver {
                    receiver = &p.expr;
                }
                let how =
                    "write an array of instances as `(0..N).map(|k| part(..))` or `[part(..); N]`";
                let (Expr::Range(range), [syn::Pat::Ident(var)]) =
                    (receiver, closure.inputs.iter().collect::<Vec<_>>().as_slice())
                else {
                    self.cx.error_at(e, how);
                    return Some(None);
                };
                let (Some(start), Some(end)) = (&range.start, &range.end) else {
                    self.cx.error_at(e, how);
                    return Some(None);
                };
                let (Some(start), Some(end)) =
                    (self.index_constant(start), self.index_constant(end))
                else {
                    return Some(None);
                };
                let end = match range.limits {
                    syn::RangeLimits::HalfOpen(_) => end,
                    syn::RangeLimits::Closed(_) => end + 1,
                };
                self.integer_names.insert(var.ident.to_string());
                let indices: Vec<Id> =
                    (start..end.max(start)).map(|i| self.g.int(i as i64)).collect();
                let name = var.ident.to_string();
                let body = &*closure.body;
                Some(Some((
                    indices.len(),
                    Box::new(move |k| (body, Some((name.clone(), Binding::Const(indices[k]))))),
                )))
            }
            _ => None,
        }
    }

    /// Whether `e` calls a part (without recording anything).
    fn part_call(&self, e: &Expr) -> bool {
        let Expr::Call(c) = e else { return false };
        let Expr::Path(f) = &*c.func else { return false };
        let path = path_text(&f.path);
        if self.parts.get(&path).is_some() {
            return true;
        }
        match f.path.get_ident().map(|i| i.to_string()) {
            Some(n) if self.library.get(&n).is_some() => {
                !((S::is_joint(&n) || S::is_load(&n)) && c.args.len() >= 4)
            }
            Some(n) => !self.is_known_function(&n) && self.lookup(&n).is_none(),
            None => true,
        }
    }

    /// Functions and declarations of the language, which no part shadows.
    fn is_known_function(&self, name: &str) -> bool {
        super::syntax::FUNCTIONS.contains(&name)
            || crate::Func::ALL.iter().any(|f| f.name() == name)
            || super::declarations::Declaration::from_name(name).is_some()
            || ConnectorKind::from_name(name).is_some()
            || S::is_joint(name)
            || S::is_load(name)
            || crate::front::tensor::TENSOR_FUNCTIONS.contains(&name)
            || matches!(
                name,
                "connect" | "heaviside" | "position" | "orientation" | "natural_frame"
            )
    }

    /// Lowers one instance of `definition` called by `call` under the
    /// name `name` (`r1`, `cells[2]`); its index.
    fn instance(&mut self, name: &str, definition: &Rc<Definition>, call: &Expr) -> Option<usize> {
        let Expr::Call(c) = call else { return None };
        let overrides = self.arguments(definition, c)?;
        let span = c.func.to_token_stream().into_iter().next().map(|t| t.span());
        let item = definition.item_at(span.unwrap_or_else(proc_macro2::Span::call_site));
        let k = self.instances.len();
        let field = name.replace(['[', ']'], "_").trim_end_matches('_').to_string();
        let part = path_text(match &*c.func {
            Expr::Path(p) => &p.path,
            _ => return None,
        });
        self.instances.push(Instance {
            path: format!("{}{name}", self.prefix),
            part,
            parent: self.instance,
            members: Vec::new(),
            origin: call.to_token_stream(),
            equations: self.equations.len()..self.equations.len(),
        });
        let (prefix, field_prefix) =
            (format!("{}{name}.", self.prefix), format!("{}{field}_", self.field_prefix));
        let saved = Level {
            scopes: std::mem::replace(&mut self.scopes, vec![HashMap::new()]),
            prefix: std::mem::replace(&mut self.prefix, prefix),
            field_prefix: std::mem::replace(&mut self.field_prefix, field_prefix),
            instance: self.instance.replace(k),
            overrides: std::mem::replace(&mut self.overrides, overrides),
            parts: std::mem::replace(&mut self.parts, definition.parts.clone()),
            integer_names: std::mem::take(&mut self.integer_names),
        };
        // A part written with Rust arguments is refused where it is
        // defined; its body's uses of them stay quiet.
        for input in &item.sig.inputs {
            if let syn::FnArg::Typed(t) = input {
                if let syn::Pat::Ident(p) = &*t.pat {
                    self.rebind(&p.ident, Binding::Broken);
                }
            }
        }
        for stmt in &item.block.stmts {
            self.stmt(stmt);
        }
        let members = self.scopes.drain(..).flat_map(|s| s.into_iter()).collect();
        self.scopes = saved.scopes;
        self.prefix = saved.prefix;
        self.field_prefix = saved.field_prefix;
        self.instance = saved.instance;
        self.overrides = saved.overrides;
        self.parts = saved.parts;
        self.integer_names = saved.integer_names;
        self.instances[k].members = members;
        self.instances[k].equations.end = self.equations.len();
        Some(k)
    }

    /// The parameters a call sets, positionally (`resistor(100.0)`) or by
    /// name (`resistor(r = 100.0)`), each lowered here.
    fn arguments(
        &mut self,
        definition: &Definition,
        c: &syn::ExprCall,
    ) -> Option<HashMap<String, Id>> {
        let params = definition.params();
        let part = c.func.to_token_stream().to_string().replace(' ', "");
        let listed = || match params.is_empty() {
            true => format!("`{part}` has no parameters"),
            false => format!(
                "its parameters are {}",
                params.iter().map(|p| format!("`{p}`")).collect::<Vec<_>>().join(", ")
            ),
        };
        let mut out = HashMap::new();
        let mut ok = true;
        let mut named = false;
        for (k, arg) in c.args.iter().enumerate() {
            let (name, value) = match arg {
                Expr::Assign(a) => {
                    named = true;
                    let name = match &*a.left {
                        Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                        _ => None,
                    };
                    let Some(name) = name else {
                        self.cx.error_at(&a.left, "name a parameter: `resistor(r = 100.0)`");
                        ok = false;
                        continue;
                    };
                    if !params.contains(&name) {
                        let hint = match did_you_mean(&name, params.iter().map(String::as_str)) {
                            Some(s) => format!("did you mean `{s}`?"),
                            None => listed(),
                        };
                        self.cx.error_at(
                            &a.left,
                            format!("`{part}` has no parameter `{name}`; {hint}"),
                        );
                        ok = false;
                        continue;
                    }
                    (name, &*a.right)
                }
                positional => {
                    if named {
                        self.cx.error_at(positional, "positional arguments come before named ones");
                        ok = false;
                        continue;
                    }
                    let Some(name) = params.get(k) else {
                        let n = c.args.len();
                        self.cx.error_at(
                            positional,
                            format!(
                                "`{part}` takes at most {} arguments, not {n}: {}",
                                params.len(),
                                listed()
                            ),
                        );
                        ok = false;
                        break;
                    };
                    (name.clone(), positional)
                }
            };
            if out.contains_key(&name) {
                self.cx.error_at(arg, format!("`{name}` is given twice"));
                ok = false;
                continue;
            }
            match self.value(value) {
                Some(v) => {
                    out.insert(name, v);
                }
                None => ok = false,
            }
        }
        ok.then_some(out)
    }

    /// `let p = pin();` (or another connector) in a component's body.
    pub(in crate::front) fn connector(
        &mut self,
        ident: &syn::Ident,
        kind: ConnectorKind,
        call: &syn::ExprCall,
        local: &syn::Local,
        (doc, support): (String, bool),
    ) {
        if self.already_declared(ident) || !self.arity(call, kind.name(), 0) {
            return;
        }
        if self.in_loop() {
            return self.cx.error_at(local, format!("declare `{}()` outside loops", kind.name()));
        }
        let path = format!("{}{ident}", self.prefix);
        let origin = local.to_token_stream();
        let zero = self.g.zero();
        let declare = |this: &mut Self, name: String, doc: String| {
            this.declare_algebraic(name, zero, ident, &origin, doc)
        };
        let potential = match kind.potential() {
            Some(v) => declare(self, format!("{path}.{v}"), doc.clone()),
            None => declare(self, path.clone(), doc.clone()),
        };
        let flow = match kind.flow() {
            Some(f) => match declare(self, format!("{path}.{f}"), doc) {
                Some(id) => Some(id),
                None => return,
            },
            None => None,
        };
        let Some(potential) = potential else { return };
        self.connectors.push(Connector {
            path,
            kind,
            potential,
            flow,
            owner: self.instance,
            support,
            origin: local.to_token_stream(),
        });
        self.bind(ident, Binding::Connector(self.connectors.len() - 1));
    }

    /// `connect(a, b, ...)`.
    pub(in crate::front) fn connect(&mut self, call: &syn::ExprCall, e: &Expr) {
        if call.args.len() < 2 {
            return self
                .cx
                .error_at(e, "`connect` joins two or more connectors: `connect(r1.n, c1.p)`");
        }
        let mut members = Vec::with_capacity(call.args.len());
        for arg in &call.args {
            match self.member(arg) {
                Member::Found(Binding::Connector(c)) => members.push(c),
                Member::Reported => return,
                Member::Found(Binding::Broken | Binding::BrokenBody) => return,
                Member::Found(other) => {
                    let what = other.describe();
                    let text = crate::front::names::source_text(&arg.to_token_stream());
                    return self.cx.error_at(arg, format!("`connect` joins connectors, and `{text}` is {what}: connect a pin, a flange, a heat port or a signal (`r1.p`)"));
                }
                Member::Elsewhere => {
                    let text = crate::front::names::source_text(&arg.to_token_stream());
                    match self.lookup(&text).cloned() {
                        None if !text.contains('.') => self.unknown_name(arg, &text),
                        _ => self.cx.error_at(arg, format!("`connect` joins connectors, and `{text}` is not one: connect a pin, a flange, a heat port or a signal (`r1.p`)")),
                    }
                    return;
                }
            }
        }
        let first = members[0];
        for (arg, &c) in call.args.iter().zip(&members).skip(1) {
            let (a, b) = (&self.connectors[first], &self.connectors[c]);
            if !a.kind.connects_to(b.kind) {
                let message = format!(
                    "cannot connect `{}`, {}, to `{}`, {}: connect connectors of one kind",
                    a.path,
                    a.kind.describe(),
                    b.path,
                    b.kind.describe()
                );
                return self.cx.error_at(arg, message);
            }
        }
        let level = self.instance;
        self.connections.push(Connection { level, members, origin: e.to_token_stream() });
    }

    /// What `e` names when it is a path into an instance or a connector:
    /// `r1`, `r1.v`, `r1.p`, `r1.p.v`, `cells[2].port.t`, `gnd.p`.
    pub(in crate::front) fn member(&mut self, e: &Expr) -> Member {
        match e {
            Expr::Paren(p) => self.member(&p.expr),
            Expr::Path(p) => {
                let Some(ident) = p.path.get_ident() else { return Member::Elsewhere };
                match self.lookup(&ident.to_string()) {
                    Some(
                        b @ (Binding::Instance(_)
                        | Binding::InstanceArray(_)
                        | Binding::Connector(_)
                        | Binding::Broken),
                    ) => Member::Found(b.clone()),
                    _ => Member::Elsewhere,
                }
            }
            Expr::Index(ix) => match self.member(&ix.expr) {
                Member::Found(Binding::InstanceArray(elements)) => {
                    let Some(i) = self.index_constant(&ix.index) else { return Member::Reported };
                    match elements.get(i) {
                        Some(&k) => Member::Found(Binding::Instance(k)),
                        None => {
                            let n = elements.len();
                            self.cx.error_at(
                                &ix.index,
                                format!("index {i} is out of bounds: the array has {n} instances"),
                            );
                            Member::Reported
                        }
                    }
                }
                other => other,
            },
            Expr::Field(f) => {
                let name = match &f.member {
                    syn::Member::Named(i) => i.to_string(),
                    syn::Member::Unnamed(i) => i.index.to_string(),
                };
                let base = match (&*f.base, self.member(&f.base)) {
                    (Expr::Path(p), Member::Elsewhere) => {
                        // A ground's pin: the electrical ground of the
                        // standard library, created when first used.
                        let ground = p.path.get_ident().map(|i| i.to_string());
                        match ground.as_deref().map(|g| (g, self.lookup(g).cloned())) {
                            Some((g, Some(Binding::Ground))) if name == "p" => {
                                return self.ground_pin(g, e);
                            }
                            Some((j, Some(Binding::Tensor(_))))
                                if name == "flange" && S::joint_axis(self, j).is_some() =>
                            {
                                return self.joint_flange_connector(j, e);
                            }
                            _ => return Member::Elsewhere,
                        }
                    }
                    (_, found) => found,
                };
                match base {
                    Member::Found(Binding::Instance(k)) => {
                        let found = self.instances[k].members.iter().find(|(n, _)| *n == name);
                        match found {
                            Some((_, b)) => Member::Found(b.clone()),
                            None => {
                                let instance = &self.instances[k];
                                let known = instance.members.iter().map(|(n, _)| n.as_str());
                                let hint = match did_you_mean(&name, known) {
                                    Some(s) => format!("; did you mean `{s}`?"),
                                    None => String::new(),
                                };
                                let message = format!(
                                    "`{}`, an instance of `{}`, has no `{name}`{hint}",
                                    instance.path, instance.part
                                );
                                self.cx.error_at(&f.member, message);
                                Member::Reported
                            }
                        }
                    }
                    Member::Found(Binding::Connector(c)) => {
                        let connector = &self.connectors[c];
                        let kind = connector.kind;
                        if kind.potential() == Some(name.as_str()) {
                            return Member::Found(Binding::Algebraic(connector.potential));
                        }
                        if let (Some(f), Some(id)) = (kind.flow(), connector.flow) {
                            if f == name {
                                return Member::Found(Binding::Algebraic(id));
                            }
                        }
                        let message = match (kind.potential(), kind.flow()) {
                            (Some(p), Some(f)) => format!(
                                "`{}` is {} with `{p}` and `{f}`, not `{name}`",
                                connector.path,
                                kind.describe()
                            ),
                            _ => format!(
                                "`{}` is {}: use it as a value, without `.{name}`",
                                connector.path,
                                kind.describe()
                            ),
                        };
                        self.cx.error_at(&f.member, message);
                        Member::Reported
                    }
                    Member::Found(Binding::InstanceArray(_)) => {
                        let text = crate::front::names::source_text(&f.base.to_token_stream());
                        self.cx.error_at(
                            e,
                            format!(
                                "`{text}` is an array of instances: index it, `{text}[0].{name}`"
                            ),
                        );
                        Member::Reported
                    }
                    Member::Found(Binding::Broken) => Member::Found(Binding::Broken),
                    Member::Found(_) | Member::Elsewhere => Member::Elsewhere,
                    Member::Reported => Member::Reported,
                }
            }
            _ => Member::Elsewhere,
        }
    }

    /// Whether `e` is a path that starts at an instance, a connector or a
    /// ground's pin (nothing reported).
    pub(in crate::front) fn is_member_path(&self, e: &Expr) -> bool {
        let mut root = e;
        let mut first_field = None;
        loop {
            match root {
                Expr::Field(f) => {
                    first_field = Some(&f.member);
                    root = &f.base;
                }
                Expr::Index(ix) => root = &ix.expr,
                Expr::Paren(p) => root = &p.expr,
                _ => break,
            }
        }
        let Expr::Path(p) = root else { return false };
        let Some(ident) = p.path.get_ident() else { return false };
        match self.lookup(&ident.to_string()) {
            Some(
                Binding::Instance(_)
                | Binding::InstanceArray(_)
                | Binding::Connector(_)
                | Binding::Broken,
            ) => true,
            Some(Binding::Ground) => {
                matches!(first_field, Some(syn::Member::Named(m)) if m == "p")
            }
            Some(Binding::Tensor(_)) => {
                matches!(first_field, Some(syn::Member::Named(m)) if m == "flange")
                    && S::joint_axis(self, &ident.to_string()).is_some()
            }
            _ => false,
        }
    }

    /// The flange of the named joint `name`, made on first use: a
    /// connector of its own pseudo-instance whose potential is the joint's
    /// relative coordinate and whose flow acts across the joint.
    fn joint_flange_connector(&mut self, name: &str, at: &Expr) -> Member {
        let key = format!("{}{name}.flange", self.prefix);
        if let Some(&c) = self.lazy_connectors.get(&key) {
            return Member::Found(Binding::Connector(c));
        }
        let kind = match S::joint_axis(self, name) {
            Some("revolute") => ConnectorKind::Flange,
            _ => ConnectorKind::TranslationalFlange,
        };
        let (Some(p), Some(f)) = (kind.potential(), kind.flow()) else { return Member::Reported };
        let origin = at.to_token_stream();
        let zero = self.g.zero();
        let k = self.instances.len();
        self.instances.push(Instance {
            path: format!("{}{name}", self.prefix),
            part: S::joint_axis(self, name).unwrap_or("revolute").to_string(),
            parent: self.instance,
            members: Vec::new(),
            origin: origin.clone(),
            equations: self.equations.len()..self.equations.len(),
        });
        let doc = |what: &str| format!("{what} of the joint's flange");
        let potential =
            self.declare_algebraic(format!("{key}.{p}"), zero, at, &origin, doc("the coordinate"));
        let flow = self.declare_algebraic(format!("{key}.{f}"), zero, at, &origin, doc("the load"));
        let (Some(potential), Some(flow)) = (potential, flow) else { return Member::Reported };
        let Some(coordinate) = S::joint_flange(self, name, flow, at) else {
            return Member::Reported;
        };
        self.equations.push(crate::front::ir::Equation {
            lhs: potential,
            rhs: coordinate,
            origin: origin.clone(),
            is_constraint: false,
            mode: Vec::new(),
        });
        self.connectors.push(Connector {
            path: key.clone(),
            kind,
            potential,
            flow: Some(flow),
            owner: Some(k),
            support: false,
            origin,
        });
        let c = self.connectors.len() - 1;
        self.instances[k].members.push(("flange".to_string(), Binding::Connector(c)));
        self.lazy_connectors.insert(key, c);
        Member::Found(Binding::Connector(c))
    }

    /// The pin `p` of the ground `name` declared at this level, an
    /// instance of the library's electrical ground made on first use.
    fn ground_pin(&mut self, name: &str, at: &Expr) -> Member {
        let key = format!("{}{name}", self.prefix);
        if let Some(&c) = self.lazy_connectors.get(&key) {
            return Member::Found(Binding::Connector(c));
        }
        let Some(definition) = self.library.get("ground") else { return Member::Reported };
        let span = at
            .to_token_stream()
            .into_iter()
            .next()
            .map_or_else(proc_macro2::Span::call_site, |t| t.span());
        let call: Expr = syn::parse_quote_spanned!(span=> ground());
        let Some(k) = self.instance(name, &definition, &call) else {
            return Member::Reported;
        };
        let pin = self.instances[k].members.iter().find_map(|(n, b)| match (n.as_str(), b) {
            ("p", Binding::Connector(c)) => Some(*c),
            _ => None,
        });
        match pin {
            Some(c) => {
                self.lazy_connectors.insert(key, c);
                Member::Found(Binding::Connector(c))
            }
            None => Member::Reported,
        }
    }

    /// The value a member names, for an expression.
    pub(in crate::front) fn member_value(&mut self, binding: Binding, e: &Expr) -> Option<Id> {
        let text = || crate::front::names::source_text(&e.to_token_stream());
        match binding {
            Binding::Param(id)
            | Binding::Algebraic(id)
            | Binding::Time(id)
            | Binding::Const(id)
            | Binding::Value { id, .. } => Some(id),
            Binding::State(s) => Some(self.g.symbol_node(s)),
            Binding::Connector(c) => {
                let connector = &self.connectors[c];
                match connector.kind.is_signal() {
                    true => Some(connector.potential),
                    false => {
                        let (kind, p, f) =
                            (connector.kind, connector.kind.potential(), connector.kind.flow());
                        let message = format!(
                            "`{}` is {}: use `{}.{}` or `{}.{}`",
                            text(),
                            kind.describe(),
                            text(),
                            p.unwrap_or(""),
                            text(),
                            f.unwrap_or("")
                        );
                        self.cx.error_at(e, message);
                        None
                    }
                }
            }
            Binding::Instance(k) => {
                let instance = &self.instances[k];
                let message = format!(
                    "`{}` is an instance of `{}`: use one of its variables, `{}.{}`",
                    text(),
                    instance.part,
                    text(),
                    instance.members.first().map_or("v", |(n, _)| n.as_str())
                );
                self.cx.error_at(e, message);
                None
            }
            Binding::Broken | Binding::BrokenBody => None,
            other => {
                let what = other.describe();
                self.cx.error_at(e, format!("`{}` is {what}, not a value", text()));
                None
            }
        }
    }

    /// The equations of every connection, after the last statement.
    pub(in crate::front) fn connection_equations(&mut self) {
        let found = crate::front::components::connections::connection_equations(
            &mut self.g,
            &self.connectors,
            &self.connections,
        );
        match found {
            Ok(equations) => self.equations.extend(equations),
            Err(errors) => {
                for (at, message) in errors {
                    self.cx.error_at(at, message);
                }
            }
        }
    }

    /// The mistakes of a connected model said in its terms (see
    /// `components::diagnostics`); a component alone is not checked so,
    /// as its pins are meant to be connected. The first `written`
    /// equations are the statements', the rest the connections'.
    pub(in crate::front) fn connection_diagnostics(&mut self, written: usize) {
        if !self.cx.is_ok() || self.connectors.is_empty() {
            return;
        }
        use crate::front::components::diagnostics;
        let mut found =
            diagnostics::sources_in_parallel(&self.connectors, &self.connections, &self.instances);
        found.extend(diagnostics::unconnected_inputs(
            &self.g,
            &self.connectors,
            &self.connections,
            &self.instances,
            &self.equations[..written],
        ));
        match diagnostics::floating_potentials(
            &mut self.g,
            &self.connectors,
            &self.connections,
            &self.instances,
            &self.equations,
        ) {
            Ok(floating) => found.extend(floating),
            Err(e) => found.push((proc_macro2::TokenStream::new(), e.to_string())),
        }
        for (at, message) in found {
            self.cx.error_at(at, message);
        }
    }

    /// Lowers one instance of `definition` with its defaults, named as
    /// the component: the check `#[component]` makes of its body.
    pub(in crate::front) fn check_part(&mut self, definition: &Rc<Definition>) {
        let ident = &definition.item.sig.ident;
        let call: Expr = syn::parse_quote_spanned!(ident.span()=> #ident());
        if let Some(k) = self.instance(&ident.to_string(), definition, &call) {
            self.bind(ident, Binding::Instance(k));
        }
        self.connection_equations();
    }
}
