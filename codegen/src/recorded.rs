//! Every expansion written to a folder, for comparing the generated code
//! of all models before and after a change to the pipeline
//! (`.ci/compare-expansions.sh`): where the environment variable
//! `DAEGEN_EXPANSIONS` names a folder, each `#[dae_model]` expansion is
//! written there as `<package>-<crate>-<model>-<hash>.rs`, the hash that
//! of the attribute's and the function's tokens (two models of one name
//! in one crate differ in them). Without the variable, nothing happens.

use proc_macro2::TokenStream;

/// Writes `tokens`, the expansion of `attr` on `item`, where
/// `DAEGEN_EXPANSIONS` says.
pub(crate) fn record(attr: &TokenStream, item: &syn::ItemFn, tokens: &TokenStream) {
    let Some(folder) = std::env::var_os("DAEGEN_EXPANSIONS") else { return };
    let env = |name: &str| std::env::var(name).unwrap_or_default();
    // FNV-1a, stable across builds (std's hasher is seeded per process).
    let source = format!("{attr} {}", quote::quote!(#item));
    let hash = source
        .bytes()
        .fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3));
    let name = format!(
        "{}-{}-{}-{hash:016x}.rs",
        env("CARGO_PKG_NAME"),
        env("CARGO_CRATE_NAME"),
        item.sig.ident
    );
    let path = std::path::Path::new(&folder).join(name);
    let _ = std::fs::create_dir_all(&folder);
    let _ = std::fs::write(path, tokens.to_string());
}
