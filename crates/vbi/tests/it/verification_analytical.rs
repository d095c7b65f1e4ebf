//! Verification of the `analytical` stage.
