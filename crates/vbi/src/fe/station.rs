//! Stations: the cross-sections of the FE model where responses are recorded, and the
//! quantities read there. The FE model defines them (with the functionals that read them,
//! [`StationFunctional`](super::StationFunctional)); the modal basis and the influence lines
//! carry copies.

use serde::{Deserialize, Serialize};

/// Which part of the cross-section a station reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "index")]
pub enum StationTarget {
    /// One girder (deck line index, 0 = rightmost).
    Girder(usize),
    /// The whole section: mean deflection of the girders, sum of their moments.
    Section,
}

/// A cross-section of interest where responses are recorded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Station {
    /// Name, for example `span1_mid_g2` or `support2_section`.
    pub name: String,
    /// Longitudinal position x [m] from the first support.
    pub position: f64,
    /// Girder or whole section.
    pub target: StationTarget,
    /// True over an interior support, where the moment of interest is hogging.
    pub over_support: bool,
}

/// Quantities recorded at stations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Vertical deflection [m], positive upwards.
    Deflection,
    /// Bending moment [N·m], positive sagging (tension at the bottom).
    BendingMoment,
}

impl Quantity {
    /// The quantity's name in outputs (its serde name).
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Deflection => "deflection",
            Quantity::BendingMoment => "bending_moment",
        }
    }
}
