//! Verification of the `road` stage.
