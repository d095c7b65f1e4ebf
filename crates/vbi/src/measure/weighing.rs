//! Bridge weigh-in-motion: the axle loads of a crossing vehicle from the bridge's own
//! response (issue 52, item 6).
//!
//! **Moses' algorithm** (Moses, 1979, "Weigh-in-motion system using instrumented bridges",
//! ASCE Transportation Engineering Journal 105(3) 233–249; OBrien, Quilligan and Karoumi,
//! 2006, Proc. ICE Bridge Engineering 159, eq. 1). A sensor's record under a vehicle of axles
//! at offsets d_a behind the first, crossing at speed v from the entry time t₀, is the static
//! response of its influence line IL_c under the unknown axle loads A_a plus the dynamic part
//! and the noise, which a least-squares fit averages out:
//!
//! ```text
//! y_c(t_k) ≈ Σ_a A_a·IL_c(v·(t_k − t₀) − d_a)             (Φ_c,ka = IL_c(v·(t_k − t₀) − d_a))
//! A = argmin Σ_c w_c²·‖Φ_c·A − y_c‖²  ⇒  (Σ_c w_c²·Φ_cᵀΦ_c)·A = Σ_c w_c²·Φ_cᵀ·y_c
//! ```
//!
//! Several sensors are stacked, each weighted by the inverse of its residual's standard
//! deviation (a first pass weights them by the inverse of their line's peak, so that each
//! counts alike whatever its unit). The axle offsets and the speed are given; the entry time is
//! given (axle detectors) or fitted beside the loads: J(t₀) = min_A of the sum above is
//! searched on a grid of t₀ (every sample or 5 ms, whichever is coarser, and at most 400 steps)
//! over ±[`ENTRY_SEARCH`] or the vehicle's length in time, whichever is longer, and refined by
//! a golden section. An entry found with one assumed axle (late by the time the load's centroid takes
//! to enter) would otherwise bias every axle. The speed is not fitted: on a vibrating record
//! its fit scatters by a few per cent, the gross weight with it (the record's area is
//! Σ A_a·∫IL/v), and the linearised interval below does not cover that (tested); a stated
//! speed off by 1 % scales the gross weight by about 1 %.
//!
//! **Filtered Moses** (`[measurement.weighing] low_pass = true`). Where the bridge's first
//! frequency f₁ is known, each record and each column of its design Φ_c·G are low-passed
//! alike, by the zero-phase Butterworth of [`WeighingStart::low_pass_hz`] (at
//! [`WEIGHING_CUTOFF_FRACTION`] · f₁). The filter F is linear, so F(y_c) ≈ F(Φ_c)·A holds as
//! y_c ≈ Φ_c·A did: the least squares keep their unknowns and lose the bridge's vibration at
//! f₁ and above, and with it the columns' content above the cut-off. Over the validation
//! battery it weighed no better on the whole (docs/verification.md, 29b: the vehicle's own
//! dynamic axle forces, below f₁, dominate the errors), so it is not the default.
//!
//! **Uncertainty.** The linearised least squares in the loads and the fitted entry time,
//! J_c = [Φ_c, ∂(Φ_c·A)/∂t₀], with a sandwich covariance whose middle is the residuals'
//! smoothed cross-spectrum ([`sandwich_covariance`]): the residual is the bridge's vibration
//! and the filtered noise, far from white, and it moves the axle loads' differences (whose
//! columns have content at the bridge's frequency) much more than the gross weight. The
//! entry time's scatter enters the loads through its correlation with them. This is the
//! fit's own precision, named so (`*_fit_std_n`): the vehicle's dynamic axle forces vary
//! during the crossing, and the record holds them as loads, so the least squares give their
//! mean over the crossing, not the static weight. The accuracy a bridge reaches (the COST 323
//! class, [`super::criterion_class`]) is measured over known trucks.
//!
//! **Groups of axles.** By default the axles of a group (closer than 2 m: a tandem, a tridem)
//! share its load equally, A = G·B with one unknown per group: a bridge's response resolves a
//! group's load but hardly its split (the battery's tandems scattered by tens of per cent, and
//! more). `split_groups = true` fits every axle.
//!
//! The least squares, the search and the sandwich are written here: a few axles and a few
//! thousand samples need no solver crate beyond nalgebra's Cholesky and realfft.

use nalgebra::{DMatrix, DVector};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use serde::Serialize;

use super::calibration::condition_number;
use super::MeasureError;
use crate::analytical::statics::golden_maximum;
use crate::signal::{butterworth_lowpass, SampledInfluenceLine, SosFilter};

/// Half-width of the search for the entry time around the starting one [s], at least; widened
/// to the time the vehicle's length takes to pass at the stated speed.
pub const ENTRY_SEARCH: f64 = 0.5;

/// Smallest step of the entry time's grid [s].
const ENTRY_STEP: f64 = 0.005;

/// Most steps of the entry time's grid: a slow passage's wide search (the vehicle's length in
/// time at crawling speed) is stepped coarser, the golden section refining within a step.
const MAXIMUM_ENTRY_STEPS: f64 = 400.0;

/// Condition number of the normal equations above which the axle loads are not told apart
/// (axles closer than the line's resolution): the weighing says so.
pub const ILL_CONDITIONED: f64 = 1e6;

/// One sensor to weigh with: its (prepared) record and its influence line, in the same unit
/// per newton.
#[derive(Debug, Clone, Copy)]
pub struct WeighingChannel<'a> {
    /// The channel's name.
    pub name: &'a str,
    /// Where the line comes from: "influence_line" (given), "influence_line_crawl",
    /// "influence_line_model" (the model fitted to the identified modes) or
    /// "influence_line_model_unfitted".
    pub line_source: &'static str,
    /// The record, baseline removed [SI].
    pub samples: &'a [f64],
    /// Its influence line [SI per N] along the deck [m].
    pub line: &'a SampledInfluenceLine,
}

/// The vehicle to weigh: its axle layout, and where the search for its passage starts.
#[derive(Debug, Clone, PartialEq)]
pub struct WeighingStart {
    /// Distance of each axle behind the first one [m] (the first 0, non-decreasing).
    pub axle_offsets: Vec<f64>,
    /// Stated speed [m/s].
    pub speed: f64,
    /// Stated or detected time the first axle enters the bridge [s].
    pub entry_time: f64,
    /// Fit the entry time (±[`ENTRY_SEARCH`]); otherwise the given one is taken as exact
    /// (axle detectors).
    pub fit_entry: bool,
    /// Fit every axle of a group (axles closer than [`super::GROUP_SPACING`]) on its own;
    /// otherwise the axles of a group share its load equally.
    pub split_groups: bool,
    /// Cut-off [Hz] of the zero-phase Butterworth low-pass (order [`WEIGHING_FILTER_ORDER`])
    /// applied alike to each record and to each column of its design (filtered Moses): below
    /// the bridge's first frequency it takes the bridge's vibration out of the fit, and, the
    /// filter being linear, it leaves the static model y = Φ·A as it was. `None`: no filter.
    pub low_pass_hz: Option<f64>,
}

/// The weighing's low-pass cut-off as a fraction of the bridge's first frequency: 0.7 f₁,
/// where the order-4 Butterworth run both ways passes |H|² = 1/(1 + (1/0.7)¹⁶) ≈ 0.3 % of the
/// vibration at f₁ and keeps the influence lines' passage (a span's crossing lasts longer than
/// a period of f₁ at any road speed).
pub const WEIGHING_CUTOFF_FRACTION: f64 = 0.7;

/// Order of the weighing's low-pass ([`WeighingStart::low_pass_hz`]), run forwards and
/// backwards (zero phase, |H|²).
pub const WEIGHING_FILTER_ORDER: usize = 4;

/// The weighed vehicle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VehicleWeighing {
    /// "moses_least_squares".
    pub method: &'static str,
    /// The sensors weighed with, and where each one's influence line comes from.
    pub channels: Vec<WeighingSensor>,
    /// Axle loads [N], first axle first.
    pub axle_loads_n: Vec<f64>,
    /// Their standard deviations from the fit alone [N]: the noise and the bridge's vibration
    /// in the record, and the fitted entry time. Not the weighing's accuracy: the vehicle's own
    /// dynamic axle forces, which the record holds as loads, are left out (the validation
    /// battery measures them: docs/verification.md §29b).
    pub axle_load_fit_std_n: Vec<f64>,
    /// Gross weight Σ A_a [N].
    pub gross_weight_n: f64,
    /// Its standard deviation from the fit alone [N] (with the loads' covariances), as
    /// [`Self::axle_load_fit_std_n`].
    pub gross_weight_fit_std_n: f64,
    /// Axle offsets [m], as given.
    pub axle_offsets_m: Vec<f64>,
    /// The groups of axles (1 = the first) whose axles share the group's load equally
    /// (`split_groups = false`, the default): a tandem's axles 1.35 m apart are not told apart
    /// by a bridge's response (on the battery their split scatters by tens of per cent), their
    /// sum is.
    pub shared_groups: Vec<Vec<usize>>,
    /// The speed, as stated [m/s].
    pub speed_m_s: f64,
    /// Cut-off of the low-pass applied alike to the records and the design [Hz]
    /// ([`WeighingStart::low_pass_hz`]); `None` when the records were fitted unfiltered.
    pub low_pass_hz: Option<f64>,
    /// The entry time of the first axle [s], fitted or given.
    pub entry_time_s: f64,
    /// Whether the entry time was fitted from the record (else given: axle detectors).
    pub entry_time_fitted: bool,
    /// The entry time the search started from [s].
    pub starting_entry_time_s: f64,
    /// Samples in the fitting window, per sensor.
    pub samples_used: usize,
    /// Condition number of the normal equations (2-norm).
    pub condition_number: f64,
    /// Whether the axle loads are told apart ([`ILL_CONDITIONED`]).
    pub well_conditioned: bool,
    /// The given axle loads beside the weighed ones, when given.
    pub against_given: Option<GivenLoads>,
}

/// One sensor of a weighing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WeighingSensor {
    /// The channel's name.
    pub channel: String,
    /// Where its influence line comes from.
    pub line_source: &'static str,
    /// The sign applied to the line so that the vehicle weighs positive (a model's sign
    /// convention need not be the logger's): 1 or −1.
    pub line_sign: f64,
    /// RMS of the fit's residual / RMS of the record in the window [-]: what the static
    /// response under the weighed axles leaves (the vibration and the noise).
    pub residual_ratio: f64,
}

/// The given axle loads against the weighed ones.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GivenLoads {
    /// Given axle loads [N].
    pub axle_loads_n: Vec<f64>,
    /// Given gross weight [N].
    pub gross_weight_n: f64,
    /// (weighed − given) / given per axle [-].
    pub axle_errors: Vec<f64>,
    /// (weighed − given) / given of the gross weight [-].
    pub gross_weight_error: f64,
}

/// Weighs the vehicle of `start` from `channels` recorded at `times` (see the module's
/// equations); `given` are the given axle loads [N], compared when present.
pub fn weigh(
    times: &[f64],
    channels: &[WeighingChannel],
    start: &WeighingStart,
    given: Option<&[f64]>,
) -> Result<VehicleWeighing, MeasureError> {
    check(times, channels, start)?;
    let problem = Problem::new(times, channels, start);
    // Every unknown (and the entry time) needs samples of the crossing, with some to spare.
    let (first, last) = problem.window;
    if last - first < problem.sharing.ncols() + 3 {
        return Err(MeasureError::input(
            "entry_time_s",
            format!(
                "the record holds {} samples of the vehicle's passage: too few to weigh {} axle load(s); is the entry time inside the record, with the crossing after it?",
                last - first,
                problem.sharing.ncols()
            ),
        ));
    }
    // First pass: each sensor's line signed so that it weighs the vehicle positive, and each
    // weighted by its line's peak.
    let mut weights: Vec<f64> = channels.iter().map(|c| 1.0 / peak(c.line)).collect();
    let signs = problem.signs(&weights);
    let entry = problem.search(&weights, &signs);
    // Second pass: weighted by the inverse of each residual's standard deviation.
    let first = problem.fit(&weights, &signs, entry)?;
    for (w, r) in weights.iter_mut().zip(&first.residual_std) {
        if *r > 0.0 {
            *w = 1.0 / r;
        }
    }
    let entry = problem.search(&weights, &signs);
    let fit = problem.fit(&weights, &signs, entry)?;
    Ok(problem.conclude(fit, &signs, entry, given))
}

/// G and the shared groups: the identity when `split`, else one column per group of axles
/// closer than [`super::GROUP_SPACING`] (a single axle is a group of one) with 1 on each of its
/// axles.
fn sharing_of(offsets: &[f64], split: bool) -> (DMatrix<f64>, Vec<std::ops::Range<usize>>) {
    if split {
        return (DMatrix::identity(offsets.len(), offsets.len()), Vec::new());
    }
    let (_, groups) = super::axle_groups(offsets);
    let mut columns: Vec<std::ops::Range<usize>> = Vec::new();
    let mut a = 0;
    while a < offsets.len() {
        let range = groups
            .iter()
            .find(|g| g.start == a)
            .cloned()
            .unwrap_or(a..a + 1);
        a = range.end;
        columns.push(range);
    }
    let mut sharing = DMatrix::zeros(offsets.len(), columns.len());
    for (j, range) in columns.iter().enumerate() {
        for a in range.clone() {
            sharing[(a, j)] = 1.0;
        }
    }
    (sharing, groups)
}

/// The largest |IL| [SI per N] (positive).
fn peak(line: &SampledInfluenceLine) -> f64 {
    let p = line.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if p > 0.0 {
        p
    } else {
        1.0
    }
}

/// The axle offsets Moses' least squares need: the first 0, then increasing [m] (two axles at
/// one place cannot be weighed apart).
pub(super) fn check_axle_offsets(d: &[f64]) -> Result<(), MeasureError> {
    if d.first() != Some(&0.0) || d.windows(2).any(|w| w[1] <= w[0] || w[1].is_nan()) {
        return Err(MeasureError::input(
            "vehicle.axle_offsets_m",
            "weighing needs the axle offsets behind the first axle: the first 0, then increasing, in m (two axles at one place are one axle)",
        ));
    }
    Ok(())
}

fn check(
    times: &[f64],
    channels: &[WeighingChannel],
    start: &WeighingStart,
) -> Result<(), MeasureError> {
    check_axle_offsets(&start.axle_offsets)?;
    if !(start.speed.is_finite() && start.speed > 0.0 && start.entry_time.is_finite()) {
        return Err(MeasureError::input(
            "speed_kmh",
            "weighing needs a positive speed and an entry time",
        ));
    }
    if channels.is_empty() {
        return Err(MeasureError::input(
            "channels.static_reference",
            "weighing needs a deflection, strain or moment channel with an influence line (given, from the crawl run or from the bridge model)",
        ));
    }
    if times.len() < 2 {
        return Err(MeasureError::input(
            "csv",
            "weighing needs a record of two samples or more",
        ));
    }
    if channels.iter().any(|c| c.samples.len() != times.len()) {
        return Err(MeasureError::input(
            "channels",
            "every channel needs one sample per time",
        ));
    }
    if let Some(c) = channels
        .iter()
        .find(|c| c.samples.iter().any(|v| !v.is_finite()))
    {
        return Err(MeasureError::input(
            "channels",
            format!(
                "channel `{}` has a sample that is not a finite number",
                c.name
            ),
        ));
    }
    // The filter is designed at the record's own rate; a cut-off it cannot have is refused,
    // not dropped.
    let nyquist = 0.5 / (times[1] - times[0]);
    if let Some(cutoff) = start.low_pass_hz {
        if !(cutoff.is_finite() && cutoff > 0.0 && nyquist.is_finite() && cutoff < nyquist) {
            return Err(MeasureError::input(
                "weighing.low_pass",
                format!("the weighing's low-pass cut-off {cutoff} Hz is not between 0 and the record's Nyquist frequency {nyquist} Hz"),
            ));
        }
    }
    Ok(())
}

/// The least squares of one weighing: the records in the fitting window.
struct Problem<'a> {
    times: &'a [f64],
    channels: &'a [WeighingChannel<'a>],
    offsets: &'a [f64],
    /// G: axle loads A = G·B from the unknowns B (one per axle, or one per group whose axles
    /// share its load equally) [axles × unknowns].
    sharing: DMatrix<f64>,
    /// The groups whose axles share their load (0-based axle indices).
    shared_groups: Vec<std::ops::Range<usize>>,
    /// First and one-past-last sample of the window.
    window: (usize, usize),
    /// The entry time's search bounds [s] (equal when it is given).
    entry_bounds: (f64, f64),
    /// The stated speed [m/s].
    speed: f64,
    /// The low-pass applied alike to the records and the designs, with its cut-off [Hz].
    low_pass: Option<(SosFilter, f64)>,
    /// Each sensor's record in the window, low-passed when `low_pass` is set.
    records: Vec<DVector<f64>>,
}

/// What one fit gives.
struct Fit {
    loads: DVector<f64>,
    /// The loads' covariance ([`sandwich_covariance`]'s loads block).
    covariance: DMatrix<f64>,
    condition: f64,
    residual_std: Vec<f64>,
    residual_ratio: Vec<f64>,
}

impl<'a> Problem<'a> {
    fn new(
        times: &'a [f64],
        channels: &'a [WeighingChannel<'a>],
        start: &'a WeighingStart,
    ) -> Self {
        let length = channels
            .iter()
            .map(|c| *c.line.positions.last().unwrap_or(&0.0))
            .fold(0.0, f64::max);
        let vehicle = *start.axle_offsets.last().unwrap_or(&0.0);
        let search = if start.fit_entry {
            ENTRY_SEARCH.max(vehicle / start.speed)
        } else {
            0.0
        };
        let entry_bounds = (start.entry_time - search, start.entry_time + search);

        // Every sample that some trial passage can load, so that every trial is judged on the
        // same samples.
        let end = entry_bounds.1 + (length + vehicle) / start.speed;
        let (sharing, shared_groups) = sharing_of(&start.axle_offsets, start.split_groups);
        let first = times.partition_point(|&t| t < entry_bounds.0);
        let last = times.partition_point(|&t| t <= end).max(first);
        let low_pass = start.low_pass_hz.and_then(|cutoff| {
            let rate = 1.0 / (times[1] - times[0]);
            let filter = butterworth_lowpass(WEIGHING_FILTER_ORDER, cutoff, rate)
                .expect("the cut-off checked against the Nyquist frequency by `check`");
            // A window too short for the filter's edge padding is fitted unfiltered (and
            // `low_pass_hz` says so: `None`).
            (last - first > filter.default_pad_length()).then_some((filter, cutoff))
        });
        let records = channels
            .iter()
            .map(|c| {
                let mut y = c.samples[first..last].to_vec();
                if let Some((filter, _)) = &low_pass {
                    y = filter
                        .filtfilt(&y, None)
                        .expect("finite, longer than the padding");
                }
                DVector::from_vec(y)
            })
            .collect();
        Problem {
            times,
            channels,
            offsets: &start.axle_offsets,
            sharing,
            shared_groups,
            window: (first, last),
            entry_bounds,
            speed: start.speed,
            low_pass,
            records,
        }
    }

    /// Φ_c·G of sensor `c` for a passage entering at `entry`: one row per window sample, one
    /// column per unknown.
    fn design(&self, c: usize, entry: f64) -> DMatrix<f64> {
        let speed = self.speed;
        let (first, last) = self.window;
        let line = self.channels[c].line;
        let axles = DMatrix::from_fn(last - first, self.offsets.len(), |k, a| {
            line.evaluate(speed * (self.times[first + k] - entry) - self.offsets[a])
        });
        let mut design = axles * &self.sharing;
        if let Some((filter, _)) = &self.low_pass {
            for mut column in design.column_iter_mut() {
                let filtered = filter
                    .filtfilt(column.as_slice(), None)
                    .expect("finite, longer than the padding");
                column.copy_from_slice(&filtered);
            }
        }
        design
    }

    /// Sensor `c`'s record in the window (low-passed as the designs are).
    fn record(&self, c: usize) -> &DVector<f64> {
        &self.records[c]
    }

    /// s_c·Φ_c·G of every sensor for a passage entering at `entry`, `None` for a sensor of zero
    /// weight (left out of this sum).
    fn designs(&self, weights: &[f64], signs: &[f64], entry: f64) -> Vec<Option<DMatrix<f64>>> {
        (0..self.channels.len())
            .map(|c| (weights[c] != 0.0).then(|| self.design(c, entry) * signs[c]))
            .collect()
    }

    /// The loads B that minimise Σ w_c²·‖Φ_c·B − y_c‖² over `designs`, from the normal
    /// equations (Σ w_c²·Φ_cᵀΦ_c)·B = Σ w_c²·Φ_cᵀy_c, with that matrix; `None` when singular.
    fn solve(
        &self,
        weights: &[f64],
        designs: &[Option<DMatrix<f64>>],
    ) -> Option<(DVector<f64>, DMatrix<f64>)> {
        let n = self.sharing.ncols();
        let mut matrix = DMatrix::zeros(n, n);
        let mut right = DVector::zeros(n);
        for (c, phi) in designs.iter().enumerate() {
            if let Some(phi) = phi {
                let w2 = weights[c] * weights[c];
                matrix += phi.tr_mul(phi) * w2;
                right += phi.tr_mul(self.record(c)) * w2;
            }
        }
        let loads = matrix.clone().cholesky()?.solve(&right);
        Some((loads, matrix))
    }

    /// J(entry) = min_B Σ w_c²·‖s_c·Φ_c·B − y_c‖² (∞ where the equations are singular or the
    /// passage weighs the vehicle at zero or less), summed from the residuals (not as
    /// yᵀy − bᵀM⁻¹b, which cancels near the minimum).
    fn objective(&self, weights: &[f64], signs: &[f64], entry: f64) -> f64 {
        let designs = self.designs(weights, signs, entry);
        match self.solve(weights, &designs) {
            Some((loads, _)) if loads.sum() > 0.0 => designs
                .iter()
                .enumerate()
                .filter_map(|(c, phi)| {
                    let phi = phi.as_ref()?;
                    Some((self.record(c) - phi * &loads).norm_squared() * weights[c] * weights[c])
                })
                .sum(),
            _ => f64::INFINITY,
        }
    }

    /// The grid search of the entry time, then its golden-section refinement within one
    /// step of the best grid point.
    fn search(&self, weights: &[f64], signs: &[f64]) -> f64 {
        let step = self.entry_step();
        let (low, high) = self.entry_bounds;
        if high <= low {
            return low;
        }
        let entries = ((high - low) / step).ceil() as usize;
        let mut best = (f64::INFINITY, low);
        for i in 0..=entries {
            let entry = (low + i as f64 * step).min(high);
            let value = self.objective(weights, signs, entry);
            if value < best.0 {
                best = (value, entry);
            }
        }
        golden_minimum(
            |t| self.objective(weights, signs, t),
            (best.1 - step).max(low),
            (best.1 + step).min(high),
        )
    }

    /// Step of the entry time's grid [s]: a sample, or [`ENTRY_STEP`] on records sampled
    /// faster (the objective is smooth over the time an axle spacing takes to pass).
    fn entry_step(&self) -> f64 {
        let search = self.entry_bounds.1 - self.entry_bounds.0;
        (self.times[1] - self.times[0])
            .abs()
            .max(ENTRY_STEP)
            .max(search / MAXIMUM_ENTRY_STEPS)
    }

    /// J_c = [s_c·Φ_c, ∂p_c/∂t₀] of the prediction p_c = s_c·Φ_c·A, from `phi` = s_c·Φ_c (the
    /// entry time's column when it is fitted), the derivative by central differences over half the line's sample
    /// spacing (the interpolated line's slope is constant between its samples).
    fn jacobian(
        &self,
        c: usize,
        (phi, sign): (&DMatrix<f64>, f64),
        loads: &DVector<f64>,
        entry: f64,
        fit_entry: bool,
    ) -> DMatrix<f64> {
        let mut columns: Vec<DVector<f64>> = phi.column_iter().map(|c| c.into_owned()).collect();
        if fit_entry {
            let positions = &self.channels[c].line.positions;
            let spacing =
                (positions[positions.len() - 1] - positions[0]) / (positions.len() - 1) as f64;
            let dt = 0.5 * spacing / self.speed;
            let prediction = |t: f64| self.design(c, t) * sign * loads;
            columns.push((prediction(entry + dt) - prediction(entry - dt)) / (2.0 * dt));
        }
        DMatrix::from_columns(&columns)
    }

    /// +1 or −1 per sensor: the sign under which the sensor alone weighs the vehicle best
    /// (the smaller least-squares residual over the entry-time search, a passage that weighs
    /// zero or less not counting). A model's sign convention need not be the logger's, and a
    /// gauge beyond the first span answers with both signs as the vehicle crosses, so the sign
    /// of a correlation at the starting passage can mislead.
    fn signs(&self, weights: &[f64]) -> Vec<f64> {
        (0..self.channels.len())
            .map(|c| {
                let alone: Vec<f64> = (0..weights.len())
                    .map(|k| if k == c { weights[k] } else { 0.0 })
                    .collect();
                let residual = |sign: f64| {
                    let mut signs = vec![1.0; weights.len()];
                    signs[c] = sign;
                    let entry = self.search(&alone, &signs);
                    self.objective(&alone, &signs, entry)
                };
                if residual(-1.0) < residual(1.0) {
                    -1.0
                } else {
                    1.0
                }
            })
            .collect()
    }

    fn fit(&self, weights: &[f64], signs: &[f64], entry: f64) -> Result<Fit, MeasureError> {
        let singular = || {
            MeasureError::input(
                "vehicle.axle_offsets_m",
                "the axle loads cannot be told apart from the record: the influence lines do not load the axles differently within the record (is the crossing inside the record?)",
            )
        };
        let designs = self.designs(weights, signs, entry);
        let (loads, matrix) = self.solve(weights, &designs).ok_or_else(singular)?;
        if loads.sum() <= 0.0 {
            return Err(MeasureError::input(
                "weighing",
                "the record does not weigh the vehicle: the least squares give a gross weight of zero or less (is the vehicle's passage in the record, and the entry time right?)",
            ));
        }
        let condition = condition_number(&matrix);
        if !condition.is_finite() {
            return Err(singular());
        }
        let mut residual_std = Vec::new();
        let mut residual_ratio = Vec::new();
        let mut jacobians = Vec::new();
        let mut residuals = Vec::new();
        let fit_entry = self.entry_bounds.1 > self.entry_bounds.0;
        for (c, phi) in designs.iter().enumerate() {
            let phi = phi.as_ref().ok_or_else(singular)?;
            let y = self.record(c);
            let residual = y - phi * &loads;
            let n = residual.len().max(1) as f64;
            let std = (residual.norm_squared() / n).sqrt();
            let rms = (y.norm_squared() / n).sqrt();
            residual_std.push(std);
            residual_ratio.push(if rms > 0.0 { std / rms } else { 0.0 });
            jacobians.push(self.jacobian(c, (phi, signs[c]), &loads, entry, fit_entry));
            residuals.push(residual);
        }
        // The loads' block: the entry time's own scatter enters the loads
        // through their correlation.
        let axles = loads.len();
        // Without the entry time's column when the joint information is singular (a passage
        // whose prediction does not move with it); never a covariance of zeros.
        let joint = sandwich_covariance(&jacobians, &residuals, weights).or_else(|| {
            let loads_only: Vec<DMatrix<f64>> = jacobians
                .iter()
                .map(|j| j.columns(0, axles).into_owned())
                .collect();
            sandwich_covariance(&loads_only, &residuals, weights)
        });
        let inverse = joint
            .map(|covariance| covariance.view((0, 0), (axles, axles)).into_owned())
            .ok_or_else(singular)?;
        Ok(Fit {
            loads,
            covariance: inverse,
            condition,
            residual_std,
            residual_ratio,
        })
    }

    fn conclude(
        &self,
        fit: Fit,
        signs: &[f64],
        entry: f64,
        given: Option<&[f64]>,
    ) -> VehicleWeighing {
        let covariance = &self.sharing * &fit.covariance * self.sharing.transpose();
        let loads: Vec<f64> = (&self.sharing * &fit.loads).iter().copied().collect();
        let gross: f64 = loads.iter().sum();
        let gross_variance = covariance.sum();
        let against_given = given.filter(|g| g.len() == loads.len()).map(|g| {
            let given_gross: f64 = g.iter().sum();
            GivenLoads {
                axle_loads_n: g.to_vec(),
                gross_weight_n: given_gross,
                axle_errors: loads.iter().zip(g).map(|(a, p)| a / p - 1.0).collect(),
                gross_weight_error: gross / given_gross - 1.0,
            }
        });
        VehicleWeighing {
            method: "moses_least_squares",
            channels: self
                .channels
                .iter()
                .zip(signs)
                .zip(&fit.residual_ratio)
                .map(|((c, &sign), &ratio)| WeighingSensor {
                    channel: c.name.to_string(),
                    line_source: c.line_source,
                    line_sign: sign,
                    residual_ratio: ratio,
                })
                .collect(),
            axle_load_fit_std_n: (0..loads.len())
                .map(|a| covariance[(a, a)].max(0.0).sqrt())
                .collect(),
            axle_loads_n: loads,
            gross_weight_n: gross,
            gross_weight_fit_std_n: gross_variance.max(0.0).sqrt(),
            axle_offsets_m: self.offsets.to_vec(),
            shared_groups: self
                .shared_groups
                .iter()
                .map(|g| g.clone().map(|a| a + 1).collect())
                .collect(),
            speed_m_s: self.speed,
            low_pass_hz: self.low_pass.as_ref().map(|(_, cutoff)| *cutoff),
            entry_time_fitted: self.entry_bounds.1 > self.entry_bounds.0,
            entry_time_s: entry,
            starting_entry_time_s: (self.entry_bounds.0 + self.entry_bounds.1) / 2.0,
            samples_used: self.window.1 - self.window.0,
            condition_number: fit.condition,
            well_conditioned: fit.condition < ILL_CONDITIONED,
            against_given,
        }
    }
}

/// Half-width of the Daniell smoothing of the residuals' cross-periodograms, in bins of the
/// transform padded to at least twice the window: ±4 bins, about ±2 resolutions 1/T.
const SMOOTHING_BINS: usize = 4;

/// Cov(θ) = M⁻¹·B·M⁻¹, the least squares' sandwich with a spectral middle (the
/// heteroscedasticity-and-autocorrelation-consistent covariance, here in the frequency domain;
/// Brillinger 1981, "Time Series: Data Analysis and Theory", §6, for regression on series):
///
/// ```text
/// M = Σ_c w_c²·J_cᵀJ_c
/// B = Σ_c Σ_d w_c²·w_d² · (1/N)·Σ_k Re[ conj(Ĵ_c,k)·Ĵ_d,kᵀ · Ŝ_cd,k ]
/// Ŝ_cd,k = Daniell-smoothed R_c,k·conj(R_d,k) / n
/// ```
///
/// with Ĵ and R the transforms (zero-padded to N ≥ 2n) of the Jacobian's columns and of the
/// residuals r_c, n samples each. The middle weighs the residuals' spectrum by the columns'
/// own: a vibration at the bridge's frequency counts where the columns have content there
/// (the axle loads' differences and the entry time, whose columns change on the scale of an
/// axle spacing), and little where they are smooth (the gross weight). A white residual gives
/// back σ²·M⁻¹. `None` when M is singular.
fn sandwich_covariance(
    jacobians: &[DMatrix<f64>],
    residuals: &[DVector<f64>],
    weights: &[f64],
) -> Option<DMatrix<f64>> {
    let parameters = jacobians.first()?.ncols();
    let n = residuals.first()?.len();
    let length = (2 * n).next_power_of_two().max(2);
    let mut planner = RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(length);
    let transform = |samples: &[f64]| {
        let mut input = forward.make_input_vec();
        input[..samples.len()].copy_from_slice(samples);
        let mut output = forward.make_output_vec();
        forward
            .process(&mut input, &mut output)
            .expect("buffers come from the same plan");
        output
    };
    let mut bread = DMatrix::zeros(parameters, parameters);
    let mut columns = Vec::new();
    let mut spectra = Vec::new();
    for ((jacobian, residual), w) in jacobians.iter().zip(residuals).zip(weights) {
        bread += jacobian.tr_mul(jacobian) * (w * w);
        columns.push(
            (0..parameters)
                .map(|i| transform(jacobian.column(i).as_slice()))
                .collect::<Vec<_>>(),
        );
        spectra.push(transform(residual.as_slice()));
    }
    let bins = length / 2 + 1;
    let mut middle = DMatrix::zeros(parameters, parameters);
    for c in 0..spectra.len() {
        for d in 0..spectra.len() {
            let cross: Vec<Complex<f64>> = (0..bins)
                .map(|k| spectra[c][k] * spectra[d][k].conj() / n as f64)
                .collect();
            let smoothed = daniell(&cross, SMOOTHING_BINS);
            let scale = (weights[c] * weights[c] * weights[d] * weights[d]) / length as f64;
            for k in 0..bins {
                // Bins 1 … N/2 − 1 stand for their mirror images too.
                let multiplicity = if k == 0 || k == bins - 1 { 1.0 } else { 2.0 };
                for i in 0..parameters {
                    for j in 0..parameters {
                        let term = columns[c][i][k].conj() * columns[d][j][k] * smoothed[k];
                        middle[(i, j)] += multiplicity * scale * term.re;
                    }
                }
            }
        }
    }
    let inverse = bread.cholesky()?.inverse();
    let covariance = &inverse * middle * &inverse;
    Some((&covariance + covariance.transpose()) / 2.0)
}

/// The moving average of `values` over ±`half` entries (fewer at the ends).
fn daniell(values: &[Complex<f64>], half: usize) -> Vec<Complex<f64>> {
    (0..values.len())
        .map(|k| {
            let window = &values[k.saturating_sub(half)..(k + half + 1).min(values.len())];
            window.iter().sum::<Complex<f64>>() / window.len() as f64
        })
        .collect()
}

/// The minimum of a unimodal `f` on [a, b] by golden sections.
fn golden_minimum(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    if b <= a {
        return a;
    }
    golden_maximum(&|x| -f(x), a, b, 80).0
}

#[cfg(test)]
#[path = "weighing_tests.rs"]
mod tests;
