//! China, JTG D60-2015 (General Specifications for Design of Highway Bridges and Culverts)
//! §4.3.2: the impact coefficient μ from the bridge's fundamental frequency, the frequency from
//! the formulas of the commentary to §4.3.2 or from vbi's modes.

use std::f64::consts::PI;

use super::{factor, hogging, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode};
use crate::fe::Quantity;

/// JTG D60-2015 in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::JtgD60,
    name: "JTG D60-2015",
    short_label: |provision| {
        if provision == "computed_frequency" {
            "JTG vbi"
        } else {
            "JTG code"
        }
    },
    factors,
};

/// JTG D60-2015 §4.3.2, Eq. (4.3.2): the impact coefficient μ of a highway bridge from its
/// fundamental frequency f [Hz]:
///
/// ```text
/// μ = 0.05                      f < 1.5 Hz
/// μ = 0.1767 ln f − 0.0157      1.5 Hz ≤ f ≤ 14 Hz
/// μ = 0.45                      f > 14 Hz
/// ```
///
/// (The code's branches do not quite meet: 0.0559 at 1.5 Hz and 0.4506 at 14 Hz.)
pub fn jtg_d60_impact_factor(frequency_hz: f64) -> f64 {
    if frequency_hz < 1.5 {
        0.05
    } else if frequency_hz <= 14.0 {
        0.1767 * frequency_hz.ln() - 0.0157
    } else {
        0.45
    }
}

/// Which of the code's fundamental-frequency formulas of JTG D60-2015 (commentary to §4.3.2)
/// applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JtgFrequencyFormula {
    /// A simply supported beam: f = π/(2l²) √(EI_c/m_c).
    SimplySupported,
    /// A continuous beam, for positive moments and shear forces: f₁ = 13.616/(2πl²) √(EI_c/m_c).
    ContinuousPositive,
    /// A continuous beam, for negative (hogging) moments: f₂ = 23.651/(2πl²) √(EI_c/m_c).
    ContinuousNegative,
}

impl JtgFrequencyFormula {
    /// The coefficient c of f = c/(2πl²) √(EI_c/m_c): π² for a simple span (π/(2l²) = π²/(2πl²)),
    /// 13.616 and 23.651 for a continuous beam.
    pub fn coefficient(self) -> f64 {
        match self {
            JtgFrequencyFormula::SimplySupported => PI * PI,
            JtgFrequencyFormula::ContinuousPositive => 13.616,
            JtgFrequencyFormula::ContinuousNegative => 23.651,
        }
    }
}

/// The fundamental frequency [Hz] of JTG D60-2015's commentary to §4.3.2:
/// f = c/(2πl²) √(EI_c/m_c), with c of [`JtgFrequencyFormula::coefficient`], l the span [m],
/// EI_c the flexural rigidity of the mid-span section [N·m²] and m_c its mass per length
/// [kg/m] (G/g).
pub fn jtg_d60_frequency(
    formula: JtgFrequencyFormula,
    span_length: f64,
    flexural_rigidity: f64,
    mass_per_length: f64,
) -> f64 {
    formula.coefficient() / (2.0 * PI * span_length * span_length)
        * (flexural_rigidity / mass_per_length).sqrt()
}

/// JTG D60-2015: μ from the code's frequency formula (where the model gives EI_c and m_c) and
/// from vbi's computed frequency. §4.3.2 reads μ from the structure's fundamental frequency
/// (基频), which it asks to be computed by the finite-element method; its commentary gives
/// formulas for when that is not done: a simple span f = π/(2l²)√(EI_c/m_c), a continuous beam
/// f₁ for positive effects (positive moment, shear, deflection, reactions) and f₂ for negative
/// moments over an interior support. So the formula route reads f₁ or f₂ by the effect, and the
/// FE route (vbi's modes, or a load test's measured frequencies) the fundamental frequency, the
/// first vertical-bending one, for every effect (issue 46: it read the second mode for hogging,
/// 4.68 Hz → μ = 0.257 on the paper's 3 × 30 m bridge, where the clause gives 3.65 Hz → 0.213).
/// l is the longest span: the code's formulas assume equal spans, and the longest governs the
/// fundamental frequency.
fn factors(
    inputs: &CodeInputs,
    location: CodeLocation,
    quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    let negative = hogging(location.place, quantity);
    let (formula, symbol) = match (inputs.continuous(), negative) {
        (false, _) => (JtgFrequencyFormula::SimplySupported, "f"),
        (true, false) => (JtgFrequencyFormula::ContinuousPositive, "f1"),
        (true, true) => (JtgFrequencyFormula::ContinuousNegative, "f2"),
    };
    let clause = "§4.3.2, Eq. (4.3.2)";
    let mut factors = Vec::new();
    let span = inputs.longest_span();
    if let Some(section) = inputs.section {
        let f = jtg_d60_frequency(
            formula,
            span,
            section.flexural_rigidity,
            section.mass_per_length,
        );
        factors.push(factor(
            DesignCode::JtgD60,
            "code_frequency",
            clause,
            format!(
                "{symbol} = {f:.3} Hz by the code's formula ({:.3}/(2πl²)·√(EI/m), l = {span:.2} m)",
                formula.coefficient()
            ),
            jtg_d60_impact_factor(f),
        ));
    }
    // The FE route: the fundamental frequency, for every effect.
    if let Some(&f) = inputs.bending_frequencies.first() {
        if inputs.measured_frequencies {
            factors.push(factor(
                DesignCode::JtgD60,
                "measured_frequency",
                clause,
                format!("f = {f:.3} Hz, the fundamental (first) measured frequency"),
                jtg_d60_impact_factor(f),
            ));
            return factors;
        }
        factors.push(factor(
            DesignCode::JtgD60,
            "computed_frequency",
            clause,
            format!("f = {f:.3} Hz, vbi's fundamental (first vertical bending) frequency"),
            jtg_d60_impact_factor(f),
        ));
    }
    factors
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Worked examples computed by hand from the clause (docs/verification.md §25): μ(4 Hz) =
    /// 0.1767 ln 4 − 0.0157 = 0.22926; the two constant branches; the code's own branch ends.
    #[test]
    fn jtg_d60_impact_factor_follows_eq_4_3_2() {
        assert!((jtg_d60_impact_factor(4.0) - 0.229_258_2).abs() < 1e-6);
        assert_eq!(jtg_d60_impact_factor(1.2), 0.05);
        assert_eq!(jtg_d60_impact_factor(20.0), 0.45);
        assert!((jtg_d60_impact_factor(1.5) - 0.055_946).abs() < 1e-6);
        assert!((jtg_d60_impact_factor(14.0) - 0.450_622).abs() < 1e-6);
    }

    /// The simple-span formula π/(2l²)√(EI/m) is the exact first frequency of a pinned–pinned
    /// Euler–Bernoulli beam (Clough & Penzien Eq. 18-18); the continuous-beam formulas scale it
    /// by 13.616/π² and 23.651/π².
    #[test]
    fn jtg_d60_frequency_formulas_against_the_simple_beam_closed_form() {
        let (l, ei, m): (f64, f64, f64) = (30.0, 2.0e10, 1.5e4);
        let exact = PI / (2.0 * l * l) * (ei / m).sqrt();
        let simple = jtg_d60_frequency(JtgFrequencyFormula::SimplySupported, l, ei, m);
        assert!((simple / exact - 1.0).abs() < 1e-14);
        let f1 = jtg_d60_frequency(JtgFrequencyFormula::ContinuousPositive, l, ei, m);
        let f2 = jtg_d60_frequency(JtgFrequencyFormula::ContinuousNegative, l, ei, m);
        assert!((f1 / exact - 13.616 / (PI * PI)).abs() < 1e-12);
        assert!((f2 / f1 - 23.651 / 13.616).abs() < 1e-12);
    }
}
