//! Data checks and axes: ranges, scales, ticks.

use super::*;

pub(crate) fn check_series(series: &[Series]) -> Result<()> {
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

pub(crate) fn check_grid_axis(v: &[f64], name: &str) -> Result<()> {
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

pub(crate) fn finite_min_max(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
        })
}

/// y values of the points of `s` whose x lies on axis `x` (for the y range).
pub(crate) fn points_in_x<'a>(s: &'a Series, x: &'a Axis) -> impl Iterator<Item = f64> + 'a {
    s.x.iter()
        .zip(&s.y)
        .filter(|(a, _)| x.accepts(**a) && **a >= x.lo && **a <= x.hi)
        .map(|(_, b)| *b)
}

/// Most decades a log axis spans (automatic ranges keep the top ones).
pub(crate) const MAX_DECADES: f64 = 60.0;

/// One axis: its range and scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Axis {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) log: bool,
}

impl Axis {
    pub(crate) fn new(lo: f64, hi: f64, log: bool) -> Self {
        Self { lo, hi, log }
    }

    /// Whether `v` can be drawn on this axis at all.
    pub(crate) fn accepts(&self, v: f64) -> bool {
        v.is_finite() && (!self.log || v > 0.0)
    }

    /// Position of `v` along the axis, 0 at `lo` and 1 at `hi`.
    pub(crate) fn norm(&self, v: f64) -> f64 {
        if self.log {
            (v.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }

    /// The same axis extended upwards so that its current range fills only the
    /// lower `1 - frac` of it (room for a legend above the data).
    pub(crate) fn with_top_room(&self, frac: f64) -> Self {
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
    pub(crate) fn fit(
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
pub(crate) fn fmt_decimal(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// `v` in scientific notation with at most 4 significant digits: `1.5e-7`.
pub(crate) fn fmt_scientific(v: f64) -> String {
    let s = format!("{v:.3e}");
    match s.split_once('e') {
        Some((m, e)) if m.contains('.') => {
            format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
        }
        _ => s,
    }
}

/// Whether magnitudes like `a` read better in scientific notation.
pub(crate) fn wants_scientific(a: f64) -> bool {
    a != 0.0 && !(1e-3..1e5).contains(&a)
}

impl Axis {
    /// Tick label of `v`: one notation for the whole of a linear axis (chosen
    /// from its largest magnitude); on a log axis the integer multiples 1–9 of a
    /// power of ten (the ticks [`Axis::log_ticks`] places), nothing elsewhere.
    pub(crate) fn tick_label(&self, v: f64) -> String {
        if !v.is_finite() {
            return String::new();
        }
        if self.log {
            if v <= 0.0 {
                return String::new();
            }
            let mantissa = v / 10f64.powf(v.log10().floor());
            let m = mantissa.round();
            if (mantissa - m).abs() > 1e-6 || !(1.0..=9.0).contains(&m) {
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

/// `m`·10^`e`, as exact as the literal `me` (10^e is exact up to e = 22); exponents beyond
/// the f64 range give 0 or inf without overflowing the negation.
fn times_power_of_ten(m: f64, e: i32) -> f64 {
    let e = e.clamp(-400, 400);
    if e >= 0 {
        m * 10f64.powi(e)
    } else {
        m / 10f64.powi(-e)
    }
}

impl Axis {
    /// Ticks of a log axis: the labelled ones (at most `max`, at least two where the range
    /// holds two integer multiples of a power of ten) and the grid-only ones. Labelled: 1, 2, 3
    /// and 5 times the powers of ten in range, so that a range starting at 27 N is labelled
    /// from 30 N on (plotters' own ticks start at the first power of ten, 100 N); when more
    /// than `max` of them fall in range, 1, 2 and 5 times the powers of ten, then the powers
    /// of ten (every k-th one when still too many); when fewer than two, the integer multiples
    /// 1–9. Grid-only: the other integer multiples 1–9 over at most 8
    /// decades, else the unlabelled powers of ten.
    pub(crate) fn log_ticks(&self, max: usize) -> (Vec<f64>, Vec<f64>) {
        let max = max.max(2);
        // A log axis needs a positive, finite range (NaN, inf or ≤ 0: no ticks).
        if !(self.lo > 0.0 && self.hi.is_finite() && self.lo <= self.hi) {
            return (Vec::new(), Vec::new());
        }
        let (e0, e1) = (
            self.lo.log10().floor() as i32,
            (self.hi.log10().ceil() as i32).min(self.lo.log10().floor() as i32 + 700),
        );
        let (lo, hi) = (self.lo * (1.0 - 1e-12), self.hi * (1.0 + 1e-12));
        let with = |ms: &[f64], step: i32| -> Vec<f64> {
            (e0..=e1)
                .filter(|e| e.rem_euclid(step) == 0)
                .flat_map(|e| ms.iter().map(move |&m| times_power_of_ten(m, e)))
                .filter(|v| *v >= lo && *v <= hi)
                .collect()
        };
        let multiples = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0];
        let mut labelled = with(&[1.0, 2.0, 3.0, 5.0], 1);
        if labelled.len() < 2 {
            labelled = with(&multiples, 1);
        } else if labelled.len() > max {
            labelled = with(&[1.0, 2.0, 5.0], 1);
        }
        let mut step = 1;
        while labelled.len() > max {
            labelled = with(&[1.0], step);
            step += 1;
        }
        let grid = if e1 - e0 <= 8 {
            with(&multiples, 1)
        } else {
            with(&[1.0], 1)
        };
        let grid = grid.into_iter().filter(|v| !labelled.contains(v)).collect();
        (labelled, grid)
    }
}

/// Likely tick values of an axis (plotters picks "nice" steps of 1, 2 or 5
/// times a power of ten; log axes tick where [`Axis::log_ticks`] says).
pub(crate) fn likely_ticks(a: &Axis, n: usize) -> Vec<f64> {
    if a.log {
        return a.log_ticks(n).0;
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
pub(crate) fn widest_tick(a: &Axis) -> u32 {
    let text = |v: f64| text_box(&a.tick_label(v), TICK_SIZE as f64).0;
    likely_ticks(a, 8)
        .into_iter()
        .chain(likely_ticks(a, 4))
        .map(text)
        .fold(text(1.0), f32::max)
        .ceil() as u32
}

/// Width for the y tick labels and the rotated y description.
pub(crate) fn y_label_area(y: &Axis, desc: &str) -> u32 {
    let desc_w = if desc.is_empty() { 0 } else { DESC_SIZE + 12 };
    widest_tick(y) + desc_w + 18
}
