//! Extreme-value fits from Python, as the library makes them
//! ([`vbi::statistics::extreme_value`], [`vbi::lifetime::fit_block_maxima`]): the fits that
//! `vbi lifetime` reports, on any block maxima.

use pyo3::prelude::*;

use vbi::lifetime::{fit_block_maxima, ReturnLevelSettings};
use vbi::statistics::extreme_value::{fit_generalised_pareto, ExtremeValueModel};

use crate::errors::library_error;

/// Serialises a library value into Python through JSON (the same numbers `lifetime.json` has).
fn to_python<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let json = serde_json::to_string(value).map_err(|e| library_error(&e))?;
    py.import("json")?.call_method1("loads", (json,))
}

/// The maximum-likelihood fit of `values` by `model` ("gev", "gumbel", or "gpd" for the
/// exceedances of `threshold`): a dict of `location` (the threshold for "gpd"), `scale`,
/// `shape` (Coles's sign; 0 for Gumbel) and `log_likelihood`.
#[pyfunction]
#[pyo3(signature = (values, model = "gev", threshold = None))]
pub fn fit_extreme_value<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    model: &str,
    threshold: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let model = match (model, threshold) {
        ("gev", None) => ExtremeValueModel::Gev,
        ("gumbel", None) => ExtremeValueModel::Gumbel,
        ("gpd", Some(threshold)) => {
            let law = py
                .detach(|| fit_generalised_pareto(&values, threshold))
                .map_err(|e| library_error(&e))?;
            let fit = serde_json::json!({
                "location": law.threshold,
                "scale": law.scale,
                "shape": law.shape,
                "log_likelihood": law.log_likelihood(&values),
            });
            return to_python(py, &fit);
        }
        ("gpd", None) => {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "a gpd fit needs its threshold (threshold=…)",
            ))
        }
        ("gev" | "gumbel", Some(_)) => {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "a threshold belongs to a gpd fit only",
            ))
        }
        (other, _) => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "`{other}` is not an extreme-value model; expected gev, gumbel or gpd"
            )))
        }
    };
    let law = py
        .detach(|| model.fit(&values))
        .map_err(|e| library_error(&e))?;
    let fit = serde_json::json!({
        "location": law.location,
        "scale": law.scale,
        "shape": law.shape,
        "log_likelihood": law.log_likelihood(&values),
    });
    to_python(py, &fit)
}

/// The fits and return levels of block maxima, as `vbi lifetime` makes them for an effect:
/// the dict of `lifetime.json`'s `fits` (`loaded_blocks`, `unloaded_blocks`, `errors`, and per
/// law its parameters, log-likelihood and return levels with their profile-likelihood
/// (`low`, `high`) and bootstrap (`bootstrap_low`, `bootstrap_high`) intervals).
#[pyfunction]
#[pyo3(signature = (values, block_days = 1.0, sense = 1.0, return_periods_years = vec![1000.0], days_per_year = 250.0, bootstrap_resamples = 400, seed = 0))]
pub fn fit_block_maxima_parts<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    block_days: f64,
    sense: f64,
    return_periods_years: Vec<f64>,
    days_per_year: f64,
    bootstrap_resamples: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    // The limits of the lifetime file's keys (vbi-input's constants).
    use vbi_input::lifetime::{BLOCK_DAYS_RANGE, DAYS_PER_YEAR_RANGE, MAX_RETURN_PERIOD_YEARS};
    let bad = |what: String| Err(pyo3::exceptions::PyValueError::new_err(what));
    let (shortest, longest) = BLOCK_DAYS_RANGE;
    if !(block_days.is_finite() && (shortest..=longest).contains(&block_days)) {
        return bad(format!(
            "block_days = {block_days} is not allowed; expected {shortest} to {longest} days"
        ));
    }
    let (fewest, most) = DAYS_PER_YEAR_RANGE;
    if !(days_per_year.is_finite() && (fewest..=most).contains(&days_per_year)) {
        return bad(format!(
            "days_per_year = {days_per_year} is not allowed; expected {fewest} to {most} days"
        ));
    }
    if let Some(p) = return_periods_years
        .iter()
        .find(|p| !(p.is_finite() && **p > 1.0 && **p <= MAX_RETURN_PERIOD_YEARS))
    {
        return bad(format!(
            "a return period of {p} years is not allowed; expected more than 1 year and at most {MAX_RETURN_PERIOD_YEARS:e}"
        ));
    }
    if sense == 0.0 || sense.is_nan() {
        return bad(format!("sense = {sense} is not allowed; expected +1 or -1"));
    }
    let settings = ReturnLevelSettings {
        periods_years: return_periods_years,
        days_per_year,
        resamples: bootstrap_resamples,
        seed,
        exceedances: 0,
    };
    let fits = py
        .detach(|| fit_block_maxima(&values, sense.signum(), block_days, &settings))
        .map_err(|e| library_error(&e))?;
    to_python(py, &fits)
}
