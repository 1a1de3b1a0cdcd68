//! Line, stacked and dual-axis charts.

use super::*;

/// A 2-D line/scatter chart written as `<stem>.svg` and `<stem>.png`
/// ([`FIGURE_WIDTH`] × [`FIGURE_HEIGHT`] px), with automatic axis ranges.
#[allow(dead_code)] // generic API, used by the tests
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
#[allow(dead_code)] // generic API, used by the tests
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

pub(crate) struct LineFig<'a> {
    pub(crate) title: &'a str,
    pub(crate) panel: Panel<'a>,
}

impl Figure for LineFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let area = title_area(root, self.title)?;
        draw_panel(&area, &self.panel)
    }
}

/// Several panels stacked vertically sharing one x axis (e.g. δ(t) above Q(t)),
/// written as `<stem>.svg` and `<stem>.png` ([`FIGURE_WIDTH`] ×
/// [`stacked_height`] px). Each panel is `(y label, series)`; a panel with no
/// finite point is drawn empty, but at least one panel must have data.
#[allow(dead_code)] // generic API, used by the tests
pub fn stacked_charts(
    stem: &Path,
    title: &str,
    x_label: &str,
    panels: &[(String, Vec<Series>)],
) -> Result<()> {
    stacked_charts_with(stem, title, x_label, panels, &StackedOptions::default())
}

/// [`stacked_charts`] with options: log x axis, explicit x and y ranges, panel heights.
pub fn stacked_charts_with(
    stem: &Path,
    title: &str,
    x_label: &str,
    panels: &[(String, Vec<Series>)],
    options: &StackedOptions,
) -> Result<()> {
    ensure!(!panels.is_empty(), "stacked chart '{title}': no panels");
    for (label, series) in panels {
        check_series(series).with_context(|| format!("panel '{label}'"))?;
    }
    let x = Axis::fit(
        panels
            .iter()
            .flat_map(|(_, s)| s.iter().flat_map(|s| s.x.iter().copied())),
        options.x_log,
        options.x_range,
    )?
    .ok_or_else(|| anyhow!("stacked chart '{title}': no finite data to plot"))?;
    let ys: Vec<Axis> = panels
        .iter()
        .enumerate()
        .map(|(k, (_, series))| {
            let range = options.y_ranges.get(k).copied().flatten();
            Axis::fit(series.iter().flat_map(|s| points_in_x(s, &x)), false, range)
                .map(|a| a.unwrap_or(Axis::new(0.0, 1.0, false)))
        })
        .collect::<Result<_>>()?;
    let y_area = panels
        .iter()
        .zip(&ys)
        .map(|((label, _), y)| y_label_area(y, label))
        .max()
        .unwrap_or(90);
    let mut heights: Vec<f64> = (0..panels.len())
        .map(|k| options.heights.get(k).copied().unwrap_or(1.0))
        .collect();
    if heights.iter().any(|h| !(h.is_finite() && *h > 0.0)) {
        heights = vec![1.0; panels.len()];
    }
    let fixed: Vec<bool> = (0..panels.len())
        .map(|k| options.y_ranges.get(k).copied().flatten().is_some())
        .collect();
    let fig = StackedFig {
        title,
        x_label,
        panels,
        x,
        ys,
        y_area,
        heights,
        fixed,
        shared_legend_room: options.shared_legend_room,
    };
    let total: f64 = fig.heights.iter().sum::<f64>() / fig.heights.len() as f64;
    let height = (stacked_height(panels.len()) as f64 * total.max(0.5)).round() as u32;
    save_both(stem, (FIGURE_WIDTH, height), &fig)
}

struct StackedFig<'a> {
    title: &'a str,
    x_label: &'a str,
    panels: &'a [(String, Vec<Series>)],
    x: Axis,
    ys: Vec<Axis>,
    y_area: u32,
    heights: Vec<f64>,
    fixed: Vec<bool>,
    shared_legend_room: bool,
}

impl Figure for StackedFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let n = self.panels.len();
        let area = title_area(root, self.title)?;
        let (_, h) = area.dim_in_pixel();
        // Plot heights in the given proportions: the bottom panel also holds the x labels.
        let inner = h as f64 - X_AREA as f64;
        let sum: f64 = self.heights.iter().sum();
        let mut acc = 0.0;
        let breaks: Vec<i32> = self.heights[..n - 1]
            .iter()
            .map(|hk| {
                acc += hk;
                (inner * acc / sum).round() as i32
            })
            .collect();
        let no_x: [i32; 0] = [];
        let areas = area.split_by_breakpoints(no_x, breaks);
        let panel = |k: usize, y: Axis, fixed: bool| {
            let last = k + 1 == n;
            Panel {
                x_label: self.x_label,
                y_label: &self.panels[k].0,
                show_x: last,
                x: self.x,
                y,
                series: &self.panels[k].1,
                y_area: self.y_area,
                margin_bottom: if last { MARGIN } else { 8 },
                y_fixed: fixed,
            }
        };
        // The room one legend needs above the data, given to every panel.
        let room = if self.shared_legend_room {
            (0..n)
                .filter_map(|k| legend_room(&areas[k], &panel(k, self.ys[k], false)))
                .fold(0.0_f64, f64::max)
        } else {
            0.0
        };
        for (k, sub) in areas.iter().enumerate() {
            let p = if room > 0.0 {
                panel(k, self.ys[k].with_top_room(room), true)
            } else {
                panel(k, self.ys[k], self.fixed[k])
            };
            draw_panel(sub, &p)?;
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
#[allow(dead_code)] // generic API, used by the tests
pub fn dual_axis_chart(
    stem: &Path,
    title: &str,
    x_label: &str,
    left: (&str, &[Series]),
    right: (&str, &[Series]),
) -> Result<()> {
    dual_axis_chart_with(stem, title, x_label, left, right, &DualOptions::default())
}

/// [`dual_axis_chart`] with explicit ranges of x and of either y axis.
pub fn dual_axis_chart_with(
    stem: &Path,
    title: &str,
    x_label: &str,
    (left_label, left): (&str, &[Series]),
    (right_label, right): (&str, &[Series]),
    options: &DualOptions,
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
        options.x_range,
    )?
    .ok_or_else(|| anyhow!("dual-axis chart '{title}': no finite data to plot"))?;
    let fit_y = |series: &[Series], range: Option<(f64, f64)>| {
        Axis::fit(series.iter().flat_map(|s| points_in_x(s, &x)), false, range)
            .map(|a| a.unwrap_or(Axis::new(0.0, 1.0, false)))
    };
    let (y_left, y_right) = (fit_y(left, options.y_left)?, fit_y(right, options.y_right)?);
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

pub(crate) struct DualFig<'a> {
    pub(crate) title: &'a str,
    pub(crate) x_label: &'a str,
    pub(crate) left_label: &'a str,
    pub(crate) right_label: &'a str,
    pub(crate) left: Vec<Series>,
    pub(crate) right: Vec<Series>,
    pub(crate) x: Axis,
    pub(crate) y_left: Axis,
    pub(crate) y_right: Axis,
}

impl Figure for DualFig<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let area = title_area(root, self.title)?;
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
