//! End-to-end tests of `vbi run`.
