//! Verification of the `fe` stage.
