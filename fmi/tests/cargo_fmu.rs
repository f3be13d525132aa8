//! `cargo fmu` as a user runs it: with `CARGO_TARGET_DIR` set, the
//! archives go under that folder, and the last line says where.

mod support;

#[test]
fn with_cargo_target_dir_the_last_line_says_where_the_fmus_went() {
    let target = support::python_peers::target_dir();
    let workspace = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cargo-fmu"))
        .args(["fmu", "-p", "daegen-fmi", "--example", "van_der_pol_fmu"])
        .env("CARGO_TARGET_DIR", &target)
        .current_dir(&workspace)
        .output()
        .expect("cargo fmu runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    let dir = std::fs::canonicalize(target.join("fmu")).unwrap();
    let last = stdout.lines().last().unwrap_or("");
    assert_eq!(
        last,
        format!(
            "2 FMUs written to {} (fmu/ under CARGO_TARGET_DIR, cargo's target directory; --out DIR writes elsewhere)",
            dir.display()
        )
    );
    assert!(
        dir.join("van_der_pol_fmu.fmu").exists() && dir.join("van_der_pol_fmu_fmi2.fmu").exists()
    );
}
