//! Modal bending moments of a bridge known only by its mode shapes: M = EI·φ'' (sagging
//! positive, φ upwards), from the shapes' curvature at the stations, when the other program
//! gives no modal moments.
//!
//! The curvature at a node is the second derivative of the Lagrange polynomial through the 5
//! nearest nodes of its line (exact for quartics, error O(h³) on an even grid); between nodes
//! it is interpolated linearly. At an interior support the curvature's slope (the shear) jumps:
//! no stencil straddles a support, and the support's node takes the mean of its two one-sided
//! values. docs/verification.md §27 gives the accuracy measured on vbi's own modes.

use super::import::{ImportedStation, ModalImport};
use super::StationTarget;
use crate::model::station::Station;

/// Second derivative at node i of the Lagrange polynomial through the nodes `window`.
/// Hand-written: a few lines of the interpolation formula,
/// L_j''(x) = Σ_{a≠j} Σ_{b≠j,a} Π_{m≠j,a,b}(x − x_m) / Π_{m≠j}(x_j − x_m).
fn lagrange_second_derivative(
    positions: &[f64],
    values: &[f64],
    window: &[usize],
    i: usize,
) -> f64 {
    let x = positions[i];
    let mut sum = 0.0;
    for &j in window {
        let denominator: f64 = window
            .iter()
            .filter(|&&m| m != j)
            .map(|&m| positions[j] - positions[m])
            .product();
        let mut second = 0.0;
        for &a in window.iter().filter(|&&a| a != j) {
            for &b in window.iter().filter(|&&b| b != j && b != a) {
                second += window
                    .iter()
                    .filter(|&&m| m != j && m != a && m != b)
                    .map(|&m| x - positions[m])
                    .product::<f64>();
            }
        }
        sum += values[j] * second / denominator;
    }
    sum
}

/// The curvature at node i from the 5 (or fewer) nearest nodes within `segment`.
fn segment_curvature(positions: &[f64], values: &[f64], segment: (usize, usize), i: usize) -> f64 {
    let (first, last) = segment;
    let n = last - first + 1;
    let width = n.min(5);
    if width < 3 {
        return f64::NAN;
    }
    let start = (first + i.saturating_sub(first).saturating_sub(width / 2)).min(last + 1 - width);
    let window: Vec<usize> = (start..start + width).collect();
    lagrange_second_derivative(positions, values, &window, i)
}

/// Second derivative at each node of the Lagrange polynomial through the 5 nearest nodes of its
/// segment: `breaks` (node indices, such as interior supports, where the third derivative may
/// jump) split the line, no stencil straddles one, and a break node takes the mean of its two
/// one-sided values. Exact for quartics on each segment; 0 on a line of fewer than 3 nodes.
pub fn node_curvatures(positions: &[f64], values: &[f64], breaks: &[usize]) -> Vec<f64> {
    let n = positions.len();
    if n < 3 {
        return vec![0.0; n];
    }
    let mut bounds: Vec<usize> = vec![0];
    bounds.extend(breaks.iter().copied().filter(|&b| b > 0 && b + 1 < n));
    bounds.push(n - 1);
    bounds.dedup();
    let segments: Vec<(usize, usize)> = bounds.windows(2).map(|w| (w[0], w[1])).collect();
    (0..n)
        .map(|i| {
            let sides: Vec<f64> = segments
                .iter()
                .filter(|&&(a, b)| a <= i && i <= b)
                .map(|&segment| segment_curvature(positions, values, segment, i))
                .filter(|c| c.is_finite())
                .collect();
            if sides.is_empty() {
                // Segments of fewer than 3 nodes: the whole line's stencil.
                segment_curvature(positions, values, (0, n - 1), i)
            } else {
                sides.iter().sum::<f64>() / sides.len() as f64
            }
        })
        .collect()
}

/// The curvature of `values` at `x` on `positions` (linear between the nodes' curvatures).
fn curvature_at(positions: &[f64], curvatures: &[f64], x: f64) -> f64 {
    let i = positions.partition_point(|&p| p <= x);
    match i {
        0 => curvatures[0],
        i if i >= positions.len() => curvatures[positions.len() - 1],
        i => {
            let (x0, x1) = (positions[i - 1], positions[i]);
            let t = (x - x0) / (x1 - x0);
            curvatures[i - 1] * (1.0 - t) + curvatures[i] * t
        }
    }
}

/// The default stations of a basis known by its shapes (the mid-span of every span and every
/// interior support; on each line, `g<k>` with k from 1 at the lowest y, and the whole section
/// when there are several lines), with modal moments EI·φ'' from the shapes' curvature:
/// `flexural_rigidity[l]` [N·m²] of line l in ascending y; the section's moment is the lines'
/// sum. `support_positions` [m] from 0 to the deck's length.
pub fn curvature_stations(
    data: &ModalImport,
    flexural_rigidity: &[f64],
    support_positions: &[f64],
) -> Vec<ImportedStation> {
    let count = data.frequencies_hz.len();
    let mut lines: Vec<_> = data.lines.iter().collect();
    lines.sort_by(|a, b| a.lateral_position.total_cmp(&b.lateral_position));
    // The interior supports' nodes: the shear jumps there.
    let breaks = |line: &&crate::model::imported_modes::ImportedLine| -> Vec<usize> {
        let xs = &line.node_positions;
        let tolerance = 1e-9 * xs[xs.len() - 1].abs().max(1.0);
        support_positions
            .iter()
            .filter_map(|&x| xs.iter().position(|&p| (p - x).abs() <= tolerance))
            .collect()
    };
    // curvatures[l][k][node]
    let curvatures: Vec<Vec<Vec<f64>>> = lines
        .iter()
        .map(|line| {
            (0..count)
                .map(|k| {
                    let values: Vec<f64> = (0..line.node_positions.len())
                        .map(|j| line.deflection[j * count + k])
                        .collect();
                    node_curvatures(&line.node_positions, &values, &breaks(line))
                })
                .collect()
        })
        .collect();
    let moment = |l: usize, k: usize, x: f64| {
        flexural_rigidity[l] * curvature_at(&lines[l].node_positions, &curvatures[l][k], x)
    };
    let mut places: Vec<(String, f64, bool)> = support_positions
        .windows(2)
        .enumerate()
        .map(|(s, w)| (format!("span{}_mid", s + 1), (w[0] + w[1]) / 2.0, false))
        .collect();
    let interior = support_positions.len().saturating_sub(1);
    for (j, &x) in support_positions.iter().enumerate().take(interior).skip(1) {
        places.push((format!("support{}", j + 1), x, true));
    }
    let mut stations = Vec::new();
    for (name, x, over_support) in places {
        let mut targets: Vec<StationTarget> = Vec::new();
        if lines.len() > 1 {
            targets.extend((0..lines.len()).map(StationTarget::Girder));
        }
        targets.push(StationTarget::Section);
        for target in targets {
            let (suffix, moments): (String, Vec<f64>) = match target {
                StationTarget::Girder(l) => (
                    format!("g{}", l + 1),
                    (0..count).map(|k| moment(l, k, x)).collect(),
                ),
                StationTarget::Section => (
                    "section".into(),
                    (0..count)
                        .map(|k| (0..lines.len()).map(|l| moment(l, k, x)).sum())
                        .collect(),
                ),
            };
            stations.push(ImportedStation {
                station: Station {
                    name: format!("{name}_{suffix}"),
                    position: x,
                    target,
                    over_support,
                    support: false,
                },
                moments,
            });
        }
    }
    stations
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_curvatures_are_exact_for_a_quartic_on_an_uneven_grid() {
        let xs = [0.0, 0.7, 1.5, 2.0, 3.1, 4.0, 4.4];
        let f = |x: f64| 0.1 * x.powi(4) - x.powi(3) + 2.0 * x - 1.0;
        let ddf = |x: f64| 1.2 * x * x - 6.0 * x;
        let values: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
        for (x, c) in xs.iter().zip(node_curvatures(&xs, &values, &[])) {
            // Exact in exact arithmetic; round-off of products of O(10) numbers.
            assert!((c - ddf(*x)).abs() < 1e-10, "{x}: {c} vs {}", ddf(*x));
        }
    }
}
