//! `modelDescription.xml` for FMI 2.0 and 3.0 from what a generated model
//! knows: its variables ([`crate::variables`]) with their doc comments
//! and start values, and the model structure, the dependencies of each
//! derivative taken from the generated Jacobian's pattern.
//!
//! The two versions differ in form (FMI 2.0's `ScalarVariable`s refer to
//! each other by their 1-based position, FMI 3.0's typed variables by
//! value reference; a `guid` against an `instantiationToken`) and in the
//! spelling of the capability flags; the variables and their references
//! are the same. The token is a hash of the description itself, so it
//! changes when the model does.

use crate::variables::{fmi_variables, Causality, Initial, Variability, Variable};
use daegen_runtime::Model;
use std::fmt::Write;

/// The FMI version a description is written for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FmiVersion {
    /// FMI 2.0, which most importers and rigs run.
    V2,
    /// FMI 3.0.
    V3,
}

/// What the binary beside the description provides.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Capabilities {
    /// Directional derivatives from the symbolic Jacobian.
    pub directional_derivatives: bool,
    /// Getting, setting and serializing the FMU's state.
    pub fmu_state: bool,
}

impl Capabilities {
    /// What `export_fmu!` provides: every capability.
    pub const EXPORTED: Capabilities =
        Capabilities { directional_derivatives: true, fmu_state: true };
}

/// `modelDescription.xml` of `model` (with this instance's parameters as
/// start values) for `version`, its library named `identifier`.
pub fn model_description<M: Model>(
    model: &M,
    version: FmiVersion,
    identifier: &str,
    capabilities: Capabilities,
) -> String {
    let vars = fmi_variables(model);
    let body = match version {
        FmiVersion::V2 => fmi2_body::<M>(&vars, identifier, capabilities),
        FmiVersion::V3 => fmi3_body::<M>(&vars, identifier, capabilities),
    };
    let token = token(&body);
    let (version_text, key) = match version {
        FmiVersion::V2 => ("2.0", "guid"),
        FmiVersion::V3 => ("3.0", "instantiationToken"),
    };
    let info = &M::INFO;
    let summary = first_paragraph(info.doc);
    let events = match version {
        FmiVersion::V2 => format!(" numberOfEventIndicators=\"{}\"", info.events.len()),
        FmiVersion::V3 => String::new(),
    };
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription fmiVersion=\"{version_text}\" modelName=\"{}\" {key}=\"{token}\" description=\"{}\" generationTool=\"daegen\" variableNamingConvention=\"structured\"{events}>\n{body}</fmiModelDescription>\n",
        escape(info.name),
        escape(&summary),
    )
}

/// The token (`guid` of FMI 2.0, `instantiationToken` of 3.0) that
/// [`model_description`] writes for `model`: what an instance checks the
/// importer's against.
pub fn instantiation_token<M: Model>(model: &M, version: FmiVersion, identifier: &str) -> String {
    let xml = model_description(model, version, identifier, Capabilities::EXPORTED);
    let key = match version {
        FmiVersion::V2 => "guid=\"",
        FmiVersion::V3 => "instantiationToken=\"",
    };
    xml.split(key).nth(1).and_then(|rest| rest.split('"').next()).unwrap_or("").to_string()
}

/// The value references of each continuous state's derivative's
/// dependencies, from the Jacobian's pattern: `None` where they are not
/// known exactly (a differenced Jacobian, inputs or discrete values the
/// pattern leaves out), which FMI reads as "depends on every known".
fn dependencies<M: Model>(vars: &[Variable], state: usize) -> Option<Vec<usize>> {
    let info = &M::INFO;
    if !M::JACOBIAN.is_symbolic() || !info.inputs.is_empty() || !info.discrete.is_empty() {
        return None;
    }
    let mut columns: Vec<usize> =
        M::JACOBIAN.pattern().iter().filter(|&&(r, _)| r == state).map(|&(_, c)| c).collect();
    columns.sort_unstable();
    Some(columns.into_iter().filter_map(|c| vars.iter().position(|v| v.state == Some(c))).collect())
}

/// The derivatives in the order of the continuous states: (position of
/// the derivative variable, the state's index in the state vector).
fn derivatives(vars: &[Variable]) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> = vars
        .iter()
        .enumerate()
        .filter_map(|(k, v)| v.derivative_of.and_then(|s| vars[s].state).map(|state| (k, state)))
        .collect();
    out.sort_by_key(|&(_, state)| state);
    out
}

/// What FMI calls initial unknowns: the outputs, the calculated
/// derivatives, and the states whose start is a guess; positions.
fn initial_unknowns(vars: &[Variable]) -> Vec<usize> {
    vars.iter()
        .enumerate()
        .filter(|(_, v)| {
            v.causality == Causality::Output
                || (v.derivative_of.is_some() && v.initial == Some(Initial::Calculated))
                || (v.state.is_some() && v.initial == Some(Initial::Approx))
        })
        .map(|(k, _)| k)
        .collect()
}

fn causality(c: Causality) -> &'static str {
    match c {
        Causality::Independent => "independent",
        Causality::Parameter => "parameter",
        Causality::Input => "input",
        Causality::Output => "output",
        Causality::Local => "local",
    }
}

fn variability(v: Variability) -> &'static str {
    match v {
        Variability::Continuous => "continuous",
        Variability::Discrete => "discrete",
        Variability::Tunable => "tunable",
        Variability::Fixed => "fixed",
    }
}

fn initial(i: Initial) -> &'static str {
    match i {
        Initial::Exact => "exact",
        Initial::Approx => "approx",
        Initial::Calculated => "calculated",
    }
}

/// The attributes every variable has in both versions.
fn common(v: &Variable) -> String {
    let mut s = format!(
        "name=\"{}\" valueReference=\"{}\" causality=\"{}\" variability=\"{}\"",
        escape(&crate::variables::structured_name(&v.name)),
        v.value_reference,
        causality(v.causality),
        variability(v.variability)
    );
    if let Some(i) = v.initial.filter(|_| v.causality != Causality::Parameter) {
        let _ = write!(s, " initial=\"{}\"", initial(i));
    }
    if !v.description.is_empty() {
        let _ = write!(s, " description=\"{}\"", escape(&first_paragraph(&v.description)));
    }
    s
}

/// The two interface elements with the version's spelling of the
/// capability flags, and the opening of the variables.
fn interfaces(version: FmiVersion, identifier: &str, caps: Capabilities) -> String {
    let (memory, state, serialize, derivatives, completed) = match version {
        FmiVersion::V2 => (
            " canNotUseMemoryManagementFunctions=\"true\"",
            "canGetAndSetFMUstate",
            "canSerializeFMUstate",
            "providesDirectionalDerivative",
            "",
        ),
        FmiVersion::V3 => (
            "",
            "canGetAndSetFMUState",
            "canSerializeFMUState",
            "providesDirectionalDerivatives",
            " needsCompletedIntegratorStep=\"true\"",
        ),
    };
    let flags = format!(
        "modelIdentifier=\"{}\"{memory} {state}=\"{}\" {serialize}=\"{}\" {derivatives}=\"{}\"",
        escape(identifier),
        caps.fmu_state,
        caps.fmu_state,
        caps.directional_derivatives
    );
    format!(
        "  <ModelExchange {flags}{completed}/>\n  <CoSimulation {flags} canHandleVariableCommunicationStepSize=\"true\"/>\n  <ModelVariables>\n"
    )
}

/// ` start=".." derivative=".."` of a variable, the derivative's state
/// written as `refer` says (a position or a value reference).
fn value_attributes(v: &Variable, refer: impl Fn(usize) -> String) -> String {
    let mut out = String::new();
    if let Some(start) = v.start {
        let _ = write!(out, " start=\"{}\"", number(start));
    }
    if let Some(of) = v.derivative_of {
        let _ = write!(out, " derivative=\"{}\"", refer(of));
    }
    out
}

fn fmi2_body<M: Model>(vars: &[Variable], identifier: &str, caps: Capabilities) -> String {
    let mut s = interfaces(FmiVersion::V2, identifier, caps);
    for v in vars {
        let value = match v.text {
            Some(text) => format!("<String start=\"{}\"/>", escape(text)),
            None => format!("<Real{}/>", value_attributes(v, |of| (of + 1).to_string())),
        };
        let _ = writeln!(s, "    <ScalarVariable {}>{value}</ScalarVariable>", common(v));
    }
    s.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let positions = |list: &[usize]| list.iter().map(|k| (k + 1).to_string()).collect::<Vec<_>>();
    let outputs: Vec<usize> =
        (0..vars.len()).filter(|&k| vars[k].causality == Causality::Output).collect();
    if !outputs.is_empty() {
        s.push_str("    <Outputs>\n");
        for k in positions(&outputs) {
            let _ = writeln!(s, "      <Unknown index=\"{k}\"/>");
        }
        s.push_str("    </Outputs>\n");
    }
    s.push_str("    <Derivatives>\n");
    for (k, state) in derivatives(vars) {
        let deps = dependencies::<M>(vars, state)
            .map(|d| format!(" dependencies=\"{}\"", positions(&d).join(" ")))
            .unwrap_or_default();
        let _ = writeln!(s, "      <Unknown index=\"{}\"{deps}/>", k + 1);
    }
    s.push_str("    </Derivatives>\n");
    let unknowns = initial_unknowns(vars);
    if !unknowns.is_empty() {
        s.push_str("    <InitialUnknowns>\n");
        for k in positions(&unknowns) {
            let _ = writeln!(s, "      <Unknown index=\"{k}\"/>");
        }
        s.push_str("    </InitialUnknowns>\n");
    }
    s.push_str("  </ModelStructure>\n");
    s
}

fn fmi3_body<M: Model>(vars: &[Variable], identifier: &str, caps: Capabilities) -> String {
    let mut s = interfaces(FmiVersion::V3, identifier, caps);
    for v in vars {
        match v.text {
            Some(text) => {
                let start = escape(text);
                let _ =
                    writeln!(s, "    <String {}><Start value=\"{start}\"/></String>", common(v));
            }
            None => {
                let extra = value_attributes(v, |of| vars[of].value_reference.to_string());
                let _ = writeln!(s, "    <Float64 {}{extra}/>", common(v));
            }
        }
    }
    s.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let vr = |k: usize| vars[k].value_reference.to_string();
    for (k, v) in vars.iter().enumerate() {
        if v.causality == Causality::Output {
            let _ = writeln!(s, "    <Output valueReference=\"{}\"/>", vr(k));
        }
    }
    for (k, state) in derivatives(vars) {
        let deps = dependencies::<M>(vars, state)
            .map(|d| {
                let refs: Vec<String> = d.iter().map(|&j| vr(j)).collect();
                format!(" dependencies=\"{}\"", refs.join(" "))
            })
            .unwrap_or_default();
        let _ = writeln!(s, "    <ContinuousStateDerivative valueReference=\"{}\"{deps}/>", vr(k));
    }
    for k in initial_unknowns(vars) {
        let _ = writeln!(s, "    <InitialUnknown valueReference=\"{}\"/>", vr(k));
    }
    let events = M::INFO.events;
    for (k, v) in vars.iter().enumerate() {
        if events.iter().any(|e| e.name == v.name) && v.state.is_none() {
            let _ = writeln!(s, "    <EventIndicator valueReference=\"{}\"/>", vr(k));
        }
    }
    s.push_str("  </ModelStructure>\n");
    s
}

/// A number as XML reads it back exactly (Rust's shortest round trip).
fn number(x: f64) -> String {
    if x.is_finite() {
        format!("{x:?}")
    } else {
        "0.0".to_string()
    }
}

/// The first paragraph of a doc comment, its lines joined.
fn first_paragraph(doc: &str) -> String {
    let lines = doc.lines().map(str::trim).skip_while(|l| l.is_empty());
    lines.take_while(|l| !l.is_empty()).collect::<Vec<_>>().join(" ")
}

/// `text` with XML's five special characters escaped.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// A 128-bit hash of `text` (two FNV-1a 64-bit hashes of different
/// offsets), written as a GUID.
fn token(text: &str) -> String {
    let fnv = |offset: u64| {
        text.bytes().fold(offset, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
    };
    let (a, b) = (fnv(0xcbf2_9ce4_8422_2325), fnv(0x8422_2325_cbf2_9ce4));
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_tokens() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
        let t = token("abc");
        assert_eq!(t.len(), 38);
        assert_ne!(t, token("abd"));
        assert_eq!(t, token("abc"));
        assert_eq!(number(0.1), "0.1");
        assert_eq!(number(10.0), "10.0");
    }
}
