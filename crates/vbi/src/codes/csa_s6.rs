//! Canada, CSA S6 (Canadian Highway Bridge Design Code) §3.8.4.5.3: the dynamic load allowance
//! by the number of axles of the CL-W truck that load the component.

use super::{factor, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode, Place};
use crate::fe::Quantity;

/// CSA S6 in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::CsaS6,
    name: "CSA S6",
    short_label: |_| "CSA S6",
    factors,
};

/// The CL-W truck's axle spacings from axle 1 to axle 5 [m] (CSA S6 §3.8.3.2, Fig. 3.8.3.2).
pub const CL_W_AXLE_SPACINGS: [f64; 4] = [3.6, 1.2, 6.6, 6.6];

/// CSA S6 §3.8.4.5.3: the dynamic load allowance of the CL-W truck by the number of its axles
/// that load the component: 0.40 for one axle, 0.30 for two, 0.25 for three or more (deck
/// joints: 0.50). (The clause gives 0.30 also to axles 1, 2 and 3 together, the group of the
/// shortest three-axle length: [`csa_s6_allowance_of_loaded_length`].)
pub fn csa_s6_dynamic_load_allowance(axle_count: usize) -> f64 {
    match axle_count {
        0 | 1 => 0.40,
        2 => 0.30,
        _ => 0.25,
    }
}

/// The CL-W axles that a loaded length L [m] holds, at most: the largest group of consecutive
/// axles whose extent (the sum of its spacings, [`CL_W_AXLE_SPACINGS`]) is at most L, and
/// whether every group of that many axles that fits is axles 1, 2 and 3.
pub fn cl_w_axles_within(loaded_length: f64) -> (usize, bool) {
    let mut best = (1usize, false);
    for count in 2..=5 {
        let fitting: Vec<usize> = (0..=5 - count)
            .filter(|&first| {
                let extent: f64 = CL_W_AXLE_SPACINGS[first..first + count - 1].iter().sum();
                extent <= loaded_length + 1e-9
            })
            .collect();
        if fitting.is_empty() {
            break;
        }
        best = (count, count == 3 && fitting == [0]);
    }
    best
}

/// CSA S6 §3.8.4.5.3 read on a loaded length L [m]: (a) 0.40 where one axle of the CL-W truck
/// is used, (c) 0.30 where two axles, or axles 1, 2 and 3, are used, (d) 0.25 where three axles
/// other than 1, 2 and 3, or more than three, are used; the axles used are the most that L
/// holds ([`cl_w_axles_within`]). Issue 46: the allowance is of the CL-W design truck, not of
/// the simulated vehicle (a moving force printed 0.40 where the code gives 0.25).
pub fn csa_s6_allowance_of_loaded_length(loaded_length: f64) -> (usize, f64) {
    let (count, axles_1_to_3) = cl_w_axles_within(loaded_length);
    let allowance = if axles_1_to_3 {
        0.30
    } else {
        csa_s6_dynamic_load_allowance(count)
    };
    (count, allowance)
}

/// The loaded length of a station [m]: its span; over an interior support the two spans beside
/// it (a hogging moment's and a reaction's influence lines load both), at an end support the
/// one span.
fn loaded_length(place: Place) -> f64 {
    match place {
        Place::Span { start, end } => end - start,
        Place::Support { left, right } => left + right,
    }
}

/// CSA S6: the allowance of the CL-W axles that the station's loaded length holds.
fn factors(
    _inputs: &CodeInputs,
    location: CodeLocation,
    _quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    let length = loaded_length(location.place);
    if length <= 0.0 {
        return Vec::new();
    }
    let (count, allowance) = csa_s6_allowance_of_loaded_length(length);
    vec![factor(
        DesignCode::CsaS6,
        "cl_w_axles",
        "§3.8.4.5.3",
        format!("{count} CL-W axle(s) within the loaded length {length:.2} m"),
        allowance,
    )]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CL-W axles (spacings 3.6, 1.2, 6.6, 6.6 m) within a loaded length, counted by hand:
    /// one below 1.2 m; two (axles 2–3) from 1.2 m; axles 1–3 (4.8 m) alone from 4.8 m: 0.30;
    /// axles 2–4 (7.8 m) from 7.8 m: 0.25; four from 11.4 m (axles 1–4), five from 18 m.
    #[test]
    fn cl_w_axles_within_loaded_lengths_and_the_clause_s_allowances() {
        let cases = [
            (1.0, 1, 0.40),
            (1.2, 2, 0.30),
            (4.0, 2, 0.30),
            (4.8, 3, 0.30),
            (7.0, 3, 0.30),
            (7.8, 3, 0.25),
            (11.4, 4, 0.25),
            (17.9, 4, 0.25),
            (18.0, 5, 0.25),
            (30.0, 5, 0.25),
        ];
        for (length, count, allowance) in cases {
            assert_eq!(
                csa_s6_allowance_of_loaded_length(length),
                (count, allowance),
                "L = {length}"
            );
        }
    }
}
