//! Time gaps between the arrivals of one lane: the headway models (spec
//! docs/design/btls-traffic-generator.md §2; PyBTLS 1.0.1 `cpp/src/FlowGenerator.cpp`) and the
//! minimum gap that keeps a truck from catching the one ahead on the bridge (§1,
//! `FlowGenerator.cpp:103-139`).

use serde::{Deserialize, Serialize};

use super::GeneratorError;
use crate::road::SampleRng;

/// The clear distance B_s kept behind the truck ahead [m] (BTLS's buffer gap space,
/// `FlowModelData.cpp:7`).
pub const MIN_GAP_SPACE: f64 = 1.0;

/// The time B_t added to the minimum gap [s] (BTLS's buffer gap time), also the smallest
/// minimum gap and the first truck's.
pub const MIN_GAP_TIME: f64 = 0.1;

/// The gap after which HeDS's exponential tail starts [s].
pub const HEDS_TAIL_START: f64 = 4.0;

/// The upper end of HeDS's first quadratic [s].
pub const HEDS_SHORT_END: f64 = 1.0;

/// The upper end of HeDS's second quadratic [s].
pub const HEDS_MEDIUM_END: f64 = 1.5;

/// The smallest time gap [s] from the arrival of truck a (the one ahead) to that of truck b
/// (the next), so that b stays at least B_s + B_t v_b behind a's last axle while b's front axle
/// is within the no-overlap length L (the bridge): with T_g = (L_a + B_s)/v_b + B_t, L_a the
/// wheelbase of a,
/// - v_b ≤ v_a: g_min = T_g (the gap only grows);
/// - v_b > v_a: g_min = max(B_t, (T_g v_b + L)/v_a − L/v_b) (b closes in until its front
///   reaches L).
///
/// The first truck of a lane (no `ahead`) has g_min = B_t. Speeds [m/s], lengths [m].
pub fn minimum_gap(ahead: Option<(f64, f64)>, speed: f64, no_overlap_length: f64) -> f64 {
    let Some((ahead_speed, ahead_wheelbase)) = ahead else {
        return MIN_GAP_TIME;
    };
    let tg = (ahead_wheelbase + MIN_GAP_SPACE) / speed + MIN_GAP_TIME;
    if speed <= ahead_speed {
        tg
    } else {
        let closing = (tg * speed + no_overlap_length) / ahead_speed - no_overlap_length / speed;
        closing.max(MIN_GAP_TIME)
    }
}

/// A quadratic cumulative distribution of the gap t [s] over one range of HeDS:
/// F(t) = a t² + b t + c.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct QuadraticCdf {
    /// a [1/s²].
    pub a: f64,
    /// b [1/s].
    pub b: f64,
    /// c [-].
    pub c: f64,
}

impl QuadraticCdf {
    /// F(t).
    pub fn at(&self, t: f64) -> f64 {
        (self.a * t + self.b) * t + self.c
    }

    /// F′(t) [1/s].
    pub fn slope(&self, t: f64) -> f64 {
        2.0 * self.a * t + self.b
    }

    /// The gap t with F(t) = u on the rising branch of the parabola (where F′ ≥ 0): the root
    /// t = (−b + √D)/(2a), D = b² − 4a(c − u), which is the root that BTLS's `inv_quad` returns
    /// (`Generator.cpp:18-36`); computed as 2(u − c)/(b + √D) when b ≥ 0 (no cancellation, and
    /// exact for a = 0). D < 0 (u beyond the vertex) gives the vertex. Not below 0.
    pub fn inverse(&self, u: f64) -> f64 {
        let (a, b, c) = (self.a, self.b, self.c - u);
        let root_d = (b * b - 4.0 * a * c).max(0.0).sqrt();
        let t = if b >= 0.0 {
            if b + root_d > 0.0 {
                -2.0 * c / (b + root_d)
            } else {
                0.0
            }
        } else {
            (-b + root_d) / (2.0 * a)
        };
        if t.is_finite() {
            t.max(0.0)
        } else {
            0.0
        }
    }

    fn finite(&self) -> bool {
        self.a.is_finite() && self.b.is_finite() && self.c.is_finite()
    }
}

/// One flow row of HeDS: the quadratic CDF of gaps from 1.5 s to 4 s for lanes whose truck flow
/// is at most `flow_upper`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HedsFlowRow {
    /// The largest truck flow of the row [veh/h]; rows rise strictly.
    pub flow_upper: f64,
    /// F(t) for 1.5 s < t ≤ 4 s.
    pub cdf: QuadraticCdf,
}

/// The Headway Distribution Statistics model of trucks (HeDS, formerly "NHM"; O'Brien &
/// Caprani 2005, The Structural Engineer 83(16); BTLS `FlowGenerator.cpp:156-198`, its
/// `HeDS.csv`): measured gap distributions as three quadratic CDFs and an exponential tail.
///
/// With Q the lane's truck flow [veh/h], r the first row with Q ≤ Q_upper (the last row when Q
/// exceeds them all: vbi's fix of BTLS reading past its table), u₁ = F₁(1 s),
/// u₁.₅ = F₂(1.5 s), u₄ = F_r(4 s), a uniform u gives the gap
/// - u ≤ u₁: F₁⁻¹(u); u ≤ u₁.₅: F₂⁻¹(u); u ≤ u₄: F_r⁻¹(u) ([`QuadraticCdf::inverse`]);
/// - u > u₄: 4 s + E, E exponential of mean 3600/Q s: the exponential conditioned on ≥ 4 s,
///   which BTLS draws by redrawing (the same law, by memorylessness, in one draw). BTLS uses the
///   total flow (trucks and cars) there; vbi the truck flow, as the model's original code did
///   (spec §2: HeDS generates trucks only).
///
/// So the gap's CDF is F₁, F₂, F_r on [0, 1], (1, 1.5], (1.5, 4] s and
/// 1 − (1 − u₄) e^{−(t − 4)Q/3600} beyond ([`HedsTable::cdf`]) when the pieces join.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HedsTable {
    /// F₁(t) for t ≤ 1 s.
    pub below_one_second: QuadraticCdf,
    /// F₂(t) for 1 s < t ≤ 1.5 s.
    pub one_to_one_and_a_half_seconds: QuadraticCdf,
    /// F_r by truck flow, rising flows; at least one row.
    pub by_flow: Vec<HedsFlowRow>,
}

impl HedsTable {
    /// The flow row that a lane of truck flow `truck_flow` [veh/h] uses: the first with
    /// Q ≤ Q_upper, else the last.
    pub fn row(&self, truck_flow: f64) -> Option<&HedsFlowRow> {
        self.by_flow
            .iter()
            .find(|r| truck_flow <= r.flow_upper)
            .or(self.by_flow.last())
    }

    /// The model's CDF of the gap t [s] at truck flow Q [veh/h] (see the type's description).
    pub fn cdf(&self, t: f64, truck_flow: f64) -> f64 {
        let Some(row) = self.row(truck_flow) else {
            return f64::NAN;
        };
        if t <= HEDS_SHORT_END {
            self.below_one_second.at(t).max(0.0)
        } else if t <= HEDS_MEDIUM_END {
            self.one_to_one_and_a_half_seconds.at(t)
        } else if t <= HEDS_TAIL_START {
            row.cdf.at(t)
        } else {
            let u4 = row.cdf.at(HEDS_TAIL_START);
            1.0 - (1.0 - u4) * (-(t - HEDS_TAIL_START) * truck_flow / 3600.0).exp()
        }
    }

    /// One gap [s] at truck flow Q [veh/h]: one uniform, and one more in the tail.
    pub fn sample_gap(&self, truck_flow: f64, rng: &mut SampleRng) -> f64 {
        let u = rng.next_unit();
        let Some(row) = self.row(truck_flow) else {
            return HEDS_TAIL_START;
        };
        let u1 = self.below_one_second.at(HEDS_SHORT_END);
        let u15 = self.one_to_one_and_a_half_seconds.at(HEDS_MEDIUM_END);
        let u4 = row.cdf.at(HEDS_TAIL_START);
        if u > u4 {
            HEDS_TAIL_START + exponential(3600.0 / truck_flow, rng)
        } else if u <= u1 {
            self.below_one_second.inverse(u)
        } else if u <= u15 {
            self.one_to_one_and_a_half_seconds.inverse(u)
        } else {
            row.cdf.inverse(u)
        }
    }

    /// What is wrong with flow row `i`, if anything: a positive flow above the previous row's,
    /// finite coefficients, 0 ≤ F₁(1 s) ≤ F₂(1.5 s) ≤ F_r(4 s) ≤ 1 (the pieces in order) and
    /// each piece rising at its upper end (F₁′(1 s), F₂′(1.5 s), F_r′(4 s) positive, so that its
    /// inverse is defined up there).
    pub fn check_flow_row(&self, i: usize) -> Result<(), String> {
        let Some(row) = self.by_flow.get(i) else {
            return Err("the table needs at least one flow row".into());
        };
        let previous = i.checked_sub(1).map_or(0.0, |p| self.by_flow[p].flow_upper);
        if !(row.flow_upper.is_finite() && row.flow_upper > previous) {
            return Err(format!(
                "the flows must be positive and rise from row to row: {} veh/h after {previous} veh/h",
                row.flow_upper
            ));
        }
        let (f1, f2, fr) = (
            &self.below_one_second,
            &self.one_to_one_and_a_half_seconds,
            &row.cdf,
        );
        if !(f1.finite() && f2.finite() && fr.finite()) {
            return Err("the coefficients must be finite".into());
        }
        let (u1, u15, u4) = (
            f1.at(HEDS_SHORT_END),
            f2.at(HEDS_MEDIUM_END),
            fr.at(HEDS_TAIL_START),
        );
        if !(0.0 <= u1 && u1 <= u15 && u15 <= u4 && u4 <= 1.0) {
            return Err(format!(
                "the CDF must rise through its pieces: F1(1 s) = {u1}, F2(1.5 s) = {u15}, \
                 F(4 s) = {u4} must satisfy 0 <= F1(1 s) <= F2(1.5 s) <= F(4 s) <= 1"
            ));
        }
        let slopes = [
            f1.slope(HEDS_SHORT_END),
            f2.slope(HEDS_MEDIUM_END),
            fr.slope(HEDS_TAIL_START),
        ];
        if slopes.iter().any(|s| !(s.is_finite() && *s > 0.0)) {
            return Err(format!(
                "each quadratic must rise at the end of its range: F1'(1 s), F2'(1.5 s), F'(4 s) = \
                 {}, {}, {} [1/s] must be positive",
                slopes[0], slopes[1], slopes[2]
            ));
        }
        Ok(())
    }

    /// What is wrong with the table, if anything ([`HedsTable::check_flow_row`] for each row).
    pub fn check(&self) -> Result<(), GeneratorError> {
        if self.by_flow.is_empty() {
            return Err(GeneratorError::new(
                "heds.by_flow",
                "the table needs at least one flow row",
            ));
        }
        for i in 0..self.by_flow.len() {
            self.check_flow_row(i)
                .map_err(|m| GeneratorError::new(format!("heds.by_flow[{i}]"), m))?;
        }
        Ok(())
    }
}

/// An exponential deviate of mean μ [s]: −μ ln(1 − u), one uniform.
fn exponential(mean: f64, rng: &mut SampleRng) -> f64 {
    -mean * (1.0 - rng.next_unit()).ln()
}

/// How a lane's trucks are spaced in time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadwayModel {
    /// Free-flowing traffic: arrivals a Poisson process of the block's truck flow Q, gaps
    /// exponential of mean 3600/Q s, conditioned on the minimum gap ([`HeadwayModel::draw_gap`])
    /// (BTLS's model 6, "Poisson", `FlowGenerator.cpp:274-282`; BTLS draws cars too, at the
    /// total flow, vbi trucks only at the truck flow).
    FreeFlow,
    /// Measured gap distributions of trucks ([`HedsTable`]; BTLS's model 0).
    Heds(HedsTable),
    /// Every gap the same (BTLS's model 1), raised to the minimum gap where that is longer.
    Constant {
        /// The gap between arrivals [s]; positive.
        gap_s: f64,
    },
}

impl HeadwayModel {
    /// What is wrong with the model, if anything.
    pub fn check(&self) -> Result<(), GeneratorError> {
        match self {
            HeadwayModel::FreeFlow => Ok(()),
            HeadwayModel::Heds(table) => table.check(),
            HeadwayModel::Constant { gap_s } if gap_s.is_finite() && *gap_s > 0.0 => Ok(()),
            HeadwayModel::Constant { gap_s } => Err(GeneratorError::new(
                "headway.gap_s",
                format!("the constant gap must be a positive number of seconds, got {gap_s}"),
            )),
        }
    }

    /// The gap to the next arrival [s], at least `minimum_gap` g_min: BTLS redraws the model's
    /// gap until it reaches g_min, and after 10 000 draws takes g_min itself
    /// (`FlowGenerator.cpp:34-55`). HeDS does so here ([`MAX_REDRAWS`](super::MAX_REDRAWS)).
    /// The free-flow gap, an exponential conditioned on ≥ g_min, is by memorylessness
    /// g_min + E with E of the same mean: the same law in one draw, however high the flow. A
    /// constant gap below g_min is raised to it.
    pub fn draw_gap(&self, truck_flow: f64, minimum_gap: f64, rng: &mut SampleRng) -> f64 {
        let table = match self {
            HeadwayModel::Constant { gap_s } => return gap_s.max(minimum_gap),
            HeadwayModel::FreeFlow => return minimum_gap + exponential(3600.0 / truck_flow, rng),
            HeadwayModel::Heds(table) => table,
        };
        for _ in 0..super::MAX_REDRAWS {
            let gap = table.sample_gap(truck_flow, rng);
            if gap >= minimum_gap {
                return gap;
            }
        }
        minimum_gap
    }
}
