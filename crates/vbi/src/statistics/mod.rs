//! Statistics below the applications: sample quantiles and the extreme-value fits of block
//! maxima that a lifetime assessment's characteristic values come from.

pub mod extreme_value;
mod quantile;

pub use quantile::percentile_sorted;
