//! # vbi — vehicle–bridge interaction dynamics
//!
//! A pure library: physics and numerics only. It reads no files, prints nothing and keeps no
//! global state; the `vbi` command (crate `vbi-cli`) does all input and output.
//!
//! The pipeline runs one stage per module, each a function from one owned type to the next;
//! [`pipeline`] strings them together from a typed [`pipeline::Scenario`], the one path that the
//! `vbi` command, the benchmarks and the Python bindings call:
//!
//! ```text
//! pipeline::prepare_bridge:  BridgeModel -fe::discretise-> FeModel -modal::solve_modes-> ModalBasis
//!                                                                  -fe::statics-> InfluenceLines
//! pipeline::run_crossing:    VehicleModel + RoadProfile (road::generate) + ModalBasis
//!                            -solver::simulate-> ResponseHistory -analysis::analyse-> DafReport
//! ```
//!
//! Units: SI throughout (m, kg, s, N, Pa, rad). Any other unit is converted once at input by
//! the caller, with the named factors in [`units`].
//!
//! Method: Zhou et al., "Comparison of dynamic amplification factor of deflection and bending
//! moment of highway continuous box-girder bridges by mode superposition" (the paper); equation
//! numbers in doc comments refer to it.

pub mod analysis;
pub mod analytical;
mod bits;
pub mod codes;
pub mod deck;
pub mod fe;
pub mod influence;
pub mod linalg;
pub mod modal;
pub mod model;
pub mod pipeline;
pub mod road;
pub mod signal;
pub mod solver;
mod spectral;
pub mod study;
pub mod units;
pub mod vehicle;
