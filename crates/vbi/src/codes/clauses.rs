//! The design codes' dynamic allowances, one function per clause, each as the clause states it.
//!
//! Every function returns the impact factor IM (also written μ or DLA) as a fraction [-]: the
//! design dynamic response is (1 + IM) times the static one, which is what vbi's DAF measures.
//! Each clause lives in its code's file (`codes/jtg_d60.rs`, `codes/jtj_021.rs`, ...) beside
//! the code's registry entry; this module gathers them under one path. The worked examples of
//! their tests are recorded in docs/verification.md §25 and docs/design-codes.md, with the
//! clause each comes from.

pub use super::aashto_lrfd::{aashto_lrfd_dynamic_load_allowance, LrfdCase};
pub use super::aashto_standard::{aashto_standard_impact_fraction, FOOT};
pub use super::as_5100::{as_5100_dynamic_load_allowance, As5100Load};
pub use super::csa_s6::{
    cl_w_axles_within, csa_s6_allowance_of_loaded_length, csa_s6_dynamic_load_allowance,
    CL_W_AXLE_SPACINGS,
};
pub use super::en_1991_2::{
    en_1991_2_fatigue_impact_factor, en_1991_2_joint_factor, EurocodeRoughness,
};
pub use super::jtg_d60::{jtg_d60_frequency, jtg_d60_impact_factor, JtgFrequencyFormula};
pub use super::jtj_021::{jtj_021_impact_factor, Jtj021Superstructure};
