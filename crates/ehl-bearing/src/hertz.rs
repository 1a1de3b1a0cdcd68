//! Hertz elliptical point contact from the exact complete elliptic integrals.
//!
//! Conventions: x is the rolling direction with curvature radius `rx`, y the transverse direction
//! with `ry`, `rx ≤ ry` is not required (the semi-axis `a` is always along the larger radius).
//! E′ is the EHL reduced modulus, 2/E′ = (1−ν1²)/E1 + (1−ν2²)/E2.
//!
//! Formulas (Johnson, *Contact Mechanics*, ch. 4; Harris, *Rolling Bearing Analysis*), with
//! m = 1 − (b/a)², k = a/b = (1 − m)^(−1/2), R = 1/(1/Rx + 1/Ry):
//! Ry/Rx = [E(m)/(1−m) − K(m)]/[K(m) − E(m)],
//! a = (6k²E·Q·R/(πE′))^(1/3), b = (6E·Q·R/(πkE′))^(1/3),
//! δ = K·[(9/(2E·R))·(Q/(πkE′))²]^(1/3), p_max = 3Q/(2πab).

use serde::Serialize;
use std::f64::consts::PI;
use thiserror::Error;

/// Errors of the Hertz module.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum HertzError {
    /// A curvature radius is not positive and finite.
    #[error("curvature radius {name} = {value} m is not a positive finite number")]
    BadRadius {
        /// Which radius.
        name: &'static str,
        /// Its value, m.
        value: f64,
    },
    /// The reduced modulus is not positive and finite.
    #[error("reduced modulus E' = {0} Pa is not a positive finite number")]
    BadModulus(f64),
    /// The radius ratio is beyond what the ellipticity solver covers.
    #[error("radius ratio {0} is outside the supported range 1 to 1e8")]
    RatioOutOfRange(f64),
}

/// Complete elliptic integrals of the first and second kind, K(m) and E(m), parameter m = k² in [0, 1),
/// by the arithmetic–geometric mean (exact to round-off).
pub fn elliptic_ke(m: f64) -> (f64, f64) {
    debug_assert!((0.0..1.0).contains(&m), "m = {m}");
    let mut a = 1.0_f64;
    let mut g = (1.0 - m).sqrt();
    let mut c = m.sqrt();
    let mut sum = 0.5 * c * c; // Σ 2^(n−1) c_n², n = 0 term
    let mut pow2 = 0.5;
    for _ in 0..40 {
        if c.abs() < 1e-17 * a {
            break;
        }
        let an = 0.5 * (a + g);
        let gn = (a * g).sqrt();
        c = 0.5 * (a - g);
        a = an;
        g = gn;
        pow2 *= 2.0;
        sum += pow2 * c * c;
    }
    let k = PI / (2.0 * a);
    let e = k * (1.0 - sum);
    (k, e)
}

/// Ry/Rx for a given m = 1 − (b/a)² (a along Ry).
fn ratio_of_m(m: f64) -> f64 {
    let (k, e) = elliptic_ke(m);
    (e / (1.0 - m) - k) / (k - e)
}

/// Ellipse parameter m = 1 − (b/a)² for a radius ratio `ratio` = R_major/R_minor ≥ 1.
///
/// Solved by bisection–secant on ln(1 − m), which is monotone in the ratio.
pub fn ellipse_parameter(ratio: f64) -> Result<f64, HertzError> {
    if !(ratio.is_finite() && (1.0..=1e8).contains(&ratio)) {
        return Err(HertzError::RatioOutOfRange(ratio));
    }
    if ratio - 1.0 < 1e-12 {
        return Ok(0.0);
    }
    // Unknown s = ln(1/(1-m)) = 2 ln k, in (0, ~40). Brewe–Hamrock start: k ≈ 1.0339 ratio^0.636.
    let f = |s: f64| ratio_of_m(1.0 - (-s).exp()).ln() - ratio.ln();
    let mut lo = 1e-14_f64;
    let mut hi = 60.0_f64;
    let mut s = (2.0 * (1.0339 * ratio.powf(0.6360)).ln()).clamp(lo * 10.0, hi * 0.9);
    for _ in 0..200 {
        let fs = f(s);
        if fs.abs() < 1e-14 {
            break;
        }
        if fs > 0.0 {
            hi = s;
        } else {
            lo = s;
        }
        // Secant/Newton-like step with numerical slope, safeguarded by the bracket.
        let h = 1e-7 * s.max(1e-6);
        let slope = (f(s + h) - fs) / h;
        let mut next = s - fs / slope;
        if !(next > lo && next < hi && next.is_finite()) {
            next = 0.5 * (lo + hi);
        }
        if (next - s).abs() < 1e-15 * s.max(1.0) {
            s = next;
            break;
        }
        s = next;
    }
    Ok(1.0 - (-s).exp())
}

/// The geometry-only part of a Hertz contact: constants that do not depend on the load.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HertzGeometry {
    /// Curvature radius in the rolling direction, m.
    pub rx: f64,
    /// Curvature radius in the transverse direction, m.
    pub ry: f64,
    /// Reduced modulus E′, Pa.
    pub e_reduced: f64,
    /// Ellipticity k = a/b ≥ 1 (a along the larger radius), dimensionless.
    pub ellipticity: f64,
    /// Complete elliptic integral of the first kind K(m), dimensionless.
    pub k_first: f64,
    /// Complete elliptic integral of the second kind E(m), dimensionless.
    pub e_second: f64,
    /// Effective radius R = 1/(1/Rx + 1/Ry), m.
    pub r_eff: f64,
    /// Load–deflection constant K_H in Q = K_H·δ^1.5, N/m^1.5.
    pub stiffness: f64,
}

/// The load-dependent Hertz solution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HertzContact {
    /// Normal load Q, N.
    pub load: f64,
    /// Semi-axis along the larger curvature radius, m.
    pub semi_major: f64,
    /// Semi-axis along the smaller curvature radius, m.
    pub semi_minor: f64,
    /// Maximum (central) pressure p_h = 3Q/(2πab), Pa.
    pub max_pressure: f64,
    /// Elastic approach of distant points δ, m.
    pub deflection: f64,
}

impl HertzGeometry {
    /// Contact constants for curvature radii `rx`, `ry` (m) and reduced modulus `e_reduced` (Pa).
    pub fn new(rx: f64, ry: f64, e_reduced: f64) -> Result<Self, HertzError> {
        for (name, value) in [("rx", rx), ("ry", ry)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(HertzError::BadRadius { name, value });
            }
        }
        if !(e_reduced.is_finite() && e_reduced > 0.0) {
            return Err(HertzError::BadModulus(e_reduced));
        }
        let ratio = rx.max(ry) / rx.min(ry);
        let m = ellipse_parameter(ratio)?;
        let (k_first, e_second) = elliptic_ke(m);
        let ellipticity = (1.0 - m).powf(-0.5);
        let r_eff = 1.0 / (1.0 / rx + 1.0 / ry);
        // δ = K·[(9/(2E R))·(Q/(πkE′))²]^(1/3) = c·Q^(2/3)  =>  K_H = c^(-3/2)
        let c = k_first
            * (9.0 / (2.0 * e_second * r_eff) / (PI * ellipticity * e_reduced).powi(2)).cbrt();
        Ok(HertzGeometry {
            rx,
            ry,
            e_reduced,
            ellipticity,
            k_first,
            e_second,
            r_eff,
            stiffness: c.powf(-1.5),
        })
    }

    /// The contact under normal load `load` (N, ≥ 0).
    pub fn contact(&self, load: f64) -> HertzContact {
        let q = load.max(0.0);
        let k = self.ellipticity;
        let e = self.e_second;
        let base = 6.0 * e * q * self.r_eff / (PI * self.e_reduced);
        let semi_major = (base * k * k).cbrt();
        let semi_minor = (base / k).cbrt();
        let max_pressure = if q > 0.0 {
            3.0 * q / (2.0 * PI * semi_major * semi_minor)
        } else {
            0.0
        };
        HertzContact {
            load: q,
            semi_major,
            semi_minor,
            max_pressure,
            deflection: (q / self.stiffness).powf(2.0 / 3.0),
        }
    }

    /// The load (N) that gives approach `deflection` (m); zero for δ ≤ 0.
    pub fn load_at(&self, deflection: f64) -> f64 {
        if deflection > 0.0 {
            self.stiffness * deflection.powf(1.5)
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn elliptic_integrals_reference_values() {
        // Abramowitz & Stegun Table 17.1: K(0.5) = 1.8540746773, E(0.5) = 1.3506438810;
        // K(0.9) = 2.5780921134, E(0.9) = 1.1047747327.
        let (k, e) = elliptic_ke(0.5);
        assert!(rel(k, 1.854_074_677_3) < 1e-10);
        assert!(rel(e, 1.350_643_881_0) < 1e-10);
        let (k, e) = elliptic_ke(0.9);
        assert!(rel(k, 2.578_092_113_4) < 1e-10);
        assert!(rel(e, 1.104_774_732_7) < 1e-10);
        let (k, e) = elliptic_ke(0.0);
        assert!(rel(k, PI / 2.0) < 1e-15 && rel(e, PI / 2.0) < 1e-15);
    }

    #[test]
    fn ellipse_parameter_inverts_ratio() {
        for ratio in [1.0001, 1.5, 3.0, 12.0, 61.0, 100.0, 1e4] {
            let m = ellipse_parameter(ratio).unwrap();
            assert!(rel(ratio_of_m(m), ratio) < 1e-11, "ratio {ratio}");
        }
        assert!(ellipse_parameter(0.5).is_err());
        assert!(ellipse_parameter(f64::NAN).is_err());
    }

    #[test]
    fn circular_limit_closed_form() {
        // Ball of radius R0 on a flat: Rx = Ry = R0. Reference (Johnson, Contact Mechanics ch. 4):
        // a = (3 Q R0/(2E'))^(1/3), δ = (9Q²/(4E'² R0))^(1/3), p_max = 3Q/(2πa²).
        let (r0, e, q) = (3.5e-3, 228.6e9, 1000.0);
        let g = HertzGeometry::new(r0, r0, e).unwrap();
        let c = g.contact(q);
        let a = (3.0 * q * r0 / (2.0 * e)).cbrt();
        assert!(rel(c.semi_major, a) < 1e-12);
        assert!(rel(c.semi_minor, a) < 1e-12);
        assert!(rel(c.deflection, (9.0 * q * q / (4.0 * e * e * r0)).cbrt()) < 1e-12);
        assert!(rel(c.max_pressure, 3.0 * q / (2.0 * PI * a * a)) < 1e-12);
    }

    #[test]
    fn brewe_hamrock_within_a_few_percent_at_moderate_ratio() {
        // Brewe–Hamrock approximations are fits good to a few percent;
        // at Ry/Rx = 12 they should agree within 4 %.
        let ratio = 12.0;
        let g = HertzGeometry::new(1.0, ratio, 1e11).unwrap();
        assert!(rel(g.ellipticity, 1.0339 * ratio.powf(0.6360)) < 0.04);
        assert!(rel(g.e_second, 1.0003 + 0.5968 / ratio) < 0.04);
        assert!(rel(g.k_first, 1.5277 + 0.6023 * ratio.ln()) < 0.04);
    }

    #[test]
    fn load_deflection_round_trip() {
        let g = HertzGeometry::new(2.94e-3, 178.5e-3, 228.6e9).unwrap();
        let c = g.contact(500.0);
        assert!(rel(g.load_at(c.deflection), 500.0) < 1e-12);
        // p_max from the semi-axes equals 3Q/(2πab) by definition; check the area integral instead:
        // ∬ p dA = (2/3) π a b p_max = Q.
        assert!(
            rel(
                2.0 / 3.0 * PI * c.semi_major * c.semi_minor * c.max_pressure,
                500.0
            ) < 1e-12
        );
        assert!(g.ellipticity > 10.0);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(HertzGeometry::new(-1.0, 1.0, 1.0).is_err());
        assert!(HertzGeometry::new(1.0, f64::INFINITY, 1.0).is_err());
        assert!(HertzGeometry::new(1.0, 1.0, 0.0).is_err());
    }
}
