//! One chart panel: series, markers, legend placement.

use super::*;

#[derive(Clone, Copy)]
pub(crate) struct Panel<'a> {
    pub(crate) x_label: &'a str,
    pub(crate) y_label: &'a str,
    pub(crate) show_x: bool,
    pub(crate) x: Axis,
    pub(crate) y: Axis,
    pub(crate) series: &'a [Series],
    pub(crate) y_area: u32,
    pub(crate) margin_bottom: u32,
    /// The y range was given explicitly: never extend it for the legend.
    pub(crate) y_fixed: bool,
}

/// Whether a legend is drawn for these series.
pub(crate) fn wants_legend(series: &[Series]) -> bool {
    series.len() > 1 && series.iter().any(|s| !s.label.is_empty())
}

/// The fraction of the plot height to add above the data of panel `p` drawn in `area` so that
/// its legend covers no data (None when a corner of the plot is free of data, or there is no
/// legend).
pub(crate) fn legend_room<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &Panel,
) -> Option<f64> {
    if !wants_legend(p.series) {
        return None;
    }
    let (aw, ah) = area.dim_in_pixel();
    let plot = (
        aw.saturating_sub(p.y_area + 2 * MARGIN + 10),
        ah.saturating_sub(8 + p.margin_bottom + if p.show_x { X_AREA } else { 0 }),
    );
    let items: Vec<(&Series, &Axis)> = p.series.iter().map(|s| (s, &p.y)).collect();
    let (_, hits, fh) = plan_legend(&items, &p.x, plot);
    (hits > 0).then_some(fh + 0.03)
}

pub(crate) fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &Panel,
) -> Result<()> {
    let mut p = *p;
    if !p.y_fixed {
        // If every corner of the plot has data, make room above the data.
        if let Some(room) = legend_room(area, &p) {
            p.y = p.y.with_top_room(room);
        }
    }
    let p = &p;
    let xr = p.x.lo..p.x.hi;
    let yr = p.y.lo..p.y.hi;
    // Log axes tick where log_ticks says: plotters' own log ticks start at the first power of
    // ten in range, which leaves a range from 27 to 1270 unlabelled below 100.
    let (xb, xl) = p.x.log_ticks(X_LABELS);
    let (yb, yl) = p.y.log_ticks(Y_LABELS);
    let x_log = || {
        xr.clone()
            .log_scale()
            .with_key_points(xb.clone())
            .with_light_points(xl.clone())
    };
    let y_log = || {
        yr.clone()
            .log_scale()
            .with_key_points(yb.clone())
            .with_light_points(yl.clone())
    };
    match (p.x.log, p.y.log) {
        (false, false) => draw_panel_in(area, p, xr.clone(), yr.clone()),
        (true, false) => draw_panel_in(area, p, x_log(), yr.clone()),
        (false, true) => draw_panel_in(area, p, xr.clone(), y_log()),
        (true, true) => draw_panel_in(area, p, x_log(), y_log()),
    }
}

pub(crate) fn draw_panel_in<DB, XS, YS>(
    area: &DrawingArea<DB, Shift>,
    p: &Panel,
    xs: XS,
    ys: YS,
) -> Result<()>
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
        .x_labels(X_LABELS)
        .y_labels(Y_LABELS)
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
pub(crate) fn segments(s: &Series, x: &Axis, y: &Axis) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut cur = Vec::new();
    // Points outside an axis range (explicit ranges) break the line: plotters does not clip.
    let within = |v: f64, a: &Axis| {
        let tol = 1e-9 * (a.hi - a.lo).abs();
        v >= a.lo - tol && v <= a.hi + tol
    };
    for (&a, &b) in s.x.iter().zip(&s.y) {
        if x.accepts(a) && y.accepts(b) && within(a, x) && within(b, y) {
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
pub(crate) fn marker_shape(kind: usize) -> Vec<(i32, i32)> {
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
pub(crate) fn marker<DB: DrawingBackend>(
    kind: usize,
    at: (f64, f64),
    colour: RGBColor,
) -> Glyph<(f64, f64), DB> {
    EmptyElement::at(at)
        + PathElement::new(vec![], colour.stroke_width(1))
        + Polygon::new(marker_shape(kind), colour.filled())
}

/// The legend sample of a series: a short line and/or a marker.
pub(crate) fn legend_glyph<DB: DrawingBackend>(
    style: SeriesStyle,
    kind: usize,
    (x, y): (i32, i32),
    colour: RGBColor,
) -> Glyph<Px, DB> {
    let line = match style {
        SeriesStyle::Markers => vec![],
        // Two dashes: the path backtracks along the gap without drawing it.
        SeriesStyle::Dashed => vec![(-12, 0), (-3, 0)],
        _ => vec![(-12, 0), (12, 0)],
    };
    // The second dash of a dashed line is drawn as a thin bar.
    let shape = match style {
        SeriesStyle::Line => vec![],
        SeriesStyle::Dashed => vec![(3, -1), (12, -1), (12, 1), (3, 1)],
        _ => marker_shape(kind),
    };
    EmptyElement::at((x + 10, y))
        + PathElement::new(line, colour.stroke_width(2))
        + Polygon::new(shape, colour.filled())
}

/// The pieces of a polyline drawn by a series style: the whole segment, or for a dashed line
/// every other stretch of about 1/40 of the segment's x extent.
pub(crate) fn dash_pieces(
    seg: &[(f64, f64)],
    style: SeriesStyle,
    x: &Axis,
) -> Vec<Vec<(f64, f64)>> {
    if style != SeriesStyle::Dashed || seg.len() < 2 {
        return vec![seg.to_vec()];
    }
    let pos = |v: f64| if x.log { v.log10() } else { v };
    let dash = (pos(x.hi) - pos(x.lo)).abs() / 80.0;
    let mut out = Vec::new();
    let mut cur = vec![seg[0]];
    let mut start = pos(seg[0].0);
    let mut on = true;
    for &p in &seg[1..] {
        if on {
            cur.push(p);
        }
        if (pos(p.0) - start).abs() >= dash {
            if on {
                out.push(std::mem::take(&mut cur));
            } else {
                cur = vec![p];
            }
            on = !on;
            start = pos(p.0);
        }
    }
    if on && cur.len() > 1 {
        out.push(cur);
    }
    out
}

pub(crate) fn draw_series<'a, DB, X, Y>(
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
    if matches!(
        style,
        SeriesStyle::Line | SeriesStyle::LineAndMarkers | SeriesStyle::Dashed
    ) {
        for seg in segs.iter().filter(|seg| seg.len() > 1) {
            for piece in dash_pieces(seg, style, x) {
                chart
                    .draw_series(std::iter::once(PathElement::new(piece, line_style)))
                    .map_err(drawing)?;
            }
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
pub(crate) fn draw_secondary_series<'a, DB, X, Y, SX, SY>(
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
    if matches!(
        style,
        SeriesStyle::Line | SeriesStyle::LineAndMarkers | SeriesStyle::Dashed
    ) {
        for seg in segs.iter().filter(|seg| seg.len() > 1) {
            for piece in dash_pieces(seg, style, x) {
                chart
                    .draw_secondary_series(std::iter::once(PathElement::new(piece, line_style)))
                    .map_err(drawing)?;
            }
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
pub(crate) fn legend_position(
    series: &[Series],
    x: &Axis,
    y: &Axis,
    plot: (u32, u32),
) -> SeriesLabelPosition {
    let items: Vec<(&Series, &Axis)> = series.iter().map(|s| (s, y)).collect();
    legend_position_of(&items, x, plot)
}

/// [`legend_position`] for series on different y axes.
pub(crate) fn legend_position_of(
    items: &[(&Series, &Axis)],
    x: &Axis,
    plot: (u32, u32),
) -> SeriesLabelPosition {
    plan_legend(items, x, plot).0
}

/// The best legend corner, how many samples of the drawn data it covers, and
/// the legend's height as a fraction of the plot height.
pub(crate) fn plan_legend(
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
