//! What the Taylor tape every model gets by default costs at compile time:
//! the macro's expansion time and rustc's time (release) on the generated
//! code, with the default (`#[dae_model]`, the tape wherever the model
//! allows one) against `#[dae_model(taylor = 0)]` (no Taylor code), on the
//! benchmark's models and the DAE scenes of the tests.
//!
//! Expansion: median of 9; rustc: the fastest of 3 (the least disturbed by
//! the machine's load), the two variants alternating.

use crate::*;
use daegen_workprecision::expansion_cost;

/// The text of `fn name() { … }` in `file`, `$name` (a macro's) renamed.
fn function_source(file: &str, pattern: &str, name: &str) -> Option<String> {
    let start = file.find(&format!("fn {pattern}()"))?;
    let open = start + file[start..].find('{')?;
    let mut depth = 0usize;
    for (i, c) in file[open..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    let text = &file[start..open + i + 1];
                    return Some(text.replace(&format!("fn {pattern}()"), &format!("fn {name}()")));
                }
            }
            _ => {}
        }
    }
    None
}

/// The text of the model that the macro `macro_name` of `file` writes,
/// named `name`.
pub(crate) fn macro_model_source(file: &str, macro_name: &str, name: &str) -> Option<String> {
    let start = file.find(&format!("macro_rules! {macro_name}"))?;
    function_source(&file[start..], "$name", name)
}

/// One model's costs: (expansion seconds, code bytes, rustc seconds) with
/// and without the tape.
struct Costs {
    name: String,
    with: (f64, usize, f64),
    without: (f64, usize, f64),
    has_tape: bool,
}

fn measure(name: &str, source: &str, attributes: &str) -> Result<Costs, String> {
    let crate_name = name.replace(|c: char| !c.is_ascii_alphanumeric(), "_");
    let off = if attributes.is_empty() {
        "taylor = 0".to_string()
    } else {
        format!("{attributes}, taylor = 0")
    };
    let (mut with, mut without) = (None, None);
    let (mut rustc_with, mut rustc_without) = (f64::INFINITY, f64::INFINITY);
    for round in 0..3 {
        let a = expansion_cost(source, attributes, 9)?;
        let b = expansion_cost(source, &off, 9)?;
        rustc_with = rustc_with.min(rustc_seconds(&a.code, &format!("{crate_name}_tape{round}"))?);
        rustc_without =
            rustc_without.min(rustc_seconds(&b.code, &format!("{crate_name}_none{round}"))?);
        with = Some(a);
        without = Some(b);
    }
    let (a, b) = (with.ok_or("no run")?, without.ok_or("no run")?);
    Ok(Costs {
        name: name.to_string(),
        has_tape: a.code.contains("fn taylor_tape"),
        with: (a.seconds, a.bytes, rustc_with),
        without: (b.seconds, b.bytes, rustc_without),
    })
}

/// `--tape-cost`: the table, written to `results/default_tape.md`.
pub fn tape_cost_section() {
    let mut models: Vec<(String, String, String)> = vec![
        ("kepler".into(), Kepler::SOURCE.into(), String::new()),
        ("arenstorf".into(), Arenstorf::SOURCE.into(), String::new()),
        ("lorenz".into(), Lorenz::SOURCE.into(), String::new()),
        ("outer_solar_system".into(), OuterSolarSystem::SOURCE.into(), String::new()),
        ("van_der_pol".into(), VanDerPol::SOURCE.into(), String::new()),
        ("robertson".into(), Robertson::SOURCE.into(), String::new()),
        ("hires".into(), Hires::SOURCE.into(), String::new()),
        ("example_1_4".into(), Example14::SOURCE.into(), String::new()),
    ];
    let slider = include_str!("../../tests/models/slider_crank.rs");
    if let Some(s) = function_source(slider, "slider_crank", "slider_crank") {
        models.push(("slider_crank (DAE, index 3)".into(), s, String::new()));
    }
    let chain = include_str!("../../tests/models/rod_chain.rs");
    if let Some(s) = function_source(chain, "$name", "rod_chain") {
        models.push(("rod_chain global (DAE scene)".into(), s.clone(), "scene = global".into()));
        models.push(("rod_chain recursive (scene)".into(), s, "scene = recursive".into()));
    }
    let mut rows = Vec::new();
    for (name, source, attributes) in &models {
        eprint!("\r\x1b[2Ktape cost: {name}");
        match measure(name, source, attributes) {
            Ok(c) => rows.push(c),
            Err(e) => eprintln!("\n{name}: {e}"),
        }
    }
    let mut text = format!(
        "# The default Taylor tape at compile time\n\nMachine: {}. Written by `cd bench && cargo run --release -- --tape-cost` (bench/src/tape_cost.rs). Every model that is an explicit ODE with a smooth right-hand side (after index reduction) gets the tape of `Method::Taylor` without an attribute; `#[dae_model(taylor = 0)]` leaves it out. Expansion: median of 9; rustc (release, the generated code as a library): fastest of 3, the two variants alternating. Goal: ≤ 15 % more.\n\n| model | tape | expansion without → with | code without → with | rustc without → with | both |\n|---|---|---|---|---|---|\n",
        machine()
    );
    let (mut total_without, mut total_with) = (0.0, 0.0);
    for c in &rows {
        let pct = |a: f64, b: f64| 100.0 * (b / a - 1.0);
        text.push_str(&format!(
            "| {} | {} | {:.2} → {:.2} ms ({:+.0} %) | {:.1} → {:.1} kB ({:+.0} %) | {:.2} → {:.2} s ({:+.0} %) | {:+.0} % |\n",
            c.name,
            if c.has_tape { "yes" } else { "no (refused)" },
            c.without.0 * 1e3,
            c.with.0 * 1e3,
            pct(c.without.0, c.with.0),
            c.without.1 as f64 / 1e3,
            c.with.1 as f64 / 1e3,
            pct(c.without.1 as f64, c.with.1 as f64),
            c.without.2,
            c.with.2,
            pct(c.without.2, c.with.2),
            pct(c.without.0 + c.without.2, c.with.0 + c.with.2),
        ));
        total_without += c.without.0 + c.without.2;
        total_with += c.with.0 + c.with.2;
    }
    text.push_str(&format!(
        "\nAll models, expansion and rustc together: {total_without:.2} s without the tape, {total_with:.2} s with it ({:+.1} %).\n",
        100.0 * (total_with / total_without - 1.0)
    ));
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("results").join("default_tape.md");
    let _ = std::fs::write(&out, &text);
    eprintln!("\r\x1b[2Kdone");
    println!("{text}");
}
