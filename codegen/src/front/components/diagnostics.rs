//! Mistakes of a connected model that the structural check would only
//! name as equations and unknowns, said in the model's terms: potentials
//! that nothing anchors (a circuit without a ground, springs that hold
//! nothing, a wall of conductors with no temperature fixed), and ideal
//! voltage sources in parallel.
//!
//! Potentials nothing anchors: when adding one constant to every
//! potential of a connected group leaves every equation unchanged (each
//! reads them only as differences), the equations' Jacobian maps that
//! shift to zero and is singular. The test is exact: the sum of each
//! equation's partial derivatives over the group's potentials is the
//! number zero.

use super::connectors::ConnectorKind;
use super::{Connection, Connector, Instance};
use crate::front::ir::Equation;
use crate::{FxHashMap, Graph, SymbolId};
use proc_macro2::TokenStream;

/// A message and the tokens to report it on.
pub type Diagnostic = (TokenStream, String);

/// Groups of connected connectors of one physical kind whose potentials
/// are free by a constant.
pub fn floating_potentials(
    g: &mut Graph,
    connectors: &[Connector],
    connections: &[Connection],
    instances: &[Instance],
    equations: &[Equation],
) -> crate::Result<Vec<Diagnostic>> {
    let mut parent: Vec<usize> = (0..connectors.len()).collect();
    for connection in connections {
        for &c in &connection.members[1..] {
            union(&mut parent, connection.members[0], c);
        }
    }
    // A part joins its own connectors of one kind: its equations may tie
    // them (a resistor's two pins); the group is then the whole circuit.
    // A support stands apart: it is the reference the others move against
    // (a torque source's housing holds the housing, not the shaft).
    type Key = (Option<usize>, ConnectorKind, bool);
    let mut first_of: FxHashMap<Key, usize> = FxHashMap::default();
    for (c, connector) in connectors.iter().enumerate() {
        let key = (connector.owner, connector.kind, connector.support);
        match first_of.get(&key) {
            Some(&first) => union(&mut parent, first, c),
            None => {
                first_of.insert(key, c);
            }
        }
    }
    let mut group_of: FxHashMap<SymbolId, usize> = FxHashMap::default();
    for (c, connector) in connectors.iter().enumerate() {
        if connector.kind.is_signal() {
            continue;
        }
        if let Some(s) = g.as_symbol(connector.potential) {
            group_of.insert(s, find(&mut parent, c));
        }
    }
    let mut anchored: FxHashMap<usize, bool> = FxHashMap::default();
    for eq in equations {
        let r = g.sub(eq.lhs, eq.rhs)?;
        let mut sums: FxHashMap<usize, Vec<crate::Id>> = FxHashMap::default();
        for s in g.free_symbols(r) {
            if let Some(&group) = group_of.get(&s) {
                let d = g.partial(r, s)?;
                sums.entry(group).or_default().push(d);
            }
        }
        for (group, partials) in sums {
            let sum = g.sum(&partials)?;
            let shifted = !g.as_number(sum).is_some_and(|n| n.is_zero());
            *anchored.entry(group).or_insert(false) |= shifted;
        }
    }
    let mut out = Vec::new();
    let mut reported: Vec<usize> = Vec::new();
    for (c, connector) in connectors.iter().enumerate() {
        let group = find(&mut parent, c);
        if connector.kind.is_signal() || anchored.get(&group) != Some(&false) {
            continue;
        }
        if reported.contains(&group) {
            continue;
        }
        reported.push(group);
        let mut parts: Vec<&str> = Vec::new();
        let mut at: Option<&TokenStream> = None;
        for (d, other) in connectors.iter().enumerate() {
            if find(&mut parent, d) != group {
                continue;
            }
            let Some(owner) = other.owner.map(|k| top_level(instances, k)) else { continue };
            if !parts.contains(&instances[owner].path.as_str()) {
                parts.push(&instances[owner].path);
                at = at.or(Some(&instances[owner].origin));
            }
        }
        let listed = parts.iter().take(4).map(|p| format!("`{p}`")).collect::<Vec<_>>().join(", ");
        let more =
            if parts.len() > 4 { format!(" and {} more", parts.len() - 4) } else { String::new() };
        let message = match connector.kind {
            ConnectorKind::Pin => format!("the node voltages of the circuit of {listed}{more} are fixed only up to a constant: connect a ground, `let gnd = ground(); connect(gnd.p, ..);`"),
            ConnectorKind::Flange => format!("the angles of the flanges of {listed}{more} are fixed only up to a constant: nothing holds them; connect an inertia or a `fixed()`"),
            ConnectorKind::TranslationalFlange => format!("the positions of the flanges of {listed}{more} are fixed only up to a constant: nothing holds them; connect a mass or a `translational_fixed()`"),
            ConnectorKind::HeatPort => format!("the temperatures of the ports of {listed}{more} are fixed only up to a constant: connect a heat capacitor or a `fixed_temperature(..)`"),
            ConnectorKind::RealInput | ConnectorKind::RealOutput => continue,
        };
        out.push((at.unwrap_or(&connector.origin).clone(), message));
    }
    Ok(out)
}

/// Inputs of parts that nothing sets: no connection from outside the part
/// reaches them, and no statement outside it reads them (where one would
/// set them, `controller.u_s == 1.0`); `equations` are the statements',
/// without the connections'. Modelica refuses them too
/// (Modelica Language Specification §9.3: an input connector of a
/// component is connected or bound).
pub fn unconnected_inputs(
    g: &Graph,
    connectors: &[Connector],
    connections: &[Connection],
    instances: &[Instance],
    equations: &[Equation],
) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for (c, connector) in connectors.iter().enumerate() {
        let (ConnectorKind::RealInput, Some(owner)) = (connector.kind, connector.owner) else {
            continue;
        };
        let connected =
            connections.iter().any(|k| k.level != Some(owner) && k.members.contains(&c));
        if connected {
            continue;
        }
        let Some(symbol) = g.as_symbol(connector.potential) else { continue };
        let inside = &instances[owner].equations;
        let set = equations.iter().enumerate().any(|(e, eq)| {
            !inside.contains(&e)
                && (g.free_symbols(eq.lhs).contains(&symbol)
                    || g.free_symbols(eq.rhs).contains(&symbol))
        });
        if set {
            continue;
        }
        let part = &instances[owner].path;
        let input = &connector.path;
        let name = input.strip_prefix(&format!("{part}.")).unwrap_or(input);
        let at = &instances[top_level(instances, owner)].origin;
        out.push((at.clone(), format!("the input `{name}` of `{part}` is not connected: connect an output to it, `connect(source.y, {input});`, or set it, `{input} == 1.0;`")));
    }
    out
}

/// Ideal voltage sources whose pins join the same two nodes.
pub fn sources_in_parallel(
    connectors: &[Connector],
    connections: &[Connection],
    instances: &[Instance],
) -> Vec<Diagnostic> {
    const SOURCES: [&str; 4] =
        ["constant_voltage", "step_voltage", "sine_voltage", "signal_voltage"];
    let mut parent: Vec<usize> = (0..connectors.len()).collect();
    for connection in connections {
        for &c in &connection.members[1..] {
            union(&mut parent, connection.members[0], c);
        }
    }
    let pin = |k: usize, name: &str| {
        let path = format!("{}.{name}", instances[k].path);
        connectors.iter().position(|c| c.path == path)
    };
    let mut nodes: Vec<(usize, usize, usize)> = Vec::new();
    let mut out = Vec::new();
    for (k, instance) in instances.iter().enumerate() {
        if !SOURCES.contains(&instance.part.as_str()) {
            continue;
        }
        let (Some(p), Some(n)) = (pin(k, "p"), pin(k, "n")) else { continue };
        let (p, n) = (find(&mut parent, p), find(&mut parent, n));
        let same = nodes.iter().find(|&&(_, a, b)| (a, b) == (p, n) || (a, b) == (n, p));
        if let Some(&(other, _, _)) = same {
            let message = format!("`{}` and `{}` are ideal voltage sources in parallel: both fix the voltage between the same two nodes, and nothing decides how they share the current; put a resistor in series with one", instance.path, instances[other].path);
            out.push((instance.origin.clone(), message));
        } else {
            nodes.push((k, p, n));
        }
    }
    out
}

/// The ancestor of instance `k` declared at the model's level.
fn top_level(instances: &[Instance], mut k: usize) -> usize {
    while let Some(parent) = instances[k].parent {
        k = parent;
    }
    k
}

fn union(parent: &mut [usize], a: usize, b: usize) {
    let (a, b) = (find(parent, a), find(parent, b));
    parent[b] = a;
}

fn find(parent: &mut [usize], mut n: usize) -> usize {
    while parent[n] != n {
        parent[n] = parent[parent[n]];
        n = parent[n];
    }
    n
}
