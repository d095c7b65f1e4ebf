//! Verification of the `signal` stage.
