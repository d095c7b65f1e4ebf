//! Frequencies and damping of a free decay by the matrix pencil method (Hua & Sarkar 1990,
//! IEEE Trans. Acoust. Speech Signal Process. 38(5)): the bridge's own modes from the record
//! after the vehicle has left, resolved far finer than a spectrum's 1/T bins and free of the
//! vehicle's forced content.
//!
//! A free decay y_k = Σ_i a_i z_iᵏ (z_i = e^{s_iΔt}, s_i = −ζ_iω_i ± iω_i√(1 − ζ_i²)) makes the
//! Hankel matrix Y (rows y[k..k+L+1]) of rank 2·(modes). With its SVD Y = UΣVᵀ truncated to the
//! order M, V₁ (V without its last row) and V₂ (without its first) satisfy V₂ = V₁·A with the
//! eigenvalues of A = V₁⁺V₂ equal to the z_i (the signal-subspace shift invariance). Noise
//! takes the orders beyond the modes; poles outside the band or with a damping that no bridge
//! has are dropped, and the `count` modes of largest amplitude are kept.
//!
//! Hand-written (about a hundred lines on nalgebra's SVD and Schur decomposition): no
//! well-kept crate implements the matrix pencil or a subspace identification.

use nalgebra::{Complex, DMatrix};
use serde::{Deserialize, Serialize};

use super::filter::butterworth_lowpass;
use super::SignalError;

/// A mode identified from a free decay.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DecayMode {
    /// Undamped natural frequency f = |s|/(2π) [Hz] (what an FE model gives; the damped one
    /// is f·√(1 − ζ²)).
    pub frequency_hz: f64,
    /// Damping ratio ζ = −Re s/|s| [-].
    pub damping_ratio: f64,
}

/// Options of [`identify_free_decay`].
#[derive(Debug, Clone, PartialEq)]
pub struct DecayOptions {
    /// Modes to keep (the largest amplitudes).
    pub count: usize,
    /// Band [Hz].
    pub min_frequency_hz: f64,
    /// Band [Hz].
    pub max_frequency_hz: f64,
}

/// Orders beyond two per mode, which take the noise and the weaker modes: a pole is kept when
/// every one of these orders finds it (a stabilisation check).
const STABILITY_ORDERS: [usize; 3] = [4, 8, 12];

/// Largest damping ratio kept: bridges have 0.5–10 % (Bachmann et al. 1995, Vibration Problems
/// in Structures); a pole beyond 20 % is noise or the filter's.
const MAX_DAMPING: f64 = 0.2;

/// Identifies the modes of a free decay `signal` sampled at `sampling_rate_hz`: zero-phase
/// low-pass at 1.5× the band's top, decimation to at least 4× the band's top, matrix pencils of
/// the orders 2·count + [`STABILITY_ORDERS`] on the decimated signal (pencil parameter one third
/// of its length); the lowest stable poles.
/// Returns the modes in ascending frequency.
pub fn identify_free_decay(
    signal: &[f64],
    sampling_rate_hz: f64,
    options: &DecayOptions,
) -> Result<Vec<DecayMode>, SignalError> {
    let top = options.max_frequency_hz.min(0.45 * sampling_rate_hz);
    let factor = ((sampling_rate_hz / (4.0 * top)).floor() as usize).max(1);
    let smooth = if factor > 1 {
        butterworth_lowpass(8, 1.5 * top, sampling_rate_hz)?.filtfilt(signal, None)?
    } else {
        signal.to_vec()
    };
    let y: Vec<f64> = smooth.iter().step_by(factor).cloned().collect();
    let dt = factor as f64 / sampling_rate_hz;
    let orders = STABILITY_ORDERS.map(|extra| 2 * options.count + extra);
    let pencil = y.len() / 3;
    let largest = orders[orders.len() - 1];
    if pencil < largest + 2 || y.len() < 3 * (largest + 2) {
        return Err(SignalError::SignalTooShort {
            samples: signal.len(),
            required: 3 * (largest + 2) * factor,
        });
    }
    let candidates = orders.map(|order| {
        let poles = pencil_poles(&y, pencil, order);
        physical_modes(&poles, dt, options.min_frequency_hz, top)
    });
    // Stable poles: those of the lower order that the higher orders find again within 0.5 % in
    // frequency and 30 % in damping; noise poles move with the order.
    let mut modes: Vec<DecayMode> = candidates[0]
        .iter()
        .filter(|m| {
            candidates[1..].iter().all(|other| {
                other.iter().any(|o| {
                    (o.frequency_hz / m.frequency_hz - 1.0).abs() < 0.005
                        && (o.damping_ratio / m.damping_ratio - 1.0).abs() < 0.3
                })
            })
        })
        .cloned()
        .collect();
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    modes.truncate(options.count);
    Ok(modes)
}

/// The modes of `poles` (upper half-plane) in the band with a damping that a bridge can have.
fn physical_modes(
    poles: &[Complex<f64>],
    dt: f64,
    min_frequency_hz: f64,
    max_frequency_hz: f64,
) -> Vec<DecayMode> {
    poles
        .iter()
        .filter(|z| z.im > 0.0)
        .map(|z| {
            let s = z.ln() / dt;
            DecayMode {
                frequency_hz: s.norm() / (2.0 * std::f64::consts::PI),
                damping_ratio: -s.re / s.norm(),
            }
        })
        .filter(|m| {
            m.frequency_hz >= min_frequency_hz
                && m.frequency_hz <= max_frequency_hz
                && m.damping_ratio > 0.0
                && m.damping_ratio < MAX_DAMPING
        })
        .collect()
}

/// The poles z_i of order `order` of the Hankel matrix of `y` with pencil parameter `pencil`.
fn pencil_poles(y: &[f64], pencil: usize, order: usize) -> Vec<Complex<f64>> {
    let rows = y.len() - pencil;
    let hankel = DMatrix::from_fn(rows, pencil + 1, |i, j| y[i + j]);
    let svd = hankel.svd(false, true);
    let v_t = svd.v_t.expect("asked for V");
    // Columns of V of the `order` largest singular values (nalgebra sorts them descending).
    let v = v_t.rows(0, order).transpose();
    let v1 = v.rows(0, pencil).into_owned();
    let v2 = v.rows(1, pencil).into_owned();
    let shift = v1.pseudo_inverse(1e-12).expect("a finite pseudo-inverse") * v2;
    shift.complex_eigenvalues().iter().cloned().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_close_damped_modes_are_recovered_from_seven_seconds_of_decay() {
        // Closed form: a sum of three damped sines at 3.653, 4.262 and 5.707 Hz (ζ = 2 %),
        // 7.5 s at 200 Hz, a spectrum's bins (0.13 Hz) cannot split 3.653 and 4.262 cleanly.
        let fs = 200.0;
        let modes = [(3.653, 1.0), (4.262, 0.6), (5.707, 0.4)];
        let zeta = 0.02;
        let y: Vec<f64> = (0..1500)
            .map(|k| {
                let t = k as f64 / fs;
                modes
                    .iter()
                    .map(|(f, a)| {
                        let w = 2.0 * std::f64::consts::PI * f;
                        a * (-zeta * w * t).exp() * (w * (1.0f64 - zeta * zeta).sqrt() * t).sin()
                    })
                    .sum()
            })
            .collect();
        let found = identify_free_decay(
            &y,
            fs,
            &DecayOptions {
                count: 3,
                min_frequency_hz: 2.0,
                max_frequency_hz: 12.0,
            },
        )
        .unwrap();
        assert_eq!(found.len(), 3, "{found:?}");
        for (m, (f, _)) in found.iter().zip(modes) {
            assert!((m.frequency_hz / f - 1.0).abs() < 1e-4, "{m:?} vs {f}");
            assert!((m.damping_ratio - zeta).abs() < 1e-3, "{m:?}");
        }
    }
}
