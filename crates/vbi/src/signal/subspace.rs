//! Operational modal analysis of several measured channels by subspace identification: natural
//! frequencies, damping ratios and mode shapes at the sensors, with a stabilisation diagram and
//! the scatter of each mode over the model orders.
//!
//! Two block Hankel matrices, one core:
//!
//! * [`identify_free_response`], the Eigensystem Realization Algorithm (ERA, Juang & Pappa 1985,
//!   J. Guid. Control Dyn. 8(5); the multi-output matrix pencil): a free decay of l channels,
//!   y_k = C·A^k·x₀ ∈ ℝˡ, stacked as H₀[i, j] = y_{i+j} (block rows i = 0 … p−1, columns
//!   j = 0 … q−1) factors as H₀ = O·X with the observability matrix O = [C; CA; …; CA^{p−1}].
//! * [`identify_output_only`], covariance-driven stochastic subspace identification (SSI-COV,
//!   Peeters & De Roeck 1999, Mech. Syst. Signal Process. 13(6)): for a response driven by
//!   broadband forces the output correlations R_i = E[y_{k+i}·y_kᵀ] = C·A^{i−1}·G (i ≥ 1) make
//!   the block Hankel H[i, j] = R_{i+j+1} (i, j = 0 … p−1) factor in the same way.
//!
//! The core: H = U·Σ·Vᵀ; for each model order n = 2, 4, …, `max_order`, O_n = U_n·Σ_n^{1/2},
//! A = O↑⁺·O↓ (O↑ without the last block row, O↓ without the first: the shift invariance
//! O↓ = O↑·A), C = the first block row of O_n. An eigenpair A·ψ = μ·ψ gives the continuous pole
//! λ = ln(μ)·f_s (μ = e^{λΔt}), the undamped natural frequency f = |λ|/2π, the damping ratio
//! ζ = −Re λ/|λ| and the complex mode shape φ = C·ψ. Since Σ_n^{1/2} is only a change of basis
//! of the state, A is computed as U↑⁺·U↓ (the same eigenvalues; ψ in that basis, φ = U₁·ψ):
//! no division by singular values that may be zero.
//!
//! A pole is kept when f lies in the band, 0 < ζ < `max_damping_ratio` and Im μ > 0 (one of each
//! conjugate pair). It is *stable* when the next lower order (n − 2) has a pole within the
//! frequency, damping and MAC tolerances. Stable poles are clustered across orders by frequency
//! (single linkage); a cluster found at `min_stable_orders` or more orders, nearly real (mean
//! MPC ≥ `min_phase_collinearity`) and with a damping steady over the orders is a mode.
//!
//! Hand-written (a few hundred lines on faer's SVD, QR and eigendecomposition and realfft): no
//! well-kept Rust crate does operational modal analysis.

use std::f64::consts::TAU;

use faer::linalg::solvers::SolveLstsq;
use faer::{c64, Mat, MatRef};
use realfft::RealFftPlanner;
use serde::{Deserialize, Serialize};

use super::SignalError;

/// Largest block Hankel matrix built [entries]: 5·10⁷ doubles are 400 MB. A free response
/// longer than that uses only the first columns (the strongest part of the decay).
pub const HANKEL_ENTRY_LIMIT: usize = 50_000_000;

/// Periods of `min_frequency_hz` that the default block rows span.
const DEFAULT_PERIODS: f64 = 2.0;

/// Cap on the rows p·l of the default block Hankel: the SVD costs O(rows²·columns), and beyond a
/// few hundred rows the estimates of a bridge record no longer improve (on the 8 s, 4-channel
/// record of the tests, 30 noise seeds: RMS frequency error 0.12 % at 120 rows, 0.077 % at 240,
/// 0.065 % at 400, 0.064 % at 800 for five times the time).
const DEFAULT_MAX_HANKEL_ROWS: usize = 400;

/// Options of [`identify_free_response`] and [`identify_output_only`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubspaceOptions {
    /// Modes to return at most (default 3): the strongest clusters, see [`SubspaceMode`].
    pub modes: usize,
    /// Lowest frequency kept [Hz] (default 0.5 Hz: below lies the quasi-static content of a
    /// crossing). Also sets the default block rows.
    pub min_frequency_hz: f64,
    /// Highest frequency kept [Hz] (default +∞, i.e. the Nyquist frequency f_s/2).
    pub max_frequency_hz: f64,
    /// Highest model order n (even, ≥ 4; default 40): orders 2, 4, …, `max_order` are tried.
    /// Two orders per mode are needed, more to give the noise its own poles: at least 4 to 6
    /// times the modes expected in the band.
    pub max_order: usize,
    /// Block rows p of the Hankel matrix (default `None`: enough to span 2 periods of
    /// `min_frequency_hz`, p = ⌈2·f_s/f_min⌉, capped at 400/l (400 Hankel rows) and at what the
    /// record allows, and at least ⌈max_order/l⌉ + 1 so that O↑ has n rows or more).
    pub block_rows: Option<usize>,
    /// Largest damping ratio kept [-] (default 0.2: bridges have 0.5–10 %; beyond 20 % a pole
    /// models noise).
    pub max_damping_ratio: f64,
    /// Relative frequency change [-] allowed between orders n − 2 and n for a stable pole, and
    /// the linkage distance of the clusters (default 0.01).
    pub frequency_tolerance: f64,
    /// Relative damping change [-] allowed between orders n − 2 and n (default 0.2). Damping
    /// estimates of a noisy record move by 10–20 % between orders while the frequency moves by
    /// less than 1 %; a noise pole's damping typically changes by a factor. The usual 5 % of
    /// laboratory tests rejects real modes of a field record.
    pub damping_tolerance: f64,
    /// Least MAC [-] between the shapes at orders n − 2 and n (default 0.95).
    pub mac_tolerance: f64,
    /// Orders at which a cluster must be stable to be a mode (default `None`: a third of the
    /// orders tried, at least 3 and at most all but order 2, which has none below it).
    pub min_stable_orders: Option<usize>,
    /// Least mean modal phase collinearity [-] of a mode's cluster (default 0.9). A mode of a
    /// classically damped structure has MPC = 1. In trials during development, pure noise
    /// (4 channels, 8 s, 60 seeds, ERA and SSI-COV) gave 68 stable clusters with MPC 0.05–0.9
    /// (one above 0.9) while modes whose initial amplitude was 4 times the noise kept
    /// MPC > 0.98. Use 0 to keep every cluster.
    pub min_phase_collinearity: f64,
}

impl Default for SubspaceOptions {
    fn default() -> Self {
        SubspaceOptions {
            modes: 3,
            min_frequency_hz: 0.5,
            max_frequency_hz: f64::INFINITY,
            max_order: 40,
            block_rows: None,
            max_damping_ratio: 0.2,
            frequency_tolerance: 0.01,
            damping_tolerance: 0.2,
            mac_tolerance: 0.95,
            min_stable_orders: None,
            min_phase_collinearity: 0.9,
        }
    }
}

/// Which block Hankel matrix the poles come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SubspaceMethod {
    /// ERA on the samples of a free response ([`identify_free_response`]).
    FreeResponse,
    /// SSI-COV on the output correlations ([`identify_output_only`]).
    OutputOnly,
}

/// An identified mode: a cluster of stable poles over the model orders.
///
/// The standard deviations are the scatter over the model orders of the cluster: a lower bound
/// of the statistical uncertainty (which would need the record's variance, e.g. by splitting it
/// into blocks), useful to rank how well each mode is determined.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubspaceMode {
    /// Undamped natural frequency f = |λ|/2π, median over the cluster [Hz].
    pub frequency_hz: f64,
    /// Standard deviation of f over the cluster [Hz].
    pub frequency_std_hz: f64,
    /// Damping ratio ζ = −Re λ/|λ|, median over the cluster [-].
    pub damping_ratio: f64,
    /// Standard deviation of ζ over the cluster [-].
    pub damping_std: f64,
    /// Real mode shape at the channels [-]: the mean of the cluster's shapes, each rotated in
    /// the complex plane to the largest real part and normalised to a largest component +1.
    pub shape: Vec<f64>,
    /// Modal phase collinearity MPC = |φᵀφ|²/(φᴴφ)² [-], mean over the cluster: 1 for a real
    /// (classically damped) mode, lower when the channels are out of phase (noise or
    /// non-proportional damping).
    pub modal_phase_collinearity: f64,
    /// Number of orders at which the cluster is stable.
    pub stable_orders: usize,
    /// Lowest such order: strong modes take the leading singular values and appear first.
    pub lowest_stable_order: usize,
}

/// A pole of the stabilisation diagram.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StabilisationPole {
    /// Model order n.
    pub order: usize,
    /// Undamped natural frequency [Hz].
    pub frequency_hz: f64,
    /// Damping ratio [-].
    pub damping_ratio: f64,
    /// Stable with respect to order n − 2 (frequency, damping and MAC within tolerance).
    pub stable: bool,
}

/// The result of a subspace identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubspaceIdentification {
    /// Which Hankel matrix.
    pub method: SubspaceMethod,
    /// Modes in ascending frequency (at most `options.modes`).
    pub modes: Vec<SubspaceMode>,
    /// Every pole kept, by ascending order, for the stabilisation diagram.
    pub diagram: Vec<StabilisationPole>,
    /// Singular values of the block Hankel matrix, descending [unit² for SSI-COV, unit for ERA].
    pub singular_values: Vec<f64>,
    /// Block rows p used.
    pub block_rows: usize,
    /// Columns of the block Hankel matrix.
    pub hankel_columns: usize,
}

/// The checked input of either method: samples per channel, the band [Hz], the channel count
/// and the block rows p.
fn prelude(
    channels: &[&[f64]],
    sampling_rate_hz: f64,
    options: &SubspaceOptions,
    method: SubspaceMethod,
) -> Result<(usize, (f64, f64), usize, usize), SignalError> {
    let (samples, band) = check_input(channels, sampling_rate_hz, options)?;
    let outputs = channels.len();
    let p = block_rows(options, outputs, samples, sampling_rate_hz, band.0, method)?;
    Ok((samples, band, outputs, p))
}

/// Identifies the modes of a free response (the bridge after the vehicle has left) by ERA.
///
/// `channels` are the sensors (equal lengths, one sample per 1/`sampling_rate_hz`); the block
/// Hankel H₀[i, j] = y_{i+j} has p·l rows and q = N − p + 1 columns (fewer if it would exceed
/// [`HANKEL_ENTRY_LIMIT`]); then the core of the module documentation. A constant offset of a
/// channel is a pole at 0 Hz and is left out by the band.
pub fn identify_free_response(
    channels: &[&[f64]],
    sampling_rate_hz: f64,
    options: &SubspaceOptions,
) -> Result<SubspaceIdentification, SignalError> {
    let method = SubspaceMethod::FreeResponse;
    let (samples, band, outputs, p) = prelude(channels, sampling_rate_hz, options, method)?;
    let rows = p * outputs;
    let needed = p.max(options.max_order) + 1;
    let columns = (samples - p + 1).min(HANKEL_ENTRY_LIMIT / rows);
    if columns < needed {
        return Err(SignalError::HankelTooLarge {
            rows,
            columns: needed,
            limit: HANKEL_ENTRY_LIMIT,
        });
    }
    let hankel = Mat::from_fn(rows, columns, |r, c| channels[r % outputs][r / outputs + c]);
    identify(
        hankel.as_ref(),
        outputs,
        sampling_rate_hz,
        band,
        options,
        method,
        p,
    )
}

/// Identifies the modes of a response to broadband forces (traffic, wind, ground) by SSI-COV.
///
/// Each channel's mean is removed; R_i[a, b] = Σ_k y_a[k+i]·y_b[k]/(N − i) for i = 1 … 2p − 1 and
/// every channel pair, by FFT (zero-padded to avoid wrap-around); H[i, j] = R_{i+j+1} is
/// p·l × p·l; then the core of the module documentation. Needs N ≥ 4p samples (statistically,
/// the longer the better: the frequency scatter falls as 1/√N).
pub fn identify_output_only(
    channels: &[&[f64]],
    sampling_rate_hz: f64,
    options: &SubspaceOptions,
) -> Result<SubspaceIdentification, SignalError> {
    let method = SubspaceMethod::OutputOnly;
    let (_, band, outputs, p) = prelude(channels, sampling_rate_hz, options, method)?;
    let rows = p * outputs;
    if rows.saturating_mul(rows) > HANKEL_ENTRY_LIMIT {
        return Err(SignalError::HankelTooLarge {
            rows,
            columns: rows,
            limit: HANKEL_ENTRY_LIMIT,
        });
    }
    let r = output_correlations(channels, 2 * p - 1);
    let hankel = Mat::from_fn(rows, rows, |i, j| {
        r[i % outputs][j % outputs][i / outputs + j / outputs + 1]
    });
    identify(
        hankel.as_ref(),
        outputs,
        sampling_rate_hz,
        band,
        options,
        method,
        p,
    )
}

/// Modal assurance criterion of two real shapes, MAC = (aᵀb)²/((aᵀa)(bᵀb)) [-]: 1 for
/// proportional shapes (whatever the scale and sign), 0 for orthogonal ones. Shapes of different
/// lengths, empty or zero shapes give 0 (nothing in common).
pub fn mac(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return 0.0;
    }
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let (ab, aa, bb) = (dot(a, b), dot(a, a), dot(b, b));
    if aa > 0.0 && bb > 0.0 {
        (ab * ab / (aa * bb)).min(1.0)
    } else {
        0.0
    }
}

/// Checks the channels, the sampling rate and the options; returns the number of samples per
/// channel and the band [Hz] (an infinite top meaning Nyquist).
fn check_input(
    channels: &[&[f64]],
    sampling_rate_hz: f64,
    options: &SubspaceOptions,
) -> Result<(usize, (f64, f64)), SignalError> {
    if !(sampling_rate_hz.is_finite() && sampling_rate_hz > 0.0) {
        return Err(SignalError::BadSamplingRate { sampling_rate_hz });
    }
    let Some(first) = channels.first() else {
        return Err(SignalError::NoChannels);
    };
    for (channel, samples) in channels.iter().enumerate() {
        if samples.len() != first.len() {
            return Err(SignalError::ChannelLengthMismatch {
                channel,
                samples: samples.len(),
                expected: first.len(),
            });
        }
        if let Some(index) = samples.iter().position(|x| !x.is_finite()) {
            return Err(SignalError::NonFiniteChannelSample {
                channel,
                index,
                value: samples[index],
            });
        }
    }
    let nyquist_hz = 0.5 * sampling_rate_hz;
    let (low, high) = (options.min_frequency_hz, options.max_frequency_hz);
    let top = if high == f64::INFINITY {
        nyquist_hz
    } else {
        high
    };
    if !(low > 0.0 && low < top && top <= nyquist_hz) {
        return Err(SignalError::BadBand {
            min_frequency_hz: low,
            max_frequency_hz: high,
            nyquist_hz,
        });
    }
    check_options(options)?;
    Ok((first.len(), (low, top)))
}

/// Checks the options other than the band.
fn check_options(options: &SubspaceOptions) -> Result<(), SignalError> {
    let bad = |option: &'static str, value: f64, expected: &str| {
        Err(SignalError::BadSubspaceOption {
            option,
            value,
            expected: expected.to_string(),
        })
    };
    let o = options;
    if o.modes == 0 {
        return bad("modes", 0.0, "at least 1");
    }
    if o.max_order < 4 || !o.max_order.is_multiple_of(2) {
        return bad(
            "max_order",
            o.max_order as f64,
            "an even number ≥ 4 (stability compares two orders)",
        );
    }
    if !(o.max_damping_ratio > 0.0 && o.max_damping_ratio <= 1.0) {
        return bad("max_damping_ratio", o.max_damping_ratio, "in (0, 1]");
    }
    if !(o.frequency_tolerance > 0.0 && o.frequency_tolerance < 1.0) {
        return bad("frequency_tolerance", o.frequency_tolerance, "in (0, 1)");
    }
    if !(o.damping_tolerance > 0.0 && o.damping_tolerance.is_finite()) {
        return bad(
            "damping_tolerance",
            o.damping_tolerance,
            "a positive number",
        );
    }
    if !(0.0..=1.0).contains(&o.mac_tolerance) {
        return bad("mac_tolerance", o.mac_tolerance, "in [0, 1]");
    }
    if !(0.0..=1.0).contains(&o.min_phase_collinearity) {
        return bad(
            "min_phase_collinearity",
            o.min_phase_collinearity,
            "in [0, 1]",
        );
    }
    let orders = o.max_order / 2 - 1;
    match o.min_stable_orders {
        Some(k) if k == 0 || k > orders => bad(
            "min_stable_orders",
            k as f64,
            &format!("1 to the {orders} orders that can be stable (all but order 2)"),
        ),
        _ => Ok(()),
    }
}

/// Orders at which a cluster must be stable: the option, else a third of the orders tried
/// (at least 3, at most all but the lowest, which has no lower order to be stable against).
fn min_stable_orders(options: &SubspaceOptions) -> usize {
    let orders = options.max_order / 2;
    options
        .min_stable_orders
        .unwrap_or_else(|| orders.div_ceil(3).max(3).min(orders - 1))
}

/// Samples needed for `p` block rows: ERA needs q = N − p + 1 > max(p, n_max) columns, SSI-COV
/// the correlations up to lag 2p − 1 from N ≥ 4p samples.
fn samples_needed(p: usize, max_order: usize, method: SubspaceMethod) -> usize {
    match method {
        SubspaceMethod::FreeResponse => p + p.max(max_order),
        SubspaceMethod::OutputOnly => 4 * p,
    }
}

/// The block rows p: the option, or the default of [`SubspaceOptions::block_rows`] reduced to
/// what the record allows.
fn block_rows(
    options: &SubspaceOptions,
    outputs: usize,
    samples: usize,
    sampling_rate_hz: f64,
    min_frequency_hz: f64,
    method: SubspaceMethod,
) -> Result<usize, SignalError> {
    let least = options.max_order.div_ceil(outputs) + 1;
    let needed = |p| samples_needed(p, options.max_order, method);
    let p = match options.block_rows {
        Some(p) if p < least => {
            return Err(SignalError::BadSubspaceOption {
                option: "block_rows",
                value: p as f64,
                expected: format!(
                    "at least ⌈max_order/channels⌉ + 1 = {least} for max_order {} and {outputs} channels",
                    options.max_order
                ),
            })
        }
        Some(p) => p,
        None => {
            let span = (DEFAULT_PERIODS * sampling_rate_hz / min_frequency_hz).ceil();
            let cap = (DEFAULT_MAX_HANKEL_ROWS / outputs).max(least);
            let mut p = (span.min(cap as f64) as usize).max(least);
            while p > least && needed(p) > samples {
                p -= 1;
            }
            p
        }
    };
    if needed(p) > samples {
        return Err(SignalError::SignalTooShort {
            samples,
            required: needed(p),
        });
    }
    Ok(p)
}

/// Output correlations r[a][b][i] = Σ_k y_a[k+i]·y_b[k]/(N − i), i = 0 … `max_lag`, of the
/// demeaned channels, by FFT: with X_a the transform zero-padded to L ≥ N + max_lag + 1,
/// IFFT(X_a·X̄_b)[i]/L = Σ_k y_a[k+i]·y_b[k] and, at L − i, the same of (b, a).
fn output_correlations(channels: &[&[f64]], max_lag: usize) -> Vec<Vec<Vec<f64>>> {
    let n = channels[0].len();
    let length = (n + max_lag + 1).next_power_of_two();
    let mut planner = RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(length);
    let inverse = planner.plan_fft_inverse(length);
    let spectra: Vec<_> = channels
        .iter()
        .map(|y| {
            let mean = y.iter().sum::<f64>() / n as f64;
            let mut input = forward.make_input_vec();
            input
                .iter_mut()
                .zip(y.iter())
                .for_each(|(v, s)| *v = s - mean);
            let mut spectrum = forward.make_output_vec();
            forward
                .process(&mut input, &mut spectrum)
                .expect("buffers come from the same plan");
            spectrum
        })
        .collect();
    let l = channels.len();
    let mut r = vec![vec![vec![0.0; max_lag + 1]; l]; l];
    let mut output = inverse.make_output_vec();
    for a in 0..l {
        for b in a..l {
            let mut product: Vec<c64> = spectra[a]
                .iter()
                .zip(&spectra[b])
                .map(|(x, y)| x * y.conj())
                .collect();
            // Real lines at 0 Hz and Nyquist (round-off aside), as the inverse requires.
            let last = product.len() - 1;
            product[0].im = 0.0;
            product[last].im = 0.0;
            inverse
                .process(&mut product, &mut output)
                .expect("buffers come from the same plan, real end lines");
            for i in 0..=max_lag {
                let scale = 1.0 / (length as f64 * (n - i) as f64);
                r[a][b][i] = output[i] * scale;
                r[b][a][i] = output[(length - i) % length] * scale;
            }
        }
    }
    r
}

/// A pole of one model order, with its real shape.
#[derive(Debug, Clone)]
struct Pole {
    order: usize,
    frequency_hz: f64,
    damping_ratio: f64,
    shape: Vec<f64>,
    mpc: f64,
    stable: bool,
}

/// The core from the Hankel matrix: SVD, poles of every order, stabilisation, clusters.
fn identify(
    hankel: MatRef<'_, f64>,
    outputs: usize,
    sampling_rate_hz: f64,
    band: (f64, f64),
    options: &SubspaceOptions,
    method: SubspaceMethod,
    block_rows: usize,
) -> Result<SubspaceIdentification, SignalError> {
    let svd = hankel
        .thin_svd()
        .map_err(|_| SignalError::SvdNotConverged {
            rows: hankel.nrows(),
            columns: hankel.ncols(),
        })?;
    let singular_values: Vec<f64> = svd.S().column_vector().iter().copied().collect();
    let mut poles: Vec<Vec<Pole>> = (1..=options.max_order / 2)
        .map(|half| {
            let u = svd.U().subcols(0, 2 * half);
            poles_of_order(
                u,
                outputs,
                sampling_rate_hz,
                band,
                options.max_damping_ratio,
            )
        })
        .collect();
    mark_stable(&mut poles, options);
    let diagram = poles
        .iter()
        .flatten()
        .map(|p| StabilisationPole {
            order: p.order,
            frequency_hz: p.frequency_hz,
            damping_ratio: p.damping_ratio,
            stable: p.stable,
        })
        .collect();
    Ok(SubspaceIdentification {
        method,
        modes: cluster_modes(&poles, options),
        diagram,
        singular_values,
        block_rows,
        hankel_columns: hankel.ncols(),
    })
}

/// The poles of the order n = `u.ncols()` from the leading left singular vectors U_n:
/// A = U↑⁺·U↓ by least squares (QR), its eigenpairs (μ, ψ), λ = ln(μ)·f_s, φ = U₁·ψ; kept when
/// Im μ > 0, f in `band` and 0 < ζ < `max_damping`. An eigendecomposition that fails gives no
/// pole at this order.
fn poles_of_order(
    u: MatRef<'_, f64>,
    outputs: usize,
    sampling_rate_hz: f64,
    band: (f64, f64),
    max_damping: f64,
) -> Vec<Pole> {
    let order = u.ncols();
    let rows = u.nrows() - outputs;
    let a = u
        .subrows(0, rows)
        .qr()
        .solve_lstsq(u.subrows(outputs, rows));
    let Ok(eigen) = a.eigen() else {
        return Vec::new();
    };
    let (values, vectors) = (eigen.S().column_vector(), eigen.U());
    let c = u.subrows(0, outputs);
    let mut poles = Vec::new();
    for k in 0..order {
        let mu = values[k];
        if mu.im.is_nan() || mu.im <= 0.0 {
            continue;
        }
        let lambda = mu.ln() * sampling_rate_hz;
        let frequency_hz = lambda.norm() / TAU;
        let damping_ratio = -lambda.re / lambda.norm();
        let in_band = frequency_hz >= band.0 && frequency_hz <= band.1;
        if !(in_band && damping_ratio > 0.0 && damping_ratio < max_damping) {
            continue;
        }
        let phi: Vec<c64> = (0..outputs)
            .map(|i| (0..order).map(|j| vectors[(j, k)] * c[(i, j)]).sum())
            .collect();
        if let Some((shape, mpc)) = real_shape(&phi) {
            poles.push(Pole {
                order,
                frequency_hz,
                damping_ratio,
                shape,
                mpc,
                stable: false,
            });
        }
    }
    poles
}

/// The real shape of a complex one and its MPC = |φᵀφ|²/(φᴴφ)²: φ rotated by e^{iθ} with
/// θ = −½·arg(φᵀφ), which maximises Σ(Re e^{iθ}φ_j)² = ½φᴴφ + ½Re(e^{2iθ}φᵀφ), then its real part
/// normalised. `None` for a zero shape.
fn real_shape(phi: &[c64]) -> Option<(Vec<f64>, f64)> {
    let square: c64 = phi.iter().map(|z| z * z).sum();
    let energy: f64 = phi.iter().map(|z| z.norm_sqr()).sum();
    if energy.is_nan() || energy <= 0.0 {
        return None;
    }
    let rotation = c64::from_polar(1.0, -0.5 * square.arg());
    let shape = normalised(phi.iter().map(|z| (z * rotation).re).collect())?;
    Some((shape, square.norm_sqr() / (energy * energy)))
}

/// `v` divided by its component of largest magnitude (which becomes +1); `None` if zero.
fn normalised(mut v: Vec<f64>) -> Option<Vec<f64>> {
    let largest = v
        .iter()
        .copied()
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))?;
    if largest.is_nan() || largest == 0.0 {
        return None;
    }
    v.iter_mut().for_each(|x| *x /= largest);
    Some(v)
}

/// Marks a pole of order n stable when a pole of order n − 2 has a frequency and a damping
/// within the relative tolerances and a shape with MAC ≥ the tolerance.
fn mark_stable(poles: &mut [Vec<Pole>], options: &SubspaceOptions) {
    let agrees = |p: &Pole, q: &Pole| {
        (p.frequency_hz / q.frequency_hz - 1.0).abs() <= options.frequency_tolerance
            && (p.damping_ratio / q.damping_ratio - 1.0).abs() <= options.damping_tolerance
            && mac(&p.shape, &q.shape) >= options.mac_tolerance
    };
    for k in 1..poles.len() {
        let (lower, upper) = poles.split_at_mut(k);
        for p in upper[0].iter_mut() {
            p.stable = lower[k - 1].iter().any(|q| agrees(p, q));
        }
    }
}

/// Clusters the stable poles by frequency (single linkage: a gap above `frequency_tolerance`
/// between neighbours in frequency starts a new cluster), keeps one pole per order (the nearest
/// to the cluster's median frequency), and makes a mode of each cluster stable at
/// [`min_stable_orders`] orders or more, with a mean MPC of at least `min_phase_collinearity`
/// and a damping scatter std(ζ)/median(ζ) within `damping_tolerance` (in trials, noise
/// clusters wandered by 20–50 % in damping, real ones by less than 1 %; together with the MPC
/// this left no mode in 120 records of pure noise). The strongest modes are kept: most stable orders
/// first, ties to the lowest first stable order (strong modes take the leading singular values
/// and stabilise at low orders), then the lower frequency; returned by ascending frequency.
fn cluster_modes(poles: &[Vec<Pole>], options: &SubspaceOptions) -> Vec<SubspaceMode> {
    let mut stable: Vec<&Pole> = poles.iter().flatten().filter(|p| p.stable).collect();
    stable.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    let mut clusters: Vec<Vec<&Pole>> = Vec::new();
    for p in stable {
        match clusters.last_mut() {
            Some(c)
                if p.frequency_hz / c[c.len() - 1].frequency_hz - 1.0
                    <= options.frequency_tolerance =>
            {
                c.push(p)
            }
            _ => clusters.push(vec![p]),
        }
    }
    let least = min_stable_orders(options);
    let mut modes: Vec<SubspaceMode> = clusters
        .into_iter()
        .map(one_per_order)
        .filter(|c| c.len() >= least)
        .map(|c| summarise(&c))
        .filter(|m| {
            m.modal_phase_collinearity >= options.min_phase_collinearity
                && m.damping_std <= options.damping_tolerance * m.damping_ratio
        })
        .collect();
    modes.sort_by(|a, b| {
        (b.stable_orders.cmp(&a.stable_orders))
            .then(a.lowest_stable_order.cmp(&b.lowest_stable_order))
            .then(a.frequency_hz.total_cmp(&b.frequency_hz))
    });
    modes.truncate(options.modes);
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    modes
}

/// The cluster with one pole per order: the nearest to the cluster's median frequency.
fn one_per_order(cluster: Vec<&Pole>) -> Vec<&Pole> {
    let centre = median(cluster.iter().map(|p| p.frequency_hz).collect());
    let mut kept: Vec<&Pole> = Vec::with_capacity(cluster.len());
    for p in cluster {
        match kept.iter_mut().find(|q| q.order == p.order) {
            Some(q) if (p.frequency_hz - centre).abs() < (q.frequency_hz - centre).abs() => *q = p,
            Some(_) => {}
            None => kept.push(p),
        }
    }
    kept
}

/// A mode from a non-empty cluster: medians and standard deviations of f and ζ, the mean of the
/// shapes (each signed to agree with the first), the mean MPC.
fn summarise(cluster: &[&Pole]) -> SubspaceMode {
    let frequencies: Vec<f64> = cluster.iter().map(|p| p.frequency_hz).collect();
    let dampings: Vec<f64> = cluster.iter().map(|p| p.damping_ratio).collect();
    let reference = &cluster[0].shape;
    let mut shape = vec![0.0; reference.len()];
    for p in cluster {
        let dot: f64 = p.shape.iter().zip(reference).map(|(a, b)| a * b).sum();
        let sign = if dot < 0.0 { -1.0 } else { 1.0 };
        shape
            .iter_mut()
            .zip(&p.shape)
            .for_each(|(s, x)| *s += sign * x);
    }
    SubspaceMode {
        frequency_hz: median(frequencies.clone()),
        frequency_std_hz: standard_deviation(&frequencies),
        damping_ratio: median(dampings.clone()),
        damping_std: standard_deviation(&dampings),
        shape: normalised(shape.clone()).unwrap_or(shape),
        modal_phase_collinearity: cluster.iter().map(|p| p.mpc).sum::<f64>() / cluster.len() as f64,
        stable_orders: cluster.len(),
        lowest_stable_order: cluster.iter().map(|p| p.order).min().unwrap_or(0),
    }
}

/// Median of a non-empty sample (mean of the middle two for an even count).
fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    let n = x.len();
    if n % 2 == 1 {
        x[n / 2]
    } else {
        0.5 * (x[n / 2 - 1] + x[n / 2])
    }
}

/// Sample standard deviation (n − 1 in the denominator; 0 for fewer than two values).
fn standard_deviation(x: &[f64]) -> f64 {
    let n = x.len();
    if n < 2 {
        return 0.0;
    }
    let mean = x.iter().sum::<f64>() / n as f64;
    (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, SymmetricEigen};
    use rand_chacha::ChaCha8Rng;
    use rand_core::{Rng, SeedableRng};

    const FS: f64 = 200.0;
    /// The first three modes of the motivating 4-span bridge [Hz] and damping ratios [-].
    const FREQUENCIES: [f64; 3] = [3.653, 4.262, 5.707];
    const DAMPINGS: [f64; 3] = [0.05, 0.04, 0.03];
    /// Mid-span amplitudes of the first three bending modes of a 4-span continuous beam (sign
    /// patterns of the alternating, symmetric and antisymmetric modes), distinct shapes.
    const SHAPES: [[f64; 4]; 3] = [
        [1.0, -0.8, 0.8, -1.0],
        [0.7, -1.0, -1.0, 0.7],
        [1.0, 0.4, -0.4, -1.0],
    ];

    /// A standard normal draw (Box–Muller on two uniform draws in (0, 1]).
    fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
        let uniform =
            |rng: &mut ChaCha8Rng| ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
        let (u1, u2) = (uniform(rng), uniform(rng));
        (-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()
    }

    /// 8 s of free decay at 200 Hz at the 4 mid-spans: y_i(t) = Σ_m φ_im a_m e^{−ζωt}
    /// cos(ω_d t + θ_m), plus Gaussian noise of standard deviation `noise` (seeded).
    fn decay_record(amplitudes: [f64; 3], noise: f64, seed: u64) -> Vec<Vec<f64>> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let phases = [0.3, 1.1, 2.0];
        (0..4)
            .map(|i| {
                (0..1600)
                    .map(|k| {
                        let t = k as f64 / FS;
                        let clean: f64 = (0..3)
                            .map(|m| {
                                let w = TAU * FREQUENCIES[m];
                                let wd = w * (1.0 - DAMPINGS[m].powi(2)).sqrt();
                                SHAPES[m][i]
                                    * amplitudes[m]
                                    * (-DAMPINGS[m] * w * t).exp()
                                    * (wd * t + phases[m]).cos()
                            })
                            .sum();
                        clean + noise * gaussian(&mut rng)
                    })
                    .collect()
            })
            .collect()
    }

    fn bridge_options() -> SubspaceOptions {
        SubspaceOptions {
            min_frequency_hz: 2.0,
            max_frequency_hz: 20.0,
            ..SubspaceOptions::default()
        }
    }

    fn slices(channels: &[Vec<f64>]) -> Vec<&[f64]> {
        channels.iter().map(|c| c.as_slice()).collect()
    }

    /// The largest relative errors of frequency and damping and the smallest MAC of the modes
    /// against the reference, mode by mode (same count, both ascending in frequency).
    fn errors(modes: &[SubspaceMode], f: &[f64], zeta: &[f64], shapes: &[Vec<f64>]) -> [f64; 3] {
        assert_eq!(modes.len(), f.len(), "{modes:#?}");
        let mut worst = [0.0f64, 0.0, 1.0];
        for (m, mode) in modes.iter().enumerate() {
            worst[0] = worst[0].max((mode.frequency_hz / f[m] - 1.0).abs());
            worst[1] = worst[1].max((mode.damping_ratio / zeta[m] - 1.0).abs());
            worst[2] = worst[2].min(mac(&mode.shape, &shapes[m]));
        }
        worst
    }

    fn true_shapes() -> Vec<Vec<f64>> {
        SHAPES.iter().map(|s| s.to_vec()).collect()
    }

    #[test]
    fn era_recovers_a_noise_free_closed_form_decay_to_1e_6() {
        let record = decay_record([0.05, 0.04, 0.03], 0.0, 1);
        let found = identify_free_response(&slices(&record), FS, &bridge_options()).unwrap();
        let [df, dz, m] = errors(&found.modes, &FREQUENCIES, &DAMPINGS, &true_shapes());
        println!(
            "noise-free: frequency {df:e}, damping {dz:e}, 1 − MAC {:e}",
            1.0 - m
        );
        assert!(df < 1e-6 && dz < 1e-6 && 1.0 - m < 1e-6, "{df} {dz} {m}");
        for mode in &found.modes {
            assert!(mode.modal_phase_collinearity > 1.0 - 1e-6, "{mode:?}");
        }
    }

    #[test]
    fn era_recovers_a_closed_form_decay_with_2_percent_noise() {
        // Noise 2 % of the record's peak; frequencies within 0.1 %, damping within 10 %,
        // MAC > 0.99, and each true value within 3 standard deviations or the tolerance.
        let clean = decay_record([0.05, 0.04, 0.03], 0.0, 2);
        let peak = clean.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        let record = decay_record([0.05, 0.04, 0.03], 0.02 * peak, 2);
        let found = identify_free_response(&slices(&record), FS, &bridge_options()).unwrap();
        let [df, dz, m] = errors(&found.modes, &FREQUENCIES, &DAMPINGS, &true_shapes());
        println!("2 % noise: frequency {df:e}, damping {dz:e}, MAC {m}");
        assert!(df < 1e-3 && dz < 0.1 && m > 0.99, "{df} {dz} {m}");
        for (m, mode) in found.modes.iter().enumerate() {
            println!("{mode:?}");
            let f_ok = (mode.frequency_hz - FREQUENCIES[m]).abs()
                <= (3.0 * mode.frequency_std_hz).max(1e-3 * FREQUENCIES[m]);
            let z_ok = (mode.damping_ratio - DAMPINGS[m]).abs()
                <= (3.0 * mode.damping_std).max(0.1 * DAMPINGS[m]);
            assert!(f_ok && z_ok, "{mode:?}");
        }
    }

    #[test]
    fn era_finds_the_frequencies_within_half_a_percent_at_the_field_noise_level() {
        // The motivating record: 0.05 m/s² falling to the accelerometer noise 0.002 m/s² in
        // about 3 s (ζω ≈ 1.1 /s), 8 s at 200 Hz; five noise seeds.
        let mut worst = [0.0f64, 0.0, 1.0];
        for seed in 10..15 {
            let record = decay_record([0.05, 0.04, 0.03], 0.002, seed);
            let start = std::time::Instant::now();
            let found = identify_free_response(&slices(&record), FS, &bridge_options()).unwrap();
            println!("4 channels, 8 s, max_order 40: {:?}", start.elapsed());
            let e = errors(&found.modes, &FREQUENCIES, &DAMPINGS, &true_shapes());
            worst = [worst[0].max(e[0]), worst[1].max(e[1]), worst[2].min(e[2])];
        }
        println!(
            "field noise: frequency {:e}, damping {:e}, MAC {}",
            worst[0], worst[1], worst[2]
        );
        assert!(worst[0] < 5e-3, "{worst:?}");
    }

    /// Accelerations of a 3-DOF fixed-free chain (m = 1, k = 1246: 2.5, 7.0, 10.1 Hz) with
    /// modal damping `zeta` under seeded white-noise forces at every mass, discretised exactly
    /// with a zero-order hold: [A_d B_d; 0 I] = exp([A_c B_c; 0 0]·Δt); y_k = C_a x_k + D u_k.
    /// Returns the channels, the undamped frequencies [Hz] and the mass-normalised shapes.
    fn chain_record(
        seconds: f64,
        zeta: [f64; 3],
        seed: u64,
    ) -> (Vec<Vec<f64>>, Vec<f64>, Vec<Vec<f64>>) {
        let k = 1246.0;
        let stiffness =
            DMatrix::<f64>::from_row_slice(3, 3, &[2.0 * k, -k, 0.0, -k, 2.0 * k, -k, 0.0, -k, k]);
        let eigen = SymmetricEigen::new(stiffness.clone()); // M = I
        let mut order: Vec<usize> = (0..3).collect();
        order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
        let omega: Vec<f64> = order.iter().map(|&i| eigen.eigenvalues[i].sqrt()).collect();
        let phi = DMatrix::from_fn(3, 3, |r, c| eigen.eigenvectors[(r, order[c])]);
        let modal = DMatrix::from_fn(3, 3, |r, c| {
            if r == c {
                2.0 * zeta[r] * omega[r]
            } else {
                0.0
            }
        });
        let damping = &phi * modal * phi.transpose();
        let mut augmented = DMatrix::zeros(9, 9);
        augmented.view_mut((0, 3), (3, 3)).fill_with_identity();
        augmented.view_mut((3, 0), (3, 3)).copy_from(&(-&stiffness));
        augmented.view_mut((3, 3), (3, 3)).copy_from(&(-&damping));
        augmented.view_mut((3, 6), (3, 3)).fill_with_identity();
        let discrete = (augmented / FS).exp();
        let (ad, bd) = (discrete.view((0, 0), (6, 6)), discrete.view((0, 6), (6, 3)));
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut x = nalgebra::DVector::<f64>::zeros(6);
        let samples = (seconds * FS) as usize;
        let mut channels: Vec<Vec<f64>> = (0..3).map(|_| Vec::with_capacity(samples)).collect();
        for _ in 0..samples {
            let u = nalgebra::DVector::from_fn(3, |_, _| gaussian(&mut rng));
            let acceleration = &u - &stiffness * x.rows(0, 3) - &damping * x.rows(3, 3);
            for (c, a) in channels.iter_mut().zip(acceleration.iter()) {
                c.push(*a);
            }
            x = ad * &x + bd * u;
        }
        let shapes = (0..3)
            .map(|c| phi.column(c).iter().copied().collect())
            .collect();
        (channels, omega.iter().map(|w| w / TAU).collect(), shapes)
    }

    #[test]
    fn ssi_cov_recovers_a_three_dof_chain_under_white_noise_forces() {
        let zeta = [0.02, 0.025, 0.03];
        // 20 min (3000 periods of the fundamental, the usual length of an ambient record): over
        // 10 seeds the frequency scatter is 0.10–0.15 % and the damping scatter 3–6 % (at 300 s,
        // 0.27 % and up to 17 %: 0.5 % would be a 2σ test).
        let (record, f, shapes) = chain_record(1200.0, zeta, 7);
        let options = SubspaceOptions {
            min_frequency_hz: 1.0,
            max_frequency_hz: 20.0,
            ..SubspaceOptions::default()
        };
        let found = identify_output_only(&slices(&record), FS, &options).unwrap();
        for mode in &found.modes {
            println!("{mode:?}");
        }
        let [df, dz, m] = errors(&found.modes, &f, &zeta, &shapes);
        println!("SSI-COV: frequency {df:e}, damping {dz:e}, MAC {m} (reference {f:?} Hz)");
        assert!(df < 5e-3 && dz < 0.25 && m > 0.98, "{df} {dz} {m}");
    }

    #[test]
    fn noise_alone_gives_no_mode() {
        // Five records of 4 channels of white noise (8 s at 200 Hz, the accelerometer noise
        // 0.002 m/s²), ERA and SSI-COV, up to 10 modes asked: none is a mode. Also silence.
        let options = SubspaceOptions {
            modes: 10,
            ..bridge_options()
        };
        for seed in 0..5 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let record: Vec<Vec<f64>> = (0..4)
                .map(|_| (0..1600).map(|_| 0.002 * gaussian(&mut rng)).collect())
                .collect();
            let era = identify_free_response(&slices(&record), FS, &options).unwrap();
            let ssi = identify_output_only(&slices(&record), FS, &options).unwrap();
            assert!(era.modes.is_empty(), "seed {seed}: ERA {:?}", era.modes);
            assert!(ssi.modes.is_empty(), "seed {seed}: SSI-COV {:?}", ssi.modes);
            // One channel: MAC and MPC are 1 by construction and only the frequency and damping
            // stability reject noise, which is weaker (seed 4 gives a 15 Hz "mode" stable at 7
            // orders from order 22): no panic is all that is checked.
            identify_free_response(&slices(&record[..1]), FS, &options).unwrap();
        }
        let zeros = vec![vec![0.0; 400]; 2];
        let era = identify_free_response(&slices(&zeros), FS, &options).unwrap();
        let ssi = identify_output_only(&slices(&zeros), FS, &options).unwrap();
        assert!(era.modes.is_empty() && ssi.modes.is_empty());
    }

    #[test]
    fn bad_input_gives_the_errors_with_the_offending_numbers() {
        let options = bridge_options();
        let record = decay_record([0.05, 0.04, 0.03], 0.0, 1);
        let good = slices(&record);
        let era = |c: &[&[f64]], fs: f64, o: &SubspaceOptions| {
            identify_free_response(c, fs, o).unwrap_err()
        };
        assert_eq!(era(&[], FS, &options), SignalError::NoChannels);
        let short = &record[1][..100];
        assert_eq!(
            era(&[&record[0], short], FS, &options),
            SignalError::ChannelLengthMismatch {
                channel: 1,
                samples: 100,
                expected: 1600
            }
        );
        let mut bad = record[2].clone();
        bad[17] = f64::NAN;
        assert!(matches!(
            era(&[&record[0], &bad], FS, &options),
            SignalError::NonFiniteChannelSample { channel: 1, index: 17, value } if value.is_nan()
        ));
        assert_eq!(
            era(&good, 0.0, &options),
            SignalError::BadSamplingRate {
                sampling_rate_hz: 0.0
            }
        );
        for (low, high) in [(0.0, 20.0), (2.0, 150.0), (30.0, 20.0), (f64::NAN, 20.0)] {
            let band = SubspaceOptions {
                min_frequency_hz: low,
                max_frequency_hz: high,
                ..options.clone()
            };
            assert!(
                matches!(
                    era(&good, FS, &band),
                    SignalError::BadBand {
                        nyquist_hz: 100.0,
                        ..
                    }
                ),
                "{low} {high}"
            );
        }
        let tiny: Vec<&[f64]> = record.iter().map(|c| &c[..50]).collect();
        let p = SubspaceOptions {
            block_rows: Some(30),
            ..options.clone()
        };
        assert_eq!(
            era(&tiny, FS, &p),
            SignalError::SignalTooShort {
                samples: 50,
                required: 70
            }
        );
        assert_eq!(
            identify_output_only(&tiny, FS, &p).unwrap_err(),
            SignalError::SignalTooShort {
                samples: 50,
                required: 120
            }
        );
        let few = SubspaceOptions {
            block_rows: Some(5),
            ..options.clone()
        };
        assert!(matches!(
            era(&good, FS, &few),
            SignalError::BadSubspaceOption {
                option: "block_rows",
                ..
            }
        ));
        for max_order in [2, 7] {
            let order = SubspaceOptions {
                max_order,
                ..options.clone()
            };
            assert!(matches!(
                era(&good, FS, &order),
                SignalError::BadSubspaceOption {
                    option: "max_order",
                    ..
                }
            ));
        }
        let huge = SubspaceOptions {
            block_rows: Some(3000),
            ..options.clone()
        };
        let long: Vec<f64> = (0..60_000).map(|k| (k as f64 * 0.1).sin()).collect();
        let many: Vec<&[f64]> = vec![&long; 8];
        assert_eq!(
            era(&many, FS, &huge),
            SignalError::HankelTooLarge {
                rows: 24_000,
                columns: 3001,
                limit: HANKEL_ENTRY_LIMIT
            }
        );
        assert!(matches!(
            identify_output_only(&many, FS, &huge).unwrap_err(),
            SignalError::HankelTooLarge { rows: 24_000, .. }
        ));
    }

    #[test]
    fn mac_is_one_for_proportional_and_zero_for_orthogonal_shapes() {
        let a = [1.0, -0.8, 0.8, -1.0];
        let minus_two_a: Vec<f64> = a.iter().map(|x| -2.0 * x).collect();
        assert!((mac(&a, &a) - 1.0).abs() < 1e-15);
        assert!((mac(&a, &minus_two_a) - 1.0).abs() < 1e-15);
        assert_eq!(mac(&a, &[0.7, -1.0, -1.0, 0.7]), 0.0);
        assert_eq!(mac(&a, &[0.0; 4]), 0.0);
        assert_eq!(mac(&a, &[1.0]), 0.0);
    }
}
