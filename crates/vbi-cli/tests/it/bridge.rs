//! End-to-end tests of `vbi bridge` and its inputs.
