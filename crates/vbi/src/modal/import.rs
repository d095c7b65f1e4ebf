//! Modal bases imported from other programs (ANSYS, Midas, OpenSees): frequencies, damping,
//! mass-normalised vertical mode shapes at deck nodes, and modal bending moments at stations.
//!
//! The imported basis fills the same [`ModalBasis`] as [`solve_modes`](super::solve_modes), so
//! later stages cannot tell the two apart. What another program does not give is derived:
//! - slopes dw/dx at the deck nodes, by [`node_slopes`] (5-point Lagrange differentiation);
//! - station deflections, by interpolating the deck shapes at the station (Hermite along the
//!   girder line, mean of the lines for a whole-section station);
//! - mode kinds, when not given, from the deck shape alone ([`kind_from_deck_shape`]).

use thiserror::Error;

use crate::deck::{DeckField, DeckGeometry, DeckLine};

use super::{deck_vertical_shares, ModalBasis, Mode, ModeKind, StationTarget};

// The imported data are part of the bridge's description (a `BridgeModel::ImportedModes` holds
// them); re-exported here, where the basis is built from them.
pub use crate::model::imported_modes::{ImportedLine, ImportedStation, ModalImport};

/// Errors of an imported modal basis.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ImportError {
    /// No mode given.
    #[error("no mode given")]
    NoModes,
    /// A frequency that is not positive and finite.
    #[error("mode {mode}: frequency {value} Hz is not a positive number")]
    BadFrequency {
        /// 1-based mode number.
        mode: usize,
        /// The frequency [Hz].
        value: f64,
    },
    /// Frequencies not in ascending order.
    #[error("mode {mode}: frequency {value} Hz is below mode {previous_mode}'s {previous} Hz (modes must be in ascending frequency)")]
    NotAscending {
        /// 1-based mode number.
        mode: usize,
        /// Its frequency [Hz].
        value: f64,
        /// The previous mode's number.
        previous_mode: usize,
        /// The previous frequency [Hz].
        previous: f64,
    },
    /// A damping ratio outside [0, 1).
    #[error("mode {mode}: damping ratio {value} is outside [0, 1)")]
    BadDamping {
        /// 1-based mode number.
        mode: usize,
        /// The ratio.
        value: f64,
    },
    /// A list whose length does not match the number of modes.
    #[error("{what}: {found} values for {expected}")]
    WrongLength {
        /// What the list is.
        what: String,
        /// Expected length.
        expected: usize,
        /// Length found.
        found: usize,
    },
    /// No deck line given.
    #[error("no deck line given")]
    NoLines,
    /// A line with fewer than two nodes.
    #[error("deck line at y = {lateral_position} m has {nodes} node(s); at least 2 are needed")]
    LineTooShort {
        /// Lateral position of the line [m].
        lateral_position: f64,
        /// Number of nodes.
        nodes: usize,
    },
    /// Two lines at the same lateral position.
    #[error("two deck lines at the same lateral position y = {lateral_position} m")]
    DuplicateLine {
        /// Lateral position [m].
        lateral_position: f64,
    },
    /// Node positions not strictly ascending or negative.
    #[error("deck line at y = {lateral_position} m: node position {value} m after {previous} m (positions must be ≥ 0 and strictly ascending)")]
    BadPosition {
        /// Lateral position of the line [m].
        lateral_position: f64,
        /// The previous position [m].
        previous: f64,
        /// The offending position [m].
        value: f64,
    },
    /// A non-finite number.
    #[error("{what} is not a finite number ({value})")]
    NonFinite {
        /// Where it is.
        what: String,
        /// The value.
        value: f64,
    },
    /// A station's girder index beyond the lines.
    #[error("station `{station}` reads girder {girder} but the deck has {lines} lines")]
    StationGirder {
        /// Station name.
        station: String,
        /// Girder index (0-based).
        girder: usize,
        /// Number of lines.
        lines: usize,
    },
    /// Influence lines that do not fit the stations and deck lines.
    #[error("influence lines: {message}")]
    InfluenceLines {
        /// What does not fit.
        message: String,
    },
    /// A station off the deck.
    #[error("station `{station}` at x = {position} m is off the deck [0, {length}] m")]
    StationOffDeck {
        /// Station name.
        station: String,
        /// Its position [m].
        position: f64,
        /// Deck length [m].
        length: f64,
    },
}

/// Builds a [`ModalBasis`] from imported data; see the module documentation for the derived
/// parts. Modes keep their order; residuals are 0 and `dof_count` is 0 (unknown).
pub fn build_imported_basis(data: &ModalImport) -> Result<ModalBasis, ImportError> {
    check_frequencies(&data.frequencies_hz)?;
    let count = data.frequencies_hz.len();
    check_mode_list_length("damping ratios", data.damping_ratios.len(), count)?;
    check_mode_list_length("mode kinds", data.kinds.len(), count)?;
    let dampings = damping_ratios(data)?;
    let lines = sorted_checked_lines(data, count)?;
    let length = data.deck_length();
    if !(length.is_finite() && length > 0.0) {
        return Err(ImportError::NonFinite {
            what: "the deck length".into(),
            value: length,
        });
    }
    let deck = deck_geometry(&lines, length);
    let (deck_deflection, deck_slope) = deck_shapes(&lines, &deck, count);
    let (stations, station_deflection, station_moment) =
        imported_stations(data, &deck, &deck_deflection, &deck_slope, length)?;
    let modes = imported_modes(data, &deck, &deck_deflection, &deck_slope, &dampings);
    Ok(ModalBasis {
        modes,
        deck,
        deck_deflection,
        deck_slope,
        stations,
        station_deflection,
        station_moment,
        station_force: Vec::new(),
        dof_count: 0,
        check_modes: None,
    })
}

/// Checks the frequencies: at least one, each positive and finite, in ascending order.
fn check_frequencies(frequencies_hz: &[f64]) -> Result<(), ImportError> {
    if frequencies_hz.is_empty() {
        return Err(ImportError::NoModes);
    }
    for (i, &f) in frequencies_hz.iter().enumerate() {
        if !(f.is_finite() && f > 0.0) {
            return Err(ImportError::BadFrequency {
                mode: i + 1,
                value: f,
            });
        }
        if i > 0 && f < frequencies_hz[i - 1] {
            return Err(ImportError::NotAscending {
                mode: i + 1,
                value: f,
                previous_mode: i,
                previous: frequencies_hz[i - 1],
            });
        }
    }
    Ok(())
}

/// Checks that a per-mode list (`what`) has one entry per mode.
fn check_mode_list_length(what: &str, found: usize, count: usize) -> Result<(), ImportError> {
    if found == count {
        Ok(())
    } else {
        Err(ImportError::WrongLength {
            what: what.to_string(),
            expected: count,
            found,
        })
    }
}

/// Every mode's damping ratio, the given one or the default, each checked to lie in [0, 1).
fn damping_ratios(data: &ModalImport) -> Result<Vec<f64>, ImportError> {
    let mut dampings = Vec::with_capacity(data.frequencies_hz.len());
    for (i, d) in data.damping_ratios.iter().enumerate() {
        let value = d.unwrap_or(data.default_damping_ratio);
        if !(value.is_finite() && (0.0..1.0).contains(&value)) {
            return Err(ImportError::BadDamping { mode: i + 1, value });
        }
        dampings.push(value);
    }
    Ok(dampings)
}

/// The deck lines sorted by lateral position, each checked: a finite position distinct from
/// its neighbour's, at least two nodes at finite, non-negative, strictly ascending positions,
/// and one finite mode-shape value per node and mode (`count` modes).
fn sorted_checked_lines(
    data: &ModalImport,
    count: usize,
) -> Result<Vec<&ImportedLine>, ImportError> {
    if data.lines.is_empty() {
        return Err(ImportError::NoLines);
    }
    let mut lines: Vec<&ImportedLine> = data.lines.iter().collect();
    lines.sort_by(|a, b| a.lateral_position.total_cmp(&b.lateral_position));
    for (l, line) in lines.iter().enumerate() {
        let y = line.lateral_position;
        if !y.is_finite() {
            return Err(ImportError::NonFinite {
                what: "a line's lateral position".into(),
                value: y,
            });
        }
        if l > 0 && lines[l - 1].lateral_position == y {
            return Err(ImportError::DuplicateLine {
                lateral_position: y,
            });
        }
        if line.node_positions.len() < 2 {
            return Err(ImportError::LineTooShort {
                lateral_position: y,
                nodes: line.node_positions.len(),
            });
        }
        let mut previous = f64::NEG_INFINITY;
        for &x in &line.node_positions {
            if !(x.is_finite() && x >= 0.0 && x > previous) {
                return Err(ImportError::BadPosition {
                    lateral_position: y,
                    previous,
                    value: x,
                });
            }
            previous = x;
        }
        if line.deflection.len() != line.node_positions.len() * count {
            return Err(ImportError::WrongLength {
                what: format!("mode-shape values of the line at y = {y} m"),
                expected: line.node_positions.len() * count,
                found: line.deflection.len(),
            });
        }
        if let Some(&bad) = line.deflection.iter().find(|v| !v.is_finite()) {
            return Err(ImportError::NonFinite {
                what: format!("a mode-shape value of the line at y = {y} m"),
                value: bad,
            });
        }
    }
    Ok(lines)
}

/// The deck geometry of the sorted lines, numbered line by line.
fn deck_geometry(lines: &[&ImportedLine], length: f64) -> DeckGeometry {
    let mut deck_lines = Vec::with_capacity(lines.len());
    let mut first_node = 0;
    for line in lines {
        deck_lines.push(DeckLine {
            lateral_position: line.lateral_position,
            node_positions: line.node_positions.clone(),
            first_node,
        });
        first_node += line.node_positions.len();
    }
    DeckGeometry {
        lines: deck_lines,
        length,
    }
}

/// The node-major deck deflections (as given) and slopes dw/dx ([`node_slopes`] of each
/// mode's shape along each line), `count` values per node.
fn deck_shapes(lines: &[&ImportedLine], deck: &DeckGeometry, count: usize) -> (Vec<f64>, Vec<f64>) {
    let nodes = deck.node_count();
    let mut deck_deflection = Vec::with_capacity(nodes * count);
    let mut deck_slope = vec![0.0; nodes * count];
    for (line, geometry) in lines.iter().zip(&deck.lines) {
        deck_deflection.extend_from_slice(&line.deflection);
        let xs = &line.node_positions;
        let mut values = vec![0.0; xs.len()];
        for k in 0..count {
            for (i, v) in values.iter_mut().enumerate() {
                *v = line.deflection[i * count + k];
            }
            for (i, s) in node_slopes(xs, &values).into_iter().enumerate() {
                deck_slope[(geometry.first_node + i) * count + k] = s;
            }
        }
    }
    (deck_deflection, deck_slope)
}

/// The stations, their modal deflections and their modal moments (station-major).
type StationTables = (Vec<super::Station>, Vec<f64>, Vec<f64>);

/// The stations with their modal deflections and moments, station-major: each station checked
/// (one finite moment per mode, on the deck, an existing girder), its deflection interpolated
/// on the lines it reads and averaged over them, w = Σ_l w_l / n_lines.
fn imported_stations(
    data: &ModalImport,
    deck: &DeckGeometry,
    deck_deflection: &[f64],
    deck_slope: &[f64],
    length: f64,
) -> Result<StationTables, ImportError> {
    let count = data.frequencies_hz.len();
    let mut stations = Vec::with_capacity(data.stations.len());
    let mut station_deflection = Vec::with_capacity(data.stations.len() * count);
    let mut station_moment = Vec::with_capacity(data.stations.len() * count);
    for imported in &data.stations {
        let read_lines = check_station(imported, deck, count, length)?;
        let station = &imported.station;
        let mut values = vec![0.0; count];
        let mut slopes = vec![0.0; count];
        let mut mean = vec![0.0; count];
        for &l in &read_lines {
            deck.stencil(station.position, deck.lines[l].lateral_position)
                .evaluate_many(deck_deflection, deck_slope, count, &mut values, &mut slopes);
            for k in 0..count {
                mean[k] += values[k] / read_lines.len() as f64;
            }
        }
        stations.push(station.clone());
        station_deflection.extend_from_slice(&mean);
        station_moment.extend_from_slice(&imported.moments);
    }
    Ok((stations, station_deflection, station_moment))
}

/// Checks an imported station (one finite modal moment per mode, a position on the deck
/// [0, length], a girder the deck has) and returns the deck lines it reads.
fn check_station(
    imported: &ImportedStation,
    deck: &DeckGeometry,
    count: usize,
    length: f64,
) -> Result<Vec<usize>, ImportError> {
    let station = &imported.station;
    if imported.moments.len() != count {
        return Err(ImportError::WrongLength {
            what: format!("modal moments of station `{}`", station.name),
            expected: count,
            found: imported.moments.len(),
        });
    }
    if let Some(&bad) = imported.moments.iter().find(|v| !v.is_finite()) {
        return Err(ImportError::NonFinite {
            what: format!("a modal moment of station `{}`", station.name),
            value: bad,
        });
    }
    if !(station.position.is_finite() && (0.0..=length).contains(&station.position)) {
        return Err(ImportError::StationOffDeck {
            station: station.name.clone(),
            position: station.position,
            length,
        });
    }
    match station.target {
        StationTarget::Girder(g) if g >= deck.lines.len() => Err(ImportError::StationGirder {
            station: station.name.clone(),
            girder: g,
            lines: deck.lines.len(),
        }),
        StationTarget::Girder(g) => Ok(vec![g]),
        StationTarget::Section => Ok((0..deck.lines.len()).collect()),
    }
}

/// The modes: ω = 2π f, the damping ratio, and the kind given or, when not,
/// [`kind_from_deck_shape`] of the mode's deck shape; residual 0.
fn imported_modes(
    data: &ModalImport,
    deck: &DeckGeometry,
    deck_deflection: &[f64],
    deck_slope: &[f64],
    dampings: &[f64],
) -> Vec<Mode> {
    let count = data.frequencies_hz.len();
    let nodes = deck.node_count();
    let mut modes = Vec::with_capacity(count);
    for k in 0..count {
        let kind = match data.kinds[k] {
            Some(kind) => kind,
            None => {
                let field = DeckField {
                    deflection: (0..nodes).map(|n| deck_deflection[n * count + k]).collect(),
                    slope: (0..nodes).map(|n| deck_slope[n * count + k]).collect(),
                };
                kind_from_deck_shape(deck, &field)
            }
        };
        modes.push(Mode {
            circular_frequency: 2.0 * std::f64::consts::PI * data.frequencies_hz[k],
            damping_ratio: dampings[k],
            kind,
            residual: 0.0,
        });
    }
    modes
}

/// The kind of an imported mode from its deck shape alone (no mass matrix): the largest of the
/// uniform, symmetric and antisymmetric shares of [`deck_vertical_shares`](super::deck_vertical_shares)
/// (vertical bending, differential bending, torsion; a tie to the first).
pub fn kind_from_deck_shape(deck: &DeckGeometry, field: &DeckField) -> ModeKind {
    let shares = deck_vertical_shares(deck, field);
    super::solve::kind_of_largest_share(&[
        (ModeKind::VerticalBending, shares.uniform),
        (ModeKind::DifferentialBending, shares.symmetric),
        (ModeKind::Torsion, shares.antisymmetric),
    ])
}

/// Slopes dw/dx at the nodes of one line from the values there: at node i, the derivative of
/// the Lagrange polynomial through the 5 nodes nearest to it along the line (i − 2 … i + 2,
/// the window shifted inward at the line's ends; all nodes when the line has fewer than 5).
/// Exact for polynomials up to degree 4, error O(h⁴) on a smooth shape; at an interior support,
/// where the third derivative of a continuous beam's mode jumps, the error is O(h³).
///
/// With L_j the Lagrange basis of the window, w'(x_i) = Σ_j L_j'(x_i) w_j, where
/// L_i'(x_i) = Σ_{m≠i} 1/(x_i − x_m) and, for j ≠ i,
/// L_j'(x_i) = Π_{m≠i,j}(x_i − x_m) / Π_{m≠j}(x_j − x_m).
pub fn node_slopes(positions: &[f64], values: &[f64]) -> Vec<f64> {
    let n = positions.len();
    let width = n.min(5);
    let mut slopes = vec![0.0; n];
    if n < 2 {
        return slopes;
    }
    for i in 0..n {
        let start = i.saturating_sub(width / 2).min(n - width);
        let window = start..start + width;
        let xi = positions[i];
        let mut slope = 0.0;
        for j in window.clone() {
            let weight = if j == i {
                window
                    .clone()
                    .filter(|&m| m != i)
                    .map(|m| 1.0 / (xi - positions[m]))
                    .sum::<f64>()
            } else {
                let mut numerator = 1.0;
                let mut denominator = 1.0;
                for m in window.clone() {
                    if m != j {
                        denominator *= positions[j] - positions[m];
                        if m != i {
                            numerator *= xi - positions[m];
                        }
                    }
                }
                numerator / denominator
            };
            slope += weight * values[j];
        }
        slopes[i] = slope;
    }
    slopes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_slopes_are_exact_for_a_quartic_on_an_uneven_grid() {
        let xs = [0.0, 0.7, 1.5, 2.0, 3.1, 4.0, 4.4];
        let f = |x: f64| 0.1 * x.powi(4) - x.powi(3) + 2.0 * x - 1.0;
        let df = |x: f64| 0.4 * x.powi(3) - 3.0 * x * x + 2.0;
        let values: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
        let slopes = node_slopes(&xs, &values);
        for (i, &x) in xs.iter().enumerate() {
            // Tolerance: exact in exact arithmetic; round-off of products of O(10) numbers.
            assert!((slopes[i] - df(x)).abs() < 1e-10, "node {i}");
        }
        // Two nodes: the chord.
        assert_eq!(node_slopes(&[0.0, 2.0], &[1.0, 3.0]), vec![1.0, 1.0]);
    }
}
