//! Modal participation (paper Eq. 30), cut-off modes K1/K2 and the convergence mode CM.

use super::{AnalysisOptions, BendingCutoffs, DeckParticipation};
use crate::modal::{ModalBasis, ModeKind, Quantity, Station, StationTarget};

/// Root mean square over time of every modal coordinate, rms(qₖ) = √(Σᵢ qₖ(tᵢ)² / steps)
/// [kg^½·m], from the sums of squares Σᵢ qₖ(tᵢ)² (taken in the order of time) over
/// `step_count` instants.
pub(crate) fn rms_of_square_sums(square_sums: &[f64], step_count: usize) -> Vec<f64> {
    let steps = step_count.max(1) as f64;
    square_sums.iter().map(|s| (s / steps).sqrt()).collect()
}

/// Normalised participation from per-mode weights, and its running sum.
pub(crate) fn normalise(weights: Vec<f64>) -> (Vec<f64>, Vec<f64>) {
    let total: f64 = weights.iter().sum();
    let share: Vec<f64> = if total > 0.0 && total.is_finite() {
        weights.iter().map(|w| w / total).collect()
    } else {
        vec![0.0; weights.len()]
    };
    let mut running = 0.0;
    let cumulative = share
        .iter()
        .map(|p| {
            running += p;
            running
        })
        .collect();
    (share, cumulative)
}

/// Smallest K (1-based) whose cumulative participation reaches `level`.
pub(crate) fn cutoff(cumulative: &[f64], level: f64) -> Option<usize> {
    // 1e-12 absorbs the rounding of the running sum when level = 1.
    cumulative
        .iter()
        .position(|&c| c >= level - 1e-12)
        .map(|k| k + 1)
}

/// Smallest K (1-based) whose cumulative participation reaches `level` (K1 at 0.95, K2 at 0.99,
/// the paper's §5 and Table 2); None when it never does. The participation need not be
/// normalised: it is divided by its sum first (`normalise`; no share when the sum is not
/// positive and finite), then summed mode by mode as in the DAF report.
pub fn cutoff_mode(participation: &[f64], level: f64) -> Option<usize> {
    let (_, cumulative) = normalise(participation.to_vec());
    cutoff(&cumulative, level)
}

/// The cut-off mode counted among the selected modes only: the participation is restricted to
/// the modes with `selected[k]`, normalised over them, and K is the number of selected modes
/// whose cumulative share reaches `level`. With the vertical bending modes selected this is the
/// count a beam model gives (a beam has no torsion or lateral modes to count).
pub fn cutoff_mode_among(participation: &[f64], selected: &[bool], level: f64) -> Option<usize> {
    let restricted: Vec<f64> = participation
        .iter()
        .zip(selected)
        .filter(|(_, &keep)| keep)
        .map(|(&p, _)| p)
        .collect();
    cutoff_mode(&restricted, level)
}

/// Smallest K (1-based) after which every DAF(K′) stays within `tolerance`·DAF(N) of DAF(N).
pub fn convergence_mode(daf_by_modes: &[f64], tolerance: f64) -> Option<usize> {
    let &last = daf_by_modes.last()?;
    let band = tolerance * last.abs();
    let mut cm = daf_by_modes.len();
    for k in (0..daf_by_modes.len()).rev() {
        if (daf_by_modes[k] - last).abs() <= band {
            cm = k + 1;
        } else {
            break;
        }
    }
    Some(cm)
}

/// The convergence mode CM had only the first n modes been kept, n = 1…N: CM of the series
/// DAF(1…n) ([`convergence_mode`]). Where the series has not converged, CM(n) grows with n: the
/// paper's CM of a bending moment then says where the list of modes was cut, not how the bridge
/// responds (docs/paper-reproduction.md). O(N²), N ≤ a few hundred.
pub fn convergence_modes_against_modes_kept(
    daf_by_modes: &[f64],
    tolerance: f64,
) -> Vec<Option<usize>> {
    (1..=daf_by_modes.len())
        .map(|n| convergence_mode(&daf_by_modes[..n], tolerance))
        .collect()
}

/// The cut-off mode at `level` had only the first n modes been kept, n = 1…N: the participation
/// of the first n modes normalised over them ([`cutoff_mode`]). It grows with n wherever the
/// participation still spreads over the modes above n.
pub fn cutoffs_against_modes_kept(participation: &[f64], level: f64) -> Vec<Option<usize>> {
    (1..=participation.len())
        .map(|n| cutoff_mode(&participation[..n], level))
        .collect()
}

/// The stations over which the moment participation of Eq. 30 sums: each structural point once,
/// and the sagging moment only.
/// - Stations over an interior support (hogging) are left out, unless there is no other.
/// - Girder stations are kept and whole-section stations left out when both exist: a section's
///   modal moment is the sum of its girders' (docs/theory.md), so summing both counts each
///   girder twice. A beam (whole-section stations only) keeps its section stations.
pub(crate) fn moment_participation_stations(stations: &[Station]) -> Vec<usize> {
    let sagging: Vec<usize> = (0..stations.len())
        .filter(|&s| !stations[s].over_support)
        .collect();
    let candidates = if sagging.is_empty() {
        (0..stations.len()).collect()
    } else {
        sagging
    };
    let is_girder = |s: &usize| matches!(stations[*s].target, StationTarget::Girder(_));
    if candidates.iter().any(is_girder) {
        candidates.into_iter().filter(is_girder).collect()
    } else {
        candidates
    }
}

/// Participation over the whole deck (Eq. 30, MPS_k = Σ_j rms(y_k^j) / Σ_k Σ_j rms(y_k^j)):
/// deflection weighted by |φₖ| summed over all deck nodes (the structural nodes j), bending
/// moment by |cₖ| summed over the girders' sagging stations ([`moment_participation_stations`];
/// moments exist only at stations), each times rms(qₖ), since rms(cₖ qₖ(t)) = |cₖ| rms(qₖ).
pub(crate) fn deck_participation(
    basis: &ModalBasis,
    rms: &[f64],
    options: &AnalysisOptions,
) -> DeckParticipation {
    let n = basis.mode_count();
    let mut node_weight = vec![0.0; n];
    for row in basis.deck_deflection.chunks_exact(n.max(1)) {
        for (w, phi) in node_weight.iter_mut().zip(row) {
            *w += phi.abs();
        }
    }
    let mut station_weight = vec![0.0; n];
    for s in moment_participation_stations(&basis.stations) {
        for (w, c) in station_weight
            .iter_mut()
            .zip(basis.station_values(s, Quantity::BendingMoment))
        {
            *w += c.abs();
        }
    }
    let weighted = |weights: &[f64]| weights.iter().zip(rms).map(|(w, r)| w * r).collect();
    let (deflection, deflection_cumulative) = normalise(weighted(&node_weight));
    let (moment, moment_cumulative) = normalise(weighted(&station_weight));
    let bending: Vec<bool> = basis
        .modes
        .iter()
        .map(|m| m.kind == ModeKind::VerticalBending)
        .collect();
    let among_bending = |share: &[f64], level: f64| cutoff_mode_among(share, &bending, level);
    let vertical_bending = BendingCutoffs {
        deflection_k1: among_bending(&deflection, options.cutoff_k1_level),
        deflection_k2: among_bending(&deflection, options.cutoff_k2_level),
        moment_k1: among_bending(&moment, options.cutoff_k1_level),
        moment_k2: among_bending(&moment, options.cutoff_k2_level),
    };
    DeckParticipation {
        vertical_bending,
        deflection_k1: cutoff(&deflection_cumulative, options.cutoff_k1_level),
        deflection_k2: cutoff(&deflection_cumulative, options.cutoff_k2_level),
        moment_k1: cutoff(&moment_cumulative, options.cutoff_k1_level),
        moment_k2: cutoff(&moment_cumulative, options.cutoff_k2_level),
        deflection,
        deflection_cumulative,
        moment,
        moment_cumulative,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The basis keeping only the stations `keep`.
    fn with_stations(basis: &ModalBasis, keep: &[usize]) -> ModalBasis {
        let n = basis.mode_count();
        let rows = |table: &[f64]| -> Vec<f64> {
            keep.iter()
                .flat_map(|&s| table[s * n..(s + 1) * n].iter().copied())
                .collect()
        };
        ModalBasis {
            stations: keep.iter().map(|&s| basis.stations[s].clone()).collect(),
            station_deflection: rows(&basis.station_deflection),
            station_moment: rows(&basis.station_moment),
            check_modes: None,
            ..basis.clone()
        }
    }

    /// Invariant of Eq. 30 (each structural point once; the sagging moment): on the 2 × 20 m
    /// paper grillage with its default stations (girder and whole-section stations at mid-span
    /// and over the support), the moment participation equals the one computed from the girder
    /// mid-span stations alone, to round-off (1e-14). Before, the section stations (sums of the
    /// girders') and the hogging stations were summed in as well.
    #[test]
    fn moment_participation_counts_each_girder_once_and_no_hogging_station() {
        use crate::fe::{discretise, MeshOptions};
        use crate::modal::{solve_modes, ModalOptions};
        let model = crate::model::presets::paper_bridge(2, 20.0);
        let fe = discretise(&model, &MeshOptions::default()).unwrap();
        let options = ModalOptions {
            mode_count: 12,
            ..ModalOptions::default()
        };
        let basis = solve_modes(&fe, &options).unwrap();
        let stations = &basis.stations;
        assert!(stations.iter().any(|s| s.over_support));
        assert!(stations.iter().any(|s| s.target == StationTarget::Section));
        let girder_sagging: Vec<usize> = (0..stations.len())
            .filter(|&s| {
                !stations[s].over_support && matches!(stations[s].target, StationTarget::Girder(_))
            })
            .collect();
        assert!(!girder_sagging.is_empty());
        let rms: Vec<f64> = (0..basis.mode_count())
            .map(|k| 1.0 / (1.0 + k as f64))
            .collect();
        let analysis = AnalysisOptions::default();
        let all = deck_participation(&basis, &rms, &analysis);
        let girders = deck_participation(&with_stations(&basis, &girder_sagging), &rms, &analysis);
        for (k, (a, b)) in all.moment.iter().zip(&girders.moment).enumerate() {
            assert!((a - b).abs() < 1e-14, "mode {}: {a} vs {b}", k + 1);
        }
        // Hand sum of Eq. 30 over the girder mid-span stations.
        let weights: Vec<f64> = (0..basis.mode_count())
            .map(|k| {
                girder_sagging
                    .iter()
                    .map(|&s| basis.station_values(s, Quantity::BendingMoment)[k].abs())
                    .sum::<f64>()
                    * rms[k]
            })
            .collect();
        let total: f64 = weights.iter().sum();
        for (k, w) in weights.iter().enumerate() {
            assert!((all.moment[k] - w / total).abs() < 1e-14, "mode {}", k + 1);
        }
    }

    #[test]
    fn convergence_mode_is_the_first_mode_after_which_the_daf_stays_in_the_band() {
        // DAF(N) = 1.10; band ±0.011. K = 3 enters the band but K = 4 leaves it; from 5 on it stays.
        let daf = [0.5, 1.0, 1.095, 1.2, 1.105, 1.099, 1.1];
        assert_eq!(convergence_mode(&daf, 0.01), Some(5));
        assert_eq!(convergence_mode(&[], 0.01), None);
    }

    #[test]
    fn indicators_against_the_modes_kept_end_at_the_full_values_and_follow_the_definition() {
        // A series that keeps moving: CM(n) is found anew at every n.
        let daf = [0.5, 1.0, 1.095, 1.2, 1.105, 1.099, 1.1];
        let cms = convergence_modes_against_modes_kept(&daf, 0.01);
        assert_eq!(cms.len(), daf.len());
        assert_eq!(*cms.last().unwrap(), convergence_mode(&daf, 0.01));
        // n = 3: DAF(3) = 1.095, band ±0.01095; DAF(2) = 1.0 is outside: CM = 3.
        assert_eq!(cms[2], Some(3));
        assert_eq!(cms[0], Some(1));
        // Participation 90/6/3/1: with two modes kept 90/96 = 0.9375 < 0.95, so K1(2) = 2;
        // with all four, K1 = 2 and K2 = 3 (the full cut-offs).
        let share = [90.0, 6.0, 3.0, 1.0];
        assert_eq!(
            cutoffs_against_modes_kept(&share, 0.95),
            [Some(1), Some(2), Some(2), Some(2)]
        );
        let k2 = cutoffs_against_modes_kept(&share, 0.99);
        assert_eq!(k2, [Some(1), Some(2), Some(3), Some(3)]);
        assert_eq!(*k2.last().unwrap(), cutoff_mode(&share, 0.99));
    }

    #[test]
    fn cutoff_is_the_first_mode_whose_cumulative_share_reaches_the_level() {
        let (share, cumulative) = normalise(vec![90.0, 6.0, 3.0, 1.0]);
        assert!((share.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert_eq!(cutoff(&cumulative, 0.95), Some(2));
        assert_eq!(cutoff(&cumulative, 0.99), Some(3));
        assert_eq!(cutoff(&cumulative, 1.0), Some(4));
    }
}
