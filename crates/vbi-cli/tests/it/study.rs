//! End-to-end tests of `vbi study`.
