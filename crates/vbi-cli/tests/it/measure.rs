//! End-to-end tests of `vbi measure` and its inputs.
