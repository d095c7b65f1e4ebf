//! End-to-end tests of the `vbi` binary (one test binary, one module per command).

mod check;
mod common;
