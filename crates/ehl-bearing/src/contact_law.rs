//! Contact force laws Q(δ): the normal force of one ball/raceway contact as a function of the
//! approach δ of distant points (m, positive when the bodies are pressed together).

/// A normal contact force law. Implementations must be cheap: the bearing equilibrium calls them
/// many times per Newton iteration.
pub trait ContactLaw: Send + Sync + std::fmt::Debug {
    /// Normal force Q in N and its derivative dQ/dδ in N/m at approach `approach` (m).
    ///
    /// Must be continuous with a continuous derivative, and non-decreasing in δ.
    fn force(&self, approach: f64) -> (f64, f64);

    /// The approach δ (m) at which the force equals `load` (N), if the law reaches that load.
    fn approach_at(&self, load: f64) -> Option<f64> {
        // Generic inversion by bracketing Newton; laws with a closed-form inverse override this.
        invert_monotone(self, load)
    }

    /// Damping coefficient c of a c·δ̇ term at approach `approach` (m), N·s/m: the force grows by
    /// c·δ̇ when the approach changes at the rate δ̇ (m/s). Default 0 (no damping: dry laws and
    /// laws fitted by the quasi-static method).
    fn damping(&self, approach: f64) -> f64 {
        let _ = approach;
        0.0
    }

    /// For a law whose force depends on the contact angle α (rad) through the contact's
    /// curvature (the dry Hertz law of a bearing contact, `bearing::ContactLaws::hertz`): the
    /// factor c(α) (dimensionless) and dc/dα (1/rad) such that the force at angle α is
    /// c(α)·`force`(δ). `None` (the default): the law is used as given at every angle.
    fn angle_factor(&self, _contact_angle: f64) -> Option<(f64, f64)> {
        None
    }
}

/// Dry Hertz law Q = K·δ^1.5 for δ > 0, Q = 0 otherwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzLaw {
    /// Load–deflection constant K, N/m^1.5.
    pub stiffness: f64,
}

impl ContactLaw for HertzLaw {
    fn force(&self, approach: f64) -> (f64, f64) {
        if approach > 0.0 {
            let s = approach.sqrt();
            (self.stiffness * approach * s, 1.5 * self.stiffness * s)
        } else {
            (0.0, 0.0)
        }
    }

    fn approach_at(&self, load: f64) -> Option<f64> {
        if load >= 0.0 && load.is_finite() {
            Some((load / self.stiffness).powf(2.0 / 3.0))
        } else {
            None
        }
    }
}

/// Solve law(δ) = load for a monotone law, by expanding a bracket and safeguarded Newton.
pub fn invert_monotone<L: ContactLaw + ?Sized>(law: &L, load: f64) -> Option<f64> {
    if !load.is_finite() {
        return None;
    }
    let (mut lo, mut hi) = (-1e-6_f64, 1e-6_f64);
    let mut grow = 0;
    while law.force(lo).0 > load {
        lo *= 2.0;
        grow += 1;
        if grow > 60 {
            return None;
        }
    }
    grow = 0;
    while law.force(hi).0 < load {
        hi *= 2.0;
        grow += 1;
        if grow > 60 {
            return None;
        }
    }
    let mut x = 0.5 * (lo + hi);
    for _ in 0..200 {
        let (f, df) = law.force(x);
        let r = f - load;
        if r.abs() <= 1e-13 * load.abs().max(1e-9) {
            return Some(x);
        }
        if r > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let mut next = if df > 0.0 { x - r / df } else { f64::NAN };
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (hi - lo).abs() < 1e-18 {
            return Some(next);
        }
        x = next;
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hertz_law_derivative_matches_finite_difference() {
        let law = HertzLaw { stiffness: 1e10 };
        let d = 5e-6;
        let h = 1e-12;
        let fd = (law.force(d + h).0 - law.force(d - h).0) / (2.0 * h);
        assert!((fd / law.force(d).1 - 1.0).abs() < 1e-6);
        assert_eq!(law.force(-1e-6), (0.0, 0.0));
    }

    #[test]
    fn generic_inversion_matches_closed_form() {
        let law = HertzLaw { stiffness: 1e10 };
        let q = 742.0;
        let exact = law.approach_at(q).unwrap();
        let generic = invert_monotone(&law, q).unwrap();
        assert!((generic / exact - 1.0).abs() < 1e-10);
    }
}
