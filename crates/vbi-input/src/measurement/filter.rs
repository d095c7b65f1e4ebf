//! `[measurement.filter]`: the low-pass filter's order and cut-off frequency (the keys of the
//! cut-off modes K1 are read with each channel, [`crate::measurement::channels`]).

use crate::measurement::raw::RawFilter;
use crate::source::{require_in_range, InputError, SourceFile};

/// `order`: 1 to 12, default 4.
pub(crate) fn filter_order(file: &SourceFile, filter: &RawFilter) -> Result<usize, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    let filter_order = filter.order.unwrap_or(4);
    if !(1..=12).contains(&filter_order) {
        return Err(file.error_at(
            &at("filter.order"),
            format!("order {filter_order} is not allowed; expected 1 to 12"),
        ));
    }
    Ok(filter_order)
}

/// `cutoff_hz`: positive and below the Nyquist frequency [Hz].
pub(crate) fn cutoff_hz(
    file: &SourceFile,
    filter: &RawFilter,
    nyquist: f64,
) -> Result<Option<f64>, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    filter
        .cutoff_hz
        .map(|f| {
            require_in_range(
                file,
                &at("filter.cutoff_hz"),
                f,
                f64::MIN_POSITIVE,
                nyquist * 0.999,
                "Hz (below the Nyquist frequency)",
            )
        })
        .transpose()
}
