//! The `urdf("path")` statement's lowering: the file read at compile time
//! (relative to the crate's `Cargo.toml`), its mistakes reported on the
//! path as `file:line: message`, its tree written as statements and
//! lowered in their place.

use super::parse::parse;
use super::statements::statements;
use super::tree::tree;
use crate::front::lower::Lower;
use crate::mechanics::Scene;
use syn::Expr;

impl Lower<'_, Scene> {
    /// `urdf("path")`, with a free base when `floating`.
    pub(crate) fn urdf(&mut self, call: &syn::ExprCall, e: &Expr, floating: bool) {
        let path = match (call.args.len(), call.args.first()) {
            (1, Some(Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }))) => s.value(),
            _ => {
                return self.cx.error_at(call, "`urdf` takes the path of a URDF file, relative to the crate's Cargo.toml: `urdf(\"robots/arm.urdf\")`")
            }
        };
        let at = &call.args[0];
        if !self.scene.recursive {
            return self.cx.error_at(
                e,
                "a robot is loaded in joint coordinates: write `#[dae_model(scene = recursive)]`",
            );
        }
        let base = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".to_string());
        let full = std::path::Path::new(&base).join(&path);
        let text = match std::fs::read_to_string(&full) {
            Ok(text) => text,
            Err(err) => {
                return self.cx.error_at(at, format!("cannot read `{}`: {err}", full.display()))
            }
        };
        let robot = match parse(&text).and_then(|robot| tree(&robot)) {
            Ok(tree) => tree,
            Err(errors) => {
                for error in errors {
                    self.cx.error_at(at, format!("{path}:{}: {}", error.line, error.message));
                }
                return;
            }
        };
        let written = match statements(&robot, floating) {
            Ok(written) => written,
            Err((line, message)) => {
                return self.cx.error_at(at, format!("{path}:{line}: {message}"))
            }
        };
        let block = match syn::parse2::<syn::Block>(quote::quote!({ #(#written)* })) {
            Ok(block) => block,
            Err(err) => {
                return self.cx.error_at(
                    at,
                    format!("{path}: the statements made of it do not parse ({err}); report this"),
                )
            }
        };
        let parsed = block.stmts;
        self.scene.robot_files.push(full);
        self.generated_statements(&parsed);
    }
}
