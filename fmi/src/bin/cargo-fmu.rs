//! `cargo fmu`: builds a crate's `cdylib` targets that call
//! `daegen_fmi::export_fmu!` and packages each into two FMUs, FMI 3.0
//! (`<name>.fmu`) and FMI 2.0 (`<name>_fmi2.fmu`), each with Model
//! Exchange and Co-Simulation.
//!
//! ```text
//! cargo install --path fmi            # once: installs cargo-fmu
//! cargo fmu --release                 # in the crate; FMUs in target/fmu
//! cargo fmu --release -p my_model --out fmus
//! cargo fmu --example dc_motor_fmu    # an example with crate-type cdylib
//! ```
//!
//! Every argument but `--out DIR` goes to `cargo build`.

use std::path::PathBuf;
use std::process::{Command, ExitCode, Stdio};

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    // Run as `cargo fmu …`, cargo passes the subcommand's name first.
    if args.first().map(String::as_str) == Some("fmu") {
        args.remove(0);
    }
    if args.iter().any(|a| a == "-h" || a == "--help") {
        println!("cargo fmu [cargo build options] [--out DIR]\n\nBuilds the cdylib targets that call daegen_fmi::export_fmu! and packages each into\n<name>.fmu (FMI 3.0) and <name>_fmi2.fmu (FMI 2.0) in DIR (default target/fmu).");
        return ExitCode::SUCCESS;
    }
    let mut out: Option<PathBuf> = None;
    if let Some(k) = args.iter().position(|a| a == "--out") {
        if k + 1 >= args.len() {
            eprintln!("error: --out needs a directory");
            return ExitCode::FAILURE;
        }
        out = Some(PathBuf::from(args.remove(k + 1)));
        args.remove(k);
    }
    match build(&args, out) {
        Ok(made) if made.is_empty() => {
            eprintln!("error: no cdylib target was built: give the crate `crate-type = [\"cdylib\"]` and call `daegen_fmi::export_fmu!(YourModel);`");
            ExitCode::FAILURE
        }
        Ok(made) => {
            for line in &made {
                println!("{line}");
            }
            ExitCode::SUCCESS
        }
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// The target directory of the crate `args` name (`--manifest-path`),
/// from `cargo metadata`.
fn target_directory(args: &[String]) -> Result<PathBuf, String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let mut command = Command::new(cargo);
    command.args(["metadata", "--format-version", "1", "--no-deps"]);
    if let Some(k) = args.iter().position(|a| a == "--manifest-path") {
        if let Some(path) = args.get(k + 1) {
            command.args(["--manifest-path", path]);
        }
    }
    let output = command.output().map_err(|e| format!("cannot run cargo metadata: {e}"))?;
    let metadata: serde_json::Value =
        serde_json::from_slice(&output.stdout).map_err(|e| format!("cargo metadata: {e}"))?;
    metadata["target_directory"]
        .as_str()
        .map(PathBuf::from)
        .ok_or_else(|| "cargo metadata gave no target directory".to_string())
}

/// Runs `cargo build` with `args`, packages every cdylib it reports; a
/// line per FMU written.
fn build(args: &[String], out: Option<PathBuf>) -> Result<Vec<String>, String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let output = Command::new(cargo)
        .arg("build")
        .arg("--message-format=json-render-diagnostics")
        .args(args)
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        return Err("cargo build failed".to_string());
    }
    let (dir, whence) = match out {
        Some(dir) => (dir, "--out"),
        None => {
            let whence = match std::env::var_os("CARGO_TARGET_DIR") {
                Some(_) => "fmu/ under CARGO_TARGET_DIR, cargo's target directory; --out DIR writes elsewhere",
                None => "fmu/ under cargo's target directory; --out DIR writes elsewhere",
            };
            (target_directory(args)?.join("fmu"), whence)
        }
    };
    let mut made = Vec::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let Ok(message) = serde_json::from_str::<serde_json::Value>(line) else { continue };
        if message["reason"] != "compiler-artifact" {
            continue;
        }
        let cdylib = message["target"]["crate_types"]
            .as_array()
            .is_some_and(|kinds| kinds.iter().any(|k| k == "cdylib"));
        if !cdylib {
            continue;
        }
        let (_, _, ext) = daegen_fmi::archive::platform();
        let files = message["filenames"].as_array().cloned().unwrap_or_default();
        for file in files.iter().filter_map(|f| f.as_str()).filter(|f| f.ends_with(ext)) {
            let library = PathBuf::from(file);
            let archives = daegen_fmi::archive::package(&library, &dir)?;
            made.push(format!("{} (FMI 3.0)", archives.fmi3.display()));
            made.push(format!("{} (FMI 2.0)", archives.fmi2.display()));
        }
    }
    if !made.is_empty() {
        let dir = std::fs::canonicalize(&dir).unwrap_or(dir);
        made.push(format!("{} FMUs written to {} ({whence})", made.len(), dir.display()));
    }
    Ok(made)
}
