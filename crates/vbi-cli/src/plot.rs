//! Figures as PNG and SVG, drawn by plotters with an embedded DejaVu Sans font (ab_glyph), so no
//! system font library is needed.

use std::path::{Path, PathBuf};
use std::sync::Once;

use anyhow::{anyhow, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SeriesStyle {
    /// A polyline.
    Line,
    /// Markers only.
    Points,
    /// Vertical bars centred on each x, of width 0.8 × the smallest x gap.
    Bars,
    /// A dashed-looking thin line (drawn lighter).
    Thin,
    /// Separate straight segments, one per pair of points (p₀p₁, p₂p₃, …).
    Segments,
    /// Separate segments, drawn thin and lighter.
    ThinSegments,
}

/// One data series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text; empty for none.
    pub label: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: SeriesStyle,
}

impl Series {
    /// A line series.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            label: label.into(),
            points,
            style: SeriesStyle::Line,
        }
    }
}

/// One chart: axes, labels and series.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Title above the plot area.
    pub title: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// Series drawn in order.
    pub series: Vec<Series>,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Names of categories at x = 0, 1, …, drawn as the x axis's tick labels instead of numbers
    /// (for a bar chart of named items); empty for a numeric x axis.
    pub x_categories: Vec<String>,
}

const FONT: &str = "sans-serif";

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is embedded: figures render identically on any machine.
        let _ = plotters::style::register_font(
            FONT,
            plotters::style::FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// Writes `stem.png` and `stem.svg` holding the charts on a grid of `columns` columns, each
/// whole or not at all: drawn under a hidden temporary name (`.stem.partial.png`, whose
/// extension still tells plotters the format) and renamed into place, so that a run killed while
/// drawing, or a full disk, never leaves a torn figure under its final name. Returns the two
/// paths.
pub fn write_charts(charts: &[Chart], columns: usize, stem: &Path) -> Result<[PathBuf; 2]> {
    register_font();
    let columns = columns.max(1);
    let rows = charts.len().div_ceil(columns).max(1);
    let size = (640 * columns as u32, 440 * rows as u32);
    let png = stem.with_extension("png");
    let svg = stem.with_extension("svg");
    let partial = |extension: &str| {
        let name = stem
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        stem.with_file_name(format!(".{name}.partial.{extension}"))
    };
    let (png_partial, svg_partial) = (partial("png"), partial("svg"));
    let drawn = (|| -> Result<()> {
        {
            let root = BitMapBackend::new(&png_partial, size).into_drawing_area();
            draw_grid(&root, charts, rows, columns)?;
            root.present()
                .map_err(|e| anyhow!("{e}"))
                .with_context(|| format!("writing {}", png.display()))?;
        }
        let root = SVGBackend::new(&svg_partial, size).into_drawing_area();
        draw_grid(&root, charts, rows, columns)?;
        root.present()
            .map_err(|e| anyhow!("{e}"))
            .with_context(|| format!("writing {}", svg.display()))
    })();
    let renamed = drawn.and_then(|()| {
        std::fs::rename(&png_partial, &png)
            .with_context(|| format!("writing {}", png.display()))?;
        std::fs::rename(&svg_partial, &svg).with_context(|| format!("writing {}", svg.display()))
    });
    if renamed.is_err() {
        let _ = std::fs::remove_file(&png_partial);
        let _ = std::fs::remove_file(&svg_partial);
    }
    renamed.map(|()| [png, svg])
}

/// Writes one chart as `stem.png` and `stem.svg`.
pub fn write_chart(chart: &Chart, stem: &Path) -> Result<[PathBuf; 2]> {
    write_charts(std::slice::from_ref(chart), 1, stem)
}

fn draw_grid<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    charts: &[Chart],
    rows: usize,
    columns: usize,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let areas = root.split_evenly((rows, columns));
    for (chart, area) in charts.iter().zip(areas.iter()) {
        draw_chart(area, chart)?;
    }
    Ok(())
}

/// Most points a line is drawn with ([`decimated`]).
const MAX_DRAWN_POINTS: usize = 4000;

/// A line of more than `limit` points reduced for drawing: the points are cut into buckets of
/// consecutive points and each bucket gives its lowest and highest point, in their order, so
/// every peak and trough the figure can show is kept (and the first and last points). At most
/// `limit` points (limit ≥ 4).
fn decimated(points: Vec<(f64, f64)>, limit: usize) -> Vec<(f64, f64)> {
    let limit = limit.max(4);
    if points.len() <= limit {
        return points;
    }
    let buckets = limit / 2 - 1;
    let size = (points.len() - 2).div_ceil(buckets);
    let mut kept = vec![points[0]];
    for bucket in points[1..points.len() - 1].chunks(size) {
        let by_y = |a: &&(f64, f64), b: &&(f64, f64)| a.1.total_cmp(&b.1);
        let low = bucket.iter().enumerate().min_by(|a, b| by_y(&a.1, &b.1));
        let high = bucket.iter().enumerate().max_by(|a, b| by_y(&a.1, &b.1));
        if let (Some((i, &l)), Some((j, &h))) = (low, high) {
            match i.cmp(&j) {
                std::cmp::Ordering::Less => kept.extend([l, h]),
                std::cmp::Ordering::Greater => kept.extend([h, l]),
                std::cmp::Ordering::Equal => kept.push(l),
            }
        }
    }
    kept.push(points[points.len() - 1]);
    kept
}

fn finite_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return if log { (0.1, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        return (lo / 1.2, hi * 1.2);
    }
    if hi - lo < 1e-300_f64.max(1e-12 * hi.abs()) {
        let pad = if hi == 0.0 { 1.0 } else { 0.05 * hi.abs() };
        return (lo - pad, hi + pad);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

fn draw_chart<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, chart: &Chart) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let xs = chart
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0));
    let ys = chart
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1));
    let (x0, x1) = if chart.x_categories.is_empty() {
        finite_range(xs, chart.log_x)
    } else {
        (-0.6, chart.x_categories.len() as f64 - 0.4)
    };
    let (mut y0, mut y1) = finite_range(ys, chart.log_y);
    if !chart.x_categories.is_empty() && !chart.log_y {
        // Room above the values for the legend, which would otherwise hide a category's point.
        y1 += 0.4 * (y1 - y0);
    }
    if chart.series.iter().any(|s| s.style == SeriesStyle::Bars) && !chart.log_y {
        y0 = y0.min(0.0);
    }
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(&chart.title, (FONT, 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70);
    macro_rules! draw_with {
        ($ctx:expr) => {{
            let mut ctx = $ctx;
            let category = |x: &f64| {
                let i = x.round();
                if (x - i).abs() < 1e-6 && i >= 0.0 {
                    chart
                        .x_categories
                        .get(i as usize)
                        .cloned()
                        .unwrap_or_default()
                } else {
                    String::new()
                }
            };
            let mut mesh = ctx.configure_mesh();
            mesh.x_desc(chart.x_label.as_str())
                .y_desc(chart.y_label.as_str())
                .label_style((FONT, 13))
                .axis_desc_style((FONT, 14))
                .light_line_style(RGBColor(235, 235, 235));
            if !chart.x_categories.is_empty() {
                mesh.x_labels(chart.x_categories.len() + 2)
                    .x_label_formatter(&category)
                    .disable_x_mesh();
            }
            mesh.draw().map_err(|e| anyhow!("{e}"))?;
            for (i, s) in chart.series.iter().enumerate() {
                let color = PALETTE[i % PALETTE.len()];
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .filter(|p| (!chart.log_x || p.0 > 0.0) && (!chart.log_y || p.1 > 0.0))
                    .collect();
                // A line of a long history is drawn from its extremes per bucket (the CSV keeps
                // every point): an SVG of millions of points is neither readable nor small.
                let pts = match s.style {
                    SeriesStyle::Line | SeriesStyle::Thin => decimated(pts, MAX_DRAWN_POINTS),
                    SeriesStyle::Points
                    | SeriesStyle::Bars
                    | SeriesStyle::Segments
                    | SeriesStyle::ThinSegments => pts,
                };
                let drawn = match s.style {
                    SeriesStyle::Line => ctx
                        .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                        .map_err(|e| anyhow!("{e}"))?,
                    SeriesStyle::Thin => ctx
                        .draw_series(LineSeries::new(pts, color.mix(0.5).stroke_width(1)))
                        .map_err(|e| anyhow!("{e}"))?,
                    SeriesStyle::Segments | SeriesStyle::ThinSegments => {
                        let style = if s.style == SeriesStyle::Segments {
                            color.stroke_width(2)
                        } else {
                            color.mix(0.5).stroke_width(1)
                        };
                        ctx.draw_series(
                            pts.chunks_exact(2)
                                .map(|pair| PathElement::new(vec![pair[0], pair[1]], style)),
                        )
                        .map_err(|e| anyhow!("{e}"))?
                    }
                    SeriesStyle::Points => ctx
                        .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
                        .map_err(|e| anyhow!("{e}"))?,
                    SeriesStyle::Bars => {
                        let gap = pts
                            .windows(2)
                            .map(|w| (w[1].0 - w[0].0).abs())
                            .fold(f64::INFINITY, f64::min);
                        let half = if gap.is_finite() { 0.4 * gap } else { 0.4 };
                        let base = if chart.log_y { y0 } else { 0.0 };
                        ctx.draw_series(pts.into_iter().map(|(x, y)| {
                            Rectangle::new([(x - half, base), (x + half, y)], color.filled())
                        }))
                        .map_err(|e| anyhow!("{e}"))?
                    }
                };
                if !s.label.is_empty() {
                    drawn.label(s.label.clone()).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                    });
                }
            }
            if chart.series.iter().any(|s| !s.label.is_empty()) {
                ctx.configure_series_labels()
                    .label_font((FONT, 13))
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK.mix(0.3))
                    .position(SeriesLabelPosition::UpperRight)
                    .draw()
                    .map_err(|e| anyhow!("{e}"))?;
            }
        }};
    }
    match (chart.log_x, chart.log_y) {
        (false, false) => draw_with!(builder
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| anyhow!("{e}"))?),
        (true, false) => draw_with!(builder
            .build_cartesian_2d((x0..x1).log_scale(), y0..y1)
            .map_err(|e| anyhow!("{e}"))?),
        (false, true) => draw_with!(builder
            .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
            .map_err(|e| anyhow!("{e}"))?),
        (true, true) => draw_with!(builder
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(|e| anyhow!("{e}"))?),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_decimated_line_keeps_its_extremes_its_ends_and_its_order_within_the_limit() {
        // A million-point history with one sharp peak and one trough.
        let n = 1_000_000;
        let mut points: Vec<(f64, f64)> = (0..n)
            .map(|i| (i as f64 * 1e-3, (i as f64 * 1e-3).sin()))
            .collect();
        points[123_457].1 = 5.0;
        points[876_543].1 = -7.0;
        let kept = decimated(points.clone(), MAX_DRAWN_POINTS);
        assert!(kept.len() <= MAX_DRAWN_POINTS, "{}", kept.len());
        assert!(kept.contains(&points[123_457]) && kept.contains(&points[876_543]));
        assert_eq!((kept[0], *kept.last().unwrap()), (points[0], points[n - 1]));
        assert!(kept.windows(2).all(|w| w[0].0 < w[1].0), "in x order");
        // A short line is drawn as it is.
        let short = points[..100].to_vec();
        assert_eq!(decimated(short.clone(), MAX_DRAWN_POINTS), short);
    }
}
