//! End-to-end tests of `vbi modes` and its inputs.
