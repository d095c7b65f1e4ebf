//! The numbers the manual quotes are vbi's (issue 46, item 10): `scripts/doc_numbers` runs the
//! commands behind docs/paper-reproduction.md, docs/design-codes.md and the tutorial with the
//! `vbi` binary under test, computes every marked number and generated table from their outputs,
//! and fails when a page says otherwise, when a page's prose holds a decimal number that is
//! neither computed nor declared an input, or when a statement the page makes about the numbers
//! (`claim`) no longer holds. `python3 scripts/doc_numbers --write` rewrites the pages.
//!
//! It runs the paper's full study three times (about two minutes of a debug build on two cores).

use super::common::repository_root;

#[test]
fn every_documented_number_is_what_the_script_computes_from_vbis_outputs() {
    let root = repository_root();
    let vbi = assert_cmd::cargo::cargo_bin("vbi");
    let output = std::process::Command::new("python3")
        .arg(root.join("scripts/doc_numbers"))
        .arg("--vbi")
        .arg(&vbi)
        .output()
        .expect("python3 runs (the test command needs CPython 3, as CI has)");
    let printed = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        output.status.success(),
        "the manual and vbi's outputs disagree (`python3 scripts/doc_numbers --write` rewrites \
         the marked numbers; then read the prose around them):\n{printed}"
    );
}
