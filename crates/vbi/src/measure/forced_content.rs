//! The crossing's forced content recognised among the modes identified from a record that
//! includes the crossing (the Welch peaks or SSI-COV of the whole record): the vehicle's own
//! modes (body bounce and pitch, axle hop) and the harmonics of the quasi-static response are
//! driven by the vehicle and stop when it leaves, whereas the bridge's modes ring on after it
//! has left, decaying at their damping (e^{−ζωt}: to 49 % after one second at 3.65 Hz and 3 %
//! damping, 32 % at 5 %).
//!
//! For each identified frequency f and acceleration channel, the amplitude of the Hann-windowed
//! projection on e^{iωt} (ω = 2πf),
//!
//! ```text
//! A(window) = 2·|Σ_n w_n x_n e^{−iωt_n}| / Σ_n w_n,   w_n = sin²(π n/(N − 1))
//! ```
//!
//! is taken while the vehicle crosses (entry to exit) and over the first
//! [`FORCED_CONTENT_WINDOW`] to twice that after it has left. A mode whose ratio
//! A(after)/A(crossing) stays below [`FORCED_CONTENT_RATIO`] on every channel is forced content.
//! The Hann window keeps a neighbour 2/T away (2 Hz for T = 1 s) out of the projection (side
//! lobes below −31 dB, falling as 1/Δf³). Without the vehicle's exit time or a second of record
//! after it, forced content cannot be told from a mode this way: the vehicle's frequencies
//! (`[measurement.vehicle] frequencies_hz`) are then the only guard.

use serde::Serialize;

use super::preparation::crossing_window;
use super::IdentifiedMode;
use crate::measure::measurement::Measurement;
use crate::signal::MeasuredQuantity;

/// Shortest record after the vehicle has left that the check reads [s]; it reads up to twice
/// this.
pub const FORCED_CONTENT_WINDOW: f64 = 1.0;

/// Largest ratio of a mode's amplitude after the vehicle has left to its amplitude while it
/// crosses for the mode to be taken as forced content [-]: a bridge mode of 10 % damping at
/// 1 Hz keeps about 60 % over the first second, a forced component falls to the noise.
pub const FORCED_CONTENT_RATIO: f64 = 0.1;

/// Extra modes an identification that the check can read looks for, so that the modes it
/// moves to `forced_modes` leave `spectrum.modes` of the bridge's.
pub const FORCED_CONTENT_EXTRA_MODES: usize = 2;

/// Whether the identified modes were checked for the crossing's forced content.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ForcedContentCheck {
    /// The identification read only the free vibration after the vehicle had left, which
    /// holds no forced content.
    NotNeeded,
    /// Every identified mode was checked against the record after the vehicle left.
    Checked,
    /// The identification read the crossing, but the record lacks the exit time or
    /// [`FORCED_CONTENT_WINDOW`] after it: forced content could not be recognised.
    NotPossible,
}

/// The sample ranges of the crossing and of the record after the vehicle has left, when the
/// exit is known and at least [`FORCED_CONTENT_WINDOW`] is recorded after it.
fn windows(m: &Measurement) -> Option<(std::ops::Range<usize>, std::ops::Range<usize>)> {
    let crossing = crossing_window(m)?;
    let exit = crossing.exit_time_s?;
    let end = m.time[m.time.len() - 1];
    if end - exit < FORCED_CONTENT_WINDOW {
        return None;
    }
    let index = |t: f64| m.time.partition_point(|&s| s < t);
    let during = index(crossing.entry_time_s)..index(exit);
    let after = index(exit)..index(exit + 2.0 * FORCED_CONTENT_WINDOW);
    (during.len() >= 16 && after.len() >= 16).then_some((during, after))
}

/// Whether an identification of the crossing can be checked (extra modes are then sought).
pub(super) fn checkable(m: &Measurement) -> bool {
    windows(m).is_some()
}

/// The modes that ring on after the vehicle has left, and those that do not (forced), with
/// the check's status; `read_crossing`: the identification read the record while the vehicle
/// crossed.
pub(super) fn without_forced_content(
    m: &Measurement,
    modes: Vec<IdentifiedMode>,
    read_crossing: bool,
) -> (Vec<IdentifiedMode>, Vec<IdentifiedMode>, ForcedContentCheck) {
    if !read_crossing {
        return (modes, Vec::new(), ForcedContentCheck::NotNeeded);
    }
    let Some((during, after)) = windows(m) else {
        return (modes, Vec::new(), ForcedContentCheck::NotPossible);
    };
    let accelerations: Vec<&[f64]> = m
        .channels
        .iter()
        .filter(|c| c.kind == MeasuredQuantity::Acceleration)
        .map(|c| c.samples.as_slice())
        .collect();
    let rings_on = |p: &IdentifiedMode| {
        let omega = 2.0 * std::f64::consts::PI * p.frequency_hz;
        accelerations.iter().any(|x| {
            let crossing = amplitude(&m.time[during.clone()], &x[during.clone()], omega);
            let free = amplitude(&m.time[after.clone()], &x[after.clone()], omega);
            free >= FORCED_CONTENT_RATIO * crossing
        })
    };
    let (kept, forced): (Vec<_>, Vec<_>) = modes.into_iter().partition(rings_on);
    (kept, forced, ForcedContentCheck::Checked)
}

/// The amplitude of the Hann-windowed projection of `x` at `times` on e^{iωt}.
fn amplitude(times: &[f64], x: &[f64], omega: f64) -> f64 {
    let n = x.len();
    let (mut re, mut im, mut weights) = (0.0, 0.0, 0.0);
    for (k, (&t, &v)) in times.iter().zip(x).enumerate() {
        let w = (std::f64::consts::PI * k as f64 / (n - 1) as f64)
            .sin()
            .powi(2);
        re += w * v * (omega * t).cos();
        im -= w * v * (omega * t).sin();
        weights += w;
    }
    2.0 * re.hypot(im) / weights
}

#[cfg(test)]
mod tests {
    use super::amplitude;

    #[test]
    fn the_hann_projection_gives_a_sines_amplitude_and_keeps_a_neighbour_two_hertz_away_out() {
        // Reference: a sine of amplitude 0.02 at 3.83 Hz over 1 s at 200 Hz: the projection
        // gives 0.02 within 2 % (a non-integer number of periods); a sine of 0.05 at 1.57 Hz
        // beside it (2.26 Hz away) adds less than 5 % of its own amplitude.
        let times: Vec<f64> = (0..200).map(|i| i as f64 / 200.0).collect();
        let tau = 2.0 * std::f64::consts::PI;
        let sine: Vec<f64> = times
            .iter()
            .map(|t| 0.02 * (tau * 3.83 * t).sin())
            .collect();
        let a = amplitude(&times, &sine, tau * 3.83);
        assert!((a / 0.02 - 1.0).abs() < 0.02, "{a}");
        let neighbour: Vec<f64> = times
            .iter()
            .map(|t| 0.05 * (tau * 1.57 * t).sin())
            .collect();
        let leak = amplitude(&times, &neighbour, tau * 3.83);
        assert!(leak < 0.05 * 0.05, "{leak}");
    }
}
