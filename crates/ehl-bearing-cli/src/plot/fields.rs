//! Pictures of an EHL solution as a tribologist expects them: the pressure map with the Hertz
//! contact, the film map, and the centre lines in the rolling and transverse directions.
//! Coordinates in Hertz semi-axes (X = x/a_x rolling, Y = y/a_y transverse), so the Hertz contact is
//! the unit circle whatever the ellipticity.

use super::{dual_axis_chart, heatmap_with, HeatmapOptions, Series};
use anyhow::{ensure, Result};
use ehl_bearing::ehl::EhlSolution;
use std::path::Path;

/// Write `pressure_map`, `film_map`, `centreline_rolling` and `centreline_transverse` (PNG and SVG)
/// into `dir`.
pub fn plot_fields(r: &EhlSolution, dir: &Path) -> Result<()> {
    let f = &r.fields;
    let (nx, ny) = (f.x.len(), f.y.len());
    ensure!(
        nx >= 2 && ny >= 2 && f.p.len() == nx * ny && f.h.len() == nx * ny,
        "EHL fields have an inconsistent size ({nx} × {ny}, {} pressures)",
        f.p.len()
    );
    let xs: Vec<f64> = f.x.iter().map(|x| x / f.a_x).collect();
    let ys: Vec<f64> = f.y.iter().map(|y| y / f.a_y).collect();
    let grid = |v: &[f64], scale: f64| -> Vec<Vec<f64>> {
        (0..ny)
            .map(|j| (0..nx).map(|i| v[i + nx * j] * scale).collect())
            .collect()
    };
    let ph = r.p_hertz;
    let circle: (Vec<f64>, Vec<f64>) = (0..=120)
        .map(|k| {
            let t = 2.0 * std::f64::consts::PI * k as f64 / 120.0;
            (t.cos(), t.sin())
        })
        .unzip();
    let tag = format!(
        "M = {:.0}, L = {:.1}, Ry/Rx = {:.1}",
        r.moes_m, r.moes_l, r.ry_over_rx
    );
    // Centre-line films are shown up to 4 h_c: the inlet gap (tens of µm) would hide the film.
    let film_cap = 4.0 * r.h_central.max(r.h_min) * 1e6;
    let capped = |h: f64| if h <= film_cap { h } else { f64::NAN };
    heatmap_with(
        &dir.join("pressure_map"),
        &format!("Pressure p/p_h, p_h = {:.3} GPa — {tag}", ph * 1e-9),
        "X = x/a_x (rolling direction)",
        "Y = y/a_y",
        &xs,
        &ys,
        &grid(&f.p, 1.0 / ph),
        "p/p_h",
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
        &format!(
            "Film h: h_c = {:.3} µm, h_min = {:.3} µm — {tag}",
            r.h_central * 1e6,
            r.h_min * 1e6
        ),
        "X = x/a_x (rolling direction)",
        "Y = y/a_y",
        &xs,
        &ys,
        &grid(&f.h, 1e6),
        "h (µm), colours from 0.95 h_min to 1.5 h_c",
        &HeatmapOptions {
            // The inlet gap (tens of µm) would use the whole colour scale: resolve the film.
            z_range: Some((0.95 * r.h_min * 1e6, 1.5 * r.h_central.max(r.h_min) * 1e6)),
            overlays: vec![Series::line("Hertz contact", circle.0, circle.1)],
            equal_aspect: true,
            ..HeatmapOptions::default()
        },
    )?;
    // Centre lines through the grid node nearest the contact centre.
    let nearest = |v: &[f64]| {
        (0..v.len())
            .min_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
            .unwrap_or(0)
    };
    let (i0, j0) = (nearest(&xs), nearest(&ys));
    let hertz = |t: f64| (1.0 - t * t).max(0.0).sqrt();
    let rolling_p: Vec<f64> = (0..nx).map(|i| f.p[i + nx * j0] / ph).collect();
    let rolling_h: Vec<f64> = (0..nx).map(|i| capped(f.h[i + nx * j0] * 1e6)).collect();
    dual_axis_chart(
        &dir.join("centreline_rolling"),
        &format!("Centre line Y = 0 — {tag}"),
        "X = x/a_x",
        (
            "p/p_h",
            &[
                Series::line("pressure", xs.clone(), rolling_p),
                Series::line("Hertz", xs.clone(), xs.iter().map(|&x| hertz(x)).collect()),
            ],
        ),
        (
            "h (µm), up to 4 h_c",
            &[Series::line("film", xs.clone(), rolling_h)],
        ),
    )?;
    let trans_p: Vec<f64> = (0..ny).map(|j| f.p[i0 + nx * j] / ph).collect();
    let trans_h: Vec<f64> = (0..ny).map(|j| capped(f.h[i0 + nx * j] * 1e6)).collect();
    dual_axis_chart(
        &dir.join("centreline_transverse"),
        &format!("Centre line X = 0 — {tag}"),
        "Y = y/a_y",
        (
            "p/p_h",
            &[
                Series::line("pressure", ys.clone(), trans_p),
                Series::line("Hertz", ys.clone(), ys.iter().map(|&y| hertz(y)).collect()),
            ],
        ),
        (
            "h (µm), up to 4 h_c",
            &[Series::line("film", ys.clone(), trans_h)],
        ),
    )?;
    Ok(())
}
