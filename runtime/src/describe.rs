//! How a model describes itself to people: [`crate::Model::describe`] and
//! the `Display` of [`ModelInfo`], which list every name with its doc
//! comment.

use crate::info::{BlockSolution, EventDirection, ModelInfo, StructureInfo};
use std::fmt::Write;

/// The description of a model: with `parameter` (a parameter's value by
/// index), the parameters' values too.
pub(crate) fn describe(info: &ModelInfo, parameter: Option<&dyn Fn(usize) -> f64>) -> String {
    let mut out = String::new();
    // The whole doc comment: its first line beside the name, the rest
    // under it, paragraphs kept.
    let lines: Vec<&str> = info.doc.lines().map(str::trim_end).collect();
    let first = lines.iter().position(|l| !l.is_empty());
    let last = lines.iter().rposition(|l| !l.is_empty());
    match (first, last) {
        (Some(first), Some(last)) => {
            let indent = lines[first..=last]
                .iter()
                .filter(|l| !l.is_empty())
                .map(|l| l.len() - l.trim_start().len())
                .min()
                .unwrap_or(0);
            let _ = writeln!(out, "{}: {}", info.name, &lines[first][indent..]);
            for line in &lines[first + 1..=last] {
                let _ = writeln!(out, "  {}", line.get(indent..).unwrap_or(""));
            }
        }
        _ => {
            let _ = writeln!(out, "{}", info.name);
        }
    }
    components(&mut out, info.components);
    let parameters: Vec<String> = info
        .parameters
        .iter()
        .enumerate()
        .map(|(k, name)| match parameter {
            Some(value) => format!("{name} = {}", number(value(k))),
            None => name.to_string(),
        })
        .collect();
    let sets = |resets: &[&str]| {
        if resets.is_empty() {
            String::new()
        } else {
            format!(", sets {}", resets.join(", "))
        }
    };
    let events: Vec<String> = info
        .events
        .iter()
        .map(|e| {
            let direction = match e.direction {
                EventDirection::Any => "",
                EventDirection::Rising => ", rising",
                EventDirection::Falling => ", falling",
            };
            let terminal = if e.terminal { ", terminal" } else { "" };
            format!("{}{direction}{terminal}{}", e.name, sets(e.resets))
        })
        .collect();
    let event_docs: Vec<&str> = info.events.iter().map(|e| e.doc).collect();
    let clocks: Vec<String> =
        info.clocks.iter().map(|c| format!("{}{}", c.name, sets(c.resets))).collect();
    let clock_docs: Vec<&str> = info.clocks.iter().map(|c| c.doc).collect();
    // Discrete values are states, and inputs outputs, listed apart.
    let split = |names: &'static [&'static str], docs: &'static [&'static str], apart: &[&str]| {
        let (mut kept, mut kept_docs, mut other, mut other_docs) = (vec![], vec![], vec![], vec![]);
        for (k, name) in names.iter().enumerate() {
            let doc = docs.get(k).copied().unwrap_or("");
            if apart.contains(name) {
                other.push(name.to_string());
                other_docs.push(doc);
            } else {
                kept.push(name.to_string());
                kept_docs.push(doc);
            }
        }
        (kept, kept_docs, other, other_docs)
    };
    let (states, state_docs, discrete, discrete_docs) =
        split(info.states, info.state_docs, info.discrete);
    let (outputs, output_docs, inputs, input_docs) =
        split(info.outputs, info.output_docs, info.inputs);
    let sections: [(&str, Vec<String>, &[&str]); 8] = [
        ("states", states, &state_docs),
        ("discrete values", discrete, &discrete_docs),
        ("parameters", parameters, info.parameter_docs),
        ("inputs", inputs, &input_docs),
        ("algebraic variables", owned(info.algebraics), info.algebraic_docs),
        ("outputs", outputs, &output_docs),
        ("events", events, &event_docs),
        ("clocks", clocks, &clock_docs),
    ];
    let width = sections
        .iter()
        .flat_map(|(_, names, _)| names.iter().map(|n| n.chars().count()))
        .max()
        .unwrap_or(0);
    for (title, names, docs) in &sections {
        if names.is_empty() {
            continue;
        }
        let _ = writeln!(out, "{title}:");
        for (k, name) in names.iter().enumerate() {
            let doc = docs.get(k).map_or(String::new(), |d| first_paragraph(d));
            let pad = width - name.chars().count();
            let _ = writeln!(out, "  {name}{:pad$}  {doc}", "");
        }
    }
    structure(&mut out, &info.structure);
    // No trailing spaces on lines without a doc comment.
    out.lines().map(str::trim_end).collect::<Vec<_>>().join("\n") + "\n"
}

/// The "structure" section: aliases, equations solved one at a time, and
/// each block with its size before and after tearing; nothing where all
/// equations are solved one at a time (an ODE).
fn structure(out: &mut String, s: &StructureInfo) {
    if s.aliases == 0 && s.blocks.is_empty() {
        return;
    }
    let plural = |n: usize, what: &str| {
        let ending = match (n, what.ends_with('s')) {
            (1, _) => "",
            (_, true) => "es",
            (_, false) => "s",
        };
        format!("{n} {what}{ending}")
    };
    let _ = writeln!(
        out,
        "structure: {} removed, {} solved one at a time, {}",
        plural(s.aliases, "alias"),
        plural(s.one_at_a_time, "equation"),
        plural(s.blocks.len(), "block"),
    );
    for b in s.blocks {
        let how = match b.solution {
            BlockSolution::Symbolic => "linear, solved symbolically".to_string(),
            BlockSolution::Linear { lu } => format!("linear, LU of {lu} at run time"),
            BlockSolution::Newton { tearing } => {
                format!("nonlinear, Newton on {}", plural(tearing, "tearing variable"))
            }
            BlockSolution::MassMatrix => "nonlinear, in the mass-matrix form".to_string(),
        };
        let _ = writeln!(out, "  block of {}: {how}", plural(b.size, "equation"));
    }
}

/// The "components" section: each instance under its parent, with the
/// part it instantiates.
fn components(out: &mut String, components: &[crate::info::ComponentInfo]) {
    if components.is_empty() {
        return;
    }
    let _ = writeln!(out, "components:");
    let depth = |path: &str| path.matches('.').count();
    let width = components
        .iter()
        .map(|c| 2 * depth(c.path) + c.path.rsplit('.').next().unwrap_or("").chars().count())
        .max()
        .unwrap_or(0);
    for c in components {
        let name = c.path.rsplit('.').next().unwrap_or(c.path);
        let indent = 2 * depth(c.path);
        let pad = width - indent - name.chars().count();
        let _ = writeln!(out, "  {:indent$}{name}{:pad$}  {}", "", "", c.part);
    }
}

/// A parameter's value as people write it: `0.001`, `1e100`.
fn number(x: f64) -> String {
    let plain = format!("{x}");
    let short = format!("{x:e}");
    if short.len() < plain.len() {
        short
    } else {
        plain
    }
}

fn owned(names: &[&str]) -> Vec<String> {
    names.iter().map(|s| s.to_string()).collect()
}

/// A name's doc comment in its table row: its first paragraph, on one
/// line.
fn first_paragraph(doc: &str) -> String {
    let words = doc.lines().map(str::trim).skip_while(|l| l.is_empty());
    words.take_while(|l| !l.is_empty()).collect::<Vec<_>>().join(" ")
}

/// The model's names and their doc comments (parameters without values:
/// [`crate::Model::describe`] adds those).
impl std::fmt::Display for ModelInfo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&describe(self, None))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::info::EventInfo;

    const INFO: ModelInfo = ModelInfo {
        name: "Pendulum",
        doc: "\n A pendulum.\n More.\n\n Another paragraph:\n\n     indented.\n",
        states: &["theta", "der(theta)"],
        state_docs: &["Angle from the vertical\n(rad).\n\nSecond paragraph.", "rate of `theta`"],
        parameters: &["l"],
        parameter_docs: &["Length (m)."],
        outputs: &["energy"],
        output_docs: &[""],
        declared_outputs: &["energy"],
        equations: 1,
        events: &[EventInfo {
            name: "swing",
            direction: EventDirection::Rising,
            terminal: false,
            resets: &[],
            doc: "Passes under the pivot.",
        }],
        clocks: &[],
        discrete: &[],
        inputs: &[],
        algebraics: &[],
        algebraic_docs: &[],
        structure: crate::info::StructureInfo::NONE,
        components: &[],
    };

    #[test]
    fn every_name_with_its_doc_and_the_parameter_values() {
        let text = describe(&INFO, Some(&|_| 2.5));
        assert_eq!(
            text,
            "Pendulum: A pendulum.\n  More.\n\n  Another paragraph:\n\n      indented.\n\
             states:\n  theta          Angle from the vertical (rad).\n  der(theta)     rate of `theta`\n\
             parameters:\n  l = 2.5        Length (m).\n\
             outputs:\n  energy\n\
             events:\n  swing, rising  Passes under the pivot.\n"
        );
        assert!(INFO.to_string().contains("\n  l              Length (m).\n"));
    }
}
