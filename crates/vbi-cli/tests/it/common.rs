//! Helpers shared by the end-to-end tests.

use std::path::PathBuf;

/// The `vbi` binary under test.
pub fn vbi() -> assert_cmd::Command {
    assert_cmd::Command::cargo_bin("vbi").expect("the vbi binary is built")
}

/// The repository root (for `examples/`).
#[allow(dead_code)]
pub fn repository_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `vbi check FILE` (which must pass) and `vbi measure FILE --out DIR`: its measure.json.
pub fn check_and_measure(file: &std::path::Path, out: &std::path::Path) -> serde_json::Value {
    vbi().arg("check").arg(file).assert().success();
    vbi()
        .arg("measure")
        .arg(file)
        .arg("--out")
        .arg(out)
        .assert()
        .success();
    let text = std::fs::read_to_string(out.join("measure.json")).expect("measure.json written");
    serde_json::from_str(&text).unwrap()
}
