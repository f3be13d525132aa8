//! The FMUs the tests import: the examples of this crate, each built by
//! cargo as a C library (`cargo test` builds them; a test run alone builds
//! the one it needs), packaged by the same function `cargo fmu` calls.

#![allow(dead_code)]

use daegen_fmi::archive::{package, platform, Archives};
use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "../../../tests/support/python_peers.rs"]
pub mod python_peers;

/// The directory cargo writes this test's profile into (`target/debug`).
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    // target/debug/deps/<test>-<hash>
    exe.parent().and_then(Path::parent).expect("target/<profile>").to_path_buf()
}

/// The library of example `name`, built if cargo has not built it.
pub fn library(name: &str) -> PathBuf {
    let (_, _, ext) = platform();
    let path = profile_dir().join("examples").join(format!("lib{name}.{ext}"));
    if !path.exists() {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let status = Command::new(cargo)
            .args(["build", "-p", "daegen-fmi", "--example", name])
            .status()
            .expect("cargo runs");
        assert!(status.success(), "cargo build --example {name} failed");
    }
    path
}

/// The two FMUs of example `name`, packaged into a directory of `tag`'s
/// (each test its own, so tests running at once never write one file).
pub fn fmus(name: &str, tag: &str) -> Archives {
    let dir = profile_dir().join("fmu-tests").join(tag);
    package(&library(name), &dir).unwrap_or_else(|e| panic!("packaging {name}: {e}"))
}

/// FMPy's validation and both interfaces' results for `config` (see
/// `fmpy_run.py`), from FMPy in its own environment under the target
/// directory.
pub fn fmpy(config: serde_json::Value) -> serde_json::Value {
    let python = python_peers::python(&python_peers::FMPY);
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fmpy_run.py");
    let out = Command::new(python).arg(script).arg(config.to_string()).output().expect("FMPy runs");
    assert!(out.status.success(), "FMPy failed:\n{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("FMPy's results as JSON")
}
