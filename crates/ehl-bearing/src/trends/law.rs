//! The trend model evaluated as contact laws: the fitted law at a load and speed
//! ([`TrendModel::law_at`]) and each raceway's law at one speed ([`SpeedLaws`], [`RaceLaw`]),
//! which a force element gives every contact.

use super::{RaceTrends, TrendError, TrendModel};
use crate::bearing::Race;
use crate::contact_law::ContactLaw;
use crate::fit::FittedLaw;
use std::sync::Arc;

impl TrendModel {
    /// The fitted law of a contact on `race` at load `load` (N) and speed `n` (rad/s): d and ΔF
    /// from their trends at the load and speed clamped into the validity range,
    /// K = (Q − ΔF)/δ(Q, n)^d so that the law passes through the approach trend (K(Q) from its
    /// own trend only if that anchor is not positive), fitted range δ at 0.8·Q and 1.2·Q (or just
    /// above ΔF). Returns the law and whether the load was clamped.
    pub fn law_at(&self, race: Race, load: f64, n: f64) -> Result<(FittedLaw, bool), TrendError> {
        let t = self.race(race);
        let [lo, hi] = t.load_range_n;
        let qc = if load.is_nan() {
            lo
        } else {
            load.clamp(lo, hi)
        };
        let clamped = !(load >= lo && load <= hi);
        let [nlo, nhi] = t.speed_range_rad_s;
        let nc = n.clamp(nlo, nhi);
        let d = t.d.eval(qc, nc);
        let df = t.delta_f.eval(qc, nc);
        let k = t.k_at(qc, nc);
        let q_lo = (0.8 * qc).max(df + 0.05 * qc);
        let q_hi = (1.2 * qc).max(1.5 * q_lo);
        let delta = |q: f64| ((q - df) / k).powf(1.0 / d);
        let law = FittedLaw::new(k, d, df, delta(q_lo), delta(q_hi)).map_err(|source| {
            TrendError::Law {
                race,
                load_n: qc,
                speed_rad_s: nc,
                source,
            }
        })?;
        Ok((law, clamped))
    }

    /// Whether each raceway's approach trend δ(Q, n) increases with the load over the validity
    /// range (65 loads, geometric, at the lowest, middle and highest speed), so that a contact's
    /// load can be found from its approach.
    pub fn check_invertible(&self) -> Result<(), TrendError> {
        for race in [Race::Inner, Race::Outer] {
            let t = self.race(race);
            let [lo, hi] = t.load_range_n;
            let [nlo, nhi] = t.speed_range_rad_s;
            for n in [nlo, 0.5 * (nlo + nhi), nhi] {
                let mut prev = f64::NEG_INFINITY;
                for i in 0..=64 {
                    let q = lo * (hi / lo).powf(i as f64 / 64.0);
                    let d = t.approach_at(q, n);
                    if !(d.is_finite() && d > prev) {
                        return Err(TrendError::NotIncreasing {
                            race,
                            load_n: q,
                            speed_rad_s: n,
                        });
                    }
                    prev = d;
                }
            }
        }
        Ok(())
    }
}

/// The law of one raceway at one speed from the trend curves.
///
/// Inside the load range [Q_lo, Q_hi] of the trends, the contact's load is the one whose trend
/// approach equals the contact's approach: Q(δ) solves δ_trend(Q, n) = δ (safeguarded Newton,
/// started from the contact's load of the previous call, [`RaceLaw::with_hint`]), so
/// dQ/dδ = 1/(∂δ_trend/∂Q). This is the law K(Q)·δ^d(Q) + ΔF(Q) of the trends with K anchored on
/// the approach trend ([`RaceTrends::k_at`]), evaluated at its own load. Outside the range the
/// law is the fitted law with K, d, ΔF frozen at the nearest end ([`TrendModel::law_at`]), which
/// passes through the same end point (continuous force).
#[derive(Debug, Clone)]
pub struct RaceLaw {
    race: Arc<RaceTrends>,
    n: f64,
    lo: f64,
    hi: f64,
    delta_lo: f64,
    delta_hi: f64,
    law_lo: FittedLaw,
    law_hi: FittedLaw,
    hint: f64,
    tolerance: f64,
    max_iterations: usize,
}

impl RaceLaw {
    /// The same law, its load inversion started from `hint` (N; NaN: from the approach
    /// interpolated between the ends of the range).
    pub fn with_hint(&self, hint: f64) -> RaceLaw {
        RaceLaw {
            hint,
            ..self.clone()
        }
    }

    /// Whether a positive contact load `load` (N) lies outside the trends' load range.
    pub fn outside_load_range(&self, load: f64) -> bool {
        load > 0.0 && !(load >= self.lo && load <= self.hi)
    }

    /// The relative residual of the load inversion at a contact with load `load` (N) and
    /// approach `delta` (m): |δ_trend(Q, n) − δ|/(δ_hi − δ_lo), None where the law is an end law
    /// (no inversion).
    pub fn inversion_residual(&self, load: f64, delta: f64) -> Option<f64> {
        (delta > self.delta_lo && delta < self.delta_hi).then(|| {
            let d = self.race.approach_at(load, self.n);
            (d - delta).abs() / (self.delta_hi - self.delta_lo)
        })
    }

    /// (Q, dQ/dδ, relative residual) at approach δ inside [δ_lo, δ_hi].
    fn invert(&self, delta: f64) -> (f64, f64, f64) {
        let (mut a, mut b) = (self.lo, self.hi);
        let mut q = if self.hint > a && self.hint < b {
            self.hint
        } else {
            // Interpolate in the approach between the ends.
            a + (b - a) * (delta - self.delta_lo) / (self.delta_hi - self.delta_lo)
        };
        let scale = (self.delta_hi - self.delta_lo).abs().max(1e-300);
        let mut res = f64::INFINITY;
        let mut slope = 0.0;
        for _ in 0..self.max_iterations {
            let (d, dd) = self.race.approach_dq(q, self.n);
            let f = d - delta;
            res = f.abs() / scale;
            slope = dd;
            if f > 0.0 {
                b = q;
            } else {
                a = q;
            }
            if res <= self.tolerance || (b - a) <= self.tolerance * b {
                break;
            }
            let newton = q - f / dd;
            q = if dd > 0.0 && newton > a && newton < b {
                newton
            } else {
                0.5 * (a + b)
            };
        }
        let dq = if slope > 0.0 { 1.0 / slope } else { 0.0 };
        (q, dq, res)
    }
}

impl ContactLaw for RaceLaw {
    fn force(&self, approach: f64) -> (f64, f64) {
        if approach <= self.delta_lo {
            self.law_lo.force(approach)
        } else if approach >= self.delta_hi {
            self.law_hi.force(approach)
        } else {
            let (q, dq, _) = self.invert(approach);
            (q, dq)
        }
    }

    fn approach_at(&self, load: f64) -> Option<f64> {
        if !(load.is_finite() && load > 0.0) {
            return None;
        }
        if load <= self.lo {
            self.law_lo.approach_at(load)
        } else if load >= self.hi {
            self.law_hi.approach_at(load)
        } else {
            Some(self.race.approach_at(load, self.n))
        }
    }
}

/// The laws of both raceways at one speed (a force element keeps them between calls at the
/// same speed).
#[derive(Debug, Clone)]
pub struct SpeedLaws {
    n: f64,
    races: [RaceLaw; 2],
}

impl SpeedLaws {
    /// The raceway laws of `model` at relative speed `n` (rad/s, clamped into each raceway's
    /// speed range), with the load inversion's relative `tolerance` and iteration limit.
    /// `races` are the model's [inner, outer] trends, shared with the laws.
    pub fn new(
        model: &TrendModel,
        races: &[Arc<RaceTrends>; 2],
        n: f64,
        tolerance: f64,
        max_iterations: usize,
    ) -> Result<Self, TrendError> {
        let mk = |k: usize, race: Race| -> Result<RaceLaw, TrendError> {
            let t = &races[k];
            let [lo, hi] = t.load_range_n;
            let [nlo, nhi] = t.speed_range_rad_s;
            let nc = n.clamp(nlo, nhi);
            Ok(RaceLaw {
                race: races[k].clone(),
                n: nc,
                lo,
                hi,
                delta_lo: t.approach_at(lo, nc),
                delta_hi: t.approach_at(hi, nc),
                law_lo: model.law_at(race, lo, nc)?.0,
                law_hi: model.law_at(race, hi, nc)?.0,
                hint: f64::NAN,
                tolerance,
                max_iterations,
            })
        };
        Ok(SpeedLaws {
            n,
            races: [mk(0, Race::Inner)?, mk(1, Race::Outer)?],
        })
    }

    /// The speed asked for (before clamping), rad/s.
    pub fn speed(&self) -> f64 {
        self.n
    }

    /// The [inner, outer] raceway laws.
    pub fn races(&self) -> &[RaceLaw; 2] {
        &self.races
    }
}
