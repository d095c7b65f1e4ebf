//! The static-corrected (mode-acceleration) series of a run.
//!
//! The plain partial sum R_K(t) = Σ_{k≤K} cₖ qₖ(t) misses, for every K < ∞, the quasi-static
//! response of the truncated modes to the wheel loads; for a bending moment under a concentrated
//! load that part converges slowly (the paper's CM_M up to 40). The mode-acceleration method
//! (Williams 1945; Cornwell, Craig & Johnson 1983, Earthq. Eng. Struct. Dyn. 11) adds it back
//! exactly through the full-stiffness influence lines:
//!
//!   R̃_K(t) = Q(t) + Σ_{k≤K} cₖ (qₖ(t) − Fₖ(t)/ωₖ²),   Q(t) = Σ_w P_w(t) · IL(x_w(t), y_w),
//!
//! with Fₖ(t) = −Σ_w P_w(t) φₖ(x_w, y_w) the modal force of the recorded contact forces P_w
//! (compressive positive; φ is upwards positive, the solver's Eq. 25 sign). The modal equation
//! q̈ₖ + 2ζₖωₖq̇ₖ + ωₖ²qₖ = Fₖ makes qₖ − Fₖ/ωₖ² = −(q̈ₖ + 2ζₖωₖq̇ₖ)/ωₖ², the inertia and damping
//! part. With every mode of the FE model the two deflection series are equal (Σ φφᵀ/ω² = K⁻¹);
//! the moment series differ then only by the element-local share of a wheel load standing in an
//! element next to the station, which the influence line (read from the unloaded side) has
//! exactly. With few modes R̃_K is already close to its limit; in the static limit (v → 0) it
//! tends to the exact static response, so DAF → 1, where the plain series tends to the truncated
//! modes' static sum instead.
//!
//! The series are streamed: [`Streams`] takes each run's instants as they come (from a
//! recorded history, [`stream_history`], or from the solver as it computes them) and hands
//! them to the run's [`PanelSink`] one panel of [`LANES`] instants at a time, plain and then
//! corrected, so that no run's table of coordinates is held whole.

use super::check_modes::CheckModeStates;
use super::partial_sums::LANES;
use super::wheel_fields::WheelFields;
use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::{ResponseHistory, WheelPaths};

/// What receives a run's series, one panel of instants `start..start + len` at a time
/// (`panel[k · LANES + j]` is mode k at instant start + j; the lanes from `len` on are zero),
/// in the order of time.
pub(crate) trait PanelSink {
    /// The plain coordinates qₖ.
    fn plain(&mut self, panel: &[f64], instants: (usize, usize));
    /// The corrected coordinates yₖ = qₖ − Fₖ/ωₖ², and Q of the run's t-th target at instant
    /// start + j in `quasi_static[t][j]` [m, N·m or N]. With check modes
    /// ([`ModalBasis::check_modes`]) the panel holds their y after the N modes' (rows N…N + C).
    fn corrected(&mut self, panel: &[f64], quasi_static: &[[f64; LANES]], instants: (usize, usize));
}

/// One run of [`Streams`]: where its wheels are, its (station, quantity) targets and its sink.
pub(crate) struct StreamedRun<'a, S> {
    pub paths: WheelPaths<'a>,
    pub targets: Vec<(usize, Quantity)>,
    pub sink: S,
    /// Whether its instants come with their contact forces (the correction needs them).
    pub with_forces: bool,
    /// Its time step Δt [s] (the check modes' integration).
    pub time_step: f64,
    /// Whether its check modes are integrated (a corrected run on a basis that has them).
    pub with_check_modes: bool,
}

/// The series of several runs on one bridge, streamed as their instants come
/// ([`Streams::record`]): instant by instant, instant i of every run before instant i + 1 of
/// any (the order in which crossings integrated in lockstep compute them).
///
/// A run has corrected series when every mode has a positive finite frequency (a correction by
/// 1/ωₖ² does not exist otherwise), its instants come with their contact forces and its paths
/// hold a position per contact and instant; a target without an influence line keeps Q = 0.
/// The runs whose contacts take the first corrected run's paths (the same number of instants,
/// lateral positions, static loads and positions, bit for bit: the road samples of one
/// crossing) form one group, whose contacts' mode values φ(x_w) and influence-line values
/// IL(x_w) of every target of its runs are read once per instant for all of them
/// ([`WheelFields`]: the element cubics, the solver's route); every other run is a group of its
/// own. A group's panel is handed on once each of its runs has given the panel's instants.
/// Each run's sums are taken in the same order either way, so every run gets its own result
/// bit for bit.
pub(crate) struct Streams<'a, S> {
    pass: StreamPass<'a>,
    runs: Vec<RunStream<'a, S>>,
    groups: Vec<Group<'a>>,
}

/// What a pass over runs reads besides the runs.
struct StreamPass<'a> {
    basis: &'a ModalBasis,
    influence: &'a InfluenceLines,
    /// 1/ωₖ² [s²].
    flexibility: Vec<f64>,
    /// The basis's check modes, if it has them (each with a positive finite frequency).
    check: Option<&'a ModalBasis>,
}

/// A run being streamed: its panel being filled.
struct RunStream<'a, S> {
    run: StreamedRun<'a, S>,
    group: usize,
    corrected: bool,
    /// Where each of its targets is read among its group's wheels' lines (corrected runs).
    line_slots: Vec<usize>,
    /// Left without its remaining instants ([`Streams::abandon`]).
    abandoned: bool,
    /// qₖ of the panel's instants, `panel[k · LANES + j]` (N.max(1) × LANES).
    panel: Vec<f64>,
    /// P_w of the panel's instants, `forces[j · contacts + w]` (corrected runs only).
    forces: Vec<f64>,
    /// Q of each target at the panel's instants.
    quasi_static: Vec<[f64; LANES]>,
    /// Its check modes' states (corrected runs on a basis with check modes).
    check: Option<CheckModeStates>,
    /// Instants of the panel given so far.
    filled: usize,
}

/// Runs whose panels are handed on together.
struct Group<'a> {
    /// First instant of the panel being filled.
    start: usize,
    /// Instants of every run of the group.
    step_count: usize,
    /// Runs of the group not yet holding the whole panel.
    waiting: usize,
    /// The contacts' deck fields, for a group with corrected series.
    wheels: Option<Wheels<'a>>,
}

impl Group<'_> {
    /// Number of instants of the panel being filled (fewer than LANES at the end; 0 once the
    /// group has ended).
    fn panel_length(&self) -> usize {
        LANES.min(self.step_count.saturating_sub(self.start))
    }
}

impl<'a, S: PanelSink> Streams<'a, S> {
    /// The runs, grouped (see the type's documentation), none of their instants given yet.
    pub(crate) fn new(
        basis: &'a ModalBasis,
        influence: &'a InfluenceLines,
        runs: Vec<StreamedRun<'a, S>>,
    ) -> Self {
        let flexibility: Vec<f64> = basis
            .modes
            .iter()
            .map(|m| 1.0 / (m.circular_frequency * m.circular_frequency))
            .collect();
        let modes_correct = flexibility.iter().all(|g| g.is_finite() && *g > 0.0);
        let correctable = |run: &StreamedRun<S>| {
            let recorded = run
                .paths
                .step_count
                .saturating_mul(run.paths.contacts.len());
            modes_correct && run.with_forces && run.paths.positions.len() == recorded
        };
        let check = super::usable_check_modes(basis);
        let pass = StreamPass {
            basis,
            influence,
            flexibility,
            check,
        };
        let n = basis.mode_count();
        let rows = n + check.map_or(0, |check| check.mode_count());
        // The first corrected run's paths: the runs that share them are streamed together.
        let leader = runs
            .iter()
            .find(|run| correctable(run))
            .map(|run| run.paths);
        let mut streams = Streams {
            pass,
            runs: Vec::with_capacity(runs.len()),
            groups: Vec::new(),
        };
        let mut shared_group = None;
        for run in runs {
            let corrected = correctable(&run);
            let joins_leader = corrected
                && leader.is_some_and(|first| {
                    run.paths.step_count == first.step_count
                        && run.paths.same_as(first.contacts, first.positions)
                });
            let group = match shared_group.filter(|_| joins_leader) {
                Some(group) => group,
                None => {
                    let group = streams.new_group(&run, corrected);
                    shared_group = shared_group.or(joins_leader.then_some(group));
                    group
                }
            };
            let line_slots = match streams.groups[group].wheels.as_mut() {
                Some(wheels) if corrected => wheels.fields.slots(&run.targets),
                _ => Vec::new(),
            };
            let contacts = run.paths.contacts.len();
            let check_states = (check.filter(|_| corrected && run.with_check_modes))
                .map(|check| CheckModeStates::new(&check.modes, run.time_step));
            streams.runs.push(RunStream {
                panel: vec![0.0; rows.max(1) * LANES],
                forces: vec![0.0; if corrected { contacts * LANES } else { 0 }],
                quasi_static: vec![[0.0; LANES]; run.targets.len()],
                check: check_states,
                run,
                group,
                corrected,
                line_slots,
                abandoned: false,
                filled: 0,
            });
        }
        for g in 0..streams.groups.len() {
            streams.open_panel(g);
        }
        streams
    }

    /// A new group whose first run is `run` (with the contacts' deck fields when it is
    /// `corrected`).
    fn new_group(&mut self, run: &StreamedRun<'a, S>, corrected: bool) -> usize {
        self.groups.push(Group {
            start: 0,
            step_count: run.paths.step_count,
            waiting: 0,
            wheels: corrected.then(|| Wheels::new(&self.pass, run)),
        });
        self.groups.len() - 1
    }

    /// Gives run `r`'s next instant: its modal coordinates qₖ and, for a run streamed with its
    /// forces, the contact forces P_w [N]. Nothing for an abandoned run.
    ///
    /// # Panics
    /// If the instant is past the run's end, or past its group's current panel (a run of a
    /// group may not run ahead of the others: instant i of every run comes before instant
    /// i + 1 of any).
    pub(crate) fn record(&mut self, r: usize, modal_displacement: &[f64], contact_force: &[f64]) {
        let stream = &mut self.runs[r];
        if stream.abandoned {
            return;
        }
        let length = self.groups[stream.group].panel_length();
        assert!(
            stream.filled < length,
            "an instant past the run's end or ahead of its group"
        );
        let j = stream.filled;
        for (k, &q) in modal_displacement.iter().enumerate() {
            stream.panel[k * LANES + j] = q;
        }
        if stream.corrected {
            let contacts = stream.run.paths.contacts.len();
            stream.forces[j * contacts..(j + 1) * contacts].copy_from_slice(contact_force);
        }
        stream.filled += 1;
        if stream.filled == length {
            self.panel_done(r);
        }
    }

    /// Takes run `r` out of the streams: none of its remaining instants will come (its
    /// integration failed), and its group goes on without it.
    pub(crate) fn abandon(&mut self, r: usize) {
        let stream = &mut self.runs[r];
        if stream.abandoned {
            return;
        }
        stream.abandoned = true;
        if stream.filled < self.groups[stream.group].panel_length() {
            self.panel_done(r);
        }
    }

    /// Run `r` waits no more for the current panel of its group (it holds the panel, or it was
    /// abandoned): the panel is handed on once no run of the group waits.
    fn panel_done(&mut self, r: usize) {
        let g = self.runs[r].group;
        self.groups[g].waiting -= 1;
        if self.groups[g].waiting == 0 {
            self.hand_on(g);
        }
    }

    /// Every run's sink, and whether the run had corrected series, in order. Every run must
    /// have given all its instants or been abandoned.
    pub(crate) fn finish(self) -> Vec<(S, bool)> {
        self.runs
            .into_iter()
            .map(|stream| (stream.run.sink, stream.corrected))
            .collect()
    }

    /// Hands group `g`'s full panel to its runs' sinks, plain and then corrected, and opens
    /// the next.
    fn hand_on(&mut self, g: usize) {
        let group = &mut self.groups[g];
        let instants = (group.start, group.panel_length());
        let mut members: Vec<&mut RunStream<S>> = (self.runs.iter_mut())
            .filter(|stream| stream.group == g && !stream.abandoned)
            .collect();
        for stream in &mut members {
            if instants.1 < LANES {
                for lanes in stream.panel.chunks_exact_mut(LANES) {
                    lanes[instants.1..].fill(0.0);
                }
            }
            stream.run.sink.plain(&stream.panel, instants);
        }
        if let Some(wheels) = group.wheels.as_mut() {
            for stream in &mut members {
                stream.quasi_static.fill([0.0; LANES]);
            }
            for j in 0..instants.1 {
                wheels.correct(&self.pass, &mut members, (instants.0 + j, j));
            }
            for stream in &mut members {
                let sink = &mut stream.run.sink;
                sink.corrected(&stream.panel, &stream.quasi_static, instants);
            }
        }
        group.start += instants.1;
        self.open_panel(g);
    }

    /// Starts group `g`'s next panel: every run that goes on waits for its instants.
    fn open_panel(&mut self, g: usize) {
        let group = &mut self.groups[g];
        if group.start >= group.step_count {
            return;
        }
        for stream in self.runs.iter_mut().filter(|s| s.group == g) {
            stream.filled = 0;
            if !stream.abandoned {
                group.waiting += 1;
            }
        }
    }
}

/// Streams the recorded history of one run (its sizes checked by the caller: q of every
/// instant; the contact forces are used if recorded in full) with its targets into its sink:
/// the sink, and whether the run had corrected series.
pub(crate) fn stream_history<S: PanelSink>(
    (basis, influence): (&ModalBasis, &InfluenceLines),
    history: &ResponseHistory,
    (targets, sink): (Vec<(usize, Quantity)>, S),
) -> (S, bool) {
    let run = StreamedRun {
        paths: history.wheel_paths(),
        targets,
        sink,
        with_forces: forces_recorded(history),
        time_step: history.time_step,
        with_check_modes: true,
    };
    let mut streams = Streams::new(basis, influence, vec![run]);
    feed_histories(&[Some(history)], |r, q, p| streams.record(r, q, p));
    streams.finish().pop().expect("one run in, one out")
}

/// Whether a history holds the contact forces of every contact at every instant.
pub(super) fn forces_recorded(history: &ResponseHistory) -> bool {
    let recorded = history.step_count.saturating_mul(history.contacts.len());
    history.contact_force.len() == recorded
}

/// Calls `record(r, q, P)` with every instant of every history r (None: none of its instants)
/// in the order [`Streams::record`] takes them: instant i of every run before instant i + 1 of
/// any. P is empty where the history lacks its forces ([`forces_recorded`]). The histories'
/// modal displacements must hold every instant (checked by the caller).
pub(super) fn feed_histories(
    histories: &[Option<&ResponseHistory>],
    mut record: impl FnMut(usize, &[f64], &[f64]),
) {
    let with_forces: Vec<bool> = histories
        .iter()
        .map(|history| history.is_some_and(forces_recorded))
        .collect();
    let longest = histories.iter().flatten().map(|h| h.step_count).max();
    for i in 0..longest.unwrap_or(0) {
        for (r, history) in histories.iter().enumerate() {
            let Some(history) = history.filter(|h| i < h.step_count) else {
                continue;
            };
            let contacts = history.contacts.len();
            let forces = match with_forces[r] {
                true => &history.contact_force[i * contacts..(i + 1) * contacts],
                false => &[],
            };
            record(r, history.modal_displacements_at(i), forces);
        }
    }
}

/// The contacts of runs that share their paths, their deck fields read once for all of them.
struct Wheels<'a> {
    /// The paths of the group's runs.
    paths: WheelPaths<'a>,
    fields: WheelFields<'a>,
    /// −Fₖ of each run at the current instant (chunks of N.max(1)).
    forces: Vec<f64>,
    /// The check modes' values at the contacts, if the basis has check modes.
    check_fields: Option<WheelFields<'a>>,
    /// Fₖ of each run's check modes at the current instant (chunks of C), and their y.
    check_forces: Vec<f64>,
    check_corrected: Vec<f64>,
}

impl<'a> Wheels<'a> {
    /// The wheels of the group whose first run is `first`.
    fn new<S>(pass: &StreamPass<'a>, first: &StreamedRun<'a, S>) -> Self {
        let paths = first.paths;
        Wheels {
            paths,
            fields: WheelFields::new(pass.basis, pass.influence, paths.contacts),
            forces: Vec::new(),
            check_fields: (pass.check)
                .map(|check| WheelFields::new(check, pass.influence, paths.contacts)),
            check_forces: Vec::new(),
            check_corrected: Vec::new(),
        }
    }

    /// Corrects lane j of every run's panel for instant i, `(i, j)`, and adds each target's Q
    /// there: Fₖ = −Σ_w P_w φₖ(x_w), yₖ = qₖ − Fₖ/ωₖ², Q = Σ_w P_w IL(x_w), the contacts in order.
    fn correct<S>(
        &mut self,
        pass: &StreamPass,
        runs: &mut [&mut RunStream<S>],
        (i, j): (usize, usize),
    ) {
        let n = pass.basis.mode_count();
        let contacts = self.paths.contacts.len();
        let chunk = n.max(1);
        self.forces.clear();
        self.forces.resize(chunk * runs.len(), 0.0);
        let mut loaded = false;
        for w in 0..contacts {
            let x = self.paths.positions[i * contacts + w];
            let Some((shape, lines)) = self.fields.read(w, x) else {
                continue;
            };
            loaded = true;
            for (stream, force) in runs.iter_mut().zip(self.forces.chunks_exact_mut(chunk)) {
                let p = stream.forces[j * contacts + w];
                for (f, phi) in force.iter_mut().zip(shape) {
                    *f -= p * phi;
                }
                for (values, &slot) in stream.quasi_static.iter_mut().zip(&stream.line_slots) {
                    if let Some(value) = lines[slot] {
                        values[j] += p * value;
                    }
                }
            }
        }
        if loaded {
            for (stream, force) in runs.iter_mut().zip(self.forces.chunks_exact(chunk)) {
                for (k, (f, g)) in force.iter().zip(&pass.flexibility).enumerate() {
                    stream.panel[k * LANES + j] -= f * g;
                }
            }
        }
        self.advance_check_modes(runs, (i, j), n);
    }

    /// The check modes of every run to instant i, their y written to lane j of the panel's
    /// rows after the N modes: Fₖ = −Σ_w P_w φₖ(x_w) of the check modes, integrated exactly
    /// ([`CheckModeStates`]). The check modes move on when no wheel is on the deck too (free
    /// vibration).
    fn advance_check_modes<S>(
        &mut self,
        runs: &mut [&mut RunStream<S>],
        (i, j): (usize, usize),
        n: usize,
    ) {
        let Some(fields) = self.check_fields.as_mut() else {
            return;
        };
        let c = runs
            .iter()
            .find_map(|stream| stream.check.as_ref().map(|states| states.mode_count()))
            .unwrap_or(0);
        if c == 0 {
            return;
        }
        let contacts = self.paths.contacts.len();
        self.check_forces.clear();
        self.check_forces.resize(c * runs.len(), 0.0);
        for w in 0..contacts {
            let x = self.paths.positions[i * contacts + w];
            let Some((shape, _)) = fields.read(w, x) else {
                continue;
            };
            for (stream, force) in runs.iter().zip(self.check_forces.chunks_exact_mut(c)) {
                let p = stream.forces[j * contacts + w];
                for (f, phi) in force.iter_mut().zip(shape) {
                    *f -= p * phi;
                }
            }
        }
        self.check_corrected.resize(c, 0.0);
        for (stream, force) in runs.iter_mut().zip(self.check_forces.chunks_exact(c)) {
            let Some(states) = stream.check.as_mut() else {
                continue;
            };
            states.next_instant(force, &mut self.check_corrected);
            for (k, &y) in self.check_corrected.iter().enumerate() {
                stream.panel[(n + k) * LANES + j] = y;
            }
        }
    }
}
