//! Library verification tests, one module per stage. Each test names what it verifies and cites
//! the source of its reference values.

mod batched_crossings;
mod module_dependencies;
mod verification_analytical;
mod verification_catching_up;
mod verification_damage;
mod verification_default_settings;
mod verification_fe;
mod verification_fe_analytical;
mod verification_grillage_decks;
mod verification_lifetime_dynamics;
mod verification_modal;
mod verification_pitching;
mod verification_road;
mod verification_road_events;
mod verification_signal;
mod verification_solver;
mod verification_solver_fe;
mod verification_station_forces;
mod verification_traffic;
mod verification_vbi2d_cases;
mod verification_vehicle;
