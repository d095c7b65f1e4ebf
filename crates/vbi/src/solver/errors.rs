//! The errors and warnings of a crossing: [`SolverError`] (the run cannot be done or failed) and
//! [`SolverWarning`] (the run completed, but something deserves attention).

use serde::{Deserialize, Serialize};

/// Errors of [`simulate`](super::simulate) and of the [`Integrator`](super::Integrator).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolverError {
    /// [`Integrator::step`](super::Integrator::step) was called after the last instant.
    #[error("the crossing is already integrated to its last instant ({steps} steps)")]
    AlreadyFinished {
        /// Time steps of the run.
        steps: usize,
    },
    /// The speed is not a positive finite number.
    #[error("speed {speed} m/s must be positive and finite")]
    InvalidSpeed {
        /// The offending speed [m/s].
        speed: f64,
    },
    /// A crossing parameter is not finite or out of range.
    #[error("crossing parameter `{name}` = {value} is invalid: {reason}")]
    InvalidCrossing {
        /// Field name.
        name: &'static str,
        /// Offending value.
        value: f64,
        /// What is allowed.
        reason: &'static str,
    },
    /// A crossing without vehicles.
    #[error("the crossing has no vehicle")]
    NoVehicle,
    /// A speed profile whose knots do not increase strictly, or that has no knot.
    #[error("vehicle {vehicle}: the speed profile's knots must increase strictly in travel (knot {knot})")]
    InvalidSpeedProfile {
        /// Vehicle number (from 1).
        vehicle: usize,
        /// Offending knot (from 1; 0 for an empty profile).
        knot: usize,
    },
    /// Two vehicles occupy the same part of the deck or road at t = 0.
    #[error(transparent)]
    VehiclesOverlap(crate::traffic::VehiclesOverlap),
    /// The time step (given or derived) is not positive and finite.
    #[error("time step {time_step} s must be positive and finite")]
    InvalidTimeStep {
        /// The offending time step [s].
        time_step: f64,
    },
    /// Newmark parameters outside the allowed range (β ≥ 0, γ ≥ 0.5).
    #[error("Newmark parameters beta = {beta}, gamma = {gamma} are not allowed (need beta >= 0, gamma >= 0.5)")]
    InvalidNewmark {
        /// β [-].
        beta: f64,
        /// γ [-].
        gamma: f64,
    },
    /// A conditionally stable Newmark scheme with a time step beyond its stability limit.
    #[error("time step {time_step} s is unstable for mode {mode} (ω = {circular_frequency} rad/s): the limit is {limit} s for beta = {beta}, gamma = {gamma}")]
    UnstableTimeStep {
        /// Time step [s].
        time_step: f64,
        /// Mode number, 1-based.
        mode: usize,
        /// ω of that mode [rad/s].
        circular_frequency: f64,
        /// Largest stable time step [s].
        limit: f64,
        /// β [-].
        beta: f64,
        /// γ [-].
        gamma: f64,
    },
    /// The modal basis is inconsistent or empty.
    #[error("modal basis is invalid: {reason} (expected {expected}, found {found})")]
    InvalidBasis {
        /// What is wrong.
        reason: &'static str,
        /// Expected size or value.
        expected: usize,
        /// Found size or value.
        found: usize,
    },
    /// A mode has a negative or non-finite frequency or damping ratio.
    #[error("mode {mode} has invalid properties: omega = {circular_frequency} rad/s, zeta = {damping_ratio}")]
    InvalidMode {
        /// Mode number, 1-based.
        mode: usize,
        /// ω [rad/s].
        circular_frequency: f64,
        /// ζ [-].
        damping_ratio: f64,
    },
    /// The vehicle model is inconsistent.
    #[error("vehicle `{vehicle}` is invalid: {reason}")]
    InvalidVehicle {
        /// Vehicle name.
        vehicle: String,
        /// What is wrong.
        reason: String,
    },
    /// A vehicle never reaches the deck end from its start position.
    #[error(
        "the vehicle starts at travel s = {start_position} m, beyond the deck end at {deck_length} m"
    )]
    StartsBeyondDeck {
        /// Front-axle start position [m].
        start_position: f64,
        /// Deck length [m].
        deck_length: f64,
    },
    /// The run would record more values than allowed.
    #[error("the run needs {steps} time steps × {values_per_step} values, more than the limit {limit} (the recorded modal, vehicle and contact values, and four per station for the DAF analysis); use a larger time step, fewer modes or fewer stations")]
    TooLong {
        /// Number of time steps.
        steps: usize,
        /// Values recorded per step.
        values_per_step: usize,
        /// Limit on steps × values.
        limit: usize,
    },
    /// The per-step coupled system was singular.
    #[error("the coupled system is singular at t = {time} s")]
    SingularSystem {
        /// Time [s].
        time: f64,
    },
    /// The response became non-finite.
    #[error("the response became non-finite at t = {time} s")]
    NonFinite {
        /// Time [s].
        time: f64,
    },
}

/// A warning attached to a result: the run completed, but something deserves attention.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, thiserror::Error)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum SolverWarning {
    /// The time step resolves mode `mode` (and all higher ones) with fewer than the required
    /// steps per period.
    #[error("time step {time_step} s under-resolves mode {mode} ({frequency_hz:.3} Hz, period {period:.6} s < {steps_per_period} steps) and {further_modes} higher mode(s)")]
    ModeUnderResolved {
        /// First under-resolved mode, 1-based.
        mode: usize,
        /// Its frequency [Hz].
        frequency_hz: f64,
        /// Its period [s].
        period: f64,
        /// Time step [s].
        time_step: f64,
        /// Required steps per period [-].
        steps_per_period: f64,
        /// Number of higher modes also under-resolved.
        further_modes: usize,
    },
    /// A vehicle changes speed (it brakes or accelerates) but none of its bodies has a centre
    /// of mass height: its speed changes, but not the load its axles carry (the pitching of
    /// braking and acceleration, docs/theory.md, needs the heights).
    #[error(
        "vehicle {vehicle} ({name}) changes speed (between {lowest_kmh:.1} and {highest_kmh:.1} km/h) \
         but has no centre-of-mass heights: only its speed changes, not the load its axles carry \
         (give each body's centre_of_mass_height_m for the pitching of braking and acceleration, \
         docs/theory.md); the tyres' horizontal forces on the deck are not modelled"
    )]
    SpeedChangeWithoutPitch {
        /// The vehicle's number in the event (from 1).
        vehicle: usize,
        /// Its name.
        name: String,
        /// Its lowest speed [km/h].
        lowest_kmh: f64,
        /// Its highest speed [km/h].
        highest_kmh: f64,
    },
    /// The default time step leaves bridge modes above the resolved frequency to respond
    /// quasi-statically (fewer than the required steps per period).
    #[error("the default time step {time_step} s leaves mode {mode} ({frequency_hz:.1} Hz) and {further_modes} other mode(s) with fewer than 20 steps per period: each is above 5 × both the highest excitation frequency ({excitation_frequency_hz:.2} Hz: the bridge's first mode, the vehicle's modes, the road samples under a wheel) and the rate at which the load passes its shape, so it responds quasi-statically (set `time_step_s` to resolve it, or keep fewer `modes`)")]
    ModesQuasiStatic {
        /// First mode above the resolved frequency, 1-based.
        mode: usize,
        /// Its frequency [Hz].
        frequency_hz: f64,
        /// Number of other modes also left unresolved.
        further_modes: usize,
        /// Highest excitation frequency [Hz].
        excitation_frequency_hz: f64,
        /// Time step [s].
        time_step: f64,
    },
    /// A user-given time step resolves one of the vehicle's own modes (on a rigid road) with
    /// fewer than the required steps per period.
    #[error("time step {time_step} s under-resolves the vehicle's {mode} mode ({frequency_hz:.2} Hz: fewer than {steps_per_period} steps per period) and {further_modes} higher vehicle mode(s); the wheel forces, and so the DAF, depend on it")]
    VehicleModeUnderResolved {
        /// The mode's label, for example `axle 1 hop`.
        mode: String,
        /// Its frequency [Hz].
        frequency_hz: f64,
        /// Time step [s].
        time_step: f64,
        /// Required steps per period [-].
        steps_per_period: f64,
        /// Number of higher vehicle modes also under-resolved.
        further_modes: usize,
    },
    /// A static deflection larger than span/100: an input in a wrong unit, most likely
    /// (`crossing::plausibility`).
    #[error("the static deflection at `{station}` is {deflection:.4} m, more than span/100 = {limit:.4} m of its {span_length} m span: no bridge deflects that much under a vehicle; check the units of the stiffness (EI in N·m², E in GPa) and of the vehicle's masses")]
    StaticDeflectionImplausible {
        /// The station.
        station: String,
        /// Its largest static deflection [m].
        deflection: f64,
        /// Its span [m].
        span_length: f64,
        /// span/100 [m].
        limit: f64,
    },
    /// A fundamental frequency outside the range of real bridges (`crossing::plausibility`).
    #[error("the bridge's first bending frequency {frequency_hz:.3} Hz lies outside {low_hz:.2}–{high_hz:.2} Hz, the range of real bridges of a {span_length} m span (EN 1991-2 Figure 6.10 widened by a factor of 3): check the units of the stiffness and the mass per length")]
    FrequencyImplausible {
        /// The frequency [Hz].
        frequency_hz: f64,
        /// The longest span [m].
        span_length: f64,
        /// Lower end of the range [Hz].
        low_hz: f64,
        /// Upper end of the range [Hz].
        high_hz: f64,
    },
    /// Imported mode shapes whose size does not fit a mass-normalised mode of a real deck
    /// (`crossing::plausibility`).
    #[error("the first imported vertical bending mode's largest deflection {amplitude:.3e} implies a deck mass of 2/(L·φ²) = {implied_mass_per_length:.3e} kg/m over the {length} m deck if the shapes are mass-normalised, outside {low:.0}–{high:.0} kg/m of real bridge decks: check that the shapes are mass-normalised (φᵀMφ = 1 with M in kg and φ in m), not scaled to a unit maximum or given in mm")]
    ImportedShapesImplausible {
        /// The largest |φ| of the first vertical bending mode over the deck nodes [m per unit
        /// modal coordinate].
        amplitude: f64,
        /// 2/(L·φ²) [kg/m].
        implied_mass_per_length: f64,
        /// The deck's length [m].
        length: f64,
        /// Lowest plausible mass per length [kg/m].
        low: f64,
        /// Highest plausible mass per length [kg/m].
        high: f64,
    },
    /// The bridge has no station: the run integrates the crossing but reports no DAF.
    #[error("the bridge has no station, so the run reports no DAF: give the scenario's [[station]] tables, or an imported basis's station_moments_csv (or flexural_rigidity_n_m2 for its default stations)")]
    NoStations,
    /// The static reference of a bridge known only by its modes is their modal flexibility,
    /// truncated to the modes given (`modal::flexibility`).
    #[error("the static reference is the modal flexibility of the {mode_count} imported modes, not the full stiffness: deflections are close with a few modes, bending moments under concentrated wheel loads converge slowly (a few per cent at 10 modes), and so do the DAFs divided by them; give the stations' influence lines (influence_lines_csv) or import the model's matrices (type = \"imported_matrices\") for the exact reference")]
    TruncatedStaticReference {
        /// Modes in the basis.
        mode_count: usize,
    },
    /// Imported matrices whose static stiffness or mass does not fit the deck lines' EI and
    /// mass per length (`crossing::plausibility`): the usual sign of matrices in other units
    /// than the declared ones.
    #[error("the imported model's {what} is {ratio:.3e} times {reference}, outside {low:.3}–{high:.3}: check `units` (the matrices' force and length units) and the deck lines' flexural_rigidity_n_m2 and mass_per_length_kg_per_m")]
    ImportedModelImplausible {
        /// What was measured, in words.
        what: String,
        /// What it is compared with, in words.
        reference: String,
        /// The ratio measured / reference [-].
        ratio: f64,
        /// The lowest plausible ratio [-].
        low: f64,
        /// The highest plausible ratio [-].
        high: f64,
    },
    /// The converged (static-corrected) DAF of an entry still moves by more than the tolerance
    /// over the last modes kept: more modes are needed for that station and quantity.
    #[error("the converged DAF of {quantity} at `{station}` still changes by {change:.4} over the last {window} mode(s) kept or {check_modes} check mode(s) above them (twice their change), more than {tolerance} of its value, and {further_entries} other station quantity(ies) likewise: keep more `modes` (docs/theory.md, convergence)")]
    DafNotConverged {
        /// The station whose DAF moves most.
        station: String,
        /// Its quantity's name.
        quantity: String,
        /// The convergence indicator's change ([`crate::analysis::DafConvergence`]) [-].
        change: f64,
        /// The number of last modes kept over which the change is taken.
        window: usize,
        /// The number of check modes above them over which it is taken too.
        #[serde(default)]
        check_modes: usize,
        /// The relative tolerance [-].
        tolerance: f64,
        /// How many other entries exceed the tolerance.
        further_entries: usize,
    },
    /// The DAFs at the default time step halved `halvings` times still differ by more than the
    /// tolerance from those at twice the step ([`crate::crossing::time_step_check`]).
    #[error("the {quantity} DAF at `{station}` still changes by {relative_change:.2e} of its value between the time steps {time_step} s and twice it ({halvings} halving(s) of the default step), more than {tolerance}: give a smaller `time_step_s`, or keep fewer `modes` (docs/theory.md, the check of the time step)")]
    TimeStepNotConverged {
        /// The station whose DAF moves most.
        station: String,
        /// Its quantity's name.
        quantity: String,
        /// |DAF(Δt) − DAF(2Δt)| / |DAF(Δt)| [-].
        relative_change: f64,
        /// The run's time step Δt [s].
        time_step: f64,
        /// How many times the default step was halved.
        halvings: u32,
        /// The relative tolerance [-].
        tolerance: f64,
    },
    /// The check of the time step could not run, or the step could not be halved (the solver
    /// refused the run at the other step); a failed halving keeps the comparison that asked for
    /// it.
    #[error(
        "the time step {time_step} s could not be checked or refined: the run at another step failed ({reason})"
    )]
    TimeStepUnchecked {
        /// The run's time step [s].
        time_step: f64,
        /// The check's error.
        reason: String,
    },
    /// The headline DAF of some entries is the paper's plain modal sum: the static-corrected
    /// series needs every mode to have a positive frequency.
    #[error("{entries} DAF(s) are the paper's plain modal sums, not the converged static-corrected series: a mode of the basis has no positive frequency")]
    HeadlineIsPaperSeries {
        /// Number of entries.
        entries: usize,
    },
    /// The wheel advances more than one road sample per time step.
    #[error("time step {time_step} s under-resolves the road: at {speed:.3} m/s a wheel crosses {distance_per_step:.4} m per step, more than the sample spacing {sample_spacing} m")]
    RoadUnderResolved {
        /// Time step [s].
        time_step: f64,
        /// Speed [m/s].
        speed: f64,
        /// Distance per step [m].
        distance_per_step: f64,
        /// Road sample spacing [m].
        sample_spacing: f64,
    },
    /// The set of tyres in flight did not settle within the passes allowed per step (tyres
    /// switching between contact and flight within one step); the last pass was kept.
    #[error("the tyre contact set did not settle in {steps} time step(s), first at t = {first_time:.4} s; the last of {passes} passes was kept (a finer time step resolves take-off and landing)")]
    ContactSetUnsettled {
        /// Time of the first such step [s].
        first_time: f64,
        /// Number of such steps.
        steps: usize,
        /// Passes allowed per step.
        passes: usize,
    },
}
