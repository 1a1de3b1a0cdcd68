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
const FONT_BYTES: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
const TITLE_SIZE: u32 = 26;
const DESC_SIZE: u32 = 20;
const TICK_SIZE: u32 = 16;
const LEGEND_SIZE: u32 = 16;
const MARGIN: u32 = 15;
const X_AREA: u32 = 60;
/// Most tick labels on an x axis and on a y axis.
const X_LABELS: usize = 10;
const Y_LABELS: usize = 8;

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
    /// A dashed line (e.g. a fit extrapolated beyond its data).
    Dashed,
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
#[allow(dead_code)] // generic API, used by the tests
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

/// Options of [`stacked_charts_with`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StackedOptions {
    /// Logarithmic x axis (non-positive x values are skipped).
    pub x_log: bool,
    /// Explicit x range `(min, max)`; automatic when `None`.
    pub x_range: Option<(f64, f64)>,
    /// Explicit y range of each panel (missing or `None`: automatic).
    pub y_ranges: Vec<Option<(f64, f64)>>,
    /// Relative heights of the panels (missing or empty: equal).
    pub heights: Vec<f64>,
    /// When a legend would cover data in some panel, raise the top of every panel's y range
    /// by the same fraction to make room above the data, explicit ranges included (panels
    /// given one y range stay on one scale). Without it explicit ranges are never changed.
    pub shared_legend_room: bool,
}

/// Options of [`dual_axis_chart_with`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DualOptions {
    /// Explicit x range `(min, max)`; automatic when `None`.
    pub x_range: Option<(f64, f64)>,
    /// Explicit range of the left y axis; automatic when `None`.
    pub y_left: Option<(f64, f64)>,
    /// Explicit range of the right y axis; automatic when `None`.
    pub y_right: Option<(f64, f64)>,
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

mod axes;
mod backend;
mod charts;
pub mod contact;
pub mod fields;
mod heatmap;
mod panel;
pub mod study;
#[cfg(test)]
mod tests;

use axes::*;
use backend::*;
pub use charts::*;
pub use heatmap::*;
use panel::*;
