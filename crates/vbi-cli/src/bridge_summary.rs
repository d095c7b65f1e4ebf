//! What `vbi modes` prints and draws of the bridge before its modes: each girder's section
//! properties, the total mass, the mesh, and a plan of members, bearings, stations (and, from
//! `vbi run`, the wheel paths).

use std::io::Write;
use std::path::Path;

use anyhow::Result;
use serde::Serialize;

use vbi::fe::{deck_plan, DeckPlan, FeError, MemberKind, MeshOptions, Station, StationTarget};
use vbi::model::{BridgeModel, GirderShape};

use crate::plot::{write_chart, Chart, Series, SeriesStyle};

/// One girder line's section, as printed.
#[derive(Debug, Serialize)]
pub struct GirderRow {
    /// Girder number, 1 at the right edge (y most negative).
    pub girder: usize,
    /// Lateral position y [m].
    pub y_m: f64,
    /// Shape name (`box`, `t_beam`, `i_girder`, `voided_slab`, `properties`).
    pub shape: &'static str,
    /// Area A [m²].
    pub area_m2: f64,
    /// I_y [m⁴] (vertical bending).
    pub second_moment_y_m4: f64,
    /// I_z [m⁴] (lateral bending).
    pub second_moment_z_m4: f64,
    /// Torsion constant J [m⁴].
    pub torsion_constant_m4: f64,
    /// Centroid above the soffit [m].
    pub centroid_height_m: f64,
    /// Mass per length, structure and pavement [kg/m] (barriers apart).
    pub mass_per_length_kg_per_m: f64,
}

/// The model's summary in `vbi modes`.
#[derive(Debug, Serialize)]
pub struct BridgeSummary {
    /// Number of spans and their total length [m].
    pub span_count: usize,
    /// Total length along the girders [m].
    pub length_m: f64,
    /// The deck's extent along x [m] (longer than `length_m` on a skewed grillage).
    pub deck_length_m: f64,
    /// Skew angle of the support lines [°] (grillages only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub skew_angle_deg: Option<f64>,
    /// Total mass of the model [kg].
    pub total_mass_kg: f64,
    /// Mesh nodes.
    pub node_count: usize,
    /// Girder (or beam) elements.
    pub girder_element_count: usize,
    /// Slab strip and diaphragm elements.
    pub transverse_element_count: usize,
    /// Longest girder element [m].
    pub longest_girder_element_m: f64,
    /// Deck width [m] (grillages only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub deck_width_m: Option<f64>,
    /// Each girder's section (grillages only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub girders: Vec<GirderRow>,
}

/// The name of a girder shape.
fn shape_name(shape: &GirderShape) -> &'static str {
    match shape {
        GirderShape::Box(_) => "box",
        GirderShape::TBeam(_) => "t_beam",
        GirderShape::IGirder(_) => "i_girder",
        GirderShape::VoidedSlab(_) => "voided_slab",
        GirderShape::Properties(_) => "properties",
    }
}

/// The summary and the plan of a continuous beam or a grillage (None for imported models).
pub fn summarise(model: &BridgeModel) -> Result<Option<(BridgeSummary, DeckPlan)>, FeError> {
    if !matches!(
        model,
        BridgeModel::ContinuousBeam(_) | BridgeModel::Grillage(_)
    ) {
        return Ok(None);
    }
    let plan = deck_plan(model, &MeshOptions::default())?;
    let mut girders = Vec::new();
    if let BridgeModel::Grillage(g) = model {
        let positions = g.girder_positions();
        for (i, &y) in positions.iter().enumerate() {
            let s = g.girder_section(i)?;
            girders.push(GirderRow {
                girder: i + 1,
                y_m: y,
                shape: shape_name(g.girder_shape(i)),
                area_m2: s.area,
                second_moment_y_m4: s.second_moment_y,
                second_moment_z_m4: s.second_moment_z,
                torsion_constant_m4: s.torsion_constant,
                centroid_height_m: s.centroid_height,
                mass_per_length_kg_per_m: g.material.density * s.area + g.added_mass_per_length(i),
            });
        }
    }
    let summary = BridgeSummary {
        span_count: model.span_lengths().len(),
        length_m: model.length(),
        deck_length_m: model.deck_length(),
        skew_angle_deg: match model {
            BridgeModel::Grillage(g) => Some(g.skew_angle.to_degrees()),
            _ => None,
        },
        total_mass_kg: plan.total_mass,
        node_count: plan.node_count,
        girder_element_count: plan.girder_element_count,
        transverse_element_count: plan.transverse_element_count,
        longest_girder_element_m: plan.longest_girder_element,
        deck_width_m: match model {
            BridgeModel::Grillage(g) => Some(g.deck_width),
            _ => None,
        },
        girders,
    };
    Ok(Some((summary, plan)))
}

/// Prints the summary as lines of text.
pub fn print(out: &mut impl Write, summary: &BridgeSummary) -> std::io::Result<()> {
    writeln!(
        out,
        "model: {} span(s), {:.3} m{}; total mass {:.1} t; mesh of {} nodes, {} girder elements \
         (longest {:.3} m) and {} transverse elements",
        summary.span_count,
        summary.length_m,
        match summary.skew_angle_deg {
            Some(skew) if skew != 0.0 => format!(
                " along the girders, skewed {skew:.1}° (deck x from 0 to {:.3} m)",
                summary.deck_length_m
            ),
            _ => String::new(),
        },
        summary.total_mass_kg / 1000.0,
        summary.node_count,
        summary.girder_element_count,
        summary.longest_girder_element_m,
        summary.transverse_element_count
    )?;
    if summary.girders.is_empty() {
        return Ok(());
    }
    writeln!(
        out,
        "{:>6} {:>8}  {:<11} {:>9} {:>10} {:>10} {:>10} {:>12} {:>12}",
        "girder",
        "y [m]",
        "shape",
        "A [m²]",
        "I_y [m⁴]",
        "I_z [m⁴]",
        "J [m⁴]",
        "centroid [m]",
        "mass [kg/m]"
    )?;
    for g in &summary.girders {
        writeln!(
            out,
            "{:>6} {:>8.3}  {:<11} {:>9.4} {:>10.4} {:>10.4} {:>10.4} {:>12.3} {:>12.1}",
            g.girder,
            g.y_m,
            g.shape,
            g.area_m2,
            g.second_moment_y_m4,
            g.second_moment_z_m4,
            g.torsion_constant_m4,
            g.centroid_height_m,
            g.mass_per_length_kg_per_m
        )?;
    }
    Ok(())
}

/// Draws the plan (`plan.png`, `plan.svg` in `dir`): girder lines, slab strips, diaphragms,
/// bearings, the stations, and `wheel_paths` (lateral positions y [m]) if any.
pub fn write_plan(
    dir: &Path,
    summary: &BridgeSummary,
    plan: &DeckPlan,
    stations: &[Station],
    line_positions: &[f64],
    wheel_paths: &[f64],
) -> Result<()> {
    let (length, deck_length) = (summary.length_m, summary.deck_length_m);
    // The deck edges start where the girders' first support line, extended, meets them.
    let tan = summary.skew_angle_deg.unwrap_or(0.0).to_radians().tan();
    let first_girder = plan.members.iter().find(|m| m.kind == MemberKind::Girder);
    let edge_start = |y: f64| match first_girder {
        Some(m) => m.start[0] + (y - m.start[1]) * tan,
        None => 0.0,
    };
    let segments = |kind: MemberKind| -> Vec<(f64, f64)> {
        plan.members
            .iter()
            .filter(|m| m.kind == kind)
            .flat_map(|m| [(m.start[0], m.start[1]), (m.end[0], m.end[1])])
            .collect()
    };
    let edges: Vec<(f64, f64)> = summary
        .deck_width_m
        .map(|w| {
            let (right, left) = (edge_start(-w / 2.0), edge_start(w / 2.0));
            vec![
                (right, -w / 2.0),
                (right + length, -w / 2.0),
                (left, w / 2.0),
                (left + length, w / 2.0),
            ]
        })
        .unwrap_or_default();
    let mut series = vec![
        Series {
            label: "slab strips".into(),
            points: segments(MemberKind::SlabStrip),
            style: SeriesStyle::ThinSegments,
        },
        Series {
            label: "deck edges".into(),
            points: edges,
            style: SeriesStyle::Segments,
        },
        Series {
            label: "girders".into(),
            points: segments(MemberKind::Girder),
            style: SeriesStyle::Segments,
        },
        Series {
            label: "diaphragms".into(),
            points: segments(MemberKind::Diaphragm),
            style: SeriesStyle::Segments,
        },
        Series {
            label: "bearings".into(),
            points: plan.bearings.iter().map(|b| (b[0], b[1])).collect(),
            style: SeriesStyle::Points,
        },
    ];
    let station_points: Vec<(f64, f64)> = stations
        .iter()
        .flat_map(|s| match s.target {
            StationTarget::Girder(g) => {
                vec![(s.position, line_positions.get(g).copied().unwrap_or(0.0))]
            }
            StationTarget::Section => line_positions.iter().map(|&y| (s.position, y)).collect(),
        })
        .collect();
    series.push(Series {
        label: "stations".into(),
        points: station_points,
        style: SeriesStyle::Points,
    });
    series.push(Series {
        label: "wheel paths".into(),
        points: wheel_paths
            .iter()
            .flat_map(|&y| [(0.0, y), (deck_length, y)])
            .collect(),
        style: SeriesStyle::Segments,
    });
    series.retain(|s| !s.points.is_empty());
    let chart = Chart {
        title: "plan of the model".into(),
        x_label: "x along the bridge [m]".into(),
        y_label: "y lateral, to the left [m]".into(),
        series,
        ..Chart::default()
    };
    write_chart(&chart, &dir.join("plan"))?;
    Ok(())
}

/// The plan of a run's bridge with its vehicles' wheel paths, if the bridge is vbi's own.
pub fn write_run_plan(
    dir: &Path,
    bridge: &vbi::crossing::PreparedBridge,
    crossing: &vbi::solver::Crossing,
) -> Result<()> {
    let Some((summary, plan)) = summarise(&bridge.spec.model)? else {
        return Ok(());
    };
    let mut paths: Vec<f64> = crossing
        .vehicles
        .iter()
        .flat_map(|run| {
            let sign = match run.direction {
                vbi::solver::TravelDirection::Forward => 1.0,
                vbi::solver::TravelDirection::Backward => -1.0,
            };
            run.vehicle
                .contacts
                .iter()
                .map(move |c| run.lateral_position + sign * c.lateral_offset)
        })
        .collect();
    paths.sort_by(f64::total_cmp);
    paths.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    let lines: Vec<f64> = bridge
        .basis
        .deck
        .lines
        .iter()
        .map(|l| l.lateral_position)
        .collect();
    write_plan(dir, &summary, &plan, &bridge.basis.stations, &lines, &paths)
}
