//! The Grave vehicle model (Grave 2001, PhD thesis, Trinity College Dublin; BTLS manual,
//! "The Grave Traffic Model (Model 0)"; PyBTLS 1.0.1 `cpp/src/VehicleGenGrave.cpp`,
//! `cpp/src/VehModelDataGrave.cpp`; spec docs/design/btls-traffic-generator.md §3.1): a truck
//! of 2 to 5 axles whose gross weight, axle spacings and axle loads are drawn from bounded
//! normal mixtures fitted to weigh-in-motion records of a site.
//!
//! Draws of one truck, in this order: the class (one uniform against the block's cumulative
//! class fractions), the gross vehicle weight W (mixture of the lane's direction and the class,
//! bounds [`GROSS_WEIGHT_BOUNDS`]), each axle spacing front to back (bounds
//! [`AXLE_SPACING_BOUNDS`]), then the axle loads:
//! - 2 and 3 axles: a share sᵢ per axle (mixture, bounds [`AXLE_SHARE_BOUNDS`]), rescaled to the
//!   gross weight: Pᵢ = W sᵢ / Σⱼ sⱼ;
//! - 4 and 5 axles: the GVW band k of W (50 kN wide from 25 kN, [`TandemLoadShareTable`]) gives
//!   single normals of the front axle's share s₁, the second's s₂ and the rear group's s_T
//!   (tandem or tridem), each bounded; P₁ = W s₁/S, P₂ = W s₂/S, and each axle of the group
//!   carries W s_T/(S (n − 2)), S = s₁ + s₂ + s_T.
//!
//! The only correlations are the loads' shares of W and, for 4 and 5 axles, their dependence on
//! the band of W; spacings and W are independent. Track widths are not drawn (vbi's lifetime
//! vehicles are planar), nor cars: a 2-axle vehicle below 35 × 100 kg, the model's lower GVW
//! bound, is what BTLS counts as a car (34.3 kN), and vbi generates trucks only.
//!
//! BTLS's bounds act on the file's values. The axle-load files hold percentages of the gross
//! weight, so BTLS's bounds [15, 500] (meant for 100 kg) cut every share below 15 %: the
//! Auxerre 4-axle top band's front share 13.9 ± 0.7 % is drawn above 15 % only (a normal
//! truncated there). vbi reproduces this, so that its trucks are BTLS's; the bounds are data
//! ([`TandemLoadShareTable::share_lower_bound`], each mixture's bounds), not code.

use serde::{Deserialize, Serialize};

use super::mixture::{bounded_draw, standard_normal, NormalMixture};
use super::GeneratorError;
use crate::road::SampleRng;
use crate::traffic::TravelDirection;
use crate::units::{DM, HUNDRED_KG_WEIGHT, KN};

/// The axle counts of the model's four truck classes; arrays by class are indexed axles − 2.
pub const AXLE_COUNTS: [usize; 4] = [2, 3, 4, 5];

/// Bounds of a truck's gross weight [N]: BTLS's [35, 1000] × 100 kg (`VehicleGenGrave.cpp`,
/// `GenerateCommonProps`), 34.3 kN to 981 kN.
pub const GROSS_WEIGHT_BOUNDS: (f64, f64) = (35.0 * HUNDRED_KG_WEIGHT, 1000.0 * HUNDRED_KG_WEIGHT);

/// Bounds of an axle spacing [m]: BTLS's [0.5, 200] dm.
pub const AXLE_SPACING_BOUNDS: (f64, f64) = (0.5 * DM, 200.0 * DM);

/// Bounds of an axle-load share [-, fraction of the gross weight]: BTLS's [15, 500] applied to
/// the files' percentages, 0.15 to 5 (see the module's description).
pub const AXLE_SHARE_BOUNDS: (f64, f64) = (0.15, 5.0);

/// Gross weight at which the first band of the 4- and 5-axle load-share tables starts [N]
/// (BTLS: band k covers [25 + 50 (k − 1), 25 + 50 k) kN, `VehicleGenGrave.cpp`,
/// `GenerateTruck45`).
pub const GVW_BAND_START: f64 = 25.0 * KN;

/// Width of a band of the 4- and 5-axle load-share tables [N].
pub const GVW_BAND_WIDTH: f64 = 50.0 * KN;

/// The load shares of a 4- or 5-axle truck in one GVW band: single normals of the front axle's
/// share s₁, the second axle's s₂ and the rear group's (tandem or tridem) total s_T, fractions
/// of the gross weight [-] (BTLS's `AW4&5.csv` row, in % there).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GvwBandLoadShares {
    /// Means of s₁, s₂, s_T [-]; zero or positive. All three zero: the band has no data.
    pub mean: [f64; 3],
    /// Standard deviations of s₁, s₂, s_T [-]; zero or positive.
    pub standard_deviation: [f64; 3],
}

impl GvwBandLoadShares {
    /// Whether the band holds data (a mean above zero); site files fill bands that no truck
    /// reached with zeros.
    pub fn has_data(&self) -> bool {
        self.mean.iter().any(|&m| m > 0.0)
    }
}

/// The load shares of 4- or 5-axle trucks by GVW band: band i covers gross weights in
/// [25 kN + 50 kN·i, 25 kN + 50 kN·(i + 1)) ([`GVW_BAND_START`], [`GVW_BAND_WIDTH`]); the first
/// band also takes lighter trucks and the last one heavier ones (BTLS's 11 bands: the last from
/// 525 kN). A band without data ([`GvwBandLoadShares::has_data`]) gives way to the nearest band
/// below with data, else above (BTLS would redraw zeros against its bounds without end).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TandemLoadShareTable {
    /// The bands, lightest first; at least one with data.
    pub bands: Vec<GvwBandLoadShares>,
    /// Smallest share accepted [-]; positive ([`AXLE_SHARE_BOUNDS`] as BTLS).
    pub share_lower_bound: f64,
    /// Largest share accepted [-].
    pub share_upper_bound: f64,
}

impl TandemLoadShareTable {
    /// The band whose shares a truck of gross weight `gross_weight` [N] draws.
    pub fn band(&self, gross_weight: f64) -> Option<&GvwBandLoadShares> {
        let last = self.bands.len().checked_sub(1)?;
        let index = ((gross_weight - GVW_BAND_START) / GVW_BAND_WIDTH).floor();
        let index = if index.is_finite() {
            index.clamp(0.0, last as f64) as usize
        } else {
            0
        };
        self.bands[..=index]
            .iter()
            .rev()
            .chain(self.bands[index..].iter())
            .find(|b| b.has_data())
    }

    /// What is wrong with the table, named `field`.
    pub fn check(&self, field: &str) -> Result<(), GeneratorError> {
        for (i, band) in self.bands.iter().enumerate() {
            let values = band.mean.iter().chain(&band.standard_deviation);
            if values.clone().any(|v| !(v.is_finite() && *v >= 0.0)) {
                return Err(GeneratorError::new(
                    format!("{field}.bands[{i}]"),
                    "a band's share means and standard deviations must be zero or positive",
                ));
            }
        }
        if !self.bands.iter().any(GvwBandLoadShares::has_data) {
            return Err(GeneratorError::new(
                format!("{field}.bands"),
                "the table needs at least one band with a share mean above zero",
            ));
        }
        let (low, high) = (self.share_lower_bound, self.share_upper_bound);
        if !(low.is_finite() && high.is_finite() && low > 0.0 && low < high) {
            return Err(GeneratorError::new(
                format!("{field}.share_lower_bound"),
                format!(
                    "the share bounds must be finite with 0 < lower < upper, got [{low}, {high}]"
                ),
            ));
        }
        Ok(())
    }
}

/// The parameters of the Grave vehicle model for one site, in SI units (BTLS's files converted
/// once at input: 100 kg → 981 N, dm → m, % → fraction).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GraveParameters {
    /// Gross vehicle weight W [N] by direction (index 0: direction 1, forward; 1: direction 2,
    /// backward) and class (index axles − 2), bounds [`GROSS_WEIGHT_BOUNDS`] (`GVWpdf.csv`).
    /// PyBTLS 1.0.1 draws every truck from direction 2's (its `GetGVW` returns direction 2's
    /// law for any direction but 1, and `m_CurDirection` is never set: measured against its
    /// generator in `crates/vbi-py/tests/test_generator_pybtls.py`); vbi uses the lane's
    /// direction, as intended.
    pub gross_weight: [[NormalMixture; 4]; 2],
    /// Axle spacings [m] by class (index axles − 2): the n − 1 spacings of an n-axle truck, front
    /// first, bounds [`AXLE_SPACING_BOUNDS`] (`ASall.csv`).
    pub axle_spacings: [Vec<NormalMixture>; 4],
    /// Axle-load shares of 2-axle trucks [-]: one mixture per axle (`AW2&3.csv`).
    pub two_axle_load_shares: Vec<NormalMixture>,
    /// Axle-load shares of 3-axle trucks [-]: one mixture per axle (`AW2&3.csv`).
    pub three_axle_load_shares: Vec<NormalMixture>,
    /// Load shares of 4-axle trucks (front, second, tandem) by GVW band (`AW4&5.csv`).
    pub four_axle_load_shares: TandemLoadShareTable,
    /// Load shares of 5-axle trucks (front, second, tridem) by GVW band (`AW4&5.csv`).
    pub five_axle_load_shares: TandemLoadShareTable,
}

/// One truck of the Grave model.
#[derive(Debug, Clone, PartialEq)]
pub struct GraveTruck {
    /// Gross vehicle weight [N]: the sum of the axle loads.
    pub gross_weight: f64,
    /// Distance from each axle to the next [m], front first (one fewer than the axles).
    pub axle_spacings: Vec<f64>,
    /// Static load of each axle [N], front first.
    pub axle_loads: Vec<f64>,
}

fn direction_index(direction: TravelDirection) -> usize {
    match direction {
        TravelDirection::Forward => 0,
        TravelDirection::Backward => 1,
    }
}

impl GraveParameters {
    /// What is wrong with the parameters: each mixture valid ([`NormalMixture::check`]), n − 1
    /// spacings for n axles, 2 and 3 share mixtures, valid band tables; gross weights, spacings
    /// and shares with a positive lower bound (a truck's spacings and loads must be positive).
    pub fn check(&self) -> Result<(), GeneratorError> {
        for (d, by_class) in self.gross_weight.iter().enumerate() {
            for (c, mixture) in by_class.iter().enumerate() {
                let field = format!("gross_weight[direction {}][{} axles]", d + 1, c + 2);
                check_positive_mixture(mixture, &field)?;
            }
        }
        for (c, spacings) in self.axle_spacings.iter().enumerate() {
            let axles = AXLE_COUNTS[c];
            if spacings.len() != axles - 1 {
                return Err(GeneratorError::new(
                    format!("axle_spacings[{axles} axles]"),
                    format!(
                        "{axles} axles need {} spacings, got {}",
                        axles - 1,
                        spacings.len()
                    ),
                ));
            }
            for (i, mixture) in spacings.iter().enumerate() {
                check_positive_mixture(mixture, &format!("axle_spacings[{axles} axles][{i}]"))?;
            }
        }
        for (name, shares, axles) in [
            ("two_axle_load_shares", &self.two_axle_load_shares, 2),
            ("three_axle_load_shares", &self.three_axle_load_shares, 3),
        ] {
            if shares.len() != axles {
                return Err(GeneratorError::new(
                    name,
                    format!(
                        "{axles} axles need {axles} share mixtures, got {}",
                        shares.len()
                    ),
                ));
            }
            for (i, mixture) in shares.iter().enumerate() {
                check_positive_mixture(mixture, &format!("{name}[{i}]"))?;
            }
        }
        self.four_axle_load_shares.check("four_axle_load_shares")?;
        self.five_axle_load_shares.check("five_axle_load_shares")
    }

    /// The class of the next truck: one uniform u against the cumulative fractions of 2, 3, 4
    /// and 5 axles (the first class whose cumulative fraction exceeds u; the last class of
    /// positive fraction when rounding leaves u above them all). Returns the axle count.
    pub fn draw_axle_count(class_fractions: &[f64; 4], rng: &mut SampleRng) -> usize {
        let u = rng.next_unit();
        let mut cumulative = 0.0;
        for (c, fraction) in class_fractions.iter().enumerate() {
            cumulative += fraction;
            if u < cumulative {
                return AXLE_COUNTS[c];
            }
        }
        let last = class_fractions.iter().rposition(|&f| f > 0.0).unwrap_or(3);
        AXLE_COUNTS[last]
    }

    /// The next truck of a lane of `direction` whose block has `class_fractions` (2, 3, 4, 5
    /// axles): class, gross weight, spacings and axle loads, in the module's draw order.
    pub fn draw_truck(
        &self,
        direction: TravelDirection,
        class_fractions: &[f64; 4],
        rng: &mut SampleRng,
    ) -> GraveTruck {
        let axles = Self::draw_axle_count(class_fractions, rng);
        let class = axles - 2;
        let gross_weight = self.gross_weight[direction_index(direction)][class].sample(rng);
        let axle_spacings = self.axle_spacings[class]
            .iter()
            .map(|m| m.sample(rng))
            .collect();
        let axle_loads = match axles {
            2 => shared_loads(&self.two_axle_load_shares, gross_weight, rng),
            3 => shared_loads(&self.three_axle_load_shares, gross_weight, rng),
            4 => group_loads(&self.four_axle_load_shares, gross_weight, axles, rng),
            _ => group_loads(&self.five_axle_load_shares, gross_weight, axles, rng),
        };
        GraveTruck {
            gross_weight,
            axle_spacings,
            axle_loads,
        }
    }
}

/// A mixture valid for a quantity that must stay positive (lower bound above zero).
fn check_positive_mixture(mixture: &NormalMixture, field: &str) -> Result<(), GeneratorError> {
    mixture.check(field)?;
    if mixture.lower_bound > 0.0 {
        Ok(())
    } else {
        Err(GeneratorError::new(
            format!("{field}.lower_bound"),
            format!(
                "the lower bound must be positive, got {}",
                mixture.lower_bound
            ),
        ))
    }
}

/// Axle loads [N] of a 2- or 3-axle truck: a share per axle, rescaled to the gross weight.
fn shared_loads(shares: &[NormalMixture], gross_weight: f64, rng: &mut SampleRng) -> Vec<f64> {
    let drawn: Vec<f64> = shares.iter().map(|m| m.sample(rng)).collect();
    let total: f64 = drawn.iter().sum();
    drawn.iter().map(|s| gross_weight * s / total).collect()
}

/// Axle loads [N] of a 4- or 5-axle truck: front, second and rear-group shares of its GVW band,
/// rescaled to the gross weight, the group's load split equally over its axles.
fn group_loads(
    table: &TandemLoadShareTable,
    gross_weight: f64,
    axles: usize,
    rng: &mut SampleRng,
) -> Vec<f64> {
    let band = table
        .band(gross_weight)
        .copied()
        .unwrap_or(GvwBandLoadShares {
            mean: [1.0; 3],
            standard_deviation: [0.0; 3],
        });
    let mut shares = [0.0; 3];
    for (share, (mean, sd)) in shares
        .iter_mut()
        .zip(band.mean.iter().zip(&band.standard_deviation))
    {
        *share = bounded_draw(
            rng,
            table.share_lower_bound,
            table.share_upper_bound,
            |rng| mean + sd * standard_normal(rng),
        );
    }
    let total: f64 = shares.iter().sum();
    let group = gross_weight * shares[2] / total / (axles - 2) as f64;
    let mut loads = vec![
        gross_weight * shares[0] / total,
        gross_weight * shares[1] / total,
    ];
    loads.resize(axles, group);
    loads
}
