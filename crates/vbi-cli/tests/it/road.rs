//! End-to-end tests of `vbi road` and its inputs.
