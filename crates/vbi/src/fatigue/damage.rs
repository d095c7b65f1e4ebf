//! Miner's sum of a history's cycles on a detail's curve, with what the fatigue DAF and the
//! equivalent stress ranges need.
//!
//! Palmgren–Miner linear damage accumulation (Miner, "Cumulative damage in fatigue", J. Appl.
//! Mech. 12, 1945; EN 1993-1-9:2005 Annex A, A.5, Eq. (A.1)): D = Σᵢ nᵢ / N_R(Δσᵢ).

use super::rainflow::Cycle;
use super::sn_curve::SnCurve;

/// The damage of the cycles of one stress history (or of many, summed) on one curve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DamageSum {
    /// The curve the damage is read on.
    #[serde(skip)]
    pub curve: SnCurve,
    /// Miner's sum D = Σ nᵢ/N_R(Δσᵢ) [-].
    pub damage: f64,
    /// The number of cycles counted, half cycles as 0.5 [-].
    pub cycles: f64,
    /// The number of cycles at or above the curve's cut-off: those that do damage [-].
    pub damaging_cycles: f64,
    /// The largest range counted [Pa].
    pub max_range: f64,
    /// Σ nᵢ Δσᵢ^m with the curve's slope m at 2 × 10⁶ cycles and no cut-off [Pa^m]: the damage
    /// on a single straight line, which the cut-off-free fatigue DAF reads.
    pub range_moment: f64,
}

impl DamageSum {
    /// No cycles yet.
    pub fn new(curve: SnCurve) -> DamageSum {
        DamageSum {
            curve,
            damage: 0.0,
            cycles: 0.0,
            damaging_cycles: 0.0,
            max_range: 0.0,
            range_moment: 0.0,
        }
    }

    /// Adds a cycle (or half cycle) of a stress history [Pa].
    pub fn add(&mut self, cycle: Cycle) {
        let damage = self.curve.damage(cycle.range, cycle.count);
        self.damage += damage;
        self.cycles += cycle.count;
        if damage > 0.0 {
            self.damaging_cycles += cycle.count;
        }
        self.max_range = self.max_range.max(cycle.range);
        self.range_moment += cycle.count * cycle.range.powf(self.curve.slope());
    }

    /// The equivalent constant-amplitude range at 2 × 10⁶ cycles, Δσ_E,2 = Δσ_C D^{1/m} [Pa]
    /// ([`SnCurve::equivalent_range_2e6`]).
    pub fn equivalent_range_2e6(&self) -> f64 {
        self.curve.equivalent_range_2e6(self.damage)
    }

    /// The damage-equivalent range of the cycles counted, on a straight line of slope m without
    /// a cut-off: Δσ_eq = (Σ nᵢ Δσᵢ^m / Σ nᵢ)^{1/m} [Pa] (EN 1993-1-9 Annex A, A.5; 0 without
    /// cycles).
    pub fn equivalent_range(&self) -> f64 {
        if self.cycles > 0.0 {
            (self.range_moment / self.cycles).powf(1.0 / self.curve.slope())
        } else {
            0.0
        }
    }
}

/// The fatigue amplification of a dynamic stress history over its static one on one curve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FatigueAmplification {
    /// D_dynamic / D_static on the detail's curve; None where the static history does no
    /// damage (every static range below the cut-off).
    pub damage_ratio: Option<f64>,
    /// The fatigue DAF (D_dynamic / D_static)^{1/m}, m the curve's slope at 2 × 10⁶ cycles: the
    /// factor on the static stress ranges that gives the dynamic damage where every range lies
    /// on the m line; None with the damage ratio.
    pub fatigue_daf: Option<f64>,
    /// The same root on a straight line of slope m without a cut-off,
    /// (Σ n Δσ^m)_dynamic / (Σ n Δσ^m)_static)^{1/m}: defined wherever the static history has
    /// a range, whatever the detail's category (the ratio of the equivalent ranges at equal
    /// cycle counts is not: dynamics add cycles).
    pub fatigue_daf_straight_line: Option<f64>,
}

impl FatigueAmplification {
    /// The amplification of `dynamic` over `static_sum`, both on the same curve.
    pub fn of(dynamic: &DamageSum, static_sum: &DamageSum) -> FatigueAmplification {
        let m = dynamic.curve.slope();
        let damage_ratio = (static_sum.damage > 0.0).then(|| dynamic.damage / static_sum.damage);
        FatigueAmplification {
            damage_ratio,
            fatigue_daf: damage_ratio.map(|r| r.powf(1.0 / m)),
            fatigue_daf_straight_line: (static_sum.range_moment > 0.0)
                .then(|| (dynamic.range_moment / static_sum.range_moment).powf(1.0 / m)),
        }
    }
}
