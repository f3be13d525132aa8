//! The Python packages some tests run or read (FMPy, the FMU importer
//! engineers script with; example-robot-data's URDF files), each in a
//! virtual environment of its own with pinned versions, made by the first
//! test that needs it and kept under the target directory
//! (`target/python-peers/<name>/`), so that the test command needs nothing
//! but `python3` on the machine.
//!
//! An environment is made in a directory of its own and renamed into
//! place when complete, so test processes running at once never see half
//! of one; the one that loses the race drops its copy.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// A Python peer: the environment's name and what pip installs into it.
pub struct Peer {
    /// The environment's directory under `target/python-peers/`; it names
    /// the pinned version, so a new pin makes a new environment.
    pub name: &'static str,
    /// pip's arguments after `install`.
    pub install: &'static [&'static str],
    /// A Python statement that succeeds once the environment is usable.
    pub check: &'static str,
}

/// FMPy, with the dependencies pip resolves for it.
pub const FMPY: Peer = Peer {
    name: "fmpy-0.3.32",
    install: &["fmpy==0.3.32"],
    check: "import fmpy; assert fmpy.__version__ == '0.3.32', fmpy.__version__",
};

/// example-robot-data's files alone: its build tools (cmake, cmeel) are
/// not needed to read them.
pub const EXAMPLE_ROBOT_DATA: Peer = Peer {
    name: "example-robot-data-5.0.0",
    install: &["--no-deps", "example-robot-data==5.0.0"],
    check: "import importlib.metadata as m; assert m.version('example-robot-data') == '5.0.0'",
};

/// The interpreter the environments are made from.
pub const BASE_PYTHON: &str = "python3";

/// The target directory this test binary was built into
/// (`target/<profile>/deps/<test>` → `target`).
pub fn target_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    exe.ancestors().nth(3).expect("target/<profile>/deps/<test>").to_path_buf()
}

/// The interpreter of `peer`'s environment under `target/python-peers/`,
/// made on first use; a test that needs it fails with what to install
/// when it cannot be made.
pub fn python(peer: &Peer) -> PathBuf {
    use std::sync::{Mutex, OnceLock};
    static MADE: OnceLock<Mutex<Vec<(&'static str, PathBuf)>>> = OnceLock::new();
    let made = MADE.get_or_init(Default::default);
    let mut made = made.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, path)) = made.iter().find(|(name, _)| *name == peer.name) {
        return path.clone();
    }
    let root = target_dir().join("python-peers");
    let path = bootstrap(peer, BASE_PYTHON, &root).unwrap_or_else(|e| panic!("{e}"));
    made.push((peer.name, path.clone()));
    path
}

/// The interpreter inside environment `dir`.
fn interpreter(dir: &Path) -> PathBuf {
    if cfg!(windows) {
        dir.join("Scripts").join("python.exe")
    } else {
        dir.join("bin").join("python")
    }
}

/// Whether `python` runs `statement` without error.
fn runs(python: &Path, statement: &str) -> bool {
    Command::new(python).args(["-c", statement]).output().is_ok_and(|o| o.status.success())
}

/// Makes `peer`'s environment in `root` from interpreter `base`, unless a
/// usable one is there: its interpreter, or one line that says what to
/// install.
pub fn bootstrap(peer: &Peer, base: &str, root: &Path) -> Result<PathBuf, String> {
    let dir = root.join(peer.name);
    let marker = dir.join("complete");
    if marker.exists() && runs(&interpreter(&dir), peer.check) {
        return Ok(interpreter(&dir));
    }
    // One left half-made, or made from an interpreter since removed.
    if dir.exists() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    let version = Command::new(base).arg("--version").output();
    if !version.as_ref().is_ok_and(|o| o.status.success()) {
        return Err(format!(
            "`{base}` not found: install Python 3.9 or newer with its venv module (Debian: `apt-get install python3 python3-venv`); the tests make their Python environments under target/python-peers/ themselves"
        ));
    }
    std::fs::create_dir_all(root).map_err(|e| format!("cannot create {}: {e}", root.display()))?;
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    let building = root.join(format!(".{}.{}.{nanos}", peer.name, std::process::id()));
    let failed = |what: &str, out: std::io::Result<std::process::Output>| -> String {
        let detail = match out {
            Ok(o) => String::from_utf8_lossy(&o.stderr).lines().last().unwrap_or("").to_string(),
            Err(e) => e.to_string(),
        };
        let _ = std::fs::remove_dir_all(&building);
        format!("{what} failed ({detail})")
    };
    let venv = Command::new(base).arg("-m").arg("venv").arg(&building).output();
    if !venv.as_ref().is_ok_and(|o| o.status.success()) {
        return Err(failed(
            &format!("`{base} -m venv` (Debian: `apt-get install python3-venv`)"),
            venv,
        ));
    }
    let python = interpreter(&building);
    let pip = Command::new(&python)
        .args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check"])
        .args(peer.install)
        .output();
    if !pip.as_ref().is_ok_and(|o| o.status.success()) {
        return Err(failed(&format!("`pip install {}` from PyPI", peer.install.join(" ")), pip));
    }
    let check = Command::new(&python).args(["-c", peer.check]).output();
    if !check.as_ref().is_ok_and(|o| o.status.success()) {
        return Err(failed(&format!("the check `{}`", peer.check), check));
    }
    std::fs::write(building.join("complete"), peer.install.join(" ")).map_err(|e| e.to_string())?;
    if std::fs::rename(&building, &dir).is_err() {
        // Another test process put its own in place first.
        let _ = std::fs::remove_dir_all(&building);
        if !marker.exists() {
            return Err(format!("cannot move the environment into {}", dir.display()));
        }
    }
    Ok(interpreter(&dir))
}
