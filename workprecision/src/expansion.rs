//! What a model costs at compile time: the macro's expansion time and the
//! size of the code it generates, measured by expanding the model's source
//! with `daegen-codegen` (the library the macro forwards to).

use std::str::FromStr;
use std::time::Instant;

/// Compile-time cost of a model.
#[derive(Clone, Debug)]
pub struct ExpansionCost {
    /// Median expansion time over a few repeats, in seconds.
    pub seconds: f64,
    /// Size of the generated code (its tokens as text), in bytes.
    pub bytes: usize,
    /// The generated code, for timing rustc on it.
    pub code: String,
}

/// Expands `source` (a model function) with `attributes` (the
/// `#[dae_model(...)]` arguments) `repeats` times.
pub fn expansion_cost(
    source: &str,
    attributes: &str,
    repeats: usize,
) -> Result<ExpansionCost, String> {
    let item = proc_macro2::TokenStream::from_str(source).map_err(|e| e.to_string())?;
    let attr = proc_macro2::TokenStream::from_str(attributes).map_err(|e| e.to_string())?;
    let mut times = Vec::new();
    let mut code = String::new();
    for _ in 0..repeats.max(1) {
        let start = Instant::now();
        let tokens = daegen::codegen::expand_dae_model(attr.clone(), item.clone());
        times.push(start.elapsed().as_secs_f64());
        code = tokens.to_string();
    }
    if code.contains("compile_error") {
        return Err(format!("the model does not expand: {code:.200}"));
    }
    times.sort_by(f64::total_cmp);
    Ok(ExpansionCost { seconds: times[times.len() / 2], bytes: code.len(), code })
}
