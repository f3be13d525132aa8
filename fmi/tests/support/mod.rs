//! The FMUs the tests import: the examples of this crate, each built by
//! cargo as a C library (`cargo test` builds them; a test run alone builds
//! the one it needs), packaged by the same function `cargo fmu` calls.

#![allow(dead_code)]

use daegen_fmi::archive::{package, platform, Archives};
use std::path::{Path, PathBuf};
use std::process::Command;

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

/// Installs FMPy from PyPI if python3 cannot import it (once per run).
fn ensure_fmpy() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let present = Command::new("python3").args(["-c", "import fmpy"]).status();
        if present.is_ok_and(|s| s.success()) {
            return;
        }
        let installed = Command::new("python3")
            .args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check", "fmpy"])
            .status()
            .expect("python3 runs");
        assert!(installed.success(), "python3 -m pip install fmpy failed");
    });
}

/// FMPy's validation and both interfaces' results for `config` (see
/// `fmpy_run.py`).
pub fn fmpy(config: serde_json::Value) -> serde_json::Value {
    ensure_fmpy();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fmpy_run.py");
    let out = Command::new("python3")
        .arg(script)
        .arg(config.to_string())
        .output()
        .expect("python3 runs (FMPy: python3 -m pip install fmpy)");
    assert!(
        out.status.success(),
        "FMPy failed (is it installed? python3 -m pip install fmpy):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("FMPy's results as JSON")
}
