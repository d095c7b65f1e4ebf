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
