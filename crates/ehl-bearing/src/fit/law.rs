//! The fitted contact law Q = K·δ^d + ΔF with its extension below the fitted range.
//!
//! For δ ≥ δ_j the law is the fitted power law. Below the joint δ_j it continues as
//!
//! ```text
//! Q(δ) = Q_j·exp(s·(δ − δ_j)),   s = Q′(δ_j)/Q(δ_j) = K·d·δ_j^(d−1) / (K·δ_j^d + ΔF),
//! ```
//!
//! which matches value and slope at δ_j (C¹), is positive with a positive slope everywhere above
//! the floating-point floor of the exponential (exactly 0 once s·(δ − δ_j) + ln(Q_j/1 N) < −745,
//! some 700 decay lengths below the joint: a separated ball), so a Newton solver never meets a flat
//! region near the fitted range, and decays to 0 as δ → −∞ (the film thickens and the
//! hydrodynamic force vanishes). The joint is δ_j = max(f·δ_min, δ*) with f the joint fraction
//! (default 0.5) and δ* = ((Q(δ_min)/2 − ΔF)/K)^(1/d) the approach where the power law falls to
//! half its value at δ_min (δ* = 0 if it never does for δ > 0, i.e. ΔF ≥ Q(δ_min)/2). So
//! Q_j ≥ Q(δ_min)/2 > 0 always (also for a fitted ΔF < 0), and the power law is never
//! extrapolated far below the data. A joint at δ_j > 0 also avoids the infinite slope of δ^d at
//! δ = 0 when d < 1.

use super::FitError;
use crate::contact_law::ContactLaw;
use serde::Serialize;

/// Default joint fraction f: the extension starts at δ_j = f·δ_min (dimensionless).
pub const DEFAULT_JOINT_FRACTION: f64 = 0.5;

/// Where an approach lies relative to the range the law was fitted on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum RangeStatus {
    /// δ < δ_j: on the exponential extension (includes all δ ≤ 0).
    Extension,
    /// δ_j ≤ δ < δ_min: power law, but below the fitted samples (extrapolated).
    BelowFitted,
    /// δ_min ≤ δ ≤ δ_max: inside the fitted range.
    Fitted,
    /// δ > δ_max: power law above the fitted samples (extrapolated).
    AboveFitted,
    /// δ is NaN.
    Undefined,
}

/// A fitted lubricated contact law Q = K·δ^d + ΔF (+ c·δ̇ via [`FittedLaw::force_with_rate`])
/// with a C¹ exponential extension below a joint approach δ_j:
///
/// ```text
/// Q(δ) = K·δ^d + ΔF                 for δ ≥ δ_j
/// Q(δ) = Q_j·exp(s·(δ − δ_j))        for δ < δ_j,   Q_j = K·δ_j^d + ΔF,   s = K·d·δ_j^(d−1)/Q_j
/// δ_j  = max(f·δ_min, δ*),  δ* = ((Q(δ_min)/2 − ΔF)/K)^(1/d)  (δ* = 0 if Q(δ_min)/2 ≤ ΔF)
/// ```
///
/// Value and slope are continuous at δ_j; Q > 0 and dQ/dδ > 0 everywhere down to the floating-point
/// floor of the tail (no flat region for a Newton solver): where s·(δ − δ_j) + ln(Q_j/1 N) falls
/// below ≈ −745 the extension is exactly 0 N with slope 0 — a contact separated by some 700 decay
/// lengths carries no load; Q → 0 as δ → −∞ (film thicker than at zero approach: the hydrodynamic force
/// vanishes). f is the joint fraction ([`DEFAULT_JOINT_FRACTION`] = 0.5); δ* keeps
/// Q_j ≥ Q(δ_min)/2, so a fitted ΔF < 0 still gives a positive law. Justification and tests:
/// `docs/fit.md`. Construct with [`FittedLaw::new`] or [`PowerLawFit::law`](super::PowerLawFit::law);
/// the constructors check the invariants (K > 0, d > 0, 0 < δ_min ≤ δ_max, Q(δ_min) > 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FittedLaw {
    k: f64,
    d: f64,
    delta_f: f64,
    c: Option<f64>,
    delta_min: f64,
    delta_max: f64,
    delta_joint: f64,
    force_joint: f64,
    tail_rate: f64,
}

impl FittedLaw {
    /// The law with stiffness `k` (N/m^d, > 0), index `d` (> 0), lift `delta_f` (N), fitted on
    /// approaches [`delta_min`, `delta_max`] (m, 0 < min ≤ max), joint at
    /// [`DEFAULT_JOINT_FRACTION`]·δ_min (or higher if ΔF < 0, see the module documentation).
    pub fn new(
        k: f64,
        d: f64,
        delta_f: f64,
        delta_min: f64,
        delta_max: f64,
    ) -> Result<Self, FitError> {
        Self::with_joint_fraction(k, d, delta_f, delta_min, delta_max, DEFAULT_JOINT_FRACTION)
    }

    /// As [`FittedLaw::new`] with the joint fraction f ∈ (0, 1] chosen: δ_j = max(f·δ_min, δ*).
    pub fn with_joint_fraction(
        k: f64,
        d: f64,
        delta_f: f64,
        delta_min: f64,
        delta_max: f64,
        fraction: f64,
    ) -> Result<Self, FitError> {
        let vals = [k, d, delta_f, delta_min, delta_max, fraction];
        if vals.iter().any(|v| !v.is_finite()) {
            return Err(FitError::LawNotFinite {
                k,
                d,
                delta_f,
                delta_min,
                delta_max,
                fraction,
            });
        }
        if !(k > 0.0 && d > 0.0) {
            return Err(FitError::LawNotIncreasing { k, d });
        }
        if !(delta_min > 0.0 && delta_max >= delta_min) {
            return Err(FitError::LawRange {
                delta_min,
                delta_max,
            });
        }
        if !(fraction > 0.0 && fraction <= 1.0) {
            return Err(FitError::LawJointFraction { fraction });
        }
        let q_min = k * delta_min.powf(d) + delta_f;
        if q_min.is_nan() || q_min <= 0.0 {
            return Err(FitError::LawForceNotPositive {
                q_min,
                delta_min,
                delta_f,
            });
        }
        let mut delta_joint = fraction * delta_min;
        let num = 0.5 * q_min - delta_f;
        if num > 0.0 {
            delta_joint = delta_joint.max((num / k).powf(1.0 / d));
        }
        let force_joint = k * delta_joint.powf(d) + delta_f;
        let slope_joint = k * d * delta_joint.powf(d - 1.0);
        let tail_rate = slope_joint / force_joint;
        if !(force_joint > 0.0 && tail_rate > 0.0 && tail_rate.is_finite()) {
            return Err(FitError::LawExtension {
                delta_joint,
                force_joint,
                tail_rate,
            });
        }
        Ok(Self {
            k,
            d,
            delta_f,
            c: None,
            delta_min,
            delta_max,
            delta_joint,
            force_joint,
            tail_rate,
        })
    }

    /// The same law with a damping coefficient c (N·s/m, finite) for [`FittedLaw::force_with_rate`].
    pub fn with_damping(mut self, c: f64) -> Result<Self, FitError> {
        if !c.is_finite() {
            return Err(FitError::LawDamping { c });
        }
        self.c = Some(c);
        Ok(self)
    }

    /// Stiffness K, N/m^d.
    pub fn k(&self) -> f64 {
        self.k
    }
    /// Nonlinear index d (dimensionless).
    pub fn d(&self) -> f64 {
        self.d
    }
    /// Hydrodynamic lift at zero approach ΔF, N (of the power law; the extended law gives
    /// Q(0) = Q_j·exp(−s·δ_j) instead).
    pub fn delta_f(&self) -> f64 {
        self.delta_f
    }
    /// Damping coefficient c, N·s/m, if any.
    pub fn c(&self) -> Option<f64> {
        self.c
    }
    /// Fitted approach range [δ_min, δ_max], m.
    pub fn fit_range(&self) -> [f64; 2] {
        [self.delta_min, self.delta_max]
    }
    /// Joint approach δ_j where the extension starts, m.
    pub fn delta_joint(&self) -> f64 {
        self.delta_joint
    }
    /// Force at the joint Q_j, N.
    pub fn force_joint(&self) -> f64 {
        self.force_joint
    }
    /// Decay rate s of the extension, 1/m (the force falls by e every 1/s below δ_j).
    pub fn tail_rate(&self) -> f64 {
        self.tail_rate
    }

    /// Whether `approach` (m) lies outside the fitted range [δ_min, δ_max] (true for NaN).
    pub fn outside_fit_range(&self, approach: f64) -> bool {
        !(approach >= self.delta_min && approach <= self.delta_max)
    }

    /// Where `approach` (m) lies relative to the joint and the fitted range.
    pub fn range_status(&self, approach: f64) -> RangeStatus {
        if approach.is_nan() {
            RangeStatus::Undefined
        } else if approach < self.delta_joint {
            RangeStatus::Extension
        } else if approach < self.delta_min {
            RangeStatus::BelowFitted
        } else if approach <= self.delta_max {
            RangeStatus::Fitted
        } else {
            RangeStatus::AboveFitted
        }
    }

    /// Force with damping: (Q + c·δ̇ in N, ∂/∂δ in N/m, ∂/∂δ̇ in N·s/m) at approach `approach` (m)
    /// and rate `rate` (m/s). Without damping c = 0. The damping term is added as fitted, on the
    /// extension too, and is not clamped: the total may be negative when the contact separates
    /// fast (a caller that needs Q ≥ 0 must decide how to treat that).
    pub fn force_with_rate(&self, approach: f64, rate: f64) -> (f64, f64, f64) {
        let (q, dq) = self.force(approach);
        let c = self.c.unwrap_or(0.0);
        (q + c * rate, dq, c)
    }
}

impl ContactLaw for FittedLaw {
    fn force(&self, approach: f64) -> (f64, f64) {
        if approach >= self.delta_joint {
            let p = approach.powf(self.d - 1.0);
            (self.k * approach * p + self.delta_f, self.k * self.d * p)
        } else {
            let q = self.force_joint * (self.tail_rate * (approach - self.delta_joint)).exp();
            (q, self.tail_rate * q)
        }
    }

    /// The fitted c inside and above the fitted range; below it c·Q(δ)/Q(δ_min), so the damping
    /// fades with the force as the contact opens instead of acting across a separated contact
    /// (continuous in δ). 0 without a damping term.
    fn damping(&self, approach: f64) -> f64 {
        let Some(c) = self.c else {
            return 0.0;
        };
        if approach >= self.delta_min {
            c
        } else {
            let q_min = self.force(self.delta_min).0;
            if q_min > 0.0 {
                c * (self.force(approach).0 / q_min).clamp(0.0, 1.0)
            } else {
                0.0
            }
        }
    }

    /// Closed-form inverse: None for a load that is not finite and positive (the law is positive
    /// everywhere and tends to 0 only as δ → −∞).
    fn approach_at(&self, load: f64) -> Option<f64> {
        if !(load.is_finite() && load > 0.0) {
            return None;
        }
        if load >= self.force_joint {
            Some(((load - self.delta_f) / self.k).powf(1.0 / self.d))
        } else {
            Some(self.delta_joint + (load / self.force_joint).ln() / self.tail_rate)
        }
    }
}
