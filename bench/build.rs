//! Copies TALOS's URDF files, which their licence (CC BY-NC-ND) keeps out
//! of the repository, from where `python3 -m pip install
//! example-robot-data==5.0.0` put them to `target/robots/`, where the robot
//! benchmark's models read them at compile time.

use std::path::Path;
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let here = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let into = Path::new(&here).join("target/robots");
    let files = ["talos_left_arm.urdf", "talos_reduced.urdf"];
    if files.iter().all(|f| into.join(f).exists()) {
        return;
    }
    let purelib = Command::new("python3")
        .args(["-c", "import os, site, sysconfig; c = [sysconfig.get_paths()['purelib'], site.getusersitepackages()] + site.getsitepackages(); print(next((p for p in c if os.path.isdir(os.path.join(p, 'cmeel.prefix', 'share', 'example-robot-data'))), c[0]))"])
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .unwrap_or_default();
    let from =
        Path::new(&purelib).join("cmeel.prefix/share/example-robot-data/robots/talos_data/robots");
    std::fs::create_dir_all(&into).expect("target/robots");
    for f in files {
        if let Err(e) = std::fs::copy(from.join(f), into.join(f)) {
            panic!(
                "{}: {e}; the robot benchmark needs `python3 -m pip install example-robot-data==5.0.0`",
                from.join(f).display()
            );
        }
    }
}
