//! End-to-end tests of the `vbi` binary (one test binary, one module per command).

mod analytic;
mod bridge;
mod check;
mod common;
mod convergence_indicator;
mod docs_commands;
mod documented_numbers;
mod imported_matrices;
mod imported_modes;
mod lifetime;
mod measure;
mod measure_batch;
mod measure_battery;
mod measure_csv_dialects;
mod measure_influence_lines_and_resampling;
mod measure_paper_bridges;
mod measure_weighing;
mod modes;
mod report;
mod road;
mod road_events;
mod robustness;
mod run;
mod study;
mod traffic;
mod vehicle;
