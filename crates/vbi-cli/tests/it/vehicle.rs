//! End-to-end tests of `vbi vehicle` and its inputs.
