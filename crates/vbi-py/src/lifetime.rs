//! `vbi.lifetime(source)`: a `[lifetime]` file read by `vbi-input` as `vbi lifetime` reads it
//! (`load`, `prepare`, the traffic file streamed by `TrafficFileReader`) and run by the
//! library's [`static_block_maxima`]: the rows of `block_maxima.csv` as numpy columns and the
//! numbers of `lifetime.json`, computed as the command computes them (the same sums in the same
//! order, so the same f64s).

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use vbi::lifetime::{BlockMaximum, EventExtreme, EventTotals};
use vbi_input::lifetime as lifetime_input;

use crate::errors::input_error;
use crate::source;

/// The parts of the result as a dict: `effect` (each row's index into `effects`), `block`,
/// `static`, `time_s` and `trucks` as numpy columns in the order of `block_maxima.csv`;
/// `effects` as `(station, quantity)` pairs; and `summary`, the numbers of `lifetime.json`.
///
/// With `shard` = `(I, N)`: the run of shard I of N (`vbi lifetime --shard I/N`): its blocks'
/// static rows (no `total` column: its totals are merged), its events, and `shard`, its
/// `shard.json` text, for [`lifetime_merge_parts`]; `summary` then has only the name, the shard
/// and its counts.
#[pyfunction]
#[pyo3(signature = (source, shard = None))]
pub fn lifetime_parts<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    shard: Option<(usize, usize)>,
) -> PyResult<Bound<'py, PyDict>> {
    let file = source::of_kind(source, "lifetime", "vbi.lifetime")?;
    let lifetime = lifetime_input::load(&file).map_err(input_error)?;
    let mut analysis = lifetime_input::prepare(&file, &lifetime).map_err(input_error)?;
    let shard = shard
        .map(|(index, count)| {
            format!("{index}/{count}")
                .parse::<vbi::study::Shard>()
                .map_err(|e| {
                    input_error(vbi_input::InputError::command_line("shard", e.to_string()))
                })
        })
        .transpose()?;
    if let Some(shard) = shard {
        py.detach(|| lifetime_input::make_shard(&file, &lifetime, &mut analysis, shard))
            .map_err(input_error)?;
    }
    let reader = lifetime_input::open_traffic(&file, &lifetime).map_err(input_error)?;
    // The run of `vbi lifetime` (no Python object is touched: without the GIL); the rows are
    // kept for the frame.
    let mut rows: Vec<BlockMaximum> = Vec::new();
    let exceedances = lifetime.return_levels.exceedances;
    // With dynamics, the events that can govern integrated in the same pass, their rows of
    // events.csv kept.
    let mut events = EventRows::default();
    let (counts, tally, peaks, totals) = py
        .detach(|| match &lifetime.dynamics {
            None => lifetime_input::run(
                &analysis,
                reader,
                exceedances,
                |block| rows.extend_from_slice(block),
                |_| {},
            )
            .map(|(counts, tally, peaks)| (counts, tally, peaks, None)),
            Some(settings) => lifetime_input::run_with_dynamics(
                &file,
                (&analysis, settings),
                (reader, exceedances),
                (
                    |block: &[BlockMaximum]| rows.extend_from_slice(block),
                    |totals: &EventTotals, extremes: &[EventExtreme]| events.add(totals, extremes),
                ),
                |_| {},
            )
            .map(|(counts, tally, peaks, totals)| (counts, tally, peaks, Some(totals))),
        })
        .map_err(input_error)?;
    let parts = PyDict::new(py);
    let column = |f: fn(&BlockMaximum) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    parts.set_item(
        "effect",
        rows.iter()
            .map(|r| r.effect as u64)
            .collect::<Vec<u64>>()
            .into_pyarray(py),
    )?;
    parts.set_item(
        "block",
        rows.iter()
            .map(|r| r.block)
            .collect::<Vec<u64>>()
            .into_pyarray(py),
    )?;
    parts.set_item("static", column(|r| r.value).into_pyarray(py))?;
    parts.set_item("time_s", column(|r| r.time).into_pyarray(py))?;
    parts.set_item(
        "trucks",
        rows.iter()
            .map(|r| r.trucks as u64)
            .collect::<Vec<u64>>()
            .into_pyarray(py),
    )?;
    if let Some(shard) = shard {
        return shard_parts(
            py,
            parts,
            (&lifetime, &analysis, shard),
            (counts, &tally, &peaks),
            totals.as_ref(),
            events,
        );
    }
    if let Some(totals) = &totals {
        let total: Vec<f64> = rows
            .iter()
            .map(|r| {
                totals.values[r.effect]
                    .get(r.block as usize)
                    .copied()
                    .unwrap_or(0.0)
            })
            .collect();
        let daf: Vec<f64> = rows
            .iter()
            .zip(&total)
            .map(|(r, t)| {
                if r.value != 0.0 {
                    t / r.value
                } else {
                    f64::NAN
                }
            })
            .collect();
        parts.set_item("total", total.into_pyarray(py))?;
        parts.set_item("daf", daf.into_pyarray(py))?;
        parts.set_item("events", events.into_dict(py)?)?;
    }
    parts.set_item("effects", effect_pairs(py, &analysis)?)?;

    // lifetime.json, as `vbi lifetime` writes it (one summary for both).
    let summary = lifetime_input::summary(
        &lifetime,
        &analysis,
        counts,
        &tally,
        &peaks,
        totals.as_ref(),
    );
    let json = serde_json::to_string(&summary).map_err(|e| crate::errors::library_error(&e))?;
    let summary = py.import("json")?.call_method1("loads", (json,))?;
    parts.set_item("summary", summary)?;
    Ok(parts)
}

/// The effects as `(station, quantity)` pairs.
fn effect_pairs<'py>(
    py: Python<'py>,
    analysis: &vbi::lifetime::StaticLifetime,
) -> PyResult<Bound<'py, PyList>> {
    let effects = PyList::empty(py);
    for effect in &analysis.effects {
        effects.append((effect.station.as_str(), effect.quantity.name()))?;
    }
    Ok(effects)
}

/// A shard's parts: its rows (already in `parts`), its events, `effects`, `shard` (its
/// shard.json text) and a `summary` of its name, shard and counts.
fn shard_parts<'py>(
    py: Python<'py>,
    parts: Bound<'py, PyDict>,
    (lifetime, analysis, shard): (
        &lifetime_input::LifetimeFile,
        &vbi::lifetime::StaticLifetime,
        vbi::study::Shard,
    ),
    (counts, tally, peaks): (
        vbi::lifetime::LifetimeCounts,
        &vbi::lifetime::BlockMaximaTally,
        &vbi::lifetime::EventPeaks,
    ),
    totals: Option<&vbi::lifetime::TotalBlockMaxima>,
    events: EventRows,
) -> PyResult<Bound<'py, PyDict>> {
    let part = vbi::lifetime::LifetimeShard::new(shard, analysis, counts, (tally, peaks), totals);
    let file = lifetime_input::ShardFile::new(lifetime, part);
    let text = serde_json::to_string(&file).map_err(|e| crate::errors::library_error(&e))?;
    parts.set_item("shard", text)?;
    if totals.is_some() {
        parts.set_item("events", events.into_dict(py)?)?;
    }
    parts.set_item("effects", effect_pairs(py, analysis)?)?;
    let summary = PyDict::new(py);
    summary.set_item("name", &lifetime.name)?;
    summary.set_item("shard", shard.to_string())?;
    summary.set_item("first_block", analysis.blocks.first)?;
    summary.set_item("blocks", counts.blocks)?;
    summary.set_item("trucks", counts.trucks)?;
    summary.set_item("events", counts.events)?;
    summary.set_item("dynamics", totals.is_some())?;
    parts.set_item("summary", summary)?;
    Ok(parts)
}

/// The shards of one lifetime run merged (Python's `vbi.merge_lifetime`): `total` and `daf`
/// (with dynamics), the merged columns of `block_maxima.csv` in its row order, and `summary`,
/// the numbers of the single run's `lifetime.json`. `shards`: each shard's `shard.json` text
/// ([`lifetime_parts`] with `shard`), in any order.
#[pyfunction]
#[pyo3(signature = (source, shards))]
pub fn lifetime_merge_parts<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    shards: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let file = source::of_kind(source, "lifetime", "vbi.merge_lifetime")?;
    let lifetime = lifetime_input::load(&file).map_err(input_error)?;
    let analysis = lifetime_input::prepare(&file, &lifetime).map_err(input_error)?;
    let mut files = Vec::with_capacity(shards.len());
    for text in &shards {
        let shard: lifetime_input::ShardFile =
            serde_json::from_str(text).map_err(|e| crate::errors::library_error(&e))?;
        files.push(shard);
    }
    let merged = lifetime_input::merge_shards(&lifetime, &analysis, &files)
        .map_err(|message| input_error(vbi_input::InputError::command_line("shards", message)))?;
    let parts = PyDict::new(py);
    if let Some(totals) = &merged.totals {
        let effects = analysis.effects.len();
        let blocks = merged.counts.blocks as usize;
        let (mut total, mut daf) = (Vec::with_capacity(blocks * effects), Vec::new());
        for block in 0..blocks {
            for e in 0..effects {
                let value = totals.values[e].get(block).copied().unwrap_or(0.0);
                let fixed = merged.tally.values[e][block];
                total.push(value);
                daf.push(if fixed != 0.0 {
                    value / fixed
                } else {
                    f64::NAN
                });
            }
        }
        parts.set_item("total", total.into_pyarray(py))?;
        parts.set_item("daf", daf.into_pyarray(py))?;
    }
    let summary = lifetime_input::summary(
        &lifetime,
        &analysis,
        merged.counts,
        &merged.tally,
        &merged.peaks,
        merged.totals.as_ref(),
    );
    let json = serde_json::to_string(&summary).map_err(|e| crate::errors::library_error(&e))?;
    let summary = py.import("json")?.call_method1("loads", (json,))?;
    parts.set_item("summary", summary)?;
    Ok(parts)
}

/// The rows of `events.csv` as columns: one per integrated event and effect it loads.
#[derive(Default)]
struct EventRows {
    event: Vec<u64>,
    trucks: Vec<u64>,
    effect: Vec<u64>,
    static_value: Vec<f64>,
    crossing_static: Vec<f64>,
    total: Vec<f64>,
    time: Vec<f64>,
}

impl EventRows {
    fn add(
        &mut self,
        totals: &vbi::lifetime::EventTotals,
        extremes: &[vbi::lifetime::EventExtreme],
    ) {
        for (e, total) in totals.totals.iter().enumerate() {
            let Some(total) = total else { continue };
            self.event.push(totals.event);
            self.trucks.push(totals.trucks as u64);
            self.effect.push(e as u64);
            self.static_value.push(extremes[e].value);
            self.crossing_static.push(total.static_value);
            self.total.push(total.total);
            self.time.push(total.time);
        }
    }

    fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("event", self.event.into_pyarray(py))?;
        dict.set_item("trucks", self.trucks.into_pyarray(py))?;
        dict.set_item("effect", self.effect.into_pyarray(py))?;
        dict.set_item("static", self.static_value.into_pyarray(py))?;
        dict.set_item("crossing_static", self.crossing_static.into_pyarray(py))?;
        dict.set_item("total", self.total.into_pyarray(py))?;
        dict.set_item("time_s", self.time.into_pyarray(py))?;
        Ok(dict)
    }
}

/// The lifetime's static fatigue (`vbi lifetime`'s fatigue.csv and fatigue_blocks.csv, issue
/// 51): `columns` (the names of the library's table of lifetime fatigue outputs), `rows` (one
/// list per detail, in that order) and `blocks` (per detail, each block's Miner's sum). The
/// static pass itself is not run: only the fatigue pass, as the command runs it after.
#[pyfunction]
pub fn lifetime_fatigue_parts<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    use vbi::outputs::LIFETIME_FATIGUE_OUTPUTS;
    let file = source::of_kind(source, "lifetime", "vbi.lifetime_fatigue")?;
    let lifetime = lifetime_input::load(&file).map_err(input_error)?;
    let analysis = lifetime_input::prepare(&file, &lifetime).map_err(input_error)?;
    let details =
        vbi_input::fatigue_details::lifetime_details(&file, &lifetime.fatigue_details, &analysis)
            .map_err(input_error)?;
    let reader = lifetime_input::open_traffic(&file, &lifetime).map_err(input_error)?;
    let fatigue = py
        .detach(|| lifetime_input::run_fatigue(&analysis, &details, reader))
        .map_err(input_error)?;
    let parts = PyDict::new(py);
    let names: Vec<&str> = LIFETIME_FATIGUE_OUTPUTS.iter().map(|r| r.name).collect();
    parts.set_item("columns", names)?;
    let rows = PyList::empty(py);
    for summary in fatigue.summaries() {
        let row = (LIFETIME_FATIGUE_OUTPUTS.iter())
            .map(|r| crate::output_tables::output_to_python(py, (r.value)(&summary)))
            .collect::<PyResult<Vec<_>>>()?;
        rows.append(row)?;
    }
    parts.set_item("rows", rows)?;
    let blocks = PyDict::new(py);
    for detail in &fatigue.details {
        blocks.set_item(
            &detail.detail.detail.name,
            detail.block_damage.clone().into_pyarray(py),
        )?;
    }
    parts.set_item("blocks", blocks)?;
    Ok(parts)
}
