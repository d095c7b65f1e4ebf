//! A fatigue detail: where it is (a station and the effect that stresses it), how the effect
//! becomes its stress, and its fatigue strength curve; and the damage of an effect history there,
//! dynamic against static.

use super::damage::{DamageSum, FatigueAmplification};
use super::rainflow::RainflowCounter;
use super::sn_curve::SnCurve;
use crate::model::station::Quantity;

/// A fatigue detail of the bridge.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FatigueDetail {
    /// The detail's name, for reports (`bottom_flange_mid_span`).
    pub name: String,
    /// The name of the station whose effect stresses it.
    pub station: String,
    /// The effect: the bending moment (direct stress) or the shear force (shear stress).
    pub quantity: Quantity,
    /// The nominal stress per unit effect at the detail's fibre [Pa per N·m, or Pa per N]:
    /// (ȳ − y)/I or Q/(I t_w) ([`super::section::GirderSection`]), or 1/W as given.
    pub stress_per_effect: f64,
    /// The stress-concentration factor k_f on the nominal stress [-] (EN 1993-1-9 §6.3(1)
    /// and Table 6.1's geometric stress concentrations; 1 where the category includes them).
    pub stress_concentration: f64,
    /// Where on the section, in words, for reports ("bottom flange", "weld toe", "0.35 m").
    pub fibre: String,
    /// The fatigue strength curve.
    pub curve: SnCurve,
}

impl FatigueDetail {
    /// The stress at the detail under an effect [Pa]: k_f × stress per effect × effect.
    pub fn stress(&self, effect: f64) -> f64 {
        self.stress_concentration * self.stress_per_effect * effect
    }
}

/// A detail's counted cycles and damage under one effect history: what one crossing, or any
/// stretch of a traffic history, does to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryDamage {
    /// The cycles and Miner's sum.
    pub sum: DamageSum,
    /// The largest stress of the history, signed [Pa] (tension positive).
    pub max_stress: f64,
    /// The smallest stress, signed [Pa].
    pub min_stress: f64,
}

impl HistoryDamage {
    /// Rainflow counting (ASTM E1049-85 §5.4.4) of the detail's stress under `effect` [the
    /// effect's SI unit per instant], and Miner's sum on its curve.
    pub fn of(detail: &FatigueDetail, effect: &[f64]) -> HistoryDamage {
        let mut sum = DamageSum::new(detail.curve);
        let mut counter = RainflowCounter::new();
        let (mut max_stress, mut min_stress) = (f64::NEG_INFINITY, f64::INFINITY);
        for &value in effect {
            let stress = detail.stress(value);
            max_stress = max_stress.max(stress);
            min_stress = min_stress.min(stress);
            counter.push(stress, |cycle| sum.add(cycle));
        }
        counter.finish(|cycle| sum.add(cycle));
        if effect.is_empty() {
            (max_stress, min_stress) = (0.0, 0.0);
        }
        HistoryDamage {
            sum,
            max_stress,
            min_stress,
        }
    }
}

/// The fatigue of one detail under one crossing: the dynamic (converged, static-corrected)
/// history against the exact static one.
#[derive(Debug, Clone, PartialEq)]
pub struct DetailFatigue {
    /// The detail.
    pub detail: FatigueDetail,
    /// The detail's curve in words ([`SnCurve::label`]).
    pub curve_label: String,
    /// The dynamic history's cycles and damage.
    pub dynamic: HistoryDamage,
    /// The static history's cycles and damage.
    pub static_history: HistoryDamage,
    /// The damage ratio and the fatigue DAFs.
    pub amplification: FatigueAmplification,
    /// Their convergence indicator in the modes, where the crossing computed it.
    pub convergence: Option<FatigueConvergence>,
}

/// The convergence indicator of a detail's fatigue DAFs in the modes: the largest change of the
/// DAF with the first K modes (the static-corrected partial sum) from the DAF with all N, over
/// the last ⌈N/2⌉ modes kept (K = N − ⌈N/2⌉ … N − 1), or twice its change with the check modes
/// added after the N where larger, as the peak DAF's indicator reads its series (docs/theory.md,
/// convergence).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FatigueConvergence {
    /// ⌈N/2⌉: the modes the change is taken over.
    pub window: usize,
    /// max |fatigue DAF(K) − fatigue DAF(N)|; None where a DAF on the curve is undefined.
    pub fatigue_daf_change: Option<f64>,
    /// The same of the fatigue DAF without cut-off.
    pub straight_line_change: Option<f64>,
}

impl DetailFatigue {
    /// The fatigue of `detail` under its effect's dynamic and static histories.
    pub fn of(detail: &FatigueDetail, dynamic: &[f64], static_history: &[f64]) -> DetailFatigue {
        let dynamic = HistoryDamage::of(detail, dynamic);
        let static_history = HistoryDamage::of(detail, static_history);
        DetailFatigue {
            detail: detail.clone(),
            curve_label: detail.curve.label(),
            amplification: FatigueAmplification::of(&dynamic.sum, &static_history.sum),
            convergence: None,
            dynamic,
            static_history,
        }
    }
}
