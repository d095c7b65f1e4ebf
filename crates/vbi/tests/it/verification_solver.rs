//! Verification of the `solver` stage.
