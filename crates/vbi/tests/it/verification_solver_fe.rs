//! Verification of the coupled solver on FE modal bases against the analytical module.
