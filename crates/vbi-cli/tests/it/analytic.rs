//! End-to-end tests of `vbi analytic` and its inputs.
