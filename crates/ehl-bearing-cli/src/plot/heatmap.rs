//! Colour maps of a field on a regular grid.

use super::*;
use plotters::coord::types::RangedCoordf64;

/// What a heat map shows: `z[j][i]` at `(x[i], y[j])` on a regular grid (`x` and `y`
/// increasing), with the figure's title and the labels of its axes and of its colour bar.
#[derive(Clone, Copy, Debug)]
pub struct HeatmapData<'a> {
    /// Title of the figure.
    pub title: &'a str,
    /// Label of the x axis.
    pub x_label: &'a str,
    /// Label of the y axis.
    pub y_label: &'a str,
    /// Abscissae of the grid, increasing.
    pub x: &'a [f64],
    /// Ordinates of the grid, increasing.
    pub y: &'a [f64],
    /// Values: `z[j][i]` at `(x[i], y[j])`, one row per ordinate.
    pub z: &'a [Vec<f64>],
    /// Label of the colour bar.
    pub z_label: &'a str,
}

/// A colour map (viridis) of `map.z` on its regular grid with a colour bar labelled
/// `map.z_label`, written as `<stem>.svg` and `<stem>.png` ([`FIGURE_WIDTH`] × [`FIGURE_HEIGHT`]
/// px). The map is bilinearly interpolated at the output resolution, so any grid size works
/// (513 × 513 included); the SVG embeds it as one PNG image. Non-finite cells are grey. Axes use
/// equal scales (see [`HeatmapOptions`]).
#[allow(dead_code)] // generic API, used by the tests
pub fn heatmap(stem: &Path, map: &HeatmapData) -> Result<()> {
    heatmap_with(stem, map, &HeatmapOptions::default())
}

/// [`heatmap`] with options: colour range, contour levels, overlaid curves, aspect.
pub fn heatmap_with(stem: &Path, map: &HeatmapData, options: &HeatmapOptions) -> Result<()> {
    check_heatmap(map, options)?;
    let z_range = colour_range(map, options.z_range)?;
    let grid = Grid {
        x: map.x,
        y: map.y,
        z: map.z,
    };
    let contours: Vec<Vec<Segment>> = options
        .contour_levels
        .iter()
        .filter(|c| c.is_finite())
        .map(|&c| grid.contour(c))
        .collect();
    let spec = HeatSpec {
        x_label: map.x_label,
        y_label: map.y_label,
        z_label: map.z_label,
        grid: &grid,
        z_range,
        contours: &contours,
        overlays: &options.overlays,
        equal_aspect: options.equal_aspect,
    };
    save_both(
        stem,
        (FIGURE_WIDTH, FIGURE_HEIGHT),
        &HeatFig {
            title: map.title,
            spec,
        },
    )
}

/// The grid's axes are increasing, `z` has one row of `x.len()` values per ordinate, and the
/// overlays are well formed; the error names the figure and what does not fit.
fn check_heatmap(map: &HeatmapData, options: &HeatmapOptions) -> Result<()> {
    let title = map.title;
    check_grid_axis(map.x, "x")?;
    check_grid_axis(map.y, "y")?;
    ensure!(
        map.z.len() == map.y.len(),
        "heatmap '{title}': z has {} rows but y has {} values",
        map.z.len(),
        map.y.len()
    );
    for (j, row) in map.z.iter().enumerate() {
        ensure!(
            row.len() == map.x.len(),
            "heatmap '{title}': z row {j} has {} values but x has {}",
            row.len(),
            map.x.len()
        );
    }
    check_series(&options.overlays).context("heatmap overlays")?;
    Ok(())
}

/// The z range of the colour scale: the given one (finite and increasing), else the range of
/// the finite values, widened by 5 % of the value (or by 1 at 0) when the field is constant.
fn colour_range(map: &HeatmapData, given: Option<(f64, f64)>) -> Result<(f64, f64)> {
    let title = map.title;
    Ok(match given {
        Some((a, b)) => {
            ensure!(
                a.is_finite() && b.is_finite() && a < b,
                "heatmap '{title}': z range ({a}, {b}) must be finite and increasing"
            );
            (a, b)
        }
        None => {
            let (lo, hi) = finite_min_max(map.z.iter().flatten().copied())
                .ok_or_else(|| anyhow!("heatmap '{title}': no finite z value"))?;
            if lo < hi {
                (lo, hi)
            } else {
                let d = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
                (lo - d, hi + d)
            }
        }
    })
}

pub(crate) struct HeatFig<'a> {
    pub(crate) title: &'a str,
    pub(crate) spec: HeatSpec<'a>,
}

impl Figure for HeatFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let area = title_area(root, self.title)?;
        draw_heatmap(&area, &self.spec)
    }
}

// ---------------------------------------------------------------------------
// Heatmaps

pub(crate) struct Grid<'a> {
    pub(crate) x: &'a [f64],
    pub(crate) y: &'a [f64],
    pub(crate) z: &'a [Vec<f64>],
}

pub(crate) type Segment = [(f64, f64); 2];

/// Index `i` and weight `t` with `v` between `g[i]` and `g[i+1]` (clamped).
pub(crate) fn locate(g: &[f64], v: f64) -> (usize, f64) {
    let n = g.len();
    let i = g.partition_point(|&a| a <= v).clamp(1, n - 1) - 1;
    let t = ((v - g[i]) / (g[i + 1] - g[i])).clamp(0.0, 1.0);
    (i, t)
}

impl Grid<'_> {
    /// z at `(xv, yv)`, bilinear between finite nodes, else the nearest node.
    pub(crate) fn sample(&self, (i, t): (usize, f64), (j, u): (usize, f64)) -> f64 {
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
    pub(crate) fn contour(&self, c: f64) -> Vec<Segment> {
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

pub(crate) struct HeatSpec<'a> {
    pub(crate) x_label: &'a str,
    pub(crate) y_label: &'a str,
    pub(crate) z_label: &'a str,
    pub(crate) grid: &'a Grid<'a>,
    pub(crate) z_range: (f64, f64),
    pub(crate) contours: &'a [Vec<Segment>],
    pub(crate) overlays: &'a [Series],
    pub(crate) equal_aspect: bool,
}

pub(crate) fn colour_of(v: f64, (lo, hi): (f64, f64)) -> RGBColor {
    if !v.is_finite() {
        return MISSING;
    }
    let t = ((v - lo) / (hi - lo)).clamp(0.0, 1.0);
    ViridisRGB.get_color(t as f32)
}

/// The chart of a heat map: linear axes in the grid's coordinates.
type MapChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Width of the colour bar, px.
const CBAR_W: u32 = 24;
/// Gap between the map and the colour bar, px.
const CBAR_GAP: u32 = 36;

/// Pixel layout of a heat map, left to right: y labels, map, gap, colour bar, its tick labels
/// and its rotated description; the whole group is centred. With equal scales the map is
/// narrowed or its top and bottom margins widened so that one unit of x and of y has the same
/// length.
struct HeatLayout {
    /// Margin above the map's plot area, px.
    top: u32,
    /// Margin below the map's x labels, px.
    bottom: u32,
    /// Left margin of the map (centring pad and figure margin), px.
    left: u32,
    /// Width of the y labels and description, px.
    y_area: u32,
    /// Where the area is split between the map and the colour bar, px from the left.
    split: u32,
    /// Width of the colour bar's tick labels, px.
    z_ticks: u32,
    /// Width of the colour bar's description, px (0 without one).
    z_desc: u32,
    /// Height of the map's plot area, px.
    map_h: u32,
}

impl HeatLayout {
    /// The layout of `s` in an area of `(aw, ah)` px, with the map's y axis and the colour
    /// bar's axis (their tick labels set widths).
    fn new((aw, ah): (u32, u32), s: &HeatSpec, y_axis: &Axis, z_axis: &Axis) -> Self {
        let g = s.grid;
        let (x0, x1) = (g.x[0], g.x[g.x.len() - 1]);
        let (y0, y1) = (g.y[0], g.y[g.y.len() - 1]);
        let y_area = y_label_area(y_axis, s.y_label);
        let z_ticks = widest_tick(z_axis) + 12;
        let z_desc = if s.z_label.is_empty() {
            0
        } else {
            text_box(s.z_label, DESC_SIZE as f64).1.ceil() as u32 + 10
        };
        let fixed_w = 2 * MARGIN + y_area + CBAR_GAP + CBAR_W + z_ticks + z_desc;
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
        Self {
            top,
            bottom,
            left: pad + MARGIN,
            y_area,
            split: pad + MARGIN + y_area + plot_w + CBAR_GAP,
            z_ticks,
            z_desc,
            map_h: ah.saturating_sub(top + bottom + X_AREA),
        }
    }
}

/// Draws the heat map `s` into `area`: the map with its axes, contours and overlays (with their
/// legend), and the colour bar beside it.
pub(crate) fn draw_heatmap<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    s: &HeatSpec,
) -> Result<()> {
    let g = s.grid;
    let (x0, x1) = (g.x[0], g.x[g.x.len() - 1]);
    let (y0, y1) = (g.y[0], g.y[g.y.len() - 1]);
    let x_axis = Axis::new(x0, x1, false);
    let y_axis = Axis::new(y0, y1, false);
    let z_axis = Axis::new(s.z_range.0, s.z_range.1, false);
    let layout = HeatLayout::new(area.dim_in_pixel(), s, &y_axis, &z_axis);
    let (main, bar) = area.split_horizontally(layout.split as i32);

    let mut chart = ChartBuilder::on(&main)
        .margin_left(layout.left)
        .margin_right(CBAR_GAP)
        .margin_top(layout.top)
        .margin_bottom(layout.bottom)
        .x_label_area_size(X_AREA)
        .y_label_area_size(layout.y_area)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(drawing)?;
    draw_map_image(&mut chart, s)?;
    draw_map_mesh(&mut chart, s, &x_axis, &y_axis)?;
    draw_contours_and_overlays(&mut chart, s, &x_axis, &y_axis)?;
    draw_colour_bar(&bar, s, &layout, &z_axis)
}

/// The map itself: one image at the plot area's own resolution, each pixel the colour of the
/// field sampled (bilinearly) at its centre.
fn draw_map_image<'a, DB: DrawingBackend + 'a>(
    chart: &mut MapChart<'a, DB>,
    s: &HeatSpec,
) -> Result<()> {
    let g = s.grid;
    let (x0, x1) = (g.x[0], g.x[g.x.len() - 1]);
    let (y0, y1) = (g.y[0], g.y[g.y.len() - 1]);
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
    Ok(())
}

/// The map's axes: tick marks, tick labels and descriptions, no grid lines.
fn draw_map_mesh<'a, DB: DrawingBackend + 'a>(
    chart: &mut MapChart<'a, DB>,
    s: &HeatSpec,
    x_axis: &Axis,
    y_axis: &Axis,
) -> Result<()> {
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
        .map_err(drawing)
}

/// The contour lines (white) and the overlaid curves over the map, and the legend of the
/// labelled overlays in the corner where it covers the fewest of their samples.
fn draw_contours_and_overlays<'a, DB: DrawingBackend + 'a>(
    chart: &mut MapChart<'a, DB>,
    s: &HeatSpec,
    x_axis: &Axis,
    y_axis: &Axis,
) -> Result<()> {
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
        draw_series(chart, o, k, colour, x_axis, y_axis)?;
    }
    if s.overlays.iter().any(|o| !o.label.is_empty()) {
        let (w, h) = chart.plotting_area().dim_in_pixel();
        let pos = legend_position(s.overlays, x_axis, y_axis, (w, h));
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

/// The colour bar in `bar`, aligned with the map's plot area: 128 bands of the colour scale,
/// its tick labels and its description (rotated, reading bottom to top).
fn draw_colour_bar<DB: DrawingBackend>(
    bar: &DrawingArea<DB, Shift>,
    s: &HeatSpec,
    layout: &HeatLayout,
    z_axis: &Axis,
) -> Result<()> {
    let (z0, z1) = s.z_range;
    let (z_ticks, z_desc) = (layout.z_ticks, layout.z_desc);
    let mut cbar = ChartBuilder::on(bar)
        .margin_left(0)
        .margin_top(layout.top)
        .margin_bottom(layout.bottom + X_AREA)
        .right_y_label_area_size(z_ticks + z_desc)
        .margin_right(
            bar.dim_in_pixel()
                .0
                .saturating_sub(CBAR_W + z_ticks + z_desc),
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
        let at = (
            (CBAR_W + z_ticks) as i32,
            (layout.top + layout.map_h / 2) as i32,
        );
        bar.draw_text(s.z_label, &style, at).map_err(drawing)?;
    }
    Ok(())
}
