//! Verification of the `vehicle` stage.
