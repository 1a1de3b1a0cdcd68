//! Pictures of an EHL solution as a tribologist expects them: the pressure map with the Hertz
//! contact, the film map, and the centre lines in the rolling and transverse directions.
//! Coordinates in Hertz semi-axes (X = x/a_x rolling, Y = y/a_y transverse), so the Hertz contact is
//! the unit circle whatever the ellipticity; the semi-axes, the Hertz pressure and the load are in
//! every title and axis label, so physical sizes can be read.
//!
//! The maps are zoomed to the contact (−1.8 ≤ X ≤ 1.4, |Y| ≤ 1.25, within the domain); the
//! rolling centre line shows −2.2 ≤ X ≤ outlet with the whole film (axis from 0); the transverse
//! centre line marks the grid nodes and gives the cell sizes: on an elongated contact with a
//! square grid of the dimensionless domain the transverse cells are several times wider than the
//! rolling ones (e.g. 21.7 vs 3.0 µm on the seed's inner contact at 257²), which is what the side
//! edges |Y| ≈ 1 are resolved with.

use super::{
    dual_axis_chart_with, heatmap_with, DualOptions, HeatmapData, HeatmapOptions, Series,
    SeriesStyle,
};
use anyhow::{ensure, Result};
use ehl_bearing::ehl::EhlSolution;
use std::path::Path;

/// Window of the maps in Hertz semi-axes: X from −1.8 to 1.4, |Y| ≤ 1.25.
const MAP_X: (f64, f64) = (-1.8, 1.4);
const MAP_Y: f64 = 1.25;
/// Start of the rolling centre line, in a_x.
const LINE_X0: f64 = -2.2;

/// Write `pressure_map`, `film_map`, `centreline_rolling` and `centreline_transverse` (PNG and SVG)
/// into `dir`.
pub fn plot_fields(r: &EhlSolution, dir: &Path) -> Result<()> {
    let v = FieldView::new(r)?;
    plot_maps(&v, dir)?;
    plot_rolling_centre_line(&v, dir)?;
    plot_transverse_centre_line(&v, dir)
}

/// An EHL solution seen in Hertz semi-axes, with the texts every figure of it carries.
struct FieldView<'a> {
    /// The solution.
    r: &'a EhlSolution,
    /// Nodes along x (rolling direction).
    nx: usize,
    /// Nodes along y (transverse).
    ny: usize,
    /// Node coordinates X = x/a_x.
    xs: Vec<f64>,
    /// Node coordinates Y = y/a_y.
    ys: Vec<f64>,
    /// Load, Hertz pressure, semi-axes and Moes groups, for every title.
    tag: String,
    /// Axis label of X (with a_x in µm).
    x_label: String,
    /// Axis label of Y (with a_y in µm).
    y_label: String,
}

impl<'a> FieldView<'a> {
    /// The view of `r`; an error if its fields have fewer than 2 × 2 nodes or sizes that do not
    /// agree.
    fn new(r: &'a EhlSolution) -> Result<Self> {
        let f = &r.fields;
        let (nx, ny) = (f.x.len(), f.y.len());
        ensure!(
            nx >= 2 && ny >= 2 && f.p.len() == nx * ny && f.h.len() == nx * ny,
            "EHL fields have an inconsistent size ({nx} × {ny}, {} pressures)",
            f.p.len()
        );
        let xs: Vec<f64> = f.x.iter().map(|x| x / f.a_x).collect();
        let ys: Vec<f64> = f.y.iter().map(|y| y / f.a_y).collect();
        let ph = r.p_hertz;
        // The load of the Hertz contact: w = (2π/3)·p_h·a_x·a_y.
        let load = 2.0 * std::f64::consts::PI / 3.0 * ph * f.a_x * f.a_y;
        let tag = format!(
            "w = {:.1} N, p_h = {:.2} GPa, a_x = {:.3} mm, a_y = {:.3} mm (M = {:.0}, L = {:.1}, Ry/Rx = {:.1})",
            load,
            ph * 1e-9,
            f.a_x * 1e3,
            f.a_y * 1e3,
            r.moes_m,
            r.moes_l,
            r.ry_over_rx
        );
        let x_label = format!("X = x/a_x, rolling direction (a_x = {:.1} µm)", f.a_x * 1e6);
        let y_label = format!("Y = y/a_y (a_y = {:.1} µm)", f.a_y * 1e6);
        Ok(Self {
            r,
            nx,
            ny,
            xs,
            ys,
            tag,
            x_label,
            y_label,
        })
    }

    /// Grid spacings Δx and Δy, µm.
    fn cell_um(&self) -> (f64, f64) {
        let f = &self.r.fields;
        ((f.x[1] - f.x[0]) * 1e6, (f.y[1] - f.y[0]) * 1e6)
    }

    /// The node nearest the contact centre, (i, j).
    fn centre_node(&self) -> (usize, usize) {
        let nearest = |v: &[f64]| {
            (0..v.len())
                .min_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
                .unwrap_or(0)
        };
        (nearest(&self.xs), nearest(&self.ys))
    }
}

/// The nodes inside the window of the maps ([`MAP_X`], [`MAP_Y`]) as index ranges along x and
/// y; the whole domain if the window holds fewer than 2 nodes in a direction.
fn map_window(v: &FieldView) -> (Vec<usize>, Vec<usize>) {
    let irange: Vec<usize> = (0..v.nx)
        .filter(|&i| v.xs[i] >= MAP_X.0 && v.xs[i] <= MAP_X.1)
        .collect();
    let jrange: Vec<usize> = (0..v.ny).filter(|&j| v.ys[j].abs() <= MAP_Y).collect();
    if irange.len() >= 2 && jrange.len() >= 2 {
        (irange, jrange)
    } else {
        ((0..v.nx).collect(), (0..v.ny).collect())
    }
}

/// The Hertz contact in Hertz semi-axes: the unit circle, 121 points.
fn hertz_circle() -> (Vec<f64>, Vec<f64>) {
    (0..=120)
        .map(|k| {
            let t = 2.0 * std::f64::consts::PI * k as f64 / 120.0;
            (t.cos(), t.sin())
        })
        .unzip()
}

/// `pressure_map` (p/p_h) and `film_map` (h in µm, colours from 0.95 h_min to 1.5 h_c), zoomed
/// to the window of the maps, with the Hertz contact overlaid.
fn plot_maps(v: &FieldView, dir: &Path) -> Result<()> {
    let (r, f, nx) = (v.r, &v.r.fields, v.nx);
    let (irange, jrange) = map_window(v);
    let wx: Vec<f64> = irange.iter().map(|&i| v.xs[i]).collect();
    let wy: Vec<f64> = jrange.iter().map(|&j| v.ys[j]).collect();
    let grid = |values: &[f64], scale: f64| -> Vec<Vec<f64>> {
        jrange
            .iter()
            .map(|&j| irange.iter().map(|&i| values[i + nx * j] * scale).collect())
            .collect()
    };
    let ph = r.p_hertz;
    let tag = &v.tag;
    let circle = hertz_circle();
    heatmap_with(
        &dir.join("pressure_map"),
        &HeatmapData {
            title: &format!("Pressure p/p_h (p_max = {:.3} p_h) — {tag}", r.p_max / ph),
            x_label: &v.x_label,
            y_label: &v.y_label,
            x: &wx,
            y: &wy,
            z: &grid(&f.p, 1.0 / ph),
            z_label: "p/p_h",
        },
        &HeatmapOptions {
            overlays: vec![Series::line(
                "Hertz contact",
                circle.0.clone(),
                circle.1.clone(),
            )],
            equal_aspect: true,
            ..HeatmapOptions::default()
        },
    )?;
    heatmap_with(
        &dir.join("film_map"),
        &HeatmapData {
            title: &format!(
                "Film h: h_c = {:.3} µm, h_min = {:.3} µm — {tag}",
                r.h_central * 1e6,
                r.h_min * 1e6
            ),
            x_label: &v.x_label,
            y_label: &v.y_label,
            x: &wx,
            y: &wy,
            z: &grid(&f.h, 1e6),
            z_label: "h (µm), colours from 0.95 h_min to 1.5 h_c",
        },
        &HeatmapOptions {
            // The inlet gap (tens of µm) would use the whole colour scale: resolve the film.
            z_range: Some((0.95 * r.h_min * 1e6, 1.5 * r.h_central.max(r.h_min) * 1e6)),
            overlays: vec![Series::line("Hertz contact", circle.0, circle.1)],
            equal_aspect: true,
            ..HeatmapOptions::default()
        },
    )
}

/// Hertz pressure profile across a semi-axis, p/p_h at `t` semi-axes from the centre.
fn hertz(t: f64) -> f64 {
    (1.0 - t * t).max(0.0).sqrt()
}

/// `centreline_rolling`: p/p_h with the Hertz profile (left axis) and h in µm from 0 (right
/// axis) along the grid line nearest Y = 0, from X = [`LINE_X0`] (or the inlet) to the outlet.
fn plot_rolling_centre_line(v: &FieldView, dir: &Path) -> Result<()> {
    let (f, nx, xs) = (&v.r.fields, v.nx, &v.xs);
    let ph = v.r.p_hertz;
    let (_, j0) = v.centre_node();
    let (dx, _) = v.cell_um();
    let x0 = LINE_X0.max(xs[0]);
    let x_end = xs[nx - 1];
    let shown: Vec<usize> = (0..nx).filter(|&i| xs[i] >= x0).collect();
    let lx: Vec<f64> = shown.iter().map(|&i| xs[i]).collect();
    let rolling_p: Vec<f64> = shown.iter().map(|&i| f.p[i + nx * j0] / ph).collect();
    let rolling_h: Vec<f64> = shown.iter().map(|&i| f.h[i + nx * j0] * 1e6).collect();
    let h_top = rolling_h.iter().copied().fold(0.0_f64, f64::max) * 1.05;
    dual_axis_chart_with(
        &dir.join("centreline_rolling"),
        &format!("Centre line Y = 0, Δx = {dx:.2} µm — {}", v.tag),
        &v.x_label,
        (
            "p/p_h",
            &[
                Series::line("pressure", lx.clone(), rolling_p),
                Series::line("Hertz", lx.clone(), lx.iter().map(|&x| hertz(x)).collect()),
            ],
        ),
        ("h (µm)", &[Series::line("film", lx.clone(), rolling_h)]),
        &DualOptions {
            x_range: Some((x0, x_end)),
            y_right: (h_top > 0.0).then_some((0.0, h_top)),
            ..DualOptions::default()
        },
    )
}

/// `centreline_transverse`: the same as the rolling centre line along the grid line nearest
/// X = 0, for |Y| ≤ 1.6 (or the domain), with the pressure's grid nodes marked and the cell
/// sizes Δy and Δx in the title.
fn plot_transverse_centre_line(v: &FieldView, dir: &Path) -> Result<()> {
    let (f, nx, ny, ys) = (&v.r.fields, v.nx, v.ny, &v.ys);
    let ph = v.r.p_hertz;
    let (i0, _) = v.centre_node();
    let (dx, dy) = v.cell_um();
    let y_end = ys[ny - 1].min(1.6);
    let tshown: Vec<usize> = (0..ny).filter(|&j| ys[j].abs() <= y_end).collect();
    let ty: Vec<f64> = tshown.iter().map(|&j| ys[j]).collect();
    let trans_p: Vec<f64> = tshown.iter().map(|&j| f.p[i0 + nx * j] / ph).collect();
    let trans_h: Vec<f64> = tshown.iter().map(|&j| f.h[i0 + nx * j] * 1e6).collect();
    let th_top = trans_h.iter().copied().fold(0.0_f64, f64::max) * 1.05;
    dual_axis_chart_with(
        &dir.join("centreline_transverse"),
        &format!(
            "Centre line X = 0, grid nodes marked: Δy = {dy:.1} µm = {:.3} a_y (Δx = {dx:.2} µm) — {}",
            dy * 1e-6 / f.a_y,
            v.tag
        ),
        &v.y_label,
        (
            "p/p_h",
            &[
                Series::new(
                    "pressure at the grid nodes",
                    ty.clone(),
                    trans_p,
                    SeriesStyle::LineAndMarkers,
                ),
                Series::line("Hertz", ty.clone(), ty.iter().map(|&y| hertz(y)).collect()),
            ],
        ),
        ("h (µm)", &[Series::line("film", ty.clone(), trans_h)]),
        &DualOptions {
            x_range: Some((-y_end, y_end)),
            y_right: (th_top > 0.0).then_some((0.0, th_top)),
            ..DualOptions::default()
        },
    )
}
