//! The static reference of a bridge known only by its modes: influence lines from the modal
//! flexibility of the modes given, F = Σₖ φₖ φₖᵀ / ωₖ² (mass-normalised φₖ).
//!
//! A unit downward load at deck point x gives each mode the force −φₖ(x) and, statically, the
//! coordinate qₖ = −φₖ(x)/ωₖ²; the response r at a station with modal values rₖ is
//! r(x) = −Σₖ rₖ φₖ(x)/ωₖ². With every mode of the model this is the exact influence line (the
//! paper's static reference); with the first N it is truncated: deflections converge as 1/ωₖ²
//! and are close with a few modes, moments under a concentrated load slowly (their modal series
//! converges like 1/k², the paper's Fig. 12). The runs that use it say so
//! ([`crate::solver::SolverWarning::TruncatedStaticReference`]).

use crate::deck::DeckField;
use crate::fe::influence::InfluenceLines;

use super::ModalBasis;

/// The influence lines of deflection and bending moment of every station of `basis`, from the
/// flexibility of its modes (no force lines: an imported basis has no modal forces).
pub fn flexibility_influence_lines(basis: &ModalBasis) -> InfluenceLines {
    let n = basis.mode_count();
    let nodes = basis.deck.node_count();
    let inverse_stiffness: Vec<f64> = basis
        .modes
        .iter()
        .map(|m| 1.0 / (m.circular_frequency * m.circular_frequency))
        .collect();
    let field = |station_values: &[f64]| -> DeckField {
        let weights: Vec<f64> = station_values
            .iter()
            .zip(&inverse_stiffness)
            .map(|(r, f)| -r * f)
            .collect();
        let sum = |table: &[f64], node: usize| -> f64 {
            table[node * n..(node + 1) * n]
                .iter()
                .zip(&weights)
                .map(|(phi, w)| phi * w)
                .sum()
        };
        DeckField {
            deflection: (0..nodes).map(|j| sum(&basis.deck_deflection, j)).collect(),
            slope: (0..nodes).map(|j| sum(&basis.deck_slope, j)).collect(),
        }
    };
    let stations = basis.stations.len();
    let deflection: Vec<DeckField> = (0..stations)
        .map(|s| field(&basis.station_deflection[s * n..(s + 1) * n]))
        .collect();
    let moment: Vec<DeckField> = (0..stations)
        .map(|s| field(&basis.station_moment[s * n..(s + 1) * n]))
        .collect();
    InfluenceLines {
        deck: basis.deck.clone(),
        stations: basis.stations.clone(),
        deflection,
        moment_left: moment.clone(),
        moment_right: moment,
        force_left: Vec::new(),
        force_right: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::{discretise, statics::influence_lines, MeshOptions};
    use crate::modal::{solve_modes, ModalOptions, Quantity};
    use crate::model::{BeamSection, BridgeModel, ContinuousBeam};

    /// With every mode of the FE model (39), the modal flexibility is K⁻¹: its influence lines
    /// equal those from the stiffness (Maxwell–Betti, the FE model's own reference) at the deck
    /// nodes to round-off (measured 3e-14 and 8e-15 of the peak); with the first 10, the
    /// mid-span deflection's line is within 0.1 % (measured 9.4e-4: the terms fall off as
    /// 1/ωₖ² ∝ k⁻⁴) and the moment's within 10 % (measured 5.9 %: its terms fall off as k⁻²).
    #[test]
    fn the_flexibility_of_every_mode_gives_the_stiffness_influence_lines() {
        let beam = ContinuousBeam::pinned(
            vec![20.0, 20.0],
            BeamSection {
                flexural_rigidity: 2e10,
                mass_per_length: 1e4,
            },
        );
        let model = BridgeModel::ContinuousBeam(beam);
        let options = MeshOptions {
            element_length: 2.0,
            ..MeshOptions::default()
        };
        let mut fe = discretise(&model, &options).unwrap();
        let exact = influence_lines(&fe).unwrap();
        // The modal moments as other programs report them, the element end moments k_e φ_e (vbi's
        // own add the inertia rows −ω² m_e φ_e, whose flexibility sum is −r_M M⁻¹, not zero).
        for f in &mut fe.station_functionals {
            f.moment_left_mass.clear();
            f.moment_right_mass.clear();
        }
        let all = solve_modes(
            &fe,
            &ModalOptions {
                mode_count: fe.dof_count(),
                ..ModalOptions::default()
            },
        )
        .unwrap();
        let compare = |basis: &ModalBasis, quantity: Quantity| -> f64 {
            let lines = flexibility_influence_lines(basis);
            let s = basis
                .stations
                .iter()
                .position(|st| st.name == "span1_mid_section")
                .unwrap();
            let (mut worst, mut scale) = (0.0_f64, 0.0_f64);
            // At the deck nodes (2 m apart): a station reads one modal moment per mode, the mean
            // of its two elements' end moments, which is exact for a load outside both; the
            // stiffness's two fields are exact on their own side (loads inside an element next
            // to the station differ by the elements' Hermite error, 3 % at 2 m elements).
            for k in 0..=20 {
                let x = 2.0 * k as f64;
                let a = exact.unit_load_response(s, quantity, x, 0.0);
                let b = lines.unit_load_response(s, quantity, x, 0.0);
                worst = worst.max((a - b).abs());
                scale = scale.max(a.abs());
            }
            worst / scale
        };
        let (d, m) = (
            compare(&all, Quantity::Deflection),
            compare(&all, Quantity::BendingMoment),
        );
        let first: Vec<usize> = (0..10).collect();
        let ten = all.select_modes(&first);
        let (d10, m10) = (
            compare(&ten, Quantity::Deflection),
            compare(&ten, Quantity::BendingMoment),
        );
        assert!(d < 1e-9);
        assert!(m < 1e-9);
        assert!(d10 < 1e-3);
        let moment_error = m10;
        assert!(moment_error > 1e-3 && moment_error < 0.1, "{moment_error}");
    }
}
