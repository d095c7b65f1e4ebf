//! # vbi — vehicle–bridge interaction dynamics
//!
//! A pure library: physics and numerics only. It reads no files, prints nothing and keeps no
//! global state; the `vbi` command (crate `vbi-cli`) does all input and output.
//!
//! Physics at the bottom, one stage per module, each a function from one owned type to the
//! next; three applications on top, each the one path that the `vbi` command, the benchmarks
//! and the Python bindings call:
//!
//! - [`crossing`] (`vbi run`): a typed [`crossing::Scenario`] → [`crossing::RunResult`];
//! - [`measure`] (`vbi measure`): a [`measure::Measurement`] → [`measure::MeasurementResult`];
//! - [`study`] (`vbi study`): cases of crossings on prepared bridges → records and statistics;
//! - [`lifetime`] (`vbi lifetime`): a stream of recorded trucks → the static block maxima of
//!   every station (issue 48's static part; dynamics to come).
//!
//! Who is on the deck, where and when, has one home below the solver: [`traffic`].
//!
//! ```text
//! crossing::prepare_bridge:  BridgeModel -fe::discretise-> FeModel -modal::solve_modes-> ModalBasis
//!                                                                  -fe::statics-> InfluenceLines
//! crossing::run_crossing:    traffic::vehicle_runs + RoadProfile (road::generate) + ModalBasis
//!                            -solver::simulate-> ResponseHistory -analysis::analyse-> DafReport
//! ```
//!
//! Dependencies run one way: model, fe, modal, vehicle, road → traffic → solver → analysis,
//! codes, fatigue → crossing → measure, study, lifetime (a test keeps the module graph acyclic).
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
pub mod crossing;
pub mod deck;
pub mod fatigue;
pub mod fe;
pub mod influence;
pub mod lifetime;
pub mod linalg;
pub mod measure;
pub mod modal;
pub mod model;
pub mod outputs;
pub mod road;
pub mod signal;
pub mod solver;
mod spectral;
pub mod statistics;
pub mod study;
pub mod traffic;
pub mod units;
pub mod vehicle;
