//! Butterworth low-pass filters as second-order sections, causal and zero-phase filtering.
//!
//! Hand-written: no maintained Rust crate offers a scipy-compatible zero-phase SOS `filtfilt`
//! (odd-extension edge padding with the steady-state initial conditions of `sosfilt_zi`), and
//! the field-test DAF depends on exactly those edges. Every function here mirrors the scipy
//! function of the same name (`scipy.signal.butter(..., output='sos')`, `sosfilt`,
//! `sosfilt_zi`, `sosfiltfilt`), so results can be cross-checked against Python line by line.

use realfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use super::SignalError;

/// One second-order section `[b0, b1, b2, a0, a1, a2]` with `a0 = 1`:
/// H(z) = (b0 + b1 z⁻¹ + b2 z⁻²) / (1 + a1 z⁻¹ + a2 z⁻²).
pub type Section = [f64; 6];

/// A digital filter as a cascade of second-order sections (scipy's `sos` array).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SosFilter {
    /// The sections, applied first to last.
    pub sections: Vec<Section>,
}

/// Designs a digital Butterworth low-pass filter of any order as second-order sections, exactly
/// as `scipy.signal.butter(order, cutoff_hz, 'low', fs=sampling_rate_hz, output='sos')`:
///
/// 1. analog prototype poles p_m = −exp(iπm/(2N)), m = −N+1, −N+3, …, N−1 (no zeros, gain 1);
/// 2. pre-warping: ω_a = 4·tan(π f_c / f_s) (scipy normalises to f_s = 2), so that the digital
///    filter has |H| = 1/√2 exactly at f_c;
/// 3. low-pass scaling p → ω_a p, gain ω_a^N; bilinear transform z = (4 + s)/(4 − s), N zeros
///    at z = −1, gain k·Re(Π 1/(4 − p));
/// 4. `zpk2sos` with `pairing='nearest'`: the poles closest to the unit circle go in the last
///    section, the overall gain in the first.
///
/// The magnitude response is |H(f)|² = 1 / (1 + (tan(πf/f_s)/tan(πf_c/f_s))^{2N}).
///
/// `order` ≥ 1; 0 < `cutoff_hz` < `sampling_rate_hz`/2.
pub fn butterworth_lowpass(
    order: usize,
    cutoff_hz: f64,
    sampling_rate_hz: f64,
) -> Result<SosFilter, SignalError> {
    if !(sampling_rate_hz.is_finite() && sampling_rate_hz > 0.0) {
        return Err(SignalError::BadSamplingRate { sampling_rate_hz });
    }
    let nyquist_hz = sampling_rate_hz / 2.0;
    if order == 0 || order > 40 {
        return Err(SignalError::BadFilterOrder { order });
    }
    if !(cutoff_hz.is_finite() && cutoff_hz > 0.0 && cutoff_hz < nyquist_hz) {
        return Err(SignalError::BadCutoff {
            cutoff_hz,
            nyquist_hz,
        });
    }
    let n = order as f64;
    let warped = 4.0 * (std::f64::consts::PI * cutoff_hz / sampling_rate_hz).tan();
    let mut poles = Vec::with_capacity(order);
    let mut gain = warped.powi(order as i32);
    let mut denominator = Complex64::new(1.0, 0.0);
    for j in 0..order {
        let m = -(n - 1.0) + 2.0 * j as f64;
        let analog = -Complex64::from_polar(1.0, std::f64::consts::PI * m / (2.0 * n))
            * Complex64::from(warped);
        let four = Complex64::from(4.0);
        denominator *= four - analog;
        poles.push((four + analog) / (four - analog));
    }
    gain *= (Complex64::from(1.0) / denominator).re;
    let zeros = vec![Complex64::new(-1.0, 0.0); order];
    Ok(SosFilter {
        sections: zpk2sos_nearest(&zeros, &poles, gain),
    })
}

/// A root kept as scipy keeps it after `_cplxreal`: exactly real, or the upper member of a
/// conjugate pair.
#[derive(Debug, Clone, Copy)]
struct Root {
    value: Complex64,
    real: bool,
}

/// scipy's `_cplxreal`: complex roots (upper half, sorted by real part then |imag|) followed by
/// real roots sorted ascending. Tolerance 100·ε·|z| as scipy.
fn cplxreal(roots: &[Complex64]) -> Vec<Root> {
    let tol = 100.0 * f64::EPSILON;
    let mut complex: Vec<Complex64> = Vec::new();
    let mut real: Vec<f64> = Vec::new();
    for z in roots {
        if z.im.abs() <= tol * z.norm() {
            real.push(z.re);
        } else if z.im > 0.0 {
            complex.push(*z);
        }
    }
    complex.sort_by(|a, b| {
        a.re.total_cmp(&b.re)
            .then_with(|| a.im.abs().total_cmp(&b.im.abs()))
    });
    real.sort_by(f64::total_cmp);
    complex
        .into_iter()
        .map(|value| Root { value, real: false })
        .chain(real.into_iter().map(|r| Root {
            value: Complex64::new(r, 0.0),
            real: true,
        }))
        .collect()
}

#[derive(Clone, Copy, PartialEq)]
enum Which {
    Any,
    Real,
    Complex,
}

/// scipy's `_nearest_real_complex_idx`: the index in `from` of the root nearest `to`, among all,
/// only real or only complex roots.
fn nearest(from: &[Root], to: Complex64, which: Which) -> Option<usize> {
    let mut order: Vec<usize> = (0..from.len()).collect();
    order.sort_by(|&a, &b| {
        (from[a].value - to)
            .norm()
            .total_cmp(&(from[b].value - to).norm())
    });
    order.into_iter().find(|&i| match which {
        Which::Any => true,
        Which::Real => from[i].real,
        Which::Complex => !from[i].real,
    })
}

/// Polynomial coefficients (highest power first) of Π (x − r), real part; a complex root
/// stands for itself and its conjugate when `conjugate` is set.
fn poly(roots: &[(Complex64, bool)]) -> Vec<f64> {
    let mut c = vec![Complex64::from(1.0)];
    for &(r, pair) in roots {
        let factors: &[Complex64] = if pair { &[r, r.conj()] } else { &[r] };
        for &f in factors {
            let mut next = vec![Complex64::from(0.0); c.len() + 1];
            for (i, ci) in c.iter().enumerate() {
                next[i] += ci;
                next[i + 1] -= ci * f;
            }
            c = next;
        }
    }
    c.into_iter().map(|x| x.re).collect()
}

/// scipy's `_single_zpksos`: numerator and denominator right-aligned in their three slots.
fn single_section(zeros: &[(Complex64, bool)], poles: &[(Complex64, bool)]) -> Section {
    let b = poly(zeros);
    let a = poly(poles);
    let mut s = [0.0; 6];
    s[3 - b.len()..3].copy_from_slice(&b);
    s[6 - a.len()..6].copy_from_slice(&a);
    s
}

/// scipy's `zpk2sos(z, p, k, pairing='nearest')` for a digital filter with as many zeros as
/// poles (true of the Butterworth low-pass).
fn zpk2sos_nearest(zeros: &[Complex64], poles: &[Complex64], gain: f64) -> Vec<Section> {
    let mut z: Vec<Complex64> = zeros.to_vec();
    let mut p: Vec<Complex64> = poles.to_vec();
    let n_sections = p.len().max(z.len()).div_ceil(2);
    if p.len() % 2 == 1 {
        p.push(Complex64::from(0.0));
        z.push(Complex64::from(0.0));
    }
    let mut z = cplxreal(&z);
    let mut p = cplxreal(&p);
    let mut sos = vec![[0.0; 6]; n_sections];
    let zero = Complex64::from(0.0);
    for si in (0..n_sections).rev() {
        // The next "worst" pole: nearest the unit circle (first index on ties, as argmin).
        let mut p1_idx = 0;
        for (i, r) in p.iter().enumerate() {
            if (1.0 - r.value.norm()).abs() < (1.0 - p[p1_idx].value.norm()).abs() {
                p1_idx = i;
            }
        }
        let p1 = p.remove(p1_idx);
        let real_poles_left = p.iter().filter(|r| r.real).count();
        let real_zeros_left = z.iter().filter(|r| r.real).count();
        if p1.real && real_poles_left == 0 {
            // Special case (1): the last remaining real pole.
            let zi = nearest(&z, p1.value, Which::Real).expect("a real zero is left");
            let z1 = z.remove(zi);
            sos[si] = single_section(
                &[(z1.value, false), (zero, false)],
                &[(p1.value, false), (zero, false)],
            );
        } else if p.len() + 1 == z.len() && !p1.real && real_poles_left == 1 && real_zeros_left == 1
        {
            // Special case (2): one real pole and one real zero left; pair with a complex zero.
            let zi = nearest(&z, p1.value, Which::Complex).expect("a complex zero is left");
            let z1 = z.remove(zi);
            sos[si] = single_section(&[(z1.value, true)], &[(p1.value, true)]);
        } else {
            let poles_of_section: Vec<(Complex64, bool)> = if p1.real {
                let mut p2_idx: Option<usize> = None;
                for (i, r) in p.iter().enumerate() {
                    if r.real
                        && p2_idx.is_none_or(|j: usize| {
                            (r.value.norm() - 1.0).abs() < (p[j].value.norm() - 1.0).abs()
                        })
                    {
                        p2_idx = Some(i);
                    }
                }
                let p2 = p.remove(p2_idx.expect("a second real pole is left"));
                vec![(p1.value, false), (p2.value, false)]
            } else {
                vec![(p1.value, true)]
            };
            if let Some(zi) = nearest(&z, p1.value, Which::Any) {
                let z1 = z.remove(zi);
                if !z1.real {
                    sos[si] = single_section(&[(z1.value, true)], &poles_of_section);
                } else if let Some(zj) = nearest(&z, p1.value, Which::Real) {
                    let z2 = z.remove(zj);
                    sos[si] =
                        single_section(&[(z1.value, false), (z2.value, false)], &poles_of_section);
                } else {
                    sos[si] = single_section(&[(z1.value, false)], &poles_of_section);
                }
            } else {
                sos[si] = single_section(&[], &poles_of_section);
            }
        }
    }
    for c in &mut sos[0][..3] {
        *c *= gain;
    }
    sos
}

impl SosFilter {
    /// Number of sections.
    pub fn len(&self) -> usize {
        self.sections.len()
    }

    /// True for a filter with no section (the identity).
    pub fn is_empty(&self) -> bool {
        self.sections.is_empty()
    }

    /// Complex frequency response H(e^{iω}) at `frequency_hz`, ω = 2πf/f_s.
    pub fn frequency_response(&self, frequency_hz: f64, sampling_rate_hz: f64) -> Complex64 {
        let w = 2.0 * std::f64::consts::PI * frequency_hz / sampling_rate_hz;
        let z1 = Complex64::from_polar(1.0, -w);
        let z2 = z1 * z1;
        self.sections.iter().fold(Complex64::from(1.0), |h, s| {
            h * (s[0] + z1 * s[1] + z2 * s[2]) / (s[3] + z1 * s[4] + z2 * s[5])
        })
    }

    /// Steady-state initial conditions of each section for a unit step input (scipy's
    /// `sosfilt_zi`): section j's state is `lfilter_zi(b_j, a_j)` times the DC gain of the
    /// sections before it. For the transposed direct form II with DC gain g = Σb/Σa,
    /// zi = [b1 + b2 − (a1 + a2)·g, b2 − a2·g].
    pub fn steady_state_initial_conditions(&self) -> Vec<[f64; 2]> {
        let mut scale = 1.0;
        self.sections
            .iter()
            .map(|s| {
                let g = (s[0] + s[1] + s[2]) / (s[3] + s[4] + s[5]);
                let zi = [
                    scale * (s[1] + s[2] - (s[4] + s[5]) * g),
                    scale * (s[2] - s[5] * g),
                ];
                scale *= g;
                zi
            })
            .collect()
    }

    /// Causal filtering (scipy's `sosfilt`), transposed direct form II in each section:
    /// y = b0·x + z0; z0 ← b1·x − a1·y + z1; z1 ← b2·x − a2·y. `initial` gives the state of
    /// each section (zeros when `None`); the final state is returned with the output.
    pub fn filter(&self, input: &[f64], initial: Option<&[[f64; 2]]>) -> (Vec<f64>, Vec<[f64; 2]>) {
        let mut state: Vec<[f64; 2]> = match initial {
            Some(zi) => zi.to_vec(),
            None => vec![[0.0; 2]; self.sections.len()],
        };
        let mut output = Vec::with_capacity(input.len());
        for &x0 in input {
            let mut x = x0;
            for (s, z) in self.sections.iter().zip(state.iter_mut()) {
                let y = s[0] * x + z[0];
                z[0] = s[1] * x - s[4] * y + z[1];
                z[1] = s[2] * x - s[5] * y;
                x = y;
            }
            output.push(x);
        }
        (output, state)
    }

    /// scipy's default `padlen` for `sosfiltfilt`:
    /// 3·(2·n_sections + 1 − min(#sections with b2 = 0, #sections with a2 = 0)).
    pub fn default_pad_length(&self) -> usize {
        let zero_b2 = self.sections.iter().filter(|s| s[2] == 0.0).count();
        let zero_a2 = self.sections.iter().filter(|s| s[5] == 0.0).count();
        3 * (2 * self.sections.len() + 1 - zero_b2.min(zero_a2))
    }

    /// Zero-phase forward–backward filtering (scipy's `sosfiltfilt` with `padtype='odd'`):
    /// the signal is extended at each end by `pad_length` samples of its odd reflection
    /// (2·x₀ − x_{k} on the left, 2·x_{n−1} − x_{n−1−k} on the right), filtered forwards from
    /// the state zi·(first extended sample), reversed, filtered again from zi·(first sample of
    /// the reversed output), reversed back and trimmed. The magnitude response is |H|², the
    /// phase is zero.
    ///
    /// `pad_length` defaults to [`SosFilter::default_pad_length`]; the signal must be longer
    /// than it.
    pub fn filtfilt(
        &self,
        input: &[f64],
        pad_length: Option<usize>,
    ) -> Result<Vec<f64>, SignalError> {
        let edge = pad_length.unwrap_or_else(|| self.default_pad_length());
        if input.len() <= edge {
            return Err(SignalError::SignalTooShort {
                samples: input.len(),
                required: edge + 1,
            });
        }
        if let Some(i) = input.iter().position(|x| !x.is_finite()) {
            return Err(SignalError::NonFiniteSample {
                index: i,
                value: input[i],
            });
        }
        let n = input.len();
        let mut extended = Vec::with_capacity(n + 2 * edge);
        for k in (1..=edge).rev() {
            extended.push(2.0 * input[0] - input[k]);
        }
        extended.extend_from_slice(input);
        for k in 1..=edge {
            extended.push(2.0 * input[n - 1] - input[n - 1 - k]);
        }
        let zi = self.steady_state_initial_conditions();
        let scaled =
            |v: f64| -> Vec<[f64; 2]> { zi.iter().map(|z| [z[0] * v, z[1] * v]).collect() };
        let (mut forward, _) = self.filter(&extended, Some(&scaled(extended[0])));
        forward.reverse();
        let (mut backward, _) = self.filter(&forward, Some(&scaled(forward[0])));
        backward.reverse();
        Ok(backward[edge..edge + n].to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_one_has_one_first_order_section() {
        // Reference: bilinear transform of ω_a/(s + ω_a) with K = tan(πf_c/f_s):
        // b = K/(1+K)·[1, 1], a = [1, (K−1)/(K+1)] (closed form), in scipy's layout
        // [b0, b1, 0, 1, a1, 0] because zpk2sos pads odd orders with a pole and zero at 0.
        let f = butterworth_lowpass(1, 10.0, 100.0).unwrap();
        let k = (std::f64::consts::PI * 0.1).tan();
        let expected = [
            k / (1.0 + k),
            k / (1.0 + k),
            0.0,
            1.0,
            (k - 1.0) / (k + 1.0),
            0.0,
        ];
        assert_eq!(f.len(), 1);
        for (a, b) in f.sections[0].iter().zip(expected) {
            // Round-off of a handful of complex operations.
            assert!((a - b).abs() < 1e-14, "{:?} vs {expected:?}", f.sections[0]);
        }
        assert_eq!(f.default_pad_length(), 3 * (2 + 1 - 1));
    }

    #[test]
    fn steady_state_conditions_make_a_constant_input_pass_unchanged() {
        let f = butterworth_lowpass(5, 3.0, 200.0).unwrap();
        let zi = f.steady_state_initial_conditions();
        let (y, _) = f.filter(&[1.0; 50], Some(&zi));
        for v in y {
            // DC gain is exactly 1 up to round-off of five cascaded sections.
            assert!((v - 1.0).abs() < 1e-12, "{v}");
        }
    }
}
