//! Verification of the `modal` stage.
