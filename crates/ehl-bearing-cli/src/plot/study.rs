//! Study figures (the seed paper's Fig. 2): K, d and ΔF against the contact load, inner and outer
//! raceways in two panels on one y scale, one marker series per speed, the trend curves drawn
//! over the load range they were fitted on, with their R² in the legend.

use super::{stacked_charts_with, Series, StackedOptions};
use anyhow::{Context, Result};
use ehl_bearing::study::{RaceTrends, ResultRow, TrendCurve, TrendModel};
use std::path::Path;

/// Range of the markers with 8 % padding (the trend curves are clipped to it).
fn padded(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold(None, |acc: Option<(f64, f64)>, v| match acc {
            None => Some((v, v)),
            Some((a, b)) => Some((a.min(v), b.max(v))),
        })?;
    let pad = if hi > lo {
        0.08 * (hi - lo)
    } else {
        0.05 * lo.abs().max(1e-12)
    };
    Some((lo - pad, hi + pad))
}

fn r2(c: &TrendCurve) -> String {
    match c.r_squared {
        Some(r) if r < 0.9 => format!("R² = {r:.2}, poor fit"),
        Some(r) => format!("R² = {r:.3}"),
        None => "R² n/a".into(),
    }
}

/// The value a figure plots for a result row.
type Get = fn(&ResultRow) -> f64;

/// Writes `k_vs_load`, `d_vs_load` and `delta_f_vs_load` (PNG and SVG) into `dir`. The markers
/// sit at the load each law was characterized at; the load axis is logarithmic when the loads
/// span more than a factor of 5.
pub fn study_figures(dir: &Path, rows: &[ResultRow], trends: Option<&TrendModel>) -> Result<()> {
    let plot = StudyPlot::new(rows, trends);
    let figures: [(&str, &str, &str, Get); 3] = [
        ("k_vs_load", "Stiffness K", "K (N/m^d)", |r| r.contact.k),
        ("d_vs_load", "Nonlinear index d", "d (–)", |r| r.contact.d),
        (
            "delta_f_vs_load",
            "Lift at zero approach ΔF",
            "ΔF (N)",
            |r| r.contact.delta_f_n,
        ),
    ];
    for (stem, title, y_label, get) in figures {
        plot.figure(dir, stem, title, y_label, get)?;
    }
    Ok(())
}

/// What the three figures of a study share: the rows drawn, their speeds, the load axis, the
/// case for the titles and the trend model.
struct StudyPlot<'a> {
    /// Result rows whose load was not floored.
    rows: Vec<&'a ResultRow>,
    /// Their inner-ring speeds, rpm, increasing, each once.
    speeds: Vec<f64>,
    /// Logarithmic load axis (the loads span more than a factor of 5).
    x_log: bool,
    /// Range of the load axis, N.
    x_range: Option<(f64, f64)>,
    /// The speeds for the titles, e.g. `1000 / 4000`.
    speeds_text: String,
    /// Method and bearing for the titles (empty without a trend model).
    case: String,
    /// The trend model, whose curves are drawn over the markers.
    trends: Option<&'a TrendModel>,
}

impl<'a> StudyPlot<'a> {
    /// The shared parts of the figures of `rows` (those with a floored load left out).
    fn new(rows: &'a [ResultRow], trends: Option<&'a TrendModel>) -> Self {
        let rows: Vec<&ResultRow> = rows.iter().filter(|r| !r.contact.load_floored).collect();
        let mut speeds: Vec<f64> = Vec::new();
        for r in &rows {
            if !speeds.contains(&r.speed_rpm) {
                speeds.push(r.speed_rpm);
            }
        }
        speeds.sort_by(f64::total_cmp);
        let loads = || rows.iter().map(|r| r.contact.characterized_load_n);
        let (qmin, qmax) = loads().fold((f64::INFINITY, 0.0_f64), |(a, b), q| (a.min(q), b.max(q)));
        let x_log = qmin > 0.0 && qmax / qmin > 5.0;
        let x_range = if x_log {
            Some((qmin / 1.15, qmax * 1.15))
        } else {
            padded(loads())
        };
        let speeds_text = speeds
            .iter()
            .map(|n| format!("{n}"))
            .collect::<Vec<_>>()
            .join(" / ");
        Self {
            rows,
            speeds,
            x_log,
            x_range,
            speeds_text,
            case: case_text(trends),
            trends,
        }
    }

    /// One figure, `<dir>/<stem>`: the value `get` against the contact load, inner and outer
    /// raceways in two panels on one y range fitted to the data, with the trend curves.
    fn figure(&self, dir: &Path, stem: &str, title: &str, y_label: &str, get: Get) -> Result<()> {
        // One y range for both raceways, fitted to the data.
        let y_range = padded(self.rows.iter().map(|r| get(r)));
        let mut panels = Vec::new();
        for race in ["inner", "outer"] {
            let mut series = self.markers(race, get);
            if let Some(m) = self.trends {
                let t = if race == "inner" { &m.inner } else { &m.outer };
                self.trend_curves(&mut series, stem, race, t, y_range);
            }
            panels.push((format!("{race}: {y_label}"), series));
        }
        stacked_charts_with(
            &dir.join(stem),
            &format!(
                "{title} against contact load, {} rpm{}",
                self.speeds_text, self.case
            ),
            if self.x_log {
                "contact load Q (N), log scale"
            } else {
                "contact load Q (N)"
            },
            &panels,
            &StackedOptions {
                x_log: self.x_log,
                x_range: self.x_range,
                y_ranges: vec![y_range, y_range],
                // Tall panels with room above the data for the legends (up to 7 rows), so
                // that no legend covers a marker.
                heights: vec![1.8, 1.8],
                shared_legend_room: true,
            },
        )
        .with_context(|| format!("plotting {stem}"))
    }

    /// One marker series per speed: `get` against the characterized load, N, of the contacts
    /// of `race`, in increasing load.
    fn markers(&self, race: &str, get: Get) -> Vec<Series> {
        let mut series = Vec::new();
        for &n in &self.speeds {
            let mut pts: Vec<(f64, f64)> = self
                .rows
                .iter()
                .filter(|r| r.speed_rpm == n && r.contact.race == race)
                .map(|r| (r.contact.characterized_load_n, get(r)))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (x, y): (Vec<f64>, Vec<f64>) = pts.into_iter().unzip();
            series.push(Series::markers(format!("{n} rpm"), x, y));
        }
        series
    }

    /// The trend curves of the figure `stem` for the raceway `race` (trends `t`), sampled at 81
    /// loads spread logarithmically over the load range they were fitted on, appended to
    /// `series`; values outside `y_range` become NaN (a break in the curve).
    fn trend_curves(
        &self,
        series: &mut Vec<Series>,
        stem: &str,
        race: &str,
        t: &RaceTrends,
        y_range: Option<(f64, f64)>,
    ) {
        let [lo, hi] = t.load_range_n;
        let q: Vec<f64> = (0..=80)
            .map(|i| lo * (hi / lo).powf(i as f64 / 80.0))
            .collect();
        let curve = |c: &TrendCurve, n: f64| -> Vec<f64> {
            q.iter().map(|&qi| clip(y_range, c.eval(qi, n))).collect()
        };
        match stem {
            "k_vs_load" => self.k_curves(series, t, &q, y_range),
            "d_vs_load" if t.d.form == "hertz_limit_speed" => {
                // The library's trend has a speed term (the data separate by speed).
                for &n in &self.speeds {
                    series.push(Series::line(
                        format!("trend d(Q, {n} rpm)"),
                        q.clone(),
                        curve(&t.d, omega(n)),
                    ));
                }
                if let Some(s) = series.last_mut() {
                    s.label = format!("{} — {}: {}", s.label, t.d.formula, r2(&t.d));
                }
            }
            "d_vs_load" => {
                series.push(Series::line(
                    format!("trend {} ({}, all speeds)", t.d.formula, r2(&t.d)),
                    q.clone(),
                    curve(&t.d, 0.0),
                ));
                self.d_fits_per_speed(series, race, y_range);
            }
            _ => {
                for &n in &self.speeds {
                    series.push(Series::line(
                        format!("trend ΔF(Q, {n} rpm)"),
                        q.clone(),
                        curve(&t.delta_f, omega(n)),
                    ));
                }
                if let Some(s) = series.last_mut() {
                    s.label = format!("{} — {}: {}", s.label, t.delta_f.formula, r2(&t.delta_f));
                }
            }
        }
    }

    /// The K trend (power fit) and the K the force element uses, (Q − ΔF)/δ^d from the d, ΔF
    /// and δ trends, at the loads `q`, N: one curve for all speeds when the speeds' curves lie
    /// within 2 % of the axis span of each other, else one per speed.
    fn k_curves(
        &self,
        series: &mut Vec<Series>,
        t: &RaceTrends,
        q: &[f64],
        y_range: Option<(f64, f64)>,
    ) {
        series.push(Series::line(
            format!("power fit K = p0·Q^p1 ({})", r2(&t.k)),
            q.to_vec(),
            q.iter()
                .map(|&qi| clip(y_range, t.k.eval(qi, 0.0)))
                .collect(),
        ));
        let used: Vec<Vec<f64>> = self
            .speeds
            .iter()
            .map(|&n| {
                q.iter()
                    .map(|&qi| clip(y_range, t.k_at(qi, omega(n))))
                    .collect()
            })
            .collect();
        // One curve when the speeds' curves would lie on top of each other
        // (within 2 % of the axis span).
        let span = y_range.map_or(f64::NAN, |(a, b)| b - a);
        let spread = used
            .iter()
            .flat_map(|c| c.iter().zip(&used[0]).map(|(a, b)| (a - b).abs() / span))
            .filter(|v| v.is_finite())
            .fold(0.0_f64, f64::max);
        if spread < 0.02 {
            series.push(Series::line(
                format!(
                    "K used by the force element, (Q − ΔF)/δ^d (all speeds: within {:.1} % of the axis)",
                    100.0 * spread
                ),
                q.to_vec(),
                used[0].clone(),
            ));
        } else {
            for (&n, k) in self.speeds.iter().zip(used) {
                series.push(Series::line(
                    format!("K used: (Q − ΔF)/δ^d, {n} rpm"),
                    q.to_vec(),
                    k,
                ));
            }
        }
    }

    /// The d trend's form d = 1.5 − p0·Q^(−p1) fitted to each speed's points of `race` alone
    /// (dashed, over that speed's load range), to show that the data do not separate by more
    /// than the trend's speed-term test admits.
    fn d_fits_per_speed(&self, series: &mut Vec<Series>, race: &str, y_range: Option<(f64, f64)>) {
        for &n in &self.speeds {
            let pts: Vec<(f64, f64)> = self
                .rows
                .iter()
                .filter(|r| r.speed_rpm == n && r.contact.race == race)
                .map(|r| (r.contact.characterized_load_n, r.contact.d))
                .collect();
            if let Some((p0, p1, r2)) = hertz_limit_fit(&pts) {
                let (lo, hi) = pts.iter().fold((f64::INFINITY, 0.0_f64), |(a, b), p| {
                    (a.min(p.0), b.max(p.0))
                });
                let qs: Vec<f64> = (0..=60)
                    .map(|i| lo * (hi / lo).powf(i as f64 / 60.0))
                    .collect();
                let mut s = Series::line(
                    format!(
                        "{n} rpm alone: d = 1.5 − {p0:.3}·Q^(−{p1:.3}), R² = {r2:.3} (figure only)"
                    ),
                    qs.clone(),
                    qs.iter()
                        .map(|&q| clip(y_range, 1.5 - p0 * q.powf(-p1)))
                        .collect(),
                );
                s.style = super::SeriesStyle::Dashed;
                series.push(s);
            }
        }
    }
}

/// The case for the titles, from the trend model: method and bearing (empty without a model).
fn case_text(trends: Option<&TrendModel>) -> String {
    trends.map_or(String::new(), |m| {
        let b = &m.bearing;
        format!(
            " — {} method; {} balls of {:.2} mm, pitch {:.1} mm, α0 = {:.1}°, f_i = {}, f_o = {}",
            m.method,
            b.ball_count,
            b.ball_diameter_m * 1e3,
            b.pitch_diameter_m * 1e3,
            b.free_contact_angle_rad.to_degrees(),
            b.inner_conformity,
            b.outer_conformity
        )
    })
}

/// Angular speed, rad/s, of a speed in rpm (its magnitude).
fn omega(rpm: f64) -> f64 {
    (rpm * std::f64::consts::PI / 30.0).abs()
}

/// `v`, or NaN (a break in the curve) outside the figure's y range `y_range`.
fn clip(y_range: Option<(f64, f64)>, v: f64) -> f64 {
    match y_range {
        Some((a, b)) if v < a || v > b => f64::NAN,
        _ => v,
    }
}

/// d = 1.5 − p0·Q^(−p1) fitted to (Q, d) points by linear least squares on
/// ln(1.5 − d) = ln p0 − p1·ln Q (points with d ≥ 1.5 skipped); returns p0, p1 and the R² of d.
fn hertz_limit_fit(pts: &[(f64, f64)]) -> Option<(f64, f64, f64)> {
    let xy: Vec<(f64, f64)> = pts
        .iter()
        .filter(|(q, d)| *q > 0.0 && *d < 1.5)
        .map(|(q, d)| (q.ln(), (1.5 - d).ln()))
        .collect();
    let n = xy.len() as f64;
    if xy.len() < 3 {
        return None;
    }
    let (mx, my) = (
        xy.iter().map(|p| p.0).sum::<f64>() / n,
        xy.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let (p0, p1) = ((my - slope * mx).exp(), -slope);
    let mean_d = pts.iter().map(|p| p.1).sum::<f64>() / pts.len() as f64;
    let ss_tot: f64 = pts.iter().map(|p| (p.1 - mean_d).powi(2)).sum();
    let ss_res: f64 = pts
        .iter()
        .map(|&(q, d)| (d - (1.5 - p0 * q.powf(-p1))).powi(2))
        .sum();
    let r2 = if ss_tot > 0.0 {
        1.0 - ss_res / ss_tot
    } else {
        f64::NAN
    };
    (p0.is_finite() && p1.is_finite()).then_some((p0, p1, r2))
}

#[cfg(test)]
mod tests {
    use super::hertz_limit_fit;

    #[test]
    fn hertz_limit_fit_recovers_an_exact_law() {
        let pts: Vec<(f64, f64)> = [27.0, 60.0, 150.0, 400.0, 1100.0]
            .iter()
            .map(|&q: &f64| (q, 1.5 - 4.2 * q.powf(-0.73)))
            .collect();
        let (p0, p1, r2) = hertz_limit_fit(&pts).unwrap();
        // Exact data: the log-linear least squares is exact up to round-off.
        assert!((p0 / 4.2 - 1.0).abs() < 1e-10, "p0 = {p0}");
        assert!((p1 - 0.73).abs() < 1e-10, "p1 = {p1}");
        assert!((r2 - 1.0).abs() < 1e-12, "R² = {r2}");
        assert!(hertz_limit_fit(&pts[..2]).is_none());
    }
}
