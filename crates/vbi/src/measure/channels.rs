//! The DAF of every measured channel (the paper's Eq. 1 on measured signals), the effect of
//! low-pass filtering at its cut-off mode K1, and the RDM of every section.

use super::influence_lines::ChannelLines;
use super::static_references::{crawl_static, separation_check};
use super::uncertainty;
use super::{
    ChannelDaf, ChannelSignals, CutoffModeEffect, MeasureError, MeasuredMoment, MeasuredRdm,
    StaticSeparation,
};
use crate::measure::measurement::{Channel, K1Source, Measurement};
use crate::signal::{
    cutoff_mode_filtering, measured_daf, rdm, static_component, static_from_influence_line,
    MeasuredQuantity, SignalError,
};

/// The DAF of every channel but the accelerations, with the signals behind it.
pub(super) fn channel_dafs(
    m: &Measurement,
    separation: Option<&StaticSeparation>,
    model_frequencies: Option<&[f64]>,
    first_frequency: Option<f64>,
    lines: &[ChannelLines],
) -> Result<(Vec<ChannelDaf>, Vec<ChannelSignals>), MeasureError> {
    let mut channels = Vec::new();
    let mut signals = Vec::new();
    let daf_channels = m.channels.iter().enumerate().filter(|(_, c)| c.has_daf());
    for ((index, c), lines) in daf_channels.zip(lines) {
        let in_channel = |source: SignalError| MeasureError::Channel {
            channel: c.name.clone(),
            source,
        };
        let (static_part, method, cutoff_hz) =
            static_part(m, c, separation, first_frequency, lines)?;
        let separation_check = match cutoff_hz {
            Some(cutoff) => separation_check(m, c, cutoff).map_err(in_channel)?,
            None => None,
        };
        let d = measured_daf(&c.samples, &static_part).map_err(in_channel)?;
        let chosen = uncertainty::Chosen {
            method,
            part: &static_part,
        };
        let (static_methods, uncertainty) =
            uncertainty::assess(m, c, &chosen, first_frequency, lines)?;
        let moment = match &c.moment {
            Some(conversion) => {
                let f = conversion.factor().map_err(in_channel)?;
                Some(MeasuredMoment {
                    newton_metres_per_strain: f,
                    static_max_n_m: d.static_max * f,
                    dynamic_max_n_m: d.dynamic_max * f,
                })
            }
            None => None,
        };
        let (cutoff_mode, filtered) = match cutoff_mode_of(m, c, model_frequencies)? {
            Some(CutoffMode {
                source,
                mode,
                frequency_hz: k1,
            }) => {
                let r = cutoff_mode_filtering(
                    &c.samples,
                    &static_part,
                    m.sampling_rate_hz,
                    m.filter_order,
                    k1,
                )
                .map_err(in_channel)?;
                let effect = CutoffModeEffect {
                    source,
                    mode,
                    mode_frequency_hz: k1,
                    cutoff_hz: r.cutoff_hz,
                    mode_gain: r.mode_gain,
                    dynamic_max: r.after.dynamic_max / c.si_per_unit,
                    daf_before: r.before.daf,
                    daf_after: r.after.daf,
                    relative_change: r.relative_change,
                };
                (Some(effect), Some(r.filtered))
            }
            None => (None, None),
        };
        channels.push(ChannelDaf {
            name: c.name.clone(),
            column: c.column.clone(),
            kind: c.kind,
            unit: c.unit.clone(),
            static_method: method,
            cutoff_hz,
            separation_check,
            static_max: d.static_max / c.si_per_unit,
            dynamic_max: d.dynamic_max / c.si_per_unit,
            daf: d.daf,
            time_of_static_max_s: m.time[d.static_max_index],
            time_of_dynamic_max_s: m.time[d.dynamic_max_index],
            section: c.section.clone(),
            moment,
            cutoff_mode,
            static_methods,
            uncertainty,
            design_codes: Vec::new(),
        });
        signals.push(ChannelSignals {
            channel_index: index,
            static_part,
            filtered_at_cutoff_mode: filtered,
        });
    }
    Ok((channels, signals))
}

/// The static part of a channel [SI]: its influence line under the vehicle's axle loads, the
/// crawl run, or the zero-phase low-pass; with the method's name and the cut-off used.
fn static_part(
    m: &Measurement,
    c: &Channel,
    separation: Option<&StaticSeparation>,
    first_frequency: Option<f64>,
    lines: &ChannelLines,
) -> Result<(Vec<f64>, &'static str, Option<f64>), MeasureError> {
    let in_channel = |source: SignalError| MeasureError::Channel {
        channel: c.name.clone(),
        source,
    };
    match (&lines.chosen, &m.vehicle, m.crawl.as_deref(), separation) {
        (Some((method, line)), Some(loads), _, _) => Ok((
            static_from_influence_line(&m.time, line, loads).map_err(in_channel)?,
            method,
            None,
        )),
        (Some(_), None, _, _) => Err(MeasureError::input(
            "vehicle",
            format!(
                "channel `{}` has an influence-line static reference, which needs the vehicle's axle loads; give the vehicle",
                c.name
            ),
        )),
        (None, _, Some(crawl), _) => {
            let part = crawl_static(m, crawl, c, first_frequency)?;
            Ok((part, "crawl_run", None))
        }
        (None, _, None, Some(s)) => {
            let cutoff = s.cutoff.cutoff_hz;
            let part = static_component(&c.samples, m.sampling_rate_hz, m.filter_order, cutoff)
                .map_err(in_channel)?;
            Ok((part, "low_pass", Some(cutoff)))
        }
        (None, _, None, None) => {
            unreachable!("a low-pass is chosen whenever a DAF channel needs one")
        }
    }
}

/// The cut-off mode K1 of a channel.
struct CutoffMode {
    /// Where it came from ("given", "run_summary", "model_mode").
    source: &'static str,
    /// Its number (1-based), when known.
    mode: Option<usize>,
    /// Its frequency [Hz].
    frequency_hz: f64,
}

impl CutoffMode {
    fn new(source: &'static str, mode: Option<usize>, frequency_hz: f64) -> Option<Self> {
        Some(Self {
            source,
            mode,
            frequency_hz,
        })
    }
}

/// The cut-off mode K1 of a channel, when asked.
fn cutoff_mode_of(
    m: &Measurement,
    c: &Channel,
    model_frequencies: Option<&[f64]>,
) -> Result<Option<CutoffMode>, MeasureError> {
    let fs = m.sampling_rate_hz;
    Ok(match c.k1 {
        None => None,
        Some(K1Source::Given(f)) => CutoffMode::new("given", None, f),
        Some(K1Source::RunSummary { mode, frequency_hz }) => {
            CutoffMode::new("run_summary", Some(mode), frequency_hz)
        }
        Some(K1Source::ModelMode(mode)) => {
            let frequencies = model_frequencies.ok_or_else(|| {
                MeasureError::input(
                    "bridge",
                    format!("cut-off mode {mode} of channel `{}` is a mode of the bridge model; give the bridge model", c.name),
                )
            })?;
            let f = *frequencies.get(mode.wrapping_sub(1)).ok_or_else(|| {
                MeasureError::input(
                    "bridge_modes",
                    format!("cut-off mode {mode} of channel `{}` is beyond the {} modes computed; raise bridge_modes", c.name, frequencies.len()),
                )
            })?;
            if f >= 0.999 * fs / 2.0 {
                return Err(MeasureError::input(
                    "bridge",
                    format!("cut-off mode {mode} of channel `{}` has frequency {f} Hz, above the Nyquist frequency {} Hz; choose a lower mode or give k1_cutoff_hz", c.name, fs / 2.0),
                ));
            }
            CutoffMode::new("model_mode", Some(mode), f)
        }
    })
}

/// RDM = DAF_u / DAF_M (Eq. 31) for every section with a deflection channel and a strain or
/// moment channel.
pub(super) fn section_rdms(channels: &[ChannelDaf]) -> Result<Vec<MeasuredRdm>, MeasureError> {
    let mut rdms = Vec::new();
    for d in channels
        .iter()
        .filter(|c| c.kind == MeasuredQuantity::Deflection && c.section.is_some())
    {
        for mo in channels.iter().filter(|c| {
            matches!(
                c.kind,
                MeasuredQuantity::Strain | MeasuredQuantity::BendingMoment
            ) && c.section == d.section
        }) {
            let value = rdm(d.daf, mo.daf)?;
            let uncertainty = match (&d.uncertainty, &mo.uncertainty) {
                (Some(ud), Some(um)) => {
                    Some(value * (ud.combined / d.daf).hypot(um.combined / mo.daf))
                }
                _ => None,
            }
            .filter(|u| u.is_finite());
            rdms.push(MeasuredRdm {
                section: d.section.clone().unwrap_or_default(),
                deflection_channel: d.name.clone(),
                moment_channel: mo.name.clone(),
                daf_deflection: d.daf,
                daf_moment: mo.daf,
                rdm: value,
                uncertainty,
                side_of_one_resolved: uncertainty.map(|u| (value - 1.0).abs() > 2.0 * u),
            });
        }
    }
    Ok(rdms)
}
