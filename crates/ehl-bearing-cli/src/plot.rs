//! Plots written as SVG and PNG, with no system library involved.
//!
//! Drawing uses `plotters` with pure-Rust backends only: its SVG writer, its
//! bitmap backend with the `image` crate's PNG encoder, and `ab_glyph` for text,
//! with the DejaVu Sans font embedded in the binary (`assets/DejaVuSans.ttf`,
//! licence in `assets/DejaVuSans-LICENSE.txt`).
//!
//! Charts: [`line_chart`] / [`line_chart_with`] (lines and/or markers, log
//! axes, explicit ranges), [`stacked_charts`] (panels sharing x),
//! [`dual_axis_chart`] (two y axes sharing x) and [`heatmap`] /
//! [`heatmap_with`] (viridis map with colour bar, contours, overlaid curves).
//!
//! Every function writes `<stem>.svg` and `<stem>.png` (the parent directory is
//! created when missing). Non-finite values (and non-positive ones on a log
//! axis) are skipped: lines are broken there. Bad input (no series, mismatched
//! lengths, ragged grids, no finite value at all) is an error, never a panic.

// Removed when the commands use this module.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use anyhow::{anyhow, ensure, Context, Result};
use plotters::chart::DualCoordChartContext;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::element::ComposedElement;
use plotters_backend::text_anchor::{HPos, Pos, VPos};
use plotters_backend::FontTransform;
use plotters_backend::{BackendColor, BackendCoord, BackendTextStyle, DrawingErrorKind};

use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;

/// A pixel offset.
type Px = (i32, i32);
/// A line sample and a marker, positioned in pixels around an anchor point.
type Glyph<C, DB> = ComposedElement<C, DB, PathElement<Px>, Polygon<Px>>;

/// Width in pixels of every figure.
pub const FIGURE_WIDTH: u32 = 1000;
/// Height in pixels of a [`line_chart`] / [`heatmap`] figure.
pub const FIGURE_HEIGHT: u32 = 700;

/// Height in pixels of a [`stacked_charts`] figure with `panels` panels.
pub fn stacked_height(panels: usize) -> u32 {
    (90 + 300 * panels.max(1) as u32).max(FIGURE_HEIGHT.min(500))
}

const FONT: &str = "sans-serif";
const FONT_BYTES: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
const TITLE_SIZE: u32 = 26;
const DESC_SIZE: u32 = 20;
const TICK_SIZE: u32 = 16;
const LEGEND_SIZE: u32 = 16;
const MARGIN: u32 = 15;
const X_AREA: u32 = 60;

/// Tableau-10 palette: distinct colours for successive series.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Colours of curves drawn over a heatmap (readable on viridis).
const OVERLAY_PALETTE: [RGBColor; 4] = [
    RGBColor(255, 127, 14),
    RGBColor(255, 255, 255),
    RGBColor(214, 39, 40),
    RGBColor(0, 0, 0),
];

/// Colour of heatmap cells whose value is not finite.
const MISSING: RGBColor = RGBColor(215, 215, 215);

/// How a series is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SeriesStyle {
    /// A line through the points (broken where a value is not finite).
    #[default]
    Line,
    /// Markers only (e.g. measured or computed samples).
    Markers,
    /// A line with markers on the points.
    LineAndMarkers,
}

/// One data series of a chart: `y[k]` against `x[k]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Series {
    /// Legend text (the legend is shown when a chart has several series).
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates; must have the same length as `x`.
    pub y: Vec<f64>,
    /// How the series is drawn.
    pub style: SeriesStyle,
}

impl Series {
    /// A series with the given style.
    pub fn new(label: impl Into<String>, x: Vec<f64>, y: Vec<f64>, style: SeriesStyle) -> Self {
        Self {
            label: label.into(),
            x,
            y,
            style,
        }
    }

    /// A series drawn as a line.
    pub fn line(label: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Self {
        Self::new(label, x, y, SeriesStyle::Line)
    }

    /// A series drawn as markers only.
    pub fn markers(label: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Self {
        Self::new(label, x, y, SeriesStyle::Markers)
    }
}

/// Options of [`line_chart_with`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChartOptions {
    /// Logarithmic x axis (non-positive x values are skipped).
    pub x_log: bool,
    /// Logarithmic y axis (non-positive y values are skipped). A log axis spans
    /// at most 60 decades: an automatic range keeps the top ones, an explicit
    /// wider one is an error.
    pub y_log: bool,
    /// Explicit x range `(min, max)`; automatic (with padding) when `None`.
    pub x_range: Option<(f64, f64)>,
    /// Explicit y range `(min, max)`; automatic (with padding) when `None`.
    pub y_range: Option<(f64, f64)>,
}

/// Options of [`heatmap_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct HeatmapOptions {
    /// Colour scale range `(min, max)`; values outside are clamped. Automatic when `None`.
    pub z_range: Option<(f64, f64)>,
    /// Levels of z drawn as white contour lines (e.g. a small pressure level
    /// outlining the contact).
    pub contour_levels: Vec<f64>,
    /// Curves drawn over the map, e.g. the Hertz ellipse (labelled ones get a legend).
    pub overlays: Vec<Series>,
    /// Same scale on x and y, as a map of a contact should be (ignored when the
    /// data aspect ratio is more extreme than 1:5).
    pub equal_aspect: bool,
}

impl Default for HeatmapOptions {
    fn default() -> Self {
        Self {
            z_range: None,
            contour_levels: Vec::new(),
            overlays: Vec::new(),
            equal_aspect: true,
        }
    }
}

/// A 2-D line/scatter chart written as `<stem>.svg` and `<stem>.png`
/// ([`FIGURE_WIDTH`] × [`FIGURE_HEIGHT`] px), with automatic axis ranges.
pub fn line_chart(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<()> {
    line_chart_with(
        stem,
        title,
        x_label,
        y_label,
        series,
        &ChartOptions::default(),
    )
}

/// [`line_chart`] with options: logarithmic axes and explicit ranges.
pub fn line_chart_with(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    options: &ChartOptions,
) -> Result<()> {
    ensure!(
        !series.is_empty(),
        "line chart '{title}': no series to plot"
    );
    check_series(series)?;
    let x = Axis::fit(
        series.iter().flat_map(|s| s.x.iter().copied()),
        options.x_log,
        options.x_range,
    )
    .with_context(|| format!("line chart '{title}', x axis"))?
    .ok_or_else(|| anyhow!("line chart '{title}': no finite data to plot"))?;
    let y = Axis::fit(
        series.iter().flat_map(|s| points_in_x(s, &x)),
        options.y_log,
        options.y_range,
    )
    .with_context(|| format!("line chart '{title}', y axis"))?
    .ok_or_else(|| anyhow!("line chart '{title}': no finite data to plot"))?;
    let y_area = y_label_area(&y, y_label);
    let panel = Panel {
        x_label,
        y_label,
        show_x: true,
        x,
        y,
        series,
        y_area,
        margin_bottom: MARGIN,
        y_fixed: options.y_range.is_some(),
    };
    save_both(
        stem,
        (FIGURE_WIDTH, FIGURE_HEIGHT),
        &LineFig { title, panel },
    )
}

struct LineFig<'a> {
    title: &'a str,
    panel: Panel<'a>,
}

impl Figure for LineFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let area = root
            .titled(self.title, (FONT, TITLE_SIZE))
            .map_err(drawing)?;
        draw_panel(&area, &self.panel)
    }
}

/// Several panels stacked vertically sharing one x axis (e.g. δ(t) above Q(t)),
/// written as `<stem>.svg` and `<stem>.png` ([`FIGURE_WIDTH`] ×
/// [`stacked_height`] px). Each panel is `(y label, series)`; a panel with no
/// finite point is drawn empty, but at least one panel must have data.
pub fn stacked_charts(
    stem: &Path,
    title: &str,
    x_label: &str,
    panels: &[(String, Vec<Series>)],
) -> Result<()> {
    ensure!(!panels.is_empty(), "stacked chart '{title}': no panels");
    for (label, series) in panels {
        check_series(series).with_context(|| format!("panel '{label}'"))?;
    }
    let x = Axis::fit(
        panels
            .iter()
            .flat_map(|(_, s)| s.iter().flat_map(|s| s.x.iter().copied())),
        false,
        None,
    )?
    .ok_or_else(|| anyhow!("stacked chart '{title}': no finite data to plot"))?;
    let ys: Vec<Axis> = panels
        .iter()
        .map(|(_, series)| {
            Axis::fit(series.iter().flat_map(|s| points_in_x(s, &x)), false, None)
                .map(|a| a.unwrap_or(Axis::new(0.0, 1.0, false)))
        })
        .collect::<Result<_>>()?;
    let y_area = panels
        .iter()
        .zip(&ys)
        .map(|((label, _), y)| y_label_area(y, label))
        .max()
        .unwrap_or(90);
    let fig = StackedFig {
        title,
        x_label,
        panels,
        x,
        ys,
        y_area,
    };
    save_both(stem, (FIGURE_WIDTH, stacked_height(panels.len())), &fig)
}

struct StackedFig<'a> {
    title: &'a str,
    x_label: &'a str,
    panels: &'a [(String, Vec<Series>)],
    x: Axis,
    ys: Vec<Axis>,
    y_area: u32,
}

impl Figure for StackedFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let n = self.panels.len();
        let area = root
            .titled(self.title, (FONT, TITLE_SIZE))
            .map_err(drawing)?;
        let (_, h) = area.dim_in_pixel();
        // Equal plot heights: the bottom panel also holds the x labels.
        let inner = (h as f64 - X_AREA as f64) / n as f64;
        let breaks: Vec<i32> = (1..n).map(|k| (inner * k as f64).round() as i32).collect();
        let no_x: [i32; 0] = [];
        let areas = area.split_by_breakpoints(no_x, breaks);
        for (k, ((label, series), sub)) in self.panels.iter().zip(&areas).enumerate() {
            let last = k + 1 == n;
            let panel = Panel {
                x_label: self.x_label,
                y_label: label,
                show_x: last,
                x: self.x,
                y: self.ys[k],
                series,
                y_area: self.y_area,
                margin_bottom: if last { MARGIN } else { 8 },
                y_fixed: false,
            };
            draw_panel(sub, &panel)?;
        }
        Ok(())
    }
}

/// A chart with two y axes sharing x, e.g. the centre-line pressure (left
/// axis) and film thickness (right axis) profiles, written as `<stem>.svg` and
/// `<stem>.png` ([`FIGURE_WIDTH`] × [`FIGURE_HEIGHT`] px). Series colours run
/// on from the left ones to the right ones; the legend (always shown for
/// labelled series) marks which axis each series belongs to. Either side may be
/// empty, but not both.
pub fn dual_axis_chart(
    stem: &Path,
    title: &str,
    x_label: &str,
    (left_label, left): (&str, &[Series]),
    (right_label, right): (&str, &[Series]),
) -> Result<()> {
    ensure!(
        !left.is_empty() || !right.is_empty(),
        "dual-axis chart '{title}': no series to plot"
    );
    check_series(left)?;
    check_series(right)?;
    let x = Axis::fit(
        left.iter().chain(right).flat_map(|s| s.x.iter().copied()),
        false,
        None,
    )?
    .ok_or_else(|| anyhow!("dual-axis chart '{title}': no finite data to plot"))?;
    let fit_y = |series: &[Series]| {
        Axis::fit(series.iter().flat_map(|s| points_in_x(s, &x)), false, None)
            .map(|a| a.unwrap_or(Axis::new(0.0, 1.0, false)))
    };
    let (y_left, y_right) = (fit_y(left)?, fit_y(right)?);
    let tag = |series: &[Series], side: &str| -> Vec<Series> {
        series
            .iter()
            .map(|s| Series {
                label: if s.label.is_empty() {
                    String::new()
                } else {
                    format!("{} ({side} axis)", s.label)
                },
                ..s.clone()
            })
            .collect()
    };
    let fig = DualFig {
        title,
        x_label,
        left_label,
        right_label,
        left: tag(left, "left"),
        right: tag(right, "right"),
        x,
        y_left,
        y_right,
    };
    save_both(stem, (FIGURE_WIDTH, FIGURE_HEIGHT), &fig)
}

struct DualFig<'a> {
    title: &'a str,
    x_label: &'a str,
    left_label: &'a str,
    right_label: &'a str,
    left: Vec<Series>,
    right: Vec<Series>,
    x: Axis,
    y_left: Axis,
    y_right: Axis,
}

impl Figure for DualFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let area = root
            .titled(self.title, (FONT, TITLE_SIZE))
            .map_err(drawing)?;
        let (x, mut yl, mut yr) = (self.x, self.y_left, self.y_right);
        let left_area = y_label_area(&yl, self.left_label);
        let right_ticks = widest_tick(&yr);
        let right_area = right_ticks
            + 18
            + if self.right_label.is_empty() {
                0
            } else {
                DESC_SIZE + 12
            };
        let (aw, ah) = area.dim_in_pixel();
        let plot = (
            aw.saturating_sub(left_area + right_area + 2 * MARGIN),
            ah.saturating_sub(X_AREA + 8 + MARGIN),
        );
        let items = |yl: &'_ Axis, yr: &'_ Axis| -> Vec<(Series, Axis)> {
            self.left
                .iter()
                .map(|s| (s.clone(), *yl))
                .chain(self.right.iter().map(|s| (s.clone(), *yr)))
                .filter(|(s, _)| !s.label.is_empty())
                .collect()
        };
        let owned = items(&yl, &yr);
        let refs: Vec<(&Series, &Axis)> = owned.iter().map(|(s, a)| (s, a)).collect();
        let (_, hits, fh) = plan_legend(&refs, &x, plot);
        if !refs.is_empty() && hits > 0 {
            // Every corner has data: make room above the data on both axes.
            yl = yl.with_top_room(fh + 0.03);
            yr = yr.with_top_room(fh + 0.03);
        }
        let mut chart = ChartBuilder::on(&area)
            .margin_top(8)
            .margin_left(MARGIN)
            .margin_right(MARGIN)
            .margin_bottom(MARGIN)
            .x_label_area_size(X_AREA)
            .y_label_area_size(left_area)
            .right_y_label_area_size(right_area)
            .build_cartesian_2d(x.lo..x.hi, yl.lo..yl.hi)
            .map_err(drawing)?
            .set_secondary_coord(x.lo..x.hi, yr.lo..yr.hi);

        let x_fmt = |v: &f64| x.tick_label(*v);
        let yl_fmt = |v: &f64| yl.tick_label(*v);
        let yr_fmt = |v: &f64| yr.tick_label(*v);
        chart
            .configure_mesh()
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&yl_fmt)
            .label_style((FONT, TICK_SIZE))
            .axis_desc_style((FONT, DESC_SIZE))
            .x_labels(10)
            .y_labels(8)
            .set_all_tick_mark_size(5)
            .bold_line_style(RGBColor(215, 215, 215))
            .light_line_style(RGBColor(243, 243, 243))
            .max_light_lines(4)
            .x_desc(self.x_label)
            .y_desc(self.left_label)
            .draw()
            .map_err(drawing)?;
        chart
            .configure_secondary_axes()
            .y_label_formatter(&yr_fmt)
            .label_style((FONT, TICK_SIZE))
            .axis_desc_style((FONT, DESC_SIZE))
            .y_labels(8)
            .set_all_tick_mark_size(5)
            .draw()
            .map_err(drawing)?;
        if !self.right_label.is_empty() {
            // Reads bottom to top, like the left description.
            let (xs, ys) = chart.plotting_area().get_pixel_range();
            let style = TextStyle::from((FONT, DESC_SIZE).into_font())
                .transform(FontTransform::Rotate270)
                .pos(Pos::new(HPos::Center, VPos::Top));
            let at = (xs.end + right_ticks as i32 + 16, (ys.start + ys.end) / 2);
            root.draw_text(self.right_label, &style, at)
                .map_err(drawing)?;
        }

        for (k, s) in self.left.iter().enumerate() {
            draw_series(&mut chart, s, k, PALETTE[k % PALETTE.len()], &x, &yl)?;
        }
        for (j, s) in self.right.iter().enumerate() {
            let k = self.left.len() + j;
            draw_secondary_series(&mut chart, s, k, PALETTE[k % PALETTE.len()], &x, &yr)?;
        }

        let owned = items(&yl, &yr);
        let refs: Vec<(&Series, &Axis)> = owned.iter().map(|(s, a)| (s, a)).collect();
        if !refs.is_empty() {
            let (w, h) = chart.plotting_area().dim_in_pixel();
            let pos = legend_position_of(&refs, &x, (w, h));
            chart
                .configure_series_labels()
                .position(pos)
                .margin(10)
                .label_font((FONT, LEGEND_SIZE))
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .draw()
                .map_err(drawing)?;
        }
        Ok(())
    }
}

/// A colour map (viridis) of `z` on a regular grid — `z[j][i]` at `(x[i], y[j])`,
/// `x` and `y` increasing — with a colour bar labelled `z_label`, written as
/// `<stem>.svg` and `<stem>.png` ([`FIGURE_WIDTH`] × [`FIGURE_HEIGHT`] px).
/// The map is bilinearly interpolated at the output resolution, so any grid
/// size works (513 × 513 included); the SVG embeds it as one PNG image.
/// Non-finite cells are grey. Axes use equal scales (see [`HeatmapOptions`]).
#[allow(clippy::too_many_arguments)]
pub fn heatmap(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    x: &[f64],
    y: &[f64],
    z: &[Vec<f64>],
    z_label: &str,
) -> Result<()> {
    heatmap_with(
        stem,
        title,
        x_label,
        y_label,
        x,
        y,
        z,
        z_label,
        &HeatmapOptions::default(),
    )
}

/// [`heatmap`] with options: colour range, contour levels, overlaid curves, aspect.
#[allow(clippy::too_many_arguments)]
pub fn heatmap_with(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    x: &[f64],
    y: &[f64],
    z: &[Vec<f64>],
    z_label: &str,
    options: &HeatmapOptions,
) -> Result<()> {
    check_grid_axis(x, "x")?;
    check_grid_axis(y, "y")?;
    ensure!(
        z.len() == y.len(),
        "heatmap '{title}': z has {} rows but y has {} values",
        z.len(),
        y.len()
    );
    for (j, row) in z.iter().enumerate() {
        ensure!(
            row.len() == x.len(),
            "heatmap '{title}': z row {j} has {} values but x has {}",
            row.len(),
            x.len()
        );
    }
    check_series(&options.overlays).context("heatmap overlays")?;
    let (z_lo, z_hi) = match options.z_range {
        Some((a, b)) => {
            ensure!(
                a.is_finite() && b.is_finite() && a < b,
                "heatmap '{title}': z range ({a}, {b}) must be finite and increasing"
            );
            (a, b)
        }
        None => {
            let (lo, hi) = finite_min_max(z.iter().flatten().copied())
                .ok_or_else(|| anyhow!("heatmap '{title}': no finite z value"))?;
            if lo < hi {
                (lo, hi)
            } else {
                let d = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
                (lo - d, hi + d)
            }
        }
    };
    let grid = Grid { x, y, z };
    let contours: Vec<Vec<Segment>> = options
        .contour_levels
        .iter()
        .filter(|c| c.is_finite())
        .map(|&c| grid.contour(c))
        .collect();
    let spec = HeatSpec {
        x_label,
        y_label,
        z_label,
        grid: &grid,
        z_range: (z_lo, z_hi),
        contours: &contours,
        overlays: &options.overlays,
        equal_aspect: options.equal_aspect,
    };
    save_both(
        stem,
        (FIGURE_WIDTH, FIGURE_HEIGHT),
        &HeatFig { title, spec },
    )
}

struct HeatFig<'a> {
    title: &'a str,
    spec: HeatSpec<'a>,
}

impl Figure for HeatFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let area = root
            .titled(self.title, (FONT, TITLE_SIZE))
            .map_err(drawing)?;
        draw_heatmap(&area, &self.spec)
    }
}

// ---------------------------------------------------------------------------
// Output

fn ensure_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES).is_ok()
    });
    ensure!(ok, "the embedded plot font could not be loaded");
    Ok(())
}

fn drawing<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("plot drawing failed: {e}")
}

fn with_ext(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// A figure drawn identically on any backend.
trait Figure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>;
}

/// Draws the figure with both backends and writes `<stem>.svg` and `<stem>.png`.
fn save_both<F: Figure>(stem: &Path, size: (u32, u32), fig: &F) -> Result<()> {
    ensure_font()?;
    if let Some(dir) = stem.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating plot directory {}", dir.display()))?;
    }

    let svg_path = with_ext(stem, "svg");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        fig.draw(&root)?;
        root.present().map_err(drawing)?;
    }
    // plotters writes a non-standard data URL for embedded images; make it one
    // that browsers and editors accept, and let the image stretch to its box.
    let svg = svg.replace(
        "href=\"data:png;base64,",
        "preserveAspectRatio=\"none\" href=\"data:image/png;base64,",
    );
    std::fs::write(&svg_path, svg).with_context(|| format!("writing {}", svg_path.display()))?;

    // PNG: drawn at SUPERSAMPLE times the size, then averaged down, which
    // anti-aliases lines and markers.
    let png_path = with_ext(stem, "png");
    let (bw, bh) = (size.0 * SUPERSAMPLE, size.1 * SUPERSAMPLE);
    let mut big = vec![255u8; bw as usize * bh as usize * 3];
    {
        let root = Png {
            inner: BitMapBackend::with_buffer(&mut big, (bw, bh)),
            size,
        }
        .into_drawing_area();
        fig.draw(&root)?;
        root.present().map_err(drawing)?;
    }
    let small = downsample(&big, size);
    let mut out = BitMapBackend::new(&png_path, size);
    out.blit_bitmap((0, 0), size, &small).map_err(drawing)?;
    out.present()
        .map_err(|e| anyhow!("writing {}: {e}", png_path.display()))?;
    Ok(())
}

/// Linear scale of the PNG drawing buffer over the figure size.
const SUPERSAMPLE: u32 = 2;

/// Averages SUPERSAMPLE × SUPERSAMPLE blocks of an RGB buffer.
fn downsample(big: &[u8], (w, h): (u32, u32)) -> Vec<u8> {
    let k = SUPERSAMPLE as usize;
    let (w, h) = (w as usize, h as usize);
    let bw = w * k;
    let mut out = vec![0u8; w * h * 3];
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let mut sum = 0u32;
                for dy in 0..k {
                    for dx in 0..k {
                        sum += u32::from(big[((y * k + dy) * bw + x * k + dx) * 3 + c]);
                    }
                }
                out[(y * w + x) * 3 + c] = ((sum + (k * k / 2) as u32) / (k * k) as u32) as u8;
            }
        }
    }
    out
}

/// A stroke style scaled for the supersampled buffer.
struct Scaled {
    color: BackendColor,
    width: u32,
}

impl plotters_backend::BackendStyle for Scaled {
    fn color(&self) -> BackendColor {
        self.color
    }
    fn stroke_width(&self) -> u32 {
        self.width
    }
}

fn scaled<S: plotters_backend::BackendStyle>(style: &S) -> Scaled {
    Scaled {
        color: style.color(),
        width: style.stroke_width() * SUPERSAMPLE,
    }
}

fn up((x, y): BackendCoord) -> BackendCoord {
    let k = SUPERSAMPLE as i32;
    (x * k, y * k)
}

/// The PNG backend: plotters' bitmap backend drawn at [`SUPERSAMPLE`] times the
/// figure size (plotters sees the figure size), with its own text rendering:
/// plotters' `ab_glyph` text drops each glyph's side bearing, which makes
/// labels look unevenly spaced ("0. 8").
struct Png<'a> {
    inner: BitMapBackend<'a>,
    size: (u32, u32),
}

fn font_ref() -> &'static ab_glyph::FontRef<'static> {
    static FONT_REF: OnceLock<ab_glyph::FontRef<'static>> = OnceLock::new();
    FONT_REF.get_or_init(|| {
        // ensure_font() has already parsed the same bytes successfully.
        ab_glyph::FontRef::try_from_slice(FONT_BYTES).expect("embedded font parses")
    })
}

/// Width, height and ascent in pixels of `text` at plotters' font `size`.
fn text_box(text: &str, size: f64) -> (f32, f32, f32) {
    use ab_glyph::{Font, ScaleFont};
    let font = font_ref().as_scaled(size as f32);
    let mut width = 0.0f32;
    let mut prev = None;
    for c in text.chars() {
        let id = font.glyph_id(c);
        if let Some(p) = prev {
            width += font.kern(p, id);
        }
        width += font.h_advance(id);
        prev = Some(id);
    }
    (width, font.ascent() - font.descent(), font.ascent())
}

impl<'a> DrawingBackend for Png<'a> {
    type ErrorType = <BitMapBackend<'a> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.size
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }
    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let k = SUPERSAMPLE as i32 - 1;
        let (x, y) = up(point);
        let fill = Scaled { color, width: 1 };
        self.inner.draw_rect((x, y), (x + k, y + k), &fill, true)
    }
    fn draw_line<S: plotters_backend::BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(up(from), up(to), &scaled(style))
    }
    fn draw_rect<S: plotters_backend::BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let k = if fill { SUPERSAMPLE as i32 - 1 } else { 0 };
        let (x1, y1) = up(bottom_right);
        self.inner
            .draw_rect(up(upper_left), (x1 + k, y1 + k), &scaled(style), fill)
    }
    fn draw_path<S: plotters_backend::BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner
            .draw_path(path.into_iter().map(up), &scaled(style))
    }
    fn draw_circle<S: plotters_backend::BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner
            .draw_circle(up(center), radius * SUPERSAMPLE, &scaled(style), fill)
    }
    fn fill_polygon<S: plotters_backend::BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner
            .fill_polygon(vert.into_iter().map(up), &scaled(style))
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (w, h): (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let k = SUPERSAMPLE as usize;
        let (w, h) = (w as usize, h as usize);
        let mut big = Vec::with_capacity(w * h * k * k * 3);
        for row in src.chunks_exact(w * 3).take(h) {
            let start = big.len();
            for px in row.chunks_exact(3) {
                for _ in 0..k {
                    big.extend_from_slice(px);
                }
            }
            for _ in 1..k {
                big.extend_from_within(start..start + w * k * 3);
            }
        }
        let size = ((w * k) as u32, (h * k) as u32);
        self.inner.blit_bitmap(up(pos), size, &big)
    }

    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        style: &T,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let (w, h, _) = text_box(text, style.size());
        Ok((w.ceil() as u32, h.ceil() as u32))
    }

    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &T,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        use ab_glyph::{Font, ScaleFont};
        let colour = style.color();
        if colour.alpha == 0.0 || text.is_empty() {
            return Ok(());
        }
        let k = SUPERSAMPLE as f64;
        let size = (style.size() * k) as f32;
        let (w, h, ascent) = text_box(text, style.size() * k);
        let pos = up(pos);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Center => -w / 2.0,
            HPos::Right => -w,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0.0,
            VPos::Center => -h / 2.0,
            VPos::Bottom => -h,
        };
        let transform = style.transform();
        let font = font_ref().as_scaled(size);
        let mut caret = dx;
        let mut prev = None;
        let mut result = Ok(());
        for c in text.chars() {
            let id = font.glyph_id(c);
            if let Some(p) = prev {
                caret += font.kern(p, id);
            }
            let glyph = id.with_scale_and_position(size, ab_glyph::point(caret, dy + ascent));
            if let Some(outline) = font_ref().outline_glyph(glyph) {
                let b = outline.px_bounds();
                outline.draw(|gx, gy, coverage| {
                    if result.is_err() || coverage <= 0.0 {
                        return;
                    }
                    let lx = b.min.x as i32 + gx as i32;
                    let ly = b.min.y as i32 + gy as i32;
                    let (tx, ty) = transform.transform(lx, ly);
                    let c = BackendColor {
                        alpha: colour.alpha * f64::from(coverage.min(1.0)),
                        rgb: colour.rgb,
                    };
                    result = self.inner.draw_pixel((pos.0 + tx, pos.1 + ty), c);
                });
            }
            caret += font.h_advance(id);
            prev = Some(id);
        }
        result
    }
}

// ---------------------------------------------------------------------------
// Data checks and axes

fn check_series(series: &[Series]) -> Result<()> {
    for s in series {
        ensure!(
            s.x.len() == s.y.len(),
            "series '{}': {} x values but {} y values",
            s.label,
            s.x.len(),
            s.y.len()
        );
    }
    Ok(())
}

fn check_grid_axis(v: &[f64], name: &str) -> Result<()> {
    ensure!(
        v.len() >= 2,
        "heatmap: {name} needs at least 2 grid values, got {}",
        v.len()
    );
    ensure!(
        v.iter().all(|a| a.is_finite()),
        "heatmap: {name} grid values must be finite"
    );
    ensure!(
        v.windows(2).all(|w| w[0] < w[1]),
        "heatmap: {name} grid values must be strictly increasing"
    );
    Ok(())
}

fn finite_min_max(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
        })
}

/// y values of the points of `s` whose x lies on axis `x` (for the y range).
fn points_in_x<'a>(s: &'a Series, x: &'a Axis) -> impl Iterator<Item = f64> + 'a {
    s.x.iter()
        .zip(&s.y)
        .filter(|(a, _)| x.accepts(**a) && **a >= x.lo && **a <= x.hi)
        .map(|(_, b)| *b)
}

/// Most decades a log axis spans (automatic ranges keep the top ones).
const MAX_DECADES: f64 = 60.0;

/// One axis: its range and scale.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Axis {
    lo: f64,
    hi: f64,
    log: bool,
}

impl Axis {
    fn new(lo: f64, hi: f64, log: bool) -> Self {
        Self { lo, hi, log }
    }

    /// Whether `v` can be drawn on this axis at all.
    fn accepts(&self, v: f64) -> bool {
        v.is_finite() && (!self.log || v > 0.0)
    }

    /// Position of `v` along the axis, 0 at `lo` and 1 at `hi`.
    fn norm(&self, v: f64) -> f64 {
        if self.log {
            (v.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }

    /// The same axis extended upwards so that its current range fills only the
    /// lower `1 - frac` of it (room for a legend above the data).
    fn with_top_room(&self, frac: f64) -> Self {
        let keep = (1.0 - frac).clamp(0.3, 1.0);
        if self.log {
            let (a, b) = (self.lo.log10(), self.hi.log10());
            Self::new(self.lo, 10f64.powf(a + (b - a) / keep), true)
        } else {
            Self::new(self.lo, self.lo + (self.hi - self.lo) / keep, false)
        }
    }

    /// The explicit range if given, else the range of the drawable values with
    /// 5 % padding; `None` when there is no drawable value.
    fn fit(
        values: impl Iterator<Item = f64>,
        log: bool,
        explicit: Option<(f64, f64)>,
    ) -> Result<Option<Self>> {
        if let Some((lo, hi)) = explicit {
            ensure!(
                lo.is_finite() && hi.is_finite() && lo < hi,
                "range ({lo}, {hi}) must be finite and increasing"
            );
            ensure!(
                !log || lo > 0.0,
                "range ({lo}, {hi}) must be positive on a log axis"
            );
            ensure!(
                !log || hi.log10() - lo.log10() <= MAX_DECADES,
                "log range ({lo:e}, {hi:e}) spans more than {MAX_DECADES} decades"
            );
            return Ok(Some(Self::new(lo, hi, log)));
        }
        let probe = Self::new(1.0, 2.0, log);
        let Some((lo, hi)) = finite_min_max(values.filter(|v| probe.accepts(*v))) else {
            return Ok(None);
        };
        let axis = if log {
            // plotters slows to a crawl over hundreds of decades: keep the top ones.
            let b = hi.log10();
            let a = lo.log10().max(b - MAX_DECADES);
            let pad = if b > a { 0.05 * (b - a) } else { 0.3 };
            Self::new(10f64.powf(a - pad), 10f64.powf(b + pad), true)
        } else {
            let pad = if hi > lo {
                0.05 * (hi - lo)
            } else if lo != 0.0 {
                0.1 * lo.abs()
            } else {
                1.0
            };
            Self::new(lo - pad, hi + pad, false)
        };
        ensure!(
            axis.lo.is_finite() && axis.hi.is_finite() && axis.lo < axis.hi,
            "data range [{lo:e}, {hi:e}] is too wide or too narrow to draw"
        );
        Ok(Some(axis))
    }
}

/// `v` in plain decimals, at most 6 of them, trailing zeros dropped.
fn fmt_decimal(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// `v` in scientific notation with at most 4 significant digits: `1.5e-7`.
fn fmt_scientific(v: f64) -> String {
    let s = format!("{v:.3e}");
    match s.split_once('e') {
        Some((m, e)) if m.contains('.') => {
            format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
        }
        _ => s,
    }
}

/// Whether magnitudes like `a` read better in scientific notation.
fn wants_scientific(a: f64) -> bool {
    a != 0.0 && !(1e-3..1e5).contains(&a)
}

impl Axis {
    /// Tick label of `v`: one notation for the whole of a linear axis (chosen
    /// from its largest magnitude); on a log axis only 1, 2 and 5 times a power
    /// of ten are labelled, so the labels never run into each other.
    fn tick_label(&self, v: f64) -> String {
        if !v.is_finite() {
            return String::new();
        }
        if self.log {
            let mantissa = v / 10f64.powf(v.log10().floor());
            let m = mantissa.round();
            if (mantissa - m).abs() > 1e-6 || ![1.0, 2.0, 5.0].contains(&m) {
                return String::new();
            }
            return if wants_scientific(v) {
                fmt_scientific(v)
            } else {
                fmt_decimal(v)
            };
        }
        if v.abs() <= 1e-9 * (self.hi - self.lo) {
            return "0".to_string();
        }
        if wants_scientific(self.lo.abs().max(self.hi.abs())) {
            fmt_scientific(v)
        } else {
            fmt_decimal(v)
        }
    }
}

/// Likely tick values of an axis (plotters picks "nice" steps of 1, 2 or 5
/// times a power of ten; log axes tick at powers of ten and their multiples).
fn likely_ticks(a: &Axis, n: usize) -> Vec<f64> {
    if a.log {
        let (lo, hi) = (a.lo.log10().floor() as i32, a.hi.log10().ceil() as i32);
        return (lo..=hi)
            .take(700)
            .flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(e)))
            .filter(|v| *v >= a.lo && *v <= a.hi)
            .collect();
    }
    let raw = (a.hi - a.lo) / n as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (a.lo / step).ceil() as i64;
    let last = (a.hi / step).floor() as i64;
    (first..=last).take(100).map(|k| k as f64 * step).collect()
}

/// Width in pixels of the widest likely tick label of an axis.
fn widest_tick(a: &Axis) -> u32 {
    let text = |v: f64| text_box(&a.tick_label(v), TICK_SIZE as f64).0;
    likely_ticks(a, 8)
        .into_iter()
        .chain(likely_ticks(a, 4))
        .map(text)
        .fold(text(1.0), f32::max)
        .ceil() as u32
}

/// Width for the y tick labels and the rotated y description.
fn y_label_area(y: &Axis, desc: &str) -> u32 {
    let desc_w = if desc.is_empty() { 0 } else { DESC_SIZE + 12 };
    widest_tick(y) + desc_w + 18
}

// ---------------------------------------------------------------------------
// Line charts

#[derive(Clone, Copy)]
struct Panel<'a> {
    x_label: &'a str,
    y_label: &'a str,
    show_x: bool,
    x: Axis,
    y: Axis,
    series: &'a [Series],
    y_area: u32,
    margin_bottom: u32,
    /// The y range was given explicitly: never extend it for the legend.
    y_fixed: bool,
}

/// Whether a legend is drawn for these series.
fn wants_legend(series: &[Series]) -> bool {
    series.len() > 1 && series.iter().any(|s| !s.label.is_empty())
}

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, p: &Panel) -> Result<()> {
    let mut p = *p;
    if wants_legend(p.series) && !p.y_fixed {
        // If every corner of the plot has data, make room above the data.
        let (aw, ah) = area.dim_in_pixel();
        let plot = (
            aw.saturating_sub(p.y_area + 2 * MARGIN + 10),
            ah.saturating_sub(8 + p.margin_bottom + if p.show_x { X_AREA } else { 0 }),
        );
        let items: Vec<(&Series, &Axis)> = p.series.iter().map(|s| (s, &p.y)).collect();
        let (_, hits, fh) = plan_legend(&items, &p.x, plot);
        if hits > 0 {
            p.y = p.y.with_top_room(fh + 0.03);
        }
    }
    let p = &p;
    let xr = p.x.lo..p.x.hi;
    let yr = p.y.lo..p.y.hi;
    match (p.x.log, p.y.log) {
        (false, false) => draw_panel_in(area, p, xr, yr),
        (true, false) => draw_panel_in(area, p, xr.log_scale(), yr),
        (false, true) => draw_panel_in(area, p, xr, yr.log_scale()),
        (true, true) => draw_panel_in(area, p, xr.log_scale(), yr.log_scale()),
    }
}

fn draw_panel_in<DB, XS, YS>(area: &DrawingArea<DB, Shift>, p: &Panel, xs: XS, ys: YS) -> Result<()>
where
    DB: DrawingBackend,
    XS: AsRangedCoord<Value = f64>,
    YS: AsRangedCoord<Value = f64>,
    XS::CoordDescType: ValueFormatter<f64>,
    YS::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(area)
        .margin_top(8)
        .margin_left(MARGIN)
        .margin_right(MARGIN + 10)
        .margin_bottom(p.margin_bottom)
        .x_label_area_size(if p.show_x { X_AREA } else { 0 })
        .y_label_area_size(p.y_area)
        .build_cartesian_2d(xs, ys)
        .map_err(drawing)?;

    let x_fmt = |v: &f64| p.x.tick_label(*v);
    let y_fmt = |v: &f64| p.y.tick_label(*v);
    let mut mesh = chart.configure_mesh();
    mesh.x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style((FONT, TICK_SIZE))
        .axis_desc_style((FONT, DESC_SIZE))
        .x_labels(10)
        .y_labels(8)
        .set_all_tick_mark_size(5)
        .bold_line_style(RGBColor(215, 215, 215))
        .light_line_style(RGBColor(243, 243, 243))
        .max_light_lines(4)
        .y_desc(p.y_label);
    if p.show_x {
        mesh.x_desc(p.x_label);
    }
    mesh.draw().map_err(drawing)?;

    for (k, s) in p.series.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        draw_series(&mut chart, s, k, colour, &p.x, &p.y)?;
    }

    if wants_legend(p.series) {
        let (w, h) = chart.plotting_area().dim_in_pixel();
        let pos = legend_position(p.series, &p.x, &p.y, (w, h));
        chart
            .configure_series_labels()
            .position(pos)
            .margin(10)
            .label_font((FONT, LEGEND_SIZE))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()
            .map_err(drawing)?;
    }
    Ok(())
}

/// Runs of consecutive drawable points of a series.
fn segments(s: &Series, x: &Axis, y: &Axis) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut cur = Vec::new();
    for (&a, &b) in s.x.iter().zip(&s.y) {
        if x.accepts(a) && y.accepts(b) {
            cur.push((a, b));
        } else if !cur.is_empty() {
            out.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// Outline of marker `kind` (circle, triangle, square, diamond) in pixels
/// around its centre.
fn marker_shape(kind: usize) -> Vec<(i32, i32)> {
    match kind % 4 {
        0 => (0..16)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 16.0;
                (
                    (4.5 * a.cos()).round() as i32,
                    (4.5 * a.sin()).round() as i32,
                )
            })
            .collect(),
        1 => vec![(0, -6), (5, 3), (-5, 3)],
        2 => vec![(-4, -4), (4, -4), (4, 4), (-4, 4)],
        _ => vec![(0, -6), (5, 0), (0, 6), (-5, 0)],
    }
}

/// A data marker at `at`.
fn marker<DB: DrawingBackend>(
    kind: usize,
    at: (f64, f64),
    colour: RGBColor,
) -> Glyph<(f64, f64), DB> {
    EmptyElement::at(at)
        + PathElement::new(vec![], colour.stroke_width(1))
        + Polygon::new(marker_shape(kind), colour.filled())
}

/// The legend sample of a series: a short line and/or a marker.
fn legend_glyph<DB: DrawingBackend>(
    style: SeriesStyle,
    kind: usize,
    (x, y): (i32, i32),
    colour: RGBColor,
) -> Glyph<Px, DB> {
    let line = if style == SeriesStyle::Markers {
        vec![]
    } else {
        vec![(-12, 0), (12, 0)]
    };
    let shape = if style == SeriesStyle::Line {
        vec![]
    } else {
        marker_shape(kind)
    };
    EmptyElement::at((x + 10, y))
        + PathElement::new(line, colour.stroke_width(2))
        + Polygon::new(shape, colour.filled())
}

fn draw_series<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    s: &Series,
    k: usize,
    colour: RGBColor,
    x: &Axis,
    y: &Axis,
) -> Result<()>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let segs = segments(s, x, y);
    let style = s.style;
    let line_style = colour.stroke_width(2);
    if matches!(style, SeriesStyle::Line | SeriesStyle::LineAndMarkers) {
        for seg in segs.iter().filter(|seg| seg.len() > 1) {
            chart
                .draw_series(std::iter::once(PathElement::new(seg.clone(), line_style)))
                .map_err(drawing)?;
        }
    }
    if matches!(style, SeriesStyle::Markers | SeriesStyle::LineAndMarkers) {
        let pts = segs.iter().flatten().copied();
        chart
            .draw_series(pts.map(|p| marker::<DB>(k, p, colour)))
            .map_err(drawing)?;
    }
    // One empty drawing carries the legend entry, however the data was split.
    if !s.label.is_empty() {
        let none: Vec<PathElement<(f64, f64)>> = Vec::new();
        chart
            .draw_series(none)
            .map_err(drawing)?
            .label(s.label.clone())
            .legend(move |c| legend_glyph::<DB>(style, k, c, colour));
    }
    Ok(())
}

/// [`draw_series`] on the secondary (right-hand) axis of a dual-axis chart.
fn draw_secondary_series<'a, DB, X, Y, SX, SY>(
    chart: &mut DualCoordChartContext<'a, DB, Cartesian2d<X, Y>, Cartesian2d<SX, SY>>,
    s: &Series,
    k: usize,
    colour: RGBColor,
    x: &Axis,
    y: &Axis,
) -> Result<()>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
    SX: Ranged<ValueType = f64>,
    SY: Ranged<ValueType = f64>,
{
    let segs = segments(s, x, y);
    let style = s.style;
    let line_style = colour.stroke_width(2);
    if matches!(style, SeriesStyle::Line | SeriesStyle::LineAndMarkers) {
        for seg in segs.iter().filter(|seg| seg.len() > 1) {
            chart
                .draw_secondary_series(std::iter::once(PathElement::new(seg.clone(), line_style)))
                .map_err(drawing)?;
        }
    }
    if matches!(style, SeriesStyle::Markers | SeriesStyle::LineAndMarkers) {
        let pts = segs.iter().flatten().copied();
        chart
            .draw_secondary_series(pts.map(|p| marker::<DB>(k, p, colour)))
            .map_err(drawing)?;
    }
    if !s.label.is_empty() {
        let none: Vec<PathElement<(f64, f64)>> = Vec::new();
        chart
            .draw_secondary_series(none)
            .map_err(drawing)?
            .label(s.label.clone())
            .legend(move |c| legend_glyph::<DB>(style, k, c, colour));
    }
    Ok(())
}

/// The plot corner where a legend of these series covers the fewest data.
fn legend_position(series: &[Series], x: &Axis, y: &Axis, plot: (u32, u32)) -> SeriesLabelPosition {
    let items: Vec<(&Series, &Axis)> = series.iter().map(|s| (s, y)).collect();
    legend_position_of(&items, x, plot)
}

/// [`legend_position`] for series on different y axes.
fn legend_position_of(
    items: &[(&Series, &Axis)],
    x: &Axis,
    plot: (u32, u32),
) -> SeriesLabelPosition {
    plan_legend(items, x, plot).0
}

/// The best legend corner, how many samples of the drawn data it covers, and
/// the legend's height as a fraction of the plot height.
fn plan_legend(
    items: &[(&Series, &Axis)],
    x: &Axis,
    plot: (u32, u32),
) -> (SeriesLabelPosition, usize, f64) {
    let labelled = items.iter().filter(|(s, _)| !s.label.is_empty());
    let widest = labelled
        .clone()
        .map(|(s, _)| text_box(&s.label, LEGEND_SIZE as f64).0)
        .fold(0.0f32, f32::max) as f64;
    let rows = labelled.count() as f64;
    let (pw, ph) = (plot.0.max(1) as f64, plot.1.max(1) as f64);
    let w = widest + 60.0;
    let h = 14.0 + rows * (LEGEND_SIZE as f64 + 9.0);
    let fw = ((w + 12.0) / pw).min(1.0);
    let fh = ((h + 12.0) / ph).min(1.0);

    // Sample the data as drawn: the points, and along lines every few pixels.
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for (s, y) in items {
        for seg in segments(s, x, y) {
            let n: Vec<(f64, f64)> = seg.iter().map(|&(a, b)| (x.norm(a), y.norm(b))).collect();
            pts.extend(n.iter().copied());
            if s.style != SeriesStyle::Markers {
                for w in n.windows(2) {
                    let (du, dv) = (w[1].0 - w[0].0, w[1].1 - w[0].1);
                    let px = ((du * pw).hypot(dv * ph) / 3.0).ceil().min(2000.0) as usize;
                    for t in 1..px {
                        let t = t as f64 / px as f64;
                        pts.push((w[0].0 + t * du, w[0].1 + t * dv));
                    }
                }
            }
        }
    }
    let count = |right: bool, top: bool| {
        pts.iter()
            .filter(|&&(u, v)| {
                let in_x = if right { u >= 1.0 - fw } else { u <= fw };
                let in_y = if top { v >= 1.0 - fh } else { v <= fh };
                in_x && in_y && (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)
            })
            .count()
    };
    let candidates = [
        (SeriesLabelPosition::UpperRight, count(true, true)),
        (SeriesLabelPosition::UpperLeft, count(false, true)),
        (SeriesLabelPosition::LowerRight, count(true, false)),
        (SeriesLabelPosition::LowerLeft, count(false, false)),
    ];
    let (pos, hits) = candidates
        .into_iter()
        .min_by_key(|(_, n)| *n)
        .unwrap_or((SeriesLabelPosition::UpperRight, 0));
    (pos, hits, fh)
}

// ---------------------------------------------------------------------------
// Heatmaps

struct Grid<'a> {
    x: &'a [f64],
    y: &'a [f64],
    z: &'a [Vec<f64>],
}

type Segment = [(f64, f64); 2];

/// Index `i` and weight `t` with `v` between `g[i]` and `g[i+1]` (clamped).
fn locate(g: &[f64], v: f64) -> (usize, f64) {
    let n = g.len();
    let i = g.partition_point(|&a| a <= v).clamp(1, n - 1) - 1;
    let t = ((v - g[i]) / (g[i + 1] - g[i])).clamp(0.0, 1.0);
    (i, t)
}

impl Grid<'_> {
    /// z at `(xv, yv)`, bilinear between finite nodes, else the nearest node.
    fn sample(&self, (i, t): (usize, f64), (j, u): (usize, f64)) -> f64 {
        let z00 = self.z[j][i];
        let z10 = self.z[j][i + 1];
        let z01 = self.z[j + 1][i];
        let z11 = self.z[j + 1][i + 1];
        if z00.is_finite() && z10.is_finite() && z01.is_finite() && z11.is_finite() {
            (1.0 - u) * ((1.0 - t) * z00 + t * z10) + u * ((1.0 - t) * z01 + t * z11)
        } else {
            let ii = if t < 0.5 { i } else { i + 1 };
            let jj = if u < 0.5 { j } else { j + 1 };
            self.z[jj][ii]
        }
    }

    /// Marching-squares segments of the level `c`.
    fn contour(&self, c: f64) -> Vec<Segment> {
        let mut out = Vec::new();
        for j in 0..self.y.len() - 1 {
            for i in 0..self.x.len() - 1 {
                // Corners counter-clockwise from (i, j).
                let p = [
                    (self.x[i], self.y[j], self.z[j][i]),
                    (self.x[i + 1], self.y[j], self.z[j][i + 1]),
                    (self.x[i + 1], self.y[j + 1], self.z[j + 1][i + 1]),
                    (self.x[i], self.y[j + 1], self.z[j + 1][i]),
                ];
                if p.iter().any(|q| !q.2.is_finite()) {
                    continue;
                }
                let above: Vec<bool> = p.iter().map(|q| q.2 >= c).collect();
                // Crossing points on the edges k -> k+1.
                let cross = |k: usize| -> Option<(f64, f64)> {
                    let (a, b) = (p[k], p[(k + 1) % 4]);
                    if above[k] == above[(k + 1) % 4] {
                        return None;
                    }
                    let t = (c - a.2) / (b.2 - a.2);
                    Some((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)))
                };
                let e: Vec<Option<(f64, f64)>> = (0..4).map(cross).collect();
                let hits: Vec<(usize, (f64, f64))> = e
                    .iter()
                    .enumerate()
                    .filter_map(|(k, q)| q.map(|q| (k, q)))
                    .collect();
                match hits.len() {
                    2 => out.push([hits[0].1, hits[1].1]),
                    4 => {
                        // Saddle: the centre value decides which corners connect.
                        let centre = p.iter().map(|q| q.2).sum::<f64>() / 4.0;
                        let pts: Vec<(f64, f64)> = hits.iter().map(|h| h.1).collect();
                        if (centre >= c) == above[0] {
                            out.push([pts[0], pts[1]]);
                            out.push([pts[2], pts[3]]);
                        } else {
                            out.push([pts[3], pts[0]]);
                            out.push([pts[1], pts[2]]);
                        }
                    }
                    _ => {}
                }
            }
        }
        out
    }
}

struct HeatSpec<'a> {
    x_label: &'a str,
    y_label: &'a str,
    z_label: &'a str,
    grid: &'a Grid<'a>,
    z_range: (f64, f64),
    contours: &'a [Vec<Segment>],
    overlays: &'a [Series],
    equal_aspect: bool,
}

fn colour_of(v: f64, (lo, hi): (f64, f64)) -> RGBColor {
    if !v.is_finite() {
        return MISSING;
    }
    let t = ((v - lo) / (hi - lo)).clamp(0.0, 1.0);
    ViridisRGB.get_color(t as f32)
}

fn draw_heatmap<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, s: &HeatSpec) -> Result<()> {
    let g = s.grid;
    let (x0, x1) = (g.x[0], g.x[g.x.len() - 1]);
    let (y0, y1) = (g.y[0], g.y[g.y.len() - 1]);
    let x_axis = Axis::new(x0, x1, false);
    let y_axis = Axis::new(y0, y1, false);

    let z_axis = Axis::new(s.z_range.0, s.z_range.1, false);
    // Layout, left to right: y labels, map, gap, colour bar, its tick labels
    // and its rotated description; the whole group is centred.
    let (aw, ah) = area.dim_in_pixel();
    let y_area = y_label_area(&y_axis, s.y_label);
    let z_ticks = widest_tick(&z_axis) + 12;
    let z_desc = if s.z_label.is_empty() {
        0
    } else {
        text_box(s.z_label, DESC_SIZE as f64).1.ceil() as u32 + 10
    };
    let (cbar_w, gap) = (24u32, 36u32);
    let fixed_w = 2 * MARGIN + y_area + gap + cbar_w + z_ticks + z_desc;
    let (mut top, mut bottom) = (8u32, MARGIN);
    let avail_w = aw.saturating_sub(fixed_w) as f64;
    let avail_h = ah.saturating_sub(X_AREA + top + bottom) as f64;
    let ratio = (x1 - x0) / (y1 - y0);
    let mut plot_w = avail_w;
    if s.equal_aspect && (0.2..=5.0).contains(&ratio) && avail_w > 0.0 && avail_h > 0.0 {
        plot_w = avail_w.min(avail_h * ratio);
        let ey = (avail_h - plot_w / ratio).max(0.0) as u32;
        top += ey / 2;
        bottom += ey - ey / 2;
    }
    let plot_w = plot_w.max(1.0) as u32;
    let pad = aw.saturating_sub(fixed_w + plot_w) / 2;
    let split = pad + MARGIN + y_area + plot_w + gap;
    let (main, bar) = area.split_horizontally(split as i32);
    let (left, right) = (pad + MARGIN, gap);

    let mut chart = ChartBuilder::on(&main)
        .margin_left(left)
        .margin_right(right)
        .margin_top(top)
        .margin_bottom(bottom)
        .x_label_area_size(X_AREA)
        .y_label_area_size(y_area)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(drawing)?;

    // The map: one image at the plot's own resolution.
    let (pw, ph) = chart.plotting_area().dim_in_pixel();
    if pw > 0 && ph > 0 {
        let cols: Vec<(usize, f64)> = (0..pw)
            .map(|i| locate(g.x, x0 + (i as f64 + 0.5) / pw as f64 * (x1 - x0)))
            .collect();
        let mut rgb = Vec::with_capacity(pw as usize * ph as usize * 3);
        for j in 0..ph {
            let row = locate(g.y, y1 - (j as f64 + 0.5) / ph as f64 * (y1 - y0));
            for col in &cols {
                let RGBColor(r, gr, b) = colour_of(g.sample(*col, row), s.z_range);
                rgb.extend_from_slice(&[r, gr, b]);
            }
        }
        let image = BitMapElement::with_owned_buffer((x0, y1), (pw, ph), rgb)
            .ok_or_else(|| anyhow!("heatmap image buffer has the wrong size"))?;
        chart.draw_series(std::iter::once(image)).map_err(drawing)?;
    }

    let x_fmt = |v: &f64| x_axis.tick_label(*v);
    let y_fmt = |v: &f64| y_axis.tick_label(*v);
    chart
        .configure_mesh()
        .disable_mesh()
        .set_all_tick_mark_size(5)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style((FONT, TICK_SIZE))
        .axis_desc_style((FONT, DESC_SIZE))
        .x_labels(10)
        .y_labels(10)
        .x_desc(s.x_label)
        .y_desc(s.y_label)
        .draw()
        .map_err(drawing)?;

    for segs in s.contours {
        chart
            .draw_series(
                segs.iter()
                    .map(|sg| PathElement::new(sg.to_vec(), WHITE.stroke_width(2))),
            )
            .map_err(drawing)?;
    }
    for (k, o) in s.overlays.iter().enumerate() {
        let colour = OVERLAY_PALETTE[k % OVERLAY_PALETTE.len()];
        draw_series(&mut chart, o, k, colour, &x_axis, &y_axis)?;
    }
    if s.overlays.iter().any(|o| !o.label.is_empty()) {
        let (w, h) = chart.plotting_area().dim_in_pixel();
        let pos = legend_position(s.overlays, &x_axis, &y_axis, (w, h));
        chart
            .configure_series_labels()
            .position(pos)
            .margin(10)
            .label_font((FONT, LEGEND_SIZE))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()
            .map_err(drawing)?;
    }

    // Colour bar, aligned with the plot area.
    let (z0, z1) = s.z_range;
    let mut cbar = ChartBuilder::on(&bar)
        .margin_left(0)
        .margin_top(top)
        .margin_bottom(bottom + X_AREA)
        .right_y_label_area_size(z_ticks + z_desc)
        .margin_right(
            bar.dim_in_pixel()
                .0
                .saturating_sub(cbar_w + z_ticks + z_desc),
        )
        .build_cartesian_2d(0.0..1.0, z0..z1)
        .map_err(drawing)?;
    const STEPS: usize = 128;
    cbar.draw_series((0..STEPS).map(|k| {
        let a = z0 + (z1 - z0) * k as f64 / STEPS as f64;
        let b = z0 + (z1 - z0) * (k + 1) as f64 / STEPS as f64;
        let c = colour_of(0.5 * (a + b), s.z_range);
        Rectangle::new([(0.0, a), (1.0, b)], c.filled())
    }))
    .map_err(drawing)?;
    let z_fmt = |v: &f64| z_axis.tick_label(*v);
    cbar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .set_all_tick_mark_size(5)
        .y_label_formatter(&z_fmt)
        .label_style((FONT, TICK_SIZE))
        .y_labels(8)
        .draw()
        .map_err(drawing)?;
    if !s.z_label.is_empty() {
        // Reads bottom to top, like the y description of the map.
        let style = TextStyle::from((FONT, DESC_SIZE).into_font())
            .transform(FontTransform::Rotate270)
            .pos(Pos::new(HPos::Center, VPos::Top));
        let map_h = ah.saturating_sub(top + bottom + X_AREA);
        let at = ((cbar_w + z_ticks) as i32, (top + map_h / 2) as i32);
        bar.draw_text(s.z_label, &style, at).map_err(drawing)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn test_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("ehl-plot-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Width and height from a PNG header, after checking its signature.
    fn png_size(path: &Path) -> (u32, u32) {
        let bytes = std::fs::read(path).unwrap();
        assert!(bytes.len() > 33, "{} is too short", path.display());
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
        assert_eq!(&bytes[12..16], b"IHDR");
        let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
        let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
        (w, h)
    }

    fn check_outputs(stem: &Path, title: &str, size: (u32, u32)) -> String {
        assert_eq!(png_size(&with_ext(stem, "png")), size);
        let svg = std::fs::read_to_string(with_ext(stem, "svg")).unwrap();
        assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
        assert!(svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains(title), "title missing from the SVG");
        svg
    }

    fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
            .collect()
    }

    /// An EHL-like pressure map: Hertz dome plus an outlet spike, zero outside.
    fn pressure_map(n: usize) -> (Vec<f64>, Vec<f64>, Vec<Vec<f64>>) {
        let x = linspace(-4.5, 1.5, n);
        let y = linspace(-3.0, 3.0, n);
        let z = y
            .iter()
            .map(|&yy| {
                x.iter()
                    .map(|&xx| {
                        let r2 = xx * xx + yy * yy;
                        let dome = (1.0 - r2).max(0.0).sqrt();
                        let spike =
                            0.6 * (-((xx - 0.85) / 0.04).powi(2)).exp() * (1.0 - yy * yy).max(0.0);
                        dome + spike
                    })
                    .collect()
            })
            .collect();
        (x, y, z)
    }

    #[test]
    fn line_chart_writes_svg_and_png() {
        let stem = test_dir("line").join("q_delta");
        let x = linspace(0.0, 10.0, 30);
        let y: Vec<f64> = x.iter().map(|d| 3.0 * d.powf(1.5)).collect();
        let series = [
            Series::markers("computed", x.clone(), y.clone()),
            Series::line("fit Q = K δ^1.5", x, y),
        ];
        line_chart(&stem, "Load against approach", "δ (µm)", "Q (N)", &series).unwrap();
        check_outputs(
            &stem,
            "Load against approach",
            (FIGURE_WIDTH, FIGURE_HEIGHT),
        );
        let _ = std::fs::remove_dir_all(stem.parent().unwrap());
    }

    #[test]
    fn log_axes_and_explicit_ranges() {
        let stem = test_dir("log").join("k");
        let w = linspace(10.0, 1000.0, 20);
        let series: Vec<Series> = [1.0, 2.0, 4.0]
            .iter()
            .map(|u| {
                let k = w.iter().map(|w| 1e8 * u * w.powf(1.0 / 3.0)).collect();
                Series::new(
                    format!("u = {u} m/s"),
                    w.clone(),
                    k,
                    SeriesStyle::LineAndMarkers,
                )
            })
            .collect();
        let opts = ChartOptions {
            x_log: true,
            y_log: true,
            ..Default::default()
        };
        line_chart_with(&stem, "Stiffness", "Q (N)", "K (N/m)", &series, &opts).unwrap();
        check_outputs(&stem, "Stiffness", (FIGURE_WIDTH, FIGURE_HEIGHT));

        let opts = ChartOptions {
            x_range: Some((0.0, 500.0)),
            y_range: Some((0.0, 2e9)),
            ..Default::default()
        };
        line_chart_with(&stem, "Ranged", "Q (N)", "K (N/m)", &series, &opts).unwrap();
        check_outputs(&stem, "Ranged", (FIGURE_WIDTH, FIGURE_HEIGHT));

        // Non-positive data on a log axis is skipped, not an error.
        let s = [Series::line(
            "a",
            vec![-1.0, 0.0, 1.0, 10.0],
            vec![1.0, 2.0, 3.0, 4.0],
        )];
        let opts = ChartOptions {
            x_log: true,
            ..Default::default()
        };
        line_chart_with(&stem, "Skip", "x", "y", &s, &opts).unwrap();
        let _ = std::fs::remove_dir_all(stem.parent().unwrap());
    }

    #[test]
    fn stacked_charts_write_svg_and_png() {
        let stem = test_dir("stacked").join("dq");
        let t = linspace(0.0, 1e-3, 200);
        let d: Vec<f64> = t.iter().map(|t| 1.0 + 0.2 * (2e4 * t).sin()).collect();
        let q: Vec<f64> = d.iter().map(|d| 500.0 * d.powf(1.5)).collect();
        let panels = vec![
            ("δ (µm)".to_string(), vec![Series::line("δ", t.clone(), d)]),
            ("Q (N)".to_string(), vec![Series::line("Q", t, q)]),
        ];
        stacked_charts(&stem, "Approach and load", "t (s)", &panels).unwrap();
        check_outputs(
            &stem,
            "Approach and load",
            (FIGURE_WIDTH, stacked_height(2)),
        );
        let _ = std::fs::remove_dir_all(stem.parent().unwrap());
    }

    #[test]
    fn dual_axis_chart_writes_svg_and_png() {
        let stem = test_dir("dual").join("profile");
        let x = linspace(-4.5, 1.5, 200);
        let p: Vec<f64> = x.iter().map(|x| (1.0 - x * x).max(0.0).sqrt()).collect();
        let h: Vec<f64> = x.iter().map(|x| 0.3 + 0.2 * x * x).collect();
        let left = [Series::line("P", x.clone(), p)];
        let right = [Series::line("h", x, h)];
        dual_axis_chart(&stem, "Profiles", "X", ("P", &left), ("h (µm)", &right)).unwrap();
        check_outputs(&stem, "Profiles", (FIGURE_WIDTH, FIGURE_HEIGHT));
        // One side empty is fine; both empty or uneven is an error.
        dual_axis_chart(&stem, "Left only", "X", ("P", &left), ("h", &[])).unwrap();
        assert!(dual_axis_chart(&stem, "t", "X", ("P", &[]), ("h", &[])).is_err());
        let uneven = [Series::line("u", vec![1.0, 2.0], vec![1.0])];
        assert!(dual_axis_chart(&stem, "t", "X", ("P", &left), ("h", &uneven)).is_err());
        let _ = std::fs::remove_dir_all(stem.parent().unwrap());
    }

    #[test]
    fn heatmap_writes_svg_and_png() {
        let stem = test_dir("heat").join("p");
        let (x, y, z) = pressure_map(65);
        heatmap(
            &stem,
            "Pressure",
            "X = x/a",
            "Y = y/b",
            &x,
            &y,
            &z,
            "P = p/p_H",
        )
        .unwrap();
        let svg = check_outputs(&stem, "Pressure", (FIGURE_WIDTH, FIGURE_HEIGHT));
        assert!(svg.contains("data:image/png;base64,"), "map not embedded");
        let _ = std::fs::remove_dir_all(stem.parent().unwrap());
    }

    #[test]
    fn large_heatmap_with_contour_and_overlay() {
        let stem = test_dir("heat513").join("p");
        let (x, y, z) = pressure_map(513);
        let t = linspace(0.0, std::f64::consts::TAU, 100);
        let opts = HeatmapOptions {
            contour_levels: vec![0.05],
            overlays: vec![Series::line(
                "Hertz ellipse",
                t.iter().map(|t| t.cos()).collect(),
                t.iter().map(|t| t.sin()).collect(),
            )],
            ..Default::default()
        };
        heatmap_with(&stem, "Pressure 513", "X", "Y", &x, &y, &z, "P", &opts).unwrap();
        let svg = check_outputs(&stem, "Pressure 513", (FIGURE_WIDTH, FIGURE_HEIGHT));
        assert!(svg.len() < 4_000_000, "SVG is {} bytes", svg.len());
        let _ = std::fs::remove_dir_all(stem.parent().unwrap());
    }

    #[test]
    fn nan_and_inf_do_not_panic() {
        let dir = test_dir("nan");
        let x = vec![0.0, 1.0, 2.0, f64::NAN, 4.0, 5.0, 6.0];
        let y = vec![1.0, f64::INFINITY, 3.0, 4.0, f64::NAN, 2.0, 1.0];
        let s = [
            Series::new("a", x.clone(), y.clone(), SeriesStyle::LineAndMarkers),
            Series::markers("b", y, x),
            Series::line("empty", vec![], vec![]),
        ];
        line_chart(&dir.join("line"), "NaN line", "x", "y", &s).unwrap();
        let panels = vec![
            ("a".to_string(), s.to_vec()),
            (
                "all NaN".to_string(),
                vec![Series::line("n", vec![f64::NAN], vec![1.0])],
            ),
        ];
        stacked_charts(&dir.join("stacked"), "NaN stacked", "x", &panels).unwrap();

        let (gx, gy, mut z) = pressure_map(33);
        z[3][4] = f64::NAN;
        z[10][10] = f64::INFINITY;
        z[20][5] = f64::NEG_INFINITY;
        heatmap(&dir.join("heat"), "NaN heat", "x", "y", &gx, &gy, &z, "z").unwrap();
        // A constant field still gets a usable colour scale.
        let flat = vec![vec![2.0; gx.len()]; gy.len()];
        heatmap(&dir.join("flat"), "Flat", "x", "y", &gx, &gy, &flat, "z").unwrap();
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn bad_input_is_an_error() {
        let stem = test_dir("bad").join("x");
        let ok = Series::line("ok", vec![0.0, 1.0], vec![0.0, 1.0]);
        let uneven = Series::line("uneven", vec![0.0, 1.0, 2.0], vec![0.0, 1.0]);
        assert!(line_chart(&stem, "t", "x", "y", &[]).is_err());
        assert!(line_chart(&stem, "t", "x", "y", &[ok.clone(), uneven.clone()]).is_err());
        let nan = Series::line("nan", vec![f64::NAN], vec![f64::NAN]);
        assert!(line_chart(&stem, "t", "x", "y", &[nan]).is_err());
        let empty = Series::line("empty", vec![], vec![]);
        assert!(line_chart(&stem, "t", "x", "y", &[empty]).is_err());
        let bad_range = ChartOptions {
            y_range: Some((1.0, 0.0)),
            ..Default::default()
        };
        assert!(
            line_chart_with(&stem, "t", "x", "y", std::slice::from_ref(&ok), &bad_range).is_err()
        );
        let bad_log = ChartOptions {
            x_log: true,
            x_range: Some((-1.0, 10.0)),
            ..Default::default()
        };
        assert!(
            line_chart_with(&stem, "t", "x", "y", std::slice::from_ref(&ok), &bad_log).is_err()
        );
        assert!(stacked_charts(&stem, "t", "x", &[]).is_err());
        assert!(stacked_charts(&stem, "t", "x", &[("y".into(), vec![uneven])]).is_err());

        let x = [0.0, 1.0, 2.0];
        let y = [0.0, 1.0];
        let z = vec![vec![0.0; 3]; 2];
        assert!(heatmap(&stem, "t", "x", "y", &x, &y, &z, "z").is_ok());
        let ragged = vec![vec![0.0; 3], vec![0.0; 2]];
        assert!(heatmap(&stem, "t", "x", "y", &x, &y, &ragged, "z").is_err());
        assert!(heatmap(&stem, "t", "x", "y", &x, &y, &z[..1], "z").is_err());
        assert!(heatmap(&stem, "t", "x", "y", &[2.0, 1.0, 0.0], &y, &z, "z").is_err());
        assert!(heatmap(&stem, "t", "x", "y", &[0.0], &[0.0], &[vec![1.0]], "z").is_err());
        let all_nan = vec![vec![f64::NAN; 3]; 2];
        assert!(heatmap(&stem, "t", "x", "y", &x, &y, &all_nan, "z").is_err());
        let _ = std::fs::remove_dir_all(stem.parent().unwrap());
    }

    #[test]
    fn extreme_ranges_do_not_hang_or_panic() {
        let dir = test_dir("extreme");
        let cases = [
            (vec![0.0, 1.0], vec![1e300, 1e300 * (1.0 + 1e-15)]),
            (vec![0.0, 1.0], vec![1e-300, 2e-300]),
            (vec![0.0, 1.0], vec![5.0, 5.0]),
            (vec![0.0, 1.0], vec![0.0, 0.0]),
            (vec![1e-9, 2e-9], vec![-1e-12, 1e-12]),
        ];
        for (k, (x, y)) in cases.into_iter().enumerate() {
            let s = [Series::line("s", x, y)];
            line_chart(&dir.join(format!("c{k}")), "extreme", "x", "y", &s).unwrap();
        }
        let s = [Series::line("s", vec![0.0, 1.0], vec![-1e308, 1e308])];
        assert!(line_chart(&dir.join("overflow"), "extreme", "x", "y", &s).is_err());
        let log = ChartOptions {
            y_log: true,
            ..Default::default()
        };
        let s = [Series::line(
            "s",
            vec![0.0, 1.0, 2.0],
            vec![1e-300, 1.0, 1e300],
        )];
        line_chart_with(&dir.join("log"), "extreme", "x", "y", &s, &log).unwrap();
        let wide = ChartOptions {
            y_log: true,
            y_range: Some((1e-100, 1e100)),
            ..Default::default()
        };
        assert!(line_chart_with(&dir.join("log"), "extreme", "x", "y", &s, &wide).is_err());
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn tick_labels_are_short() {
        let lin = Axis::new(-1.0, 2.0, false);
        assert_eq!(lin.tick_label(0.30000000000000004), "0.3");
        assert_eq!(lin.tick_label(5.551115123125783e-17), "0");
        assert_eq!(lin.tick_label(-2.0), "-2");
        assert_eq!(lin.tick_label(f64::NAN), "");
        let time = Axis::new(0.0, 2e-3, false);
        assert_eq!(time.tick_label(5e-4), "0.0005");
        assert_eq!(time.tick_label(1.5e-3), "0.0015");
        let film = Axis::new(0.0, 1e-6, false);
        assert_eq!(film.tick_label(1.5e-7), "1.5e-7");
        assert_eq!(film.tick_label(0.0), "0");
        let stiff = Axis::new(5e8, 3e9, false);
        assert_eq!(stiff.tick_label(2e9), "2e9");
        assert_eq!(stiff.tick_label(2.5e9), "2.5e9");
        let log = Axis::new(50.0, 3000.0, true);
        assert_eq!(log.tick_label(200.0), "200");
        assert_eq!(log.tick_label(1000.0), "1000");
        assert_eq!(log.tick_label(700.0), "");
        assert_eq!(Axis::new(1e-8, 1e-5, true).tick_label(2e-7), "2e-7");
    }

    #[test]
    fn contour_of_a_cone_is_a_circle() {
        let x = linspace(-2.0, 2.0, 81);
        let y = x.clone();
        let z: Vec<Vec<f64>> = y
            .iter()
            .map(|b| x.iter().map(|a| (a * a + b * b).sqrt()).collect())
            .collect();
        let g = Grid {
            x: &x,
            y: &y,
            z: &z,
        };
        let segs = g.contour(1.0);
        assert!(segs.len() > 50);
        for p in segs.iter().flatten() {
            let r = (p.0 * p.0 + p.1 * p.1).sqrt();
            assert!((r - 1.0).abs() < 0.01, "r = {r}");
        }
    }

    /// Renders one example of each kind to /tmp/plot-demo for a visual check:
    /// `cargo test -p ehl-bearing-cli plot::tests::demo -- --ignored`.
    #[test]
    #[ignore]
    fn demo() {
        let dir = Path::new("/tmp/plot-demo");
        std::fs::create_dir_all(dir).unwrap();

        let d = linspace(0.0, 12.0, 13);
        let q: Vec<f64> = d
            .iter()
            .enumerate()
            .map(|(k, d)| 21.5 * d.powf(1.5) * (1.0 + 0.03 * ((k * 7 % 5) as f64 - 2.0) / 2.0))
            .collect();
        let df = linspace(0.0, 12.0, 100);
        let fit: Vec<f64> = df.iter().map(|d| 21.5 * d.powf(1.5)).collect();
        line_chart(
            &dir.join("q_delta"),
            "Contact load against mutual approach",
            "δ (µm)",
            "Q (N)",
            &[
                Series::markers("EHL solution", d, q),
                Series::line("fit Q = 21.5 δ^1.5", df, fit),
            ],
        )
        .unwrap();

        let load = linspace(50.0, 2000.0, 12);
        let speeds = [0.5, 2.0, 8.0];
        let k: Vec<Series> = speeds
            .iter()
            .map(|u| {
                let v = load
                    .iter()
                    .map(|q| 2.1e8 * q.powf(1.0 / 3.0) * (1.0 - 0.02 * u))
                    .collect();
                Series::new(
                    format!("u = {u} m/s"),
                    load.clone(),
                    v,
                    SeriesStyle::LineAndMarkers,
                )
            })
            .collect();
        line_chart(
            &dir.join("stiffness"),
            "Contact stiffness",
            "Q (N)",
            "K (N/m)",
            &k,
        )
        .unwrap();
        let lift: Vec<Series> = speeds
            .iter()
            .map(|u| {
                let v = load.iter().map(|q| 0.05 * u * q.powf(0.6)).collect();
                Series::new(
                    format!("u = {u} m/s"),
                    load.clone(),
                    v,
                    SeriesStyle::LineAndMarkers,
                )
            })
            .collect();
        line_chart_with(
            &dir.join("lift_log"),
            "Lift force (log–log)",
            "Q (N)",
            "ΔF (N)",
            &lift,
            &ChartOptions {
                x_log: true,
                y_log: true,
                ..Default::default()
            },
        )
        .unwrap();

        let t = linspace(0.0, 2e-3, 400);
        let delta: Vec<f64> = t.iter().map(|t| 8.0 + 2.0 * (6283.0 * t).sin()).collect();
        let qq: Vec<f64> = delta.iter().map(|d| 21.5 * d.powf(1.5)).collect();
        let qs: Vec<f64> = delta.iter().map(|d| 21.5 * (d - 0.3).powf(1.5)).collect();
        stacked_charts(
            &dir.join("stacked"),
            "Approach and load in time",
            "t (s)",
            &[
                (
                    "δ (µm)".to_string(),
                    vec![Series::line("δ", t.clone(), delta)],
                ),
                (
                    "Q (N)".to_string(),
                    vec![
                        Series::line("EHL", t.clone(), qq),
                        Series::line("Hertz", t, qs),
                    ],
                ),
            ],
        )
        .unwrap();

        let (x, y, z) = pressure_map(257);
        let th = linspace(0.0, std::f64::consts::TAU, 120);
        heatmap_with(
            &dir.join("pressure_map"),
            "EHL pressure",
            "X = x/a",
            "Y = y/b",
            &x,
            &y,
            &z,
            "P = p/p_H",
            &HeatmapOptions {
                contour_levels: vec![0.5],
                overlays: vec![Series::line(
                    "Hertz contact",
                    th.iter().map(|t| t.cos()).collect(),
                    th.iter().map(|t| t.sin()).collect(),
                )],
                ..Default::default()
            },
        )
        .unwrap();
        let film: Vec<Vec<f64>> = y
            .iter()
            .map(|&b| {
                x.iter()
                    .map(|&a| {
                        let r2 = a * a + b * b;
                        if r2 < 1.0 {
                            0.35e-6 - 0.1e-6 * (-((a - 0.8) / 0.1).powi(2)).exp() + 0.05e-6 * b * b
                        } else {
                            0.35e-6 + 0.5e-6 * (r2 - 1.0)
                        }
                    })
                    .collect()
            })
            .collect();
        heatmap_with(
            &dir.join("film_map"),
            "EHL film thickness",
            "x (mm)",
            "y (mm)",
            &x.iter().map(|v| v * 0.2).collect::<Vec<_>>(),
            &y.iter().map(|v| v * 0.2).collect::<Vec<_>>(),
            &film,
            "h (m)",
            &HeatmapOptions {
                z_range: Some((0.0, 1.0e-6)),
                ..Default::default()
            },
        )
        .unwrap();
        let mid = y.len() / 2;
        dual_axis_chart(
            &dir.join("centre_line_dual"),
            "Centre-line pressure and film",
            "X = x/a",
            (
                "P = p/p_H",
                &[Series::line("pressure", x.clone(), z[mid].clone())],
            ),
            (
                "h (µm)",
                &[Series::line(
                    "film",
                    x.clone(),
                    film[mid].iter().map(|h| h * 1e6).collect(),
                )],
            ),
        )
        .unwrap();
        stacked_charts(
            &dir.join("centre_line"),
            "Centre-line profiles",
            "X = x/a",
            &[
                (
                    "P = p/p_H".to_string(),
                    vec![Series::line("P", x.clone(), z[mid].clone())],
                ),
                (
                    "h (µm)".to_string(),
                    vec![Series::line(
                        "h",
                        x.clone(),
                        film[mid].iter().map(|h| h * 1e6).collect(),
                    )],
                ),
            ],
        )
        .unwrap();
    }
}
