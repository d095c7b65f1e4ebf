//! `vbi check`: exit codes and messages for good and bad files.

use crate::common::vbi;

#[test]
fn check_of_an_unknown_kind_of_file_exits_2_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mystery.toml");
    std::fs::write(&path, "[mystery]\nx = 1\n").unwrap();
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("mystery.toml:1:1"), "{stderr}");
    assert!(stderr.contains("[bridge]"), "{stderr}");
}

#[test]
fn check_of_a_toml_syntax_error_names_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.toml");
    std::fs::write(&path, "[bridge]\nspans = [30.0,\n").unwrap();
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("broken.toml:"), "{stderr}");
}

#[test]
fn check_of_a_missing_file_exits_2() {
    vbi().args(["check", "no/such/file.toml"]).assert().code(2);
}
