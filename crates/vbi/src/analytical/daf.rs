//! DAF_u(K), DAF_M(K) and RDM(K) of a continuous beam under a moving constant force
//! (the paper's Eqs. 15–17).
//!
//! With the first K modes, at a section x:
//!
//! ```text
//! w_K(t) = P Σ_{n≤K} φₙ(x) qₙ(t),   M_K(t) = P EI Σ_{n≤K} φₙ''(x) qₙ(t)
//! DAF_u(K) = max_t s_u w_K(t) / |w_s|,   DAF_M(K) = max_t s_M M_K(t) / |M_s|,
//! RDM(K) = DAF_u(K) / DAF_M(K)                                           (Eqs. 15–17)
//! ```
//!
//! where w_s, M_s are the exact static references (Eq. 14) and s_u, s_M their signs (so the
//! maximum is taken in the direction of the static response: downwards and sagging at mid-span).
//! The static reference is either the envelope (the largest static value at the section over
//! all load positions, the convention of docs/verification.md §0) or the value with the load
//! at the section (the paper's Eq. 18, which gives RDM(1) = 312/(23π²) at l/2 of two spans).
//!
//! The time maximum is taken over `output_times` equally spaced instants plus the instant the
//! force is over the section (exact values), then refined by golden-section search around the
//! largest sampled local maximum (and the second one if it could be higher).
//!
//! Beside the plain modal sums of the paper, the table carries the static-corrected
//! (mode-acceleration) series R_s(x; vt) + Σ_{n≤K} cₙ (qₙ(t) − qₙ^qs(t)) with the exact static
//! response R_s and qₙ^qs = −Pφₙ(vt)/ωₙ²: only the dynamic part is truncated, so the moment DAF
//! converges within a few modes too. It is the converged value the plain DAF_M(K) tends to.

use super::moving_force::ModalMovingForce;
use super::statics::{golden_maximum, static_envelope, static_response};
use super::{continuous_beam_modes, AnalyticalError, BeamMode, ContinuousBeam};

/// Which static response the DAF divides by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StaticReference {
    /// The largest static response at the section over all load positions (default; the
    /// convention of docs/verification.md §0: "the same loads moving quasi-statically").
    #[default]
    Envelope,
    /// The static response with the load at the section (the paper's λ₁, λ₂ in Eq. 18).
    LoadAtSection,
}

/// Over which time window the dynamic maximum is taken.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MaximumWindow {
    /// While the force is on the beam, 0 ≤ t ≤ N l / v (default).
    #[default]
    LoadOnBeam,
    /// Also over a free-vibration window of the given duration \[s\] after the force leaves.
    WithFreeVibration {
        /// Duration of the free-vibration window \[s\].
        duration: f64,
    },
}

/// Options of [`daf_by_modes`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DafOptions {
    /// Speed of the force v \[m/s\]. Default 80 km/h = 22.22 m/s (the paper's speed).
    pub speed: f64,
    /// Modal damping ratio ζ, the same for every mode \[-\]. Default 0.05 (the paper's §3).
    pub damping_ratio: f64,
    /// Largest number of modes K \[-\]; the table covers K = 1 … modes. Default 30.
    pub modes: usize,
    /// Section x \[m\] from the first support. Default `None`: l/2 of the first span.
    pub section: Option<f64>,
    /// Static reference. Default [`StaticReference::Envelope`].
    pub static_reference: StaticReference,
    /// Time window of the maximum. Default [`MaximumWindow::LoadOnBeam`].
    pub window: MaximumWindow,
    /// Number of equally spaced output times over the crossing \[-\] (the instant the force is
    /// over the section is added; a free-vibration window continues at the same spacing, up to
    /// [`MAX_OUTPUT_INSTANTS`] in all). Default 1000.
    pub output_times: usize,
}

impl Default for DafOptions {
    fn default() -> Self {
        DafOptions {
            speed: 80.0 * crate::units::KMH,
            damping_ratio: 0.05,
            modes: 30,
            section: None,
            static_reference: StaticReference::Envelope,
            window: MaximumWindow::LoadOnBeam,
            output_times: 1000,
        }
    }
}

/// The DAFs against the number of modes, with what they were computed from.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DafTable {
    /// DAF_u(K), index K − 1 \[-\] (Eq. 15).
    pub daf_deflection_by_modes: Vec<f64>,
    /// DAF_M(K), index K − 1 \[-\] (Eq. 16).
    pub daf_moment_by_modes: Vec<f64>,
    /// RDM(K) = DAF_u(K)/DAF_M(K), index K − 1 \[-\] (Eq. 17).
    pub rdm_by_modes: Vec<f64>,
    /// Time of the maximum deflection with K modes, index K − 1 \[s\].
    pub time_of_max_deflection: Vec<f64>,
    /// Time of the maximum moment with K modes, index K − 1 \[s\].
    pub time_of_max_moment: Vec<f64>,
    /// DAF_u(K) of the static-corrected (mode-acceleration) series, index K − 1 \[-\]: the exact
    /// static deflection plus the dynamic part Σ_{n≤K} φₙ(x)(qₙ − qₙ^qs), qₙ^qs = −Pφₙ(vt)/ωₙ².
    pub daf_deflection_corrected_by_modes: Vec<f64>,
    /// DAF_M(K) of the static-corrected series, index K − 1 \[-\]: converges fast where the plain
    /// modal sum of Eq. 16 converges as O(1/K).
    pub daf_moment_corrected_by_modes: Vec<f64>,
    /// RDM(K) of the static-corrected series, index K − 1 \[-\].
    pub rdm_corrected_by_modes: Vec<f64>,
    /// Natural frequencies fₙ of the modes used \[Hz\].
    pub frequencies_hz: Vec<f64>,
    /// Frequency parameters aₙ \[-\].
    pub frequency_parameters: Vec<f64>,
    /// Speed parameter α = v/(2 f₁ l) \[-\].
    pub alpha: f64,
    /// Speed v \[m/s\].
    pub speed: f64,
    /// Section x \[m\].
    pub section: f64,
    /// Static deflection reference w_s per unit downward force (upwards positive) \[m/N\].
    pub static_deflection: f64,
    /// Load position giving `static_deflection` \[m\].
    pub static_deflection_load_position: f64,
    /// Static moment reference M_s per unit downward force (sagging positive) \[m\].
    pub static_moment: f64,
    /// Load position giving `static_moment` \[m\].
    pub static_moment_load_position: f64,
    /// λ₁ = |w_s| EI / l³ per unit force \[-\] (Eq. 14).
    pub lambda_deflection: f64,
    /// λ₂ = |M_s| / l per unit force \[-\] (Eq. 14).
    pub lambda_moment: f64,
    /// Static reference used.
    pub static_reference: StaticReference,
    /// Time window of the maximum.
    pub window: MaximumWindow,
    /// Time the force is on the beam N l / v \[s\].
    pub crossing_time: f64,
    /// Whether the deflection's DAF is defined: false at an interior support, where the static
    /// deflection is zero (issue 46: the hogging moment's DAF of the paper's §2 is had there,
    /// and the deflection's series, DAF_u(K), RDM(K) and their times, are empty).
    pub deflection_defined: bool,
}

/// Everything needed to evaluate w_K(t), M_K(t) per unit force at one section.
struct Section<'a> {
    beam: &'a ContinuousBeam,
    section: f64,
    responses: Vec<ModalMovingForce>,
    shape: Vec<f64>,
    moment_shape: Vec<f64>,
    speed: f64,
    crossing: f64,
}

impl Section<'_> {
    /// Σ_{n≤k} cₙ qₙ(t).
    fn value(&self, coefficients: &[f64], k: usize, t: f64) -> f64 {
        self.responses[..k]
            .iter()
            .zip(coefficients)
            .map(|(r, c)| c * r.displacement(t))
            .sum()
    }

    /// Quasi-static modal coordinate −φₙ(vt)/ωₙ² while the force is on the beam, else 0.
    fn quasi_static(&self, n: usize, t: f64) -> f64 {
        if t <= 0.0 || t > self.crossing {
            return 0.0;
        }
        let mode = self.responses[n].mode();
        -mode.shape(self.speed * t) / mode.angular_frequency.powi(2)
    }

    /// Exact static (deflection, moment) at the section for the force at vt, 0 once it left.
    fn exact_static(&self, t: f64) -> (f64, f64) {
        if t <= 0.0 || t > self.crossing {
            return (0.0, 0.0);
        }
        let position = (self.speed * t).min(self.beam.total_length());
        static_response(self.beam, self.section, position, 1.0)
            .map(|r| (r.deflection, r.bending_moment))
            .unwrap_or((0.0, 0.0))
    }

    /// Static-corrected value R_s(t) + Σ_{n≤k} cₙ (qₙ(t) − qₙ^qs(t)); `moment` picks R_s.
    fn corrected(&self, coefficients: &[f64], k: usize, t: f64, moment: bool) -> f64 {
        let (w, m) = self.exact_static(t);
        let base = if moment { m } else { w };
        base + self.responses[..k]
            .iter()
            .zip(coefficients)
            .enumerate()
            .map(|(n, (r, c))| c * (r.displacement(t) - self.quasi_static(n, t)))
            .sum::<f64>()
    }
}

/// Most output instants of one analysis (crossing and free-vibration window together).
pub const MAX_OUTPUT_INSTANTS: usize = 2_000_000;

/// The output instants: `count` equally spaced over the crossing [0, T], then the
/// free-vibration window (T, T + extra] at the same spacing (its last instant at T + extra), so
/// that the crossing is sampled as finely whatever the window's length. Before, the `count`
/// instants spread over the whole [0, T + extra]: a 1000 s window left two of them on the
/// crossing and a DAF of 0.057.
fn output_instants(crossing: f64, extra: f64, count: usize) -> Result<Vec<f64>, AnalyticalError> {
    let spacing = crossing / (count - 1) as f64;
    let further = (extra / spacing).ceil();
    if count as f64 + further > MAX_OUTPUT_INSTANTS as f64 {
        return Err(AnalyticalError::FreeVibrationTooLong {
            duration: extra,
            samples: count as f64 + further,
            spacing,
            limit: MAX_OUTPUT_INSTANTS,
        });
    }
    let further = further as usize;
    let mut times: Vec<f64> = (0..count)
        .map(|j| crossing * j as f64 / (count - 1) as f64)
        .collect();
    times.extend((1..=further).map(|j| (crossing + j as f64 * spacing).min(crossing + extra)));
    Ok(times)
}

/// DAF_u(K), DAF_M(K) and RDM(K) for K = 1 … `options.modes` at a section (Eqs. 15–17).
pub fn daf_by_modes(
    beam: &ContinuousBeam,
    options: &DafOptions,
) -> Result<DafTable, AnalyticalError> {
    let (section, extra) = checked_section_and_window(beam, options)?;
    let modes = continuous_beam_modes(beam, options.modes)?;
    let responses = modes
        .iter()
        .map(|m| ModalMovingForce::new(m, options.damping_ratio, options.speed))
        .collect::<Result<Vec<_>, _>>()?;
    let ei = beam.flexural_rigidity;
    let crossing = beam.total_length() / options.speed;
    let sec = Section {
        beam,
        section,
        shape: modes.iter().map(|m| m.shape(section)).collect(),
        moment_shape: modes.iter().map(|m| ei * m.curvature(section)).collect(),
        responses,
        speed: options.speed,
        crossing,
    };
    let (deflection_reference, moment_reference) =
        static_references(beam, section, options.static_reference)?;
    let (ws, ms) = (deflection_reference.0, moment_reference.0);
    let deflection_defined = !is_zero_deflection(beam, ws);

    let times = output_instants(crossing, extra, options.output_times)?;
    // q_n(t_j) once for all modes.
    let history: Vec<Vec<f64>> = sec
        .responses
        .iter()
        .map(|r| times.iter().map(|&t| r.displacement(t)).collect())
        .collect();

    let mut table = empty_daf_table(
        beam,
        options,
        &modes,
        section,
        crossing,
        deflection_reference,
        moment_reference,
    );
    table.deflection_defined = deflection_defined;
    let mut sums = ModalSums::starting_from_the_static_response(&sec, &times);
    for k in 1..=options.modes {
        let n = k - 1;
        sums.add_mode(&sec, n, &history[n], &times);
        record_mode_count(&mut table, &sec, k, &times, &sums, ws, ms)?;
    }
    Ok(table)
}

/// Checks the beam and the options (a positive speed, at least 3 output instants, a section on
/// the beam, a free-vibration duration ≥ 0) and returns the section (mid-span of the first span
/// by default) and the free-vibration duration after the crossing (0 for the load on the beam).
fn checked_section_and_window(
    beam: &ContinuousBeam,
    options: &DafOptions,
) -> Result<(f64, f64), AnalyticalError> {
    beam.validate()?;
    super::positive("speed", options.speed)?;
    if options.output_times < 3 {
        return Err(AnalyticalError::OutputTimes {
            count: options.output_times,
        });
    }
    let section = options.section.unwrap_or(0.5 * beam.span_length);
    beam.check_position("section", section)?;
    let extra = match options.window {
        MaximumWindow::LoadOnBeam => 0.0,
        MaximumWindow::WithFreeVibration { duration } => {
            if !(duration.is_finite() && duration >= 0.0) {
                return Err(AnalyticalError::NotPositive {
                    name: "free-vibration duration",
                    value: duration,
                });
            }
            duration
        }
    };
    Ok((section, extra))
}

/// A static reference per unit force: (value, load position [m]).
type StaticValue = (f64, f64);

/// Whether a static deflection per unit force is a zero: below 1e-12 of the largest one of its
/// kind along the beam (l³/EI), at a support.
fn is_zero_deflection(beam: &ContinuousBeam, deflection: f64) -> bool {
    deflection.abs() < 1e-12 * beam.span_length.powi(3) / beam.flexural_rigidity
}

/// The static references per unit force at the section, (value, load position) for the
/// deflection w_s and the moment M_s: the envelope over all load positions or the value with
/// the load at the section. A zero deflection (an interior support) is returned as it is: the
/// table's deflection DAF is then undefined, and its hogging moment's DAF is had. Refused where
/// the moment is a zero (below 1e-12 of l: an end support), where no DAF is defined.
fn static_references(
    beam: &ContinuousBeam,
    section: f64,
    reference: StaticReference,
) -> Result<(StaticValue, StaticValue), AnalyticalError> {
    let ((ws, ws_at), (ms, ms_at)) = match reference {
        StaticReference::Envelope => (
            static_envelope(beam, section, |r| r.deflection)?,
            static_envelope(beam, section, |r| r.bending_moment)?,
        ),
        StaticReference::LoadAtSection => {
            let r = static_response(beam, section, section, 1.0)?;
            ((r.deflection, section), (r.bending_moment, section))
        }
    };
    // A static moment below 1e-12 of the largest one of its kind along the beam is a zero (an
    // end support): no DAF is defined there.
    if ms.abs() < 1e-12 * beam.span_length {
        return Err(AnalyticalError::ZeroStaticResponse {
            quantity: "bending moment",
            section,
        });
    }
    Ok(((ws, ws_at), (ms, ms_at)))
}

/// The table before any mode count: what it was computed from (frequencies, frequency
/// parameters, α, the static references (value, load position) and λ_u = |w_s| EI / l³,
/// λ_M = |M_s| / l), with room for the DAFs of every mode count.
fn empty_daf_table(
    beam: &ContinuousBeam,
    options: &DafOptions,
    modes: &[BeamMode],
    section: f64,
    crossing: f64,
    (ws, ws_at): StaticValue,
    (ms, ms_at): StaticValue,
) -> DafTable {
    let k_max = options.modes;
    let ei = beam.flexural_rigidity;
    DafTable {
        daf_deflection_by_modes: Vec::with_capacity(k_max),
        daf_moment_by_modes: Vec::with_capacity(k_max),
        rdm_by_modes: Vec::with_capacity(k_max),
        time_of_max_deflection: Vec::with_capacity(k_max),
        time_of_max_moment: Vec::with_capacity(k_max),
        daf_deflection_corrected_by_modes: Vec::with_capacity(k_max),
        daf_moment_corrected_by_modes: Vec::with_capacity(k_max),
        rdm_corrected_by_modes: Vec::with_capacity(k_max),
        frequencies_hz: modes.iter().map(|m| m.frequency_hz()).collect(),
        frequency_parameters: modes.iter().map(|m| m.frequency_parameter).collect(),
        alpha: beam.speed_parameter(options.speed),
        speed: options.speed,
        section,
        static_deflection: ws,
        static_deflection_load_position: ws_at,
        static_moment: ms,
        static_moment_load_position: ms_at,
        lambda_deflection: ws.abs() * ei / beam.span_length.powi(3),
        lambda_moment: ms.abs() / beam.span_length,
        static_reference: options.static_reference,
        window: options.window,
        crossing_time: crossing,
        deflection_defined: true,
    }
}

/// The modal sums at every output instant tⱼ, mode by mode: w(tⱼ) = Σ φₙ qₙ(tⱼ),
/// M(tⱼ) = Σ EIφₙ'' qₙ(tⱼ), and the static-corrected R_s(tⱼ) + Σ cₙ (qₙ(tⱼ) − qₙ^qs(tⱼ)).
struct ModalSums {
    deflection: Vec<f64>,
    moment: Vec<f64>,
    corrected_deflection: Vec<f64>,
    corrected_moment: Vec<f64>,
}

impl ModalSums {
    /// No mode yet: the plain sums 0, the static-corrected ones the exact static response.
    fn starting_from_the_static_response(sec: &Section, times: &[f64]) -> Self {
        let (corrected_deflection, corrected_moment): (Vec<f64>, Vec<f64>) =
            times.iter().map(|&t| sec.exact_static(t)).unzip();
        ModalSums {
            deflection: vec![0.0; times.len()],
            moment: vec![0.0; times.len()],
            corrected_deflection,
            corrected_moment,
        }
    }

    /// Adds mode n, given its history qₙ(tⱼ).
    fn add_mode(&mut self, sec: &Section, n: usize, history: &[f64], times: &[f64]) {
        let (phi, mphi) = (sec.shape[n], sec.moment_shape[n]);
        for (j, q) in history.iter().enumerate() {
            self.deflection[j] += phi * q;
            self.moment[j] += mphi * q;
            let dynamic = q - sec.quasi_static(n, times[j]);
            self.corrected_deflection[j] += phi * dynamic;
            self.corrected_moment[j] += mphi * dynamic;
        }
    }
}

/// Records the DAFs with the first k modes (Eqs. 15–17): DAF_u = max s_u w_k / |w_s|,
/// DAF_M = max s_M M_k / |M_s|, RDM = DAF_u / DAF_M and the times of the maxima, and the same
/// DAFs and RDM of the static-corrected sums. Refused when a DAF is not finite.
fn record_mode_count(
    table: &mut DafTable,
    sec: &Section,
    k: usize,
    times: &[f64],
    sums: &ModalSums,
    ws: f64,
    ms: f64,
) -> Result<(), AnalyticalError> {
    let sm = ms.signum();
    let (dm, tm) = maximum(
        |t| sm * sec.value(&sec.moment_shape, k, t),
        times,
        &sums.moment,
        sm,
    );
    let (cm, _) = maximum(
        |t| sm * sec.corrected(&sec.moment_shape, k, t, true),
        times,
        &sums.corrected_moment,
        sm,
    );
    let (daf_m, cdaf_m) = (dm / ms.abs(), cm / ms.abs());
    // Without a static deflection (an interior support) only the moment's DAFs are recorded,
    // and the deflection's maxima are not sought.
    let deflection = if table.deflection_defined {
        let sw = ws.signum();
        let (dw, tw) = maximum(
            |t| sw * sec.value(&sec.shape, k, t),
            times,
            &sums.deflection,
            sw,
        );
        let (cw, _) = maximum(
            |t| sw * sec.corrected(&sec.shape, k, t, false),
            times,
            &sums.corrected_deflection,
            sw,
        );
        Some((dw / ws.abs(), tw, cw / ws.abs()))
    } else {
        None
    };
    if !daf_m.is_finite() || deflection.is_some_and(|(d, _, _)| !d.is_finite()) {
        return Err(AnalyticalError::NonFinite {
            modes: k,
            deflection: deflection.map_or(0.0, |(d, _, _)| d),
            moment: daf_m,
        });
    }
    if let Some((daf_w, tw, cdaf_w)) = deflection {
        table.daf_deflection_by_modes.push(daf_w);
        table.rdm_by_modes.push(daf_w / daf_m);
        table.time_of_max_deflection.push(tw);
        table.daf_deflection_corrected_by_modes.push(cdaf_w);
        table.rdm_corrected_by_modes.push(cdaf_w / cdaf_m);
    }
    table.daf_moment_by_modes.push(daf_m);
    table.time_of_max_moment.push(tm);
    table.daf_moment_corrected_by_modes.push(cdaf_m);
    Ok(())
}

/// Largest value of f(t) = sign·R(t), given the samples R(tⱼ): the sampled maximum, refined by
/// golden-section search over the two sample intervals around the largest sampled local
/// maximum, and around the second largest when it could exceed the first (its sampled value
/// plus its drop to its lower neighbour, the most a smooth peak can rise between samples).
fn maximum(f: impl Fn(f64) -> f64, times: &[f64], sampled: &[f64], sign: f64) -> (f64, f64) {
    let n = sampled.len();
    let v = |j: usize| sign * sampled[j];
    let mut first: Option<usize> = None;
    let mut second: Option<usize> = None;
    for j in 0..n {
        let is_peak = (j == 0 || v(j) >= v(j - 1)) && (j + 1 == n || v(j) >= v(j + 1));
        if !is_peak {
            continue;
        }
        match first {
            Some(b) if v(j) <= v(b) => {
                if second.is_none_or(|s| v(j) > v(s)) {
                    second = Some(j);
                }
            }
            _ => {
                second = first;
                first = Some(j);
            }
        }
    }
    let first = first.unwrap_or(0);
    let drop = |j: usize| {
        let lower = v(j.saturating_sub(1)).min(v((j + 1).min(n - 1)));
        v(j) - lower
    };
    let mut best = (v(first), times[first]);
    let mut candidates = vec![first];
    if let Some(s) = second {
        if v(s) + drop(s) > v(first) {
            candidates.push(s);
        }
    }
    for j in candidates {
        let lo = times[j.saturating_sub(1)];
        let hi = times[(j + 1).min(n - 1)];
        // 16 golden steps shrink the bracket to 0.618¹⁶ ≈ 5e-4 of two sample intervals; the
        // value error is quadratic in that (≈ 1e-7 of the local variation between samples).
        let (t, value) = golden_maximum(&f, lo, hi, 16);
        if value > best.0 {
            best = (value, t);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rdm_with_one_mode_is_312_over_23_pi_squared() {
        // Reference: docs/verification.md §3 and the paper's Eq. 18.
        let beam = ContinuousBeam::new(2, 20.0, 3.24e10, 2.0e4).unwrap();
        let options = DafOptions {
            modes: 1,
            static_reference: StaticReference::LoadAtSection,
            ..DafOptions::default()
        };
        let table = daf_by_modes(&beam, &options).unwrap();
        let expected = 312.0 / (23.0 * std::f64::consts::PI.powi(2));
        // One mode: the same q₁(t) maximum cancels, the ratio is exact up to round-off.
        assert!((table.rdm_by_modes[0] - expected).abs() < 1e-12);
    }
}
