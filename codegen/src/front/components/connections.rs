//! Connection sets into equations (Modelica Language Specification
//! §9.2): the connectors joined by `connect`, directly or through
//! others, form a set; in each set the potentials are equal and the
//! flows sum to zero, a flow counted positive into a part through an
//! inside connector (one of a sub-instance) and negative through an
//! outside one (the connecting component's own, seen from within). A
//! connector no connection reaches from outside has zero flow.

use super::{Connection, Connector};
use crate::front::ir::Equation;
use crate::{Graph, Id};
use proc_macro2::TokenStream;

/// The equations of the connections, or the errors found (with the
/// tokens to report them on).
pub fn connection_equations(
    g: &mut Graph,
    connectors: &[Connector],
    connections: &[Connection],
) -> Result<Vec<Equation>, Vec<(TokenStream, String)>> {
    // Node 2c is connector c as its owner's parent connects it (Modelica's
    // inside connector), 2c + 1 as its owner's own body connects it
    // (Modelica's outside connector).
    let node = |c: usize, level: Option<usize>| 2 * c + usize::from(connectors[c].owner == level);
    let mut parent: Vec<usize> = (0..2 * connectors.len()).collect();
    let mut origin_of_set: Vec<Option<&TokenStream>> = vec![None; 2 * connectors.len()];
    let mut reached_from_outside = vec![false; connectors.len()];
    // A signal's source: an output seen from outside, or the connecting
    // component's own input seen from inside. `joins_sources[root]`: the
    // first connection that joined a second source to the set.
    let is_source = |n: usize| {
        let kind = connectors[n / 2].kind;
        kind.is_signal() && ((kind == super::ConnectorKind::RealOutput) != (n % 2 == 1))
    };
    let mut has_source: Vec<bool> = (0..parent.len()).map(is_source).collect();
    let mut joins_sources: Vec<Option<&TokenStream>> = vec![None; parent.len()];
    for connection in connections {
        let first = node(connection.members[0], connection.level);
        for &c in &connection.members {
            let n = node(c, connection.level);
            if n % 2 == 0 {
                reached_from_outside[c] = true;
            }
            let (a, b) = (find(&mut parent, first), find(&mut parent, n));
            if a == b {
                continue;
            }
            if has_source[a] && has_source[b] && joins_sources[a].is_none() {
                joins_sources[a] = joins_sources[b].or(Some(&connection.origin));
            }
            joins_sources[a] = joins_sources[a].or(joins_sources[b]);
            has_source[a] |= has_source[b];
            parent[b] = a;
        }
        origin_of_set[first] = Some(&connection.origin);
    }
    let mut sets: Vec<Vec<usize>> = vec![Vec::new(); parent.len()];
    let mut origins: Vec<Option<&TokenStream>> = vec![None; parent.len()];
    for n in 0..parent.len() {
        let root = find(&mut parent, n);
        if origin_of_set[n].is_some() {
            origins[root] = origins[root].or(origin_of_set[n]);
        }
        sets[root].push(n);
    }
    let mut equations = Vec::new();
    let mut errors = Vec::new();
    for (root, set) in sets.iter().enumerate() {
        let Some(origin) = origins[root] else { continue };
        // (connector, seen in its owner's own body)
        let members: Vec<(usize, bool)> = set.iter().map(|&n| (n / 2, n % 2 == 1)).collect();
        let kind = connectors[members[0].0].kind;
        if kind.is_signal() {
            let sources: Vec<&str> = set
                .iter()
                .filter(|&&n| is_source(n))
                .map(|&n| connectors[n / 2].path.as_str())
                .collect();
            if sources.len() > 1 {
                let list = sources.iter().map(|s| format!("`{s}`")).collect::<Vec<_>>().join(", ");
                let at = joins_sources[root].unwrap_or(origin);
                errors.push((at.clone(), format!("a signal has one source, and these connections join {} of them: {list}; connect each input to one output", sources.len())));
                continue;
            }
        }
        let first = connectors[members[0].0].potential;
        for &(c, _) in &members[1..] {
            let potential = connectors[c].potential;
            if potential != first {
                equations.push(equation(first, potential, origin));
            }
        }
        if kind.is_signal() {
            continue;
        }
        let mut terms = Vec::with_capacity(members.len());
        for &(c, own_body) in &members {
            let Some(flow) = connectors[c].flow else { continue };
            let term = match own_body {
                false => Ok(flow),
                true => g.neg(flow),
            };
            match term {
                Ok(t) => terms.push(t),
                Err(e) => errors.push((origin.clone(), e.to_string())),
            }
        }
        match g.sum(&terms) {
            Ok(sum) => {
                let zero = g.zero();
                equations.push(equation(sum, zero, origin));
            }
            Err(e) => errors.push((origin.clone(), e.to_string())),
        }
    }
    // An unconnected flow is zero: a pin left open carries no current. An
    // unconnected support is the housing instead: its potential is zero.
    for (c, connector) in connectors.iter().enumerate() {
        let (Some(flow), Some(_)) = (connector.flow, connector.owner) else { continue };
        if !reached_from_outside[c] {
            let zero = g.zero();
            let held = if connector.support { connector.potential } else { flow };
            equations.push(equation(held, zero, &connector.origin));
        }
    }
    match errors.is_empty() {
        true => Ok(equations),
        false => Err(errors),
    }
}

fn equation(lhs: Id, rhs: Id, origin: &TokenStream) -> Equation {
    Equation { lhs, rhs, origin: origin.clone(), is_constraint: false, mode: Vec::new() }
}

fn find(parent: &mut [usize], mut n: usize) -> usize {
    while parent[n] != n {
        parent[n] = parent[parent[n]];
        n = parent[n];
    }
    n
}
