//! Static influence lines, re-exported from [`crate::fe::influence`], where the static solve
//! ([`crate::fe::statics`]) that computes them lives. This path is kept for the consumers of the
//! influence lines (the DAF analysis, the solver, the pipeline).

pub use crate::fe::influence::InfluenceLines;
