//! The dry Hertz law of one bearing contact, with its load–deflection constant at the operating
//! contact angle.
//!
//! The curvature radius in the rolling direction depends on the contact angle α,
//! Rx = D(d_m ∓ D cos α)/(2 d_m) (− inner, + outer), and with it the ellipticity, the elliptic
//! integrals and K_H (Harris, *Rolling Bearing Analysis*; `hertz.rs`). Solving for the ellipticity
//! at every evaluation of a ball's equilibrium would cost more than the rest of the ball, so
//! ln(K_H(α)/K_H(α0)) is represented by a Chebyshev series in c = cos α on [−1, 1], fitted to the
//! exact constants once per bearing. Rx(c) is analytic on [−1, 1] with its nearest singularity at
//! c = ±d_m/D, so the series converges geometrically; the fit is checked against the exact values
//! between the nodes and refined until they agree to 1e-12 relative.

use super::geometry::{Bearing, Race};
use super::BearingError;
use crate::contact_law::{ContactLaw, HertzLaw};
use std::f64::consts::PI;
use std::sync::Arc;

/// Relative accuracy the Chebyshev fit of K_H(α) must reach against the exact constants.
const FIT_TOLERANCE: f64 = 1e-12;

/// Dry Hertz law Q = K_H(α)·δ^1.5 of one ball/raceway contact whose constant follows the
/// operating contact angle α. [`ContactLaw::force`] gives the law at the free contact angle α0;
/// [`ContactLaw::angle_factor`] gives K_H(α)/K_H(α0) and its derivative, which the bearing model
/// applies at each contact's operating angle.
#[derive(Debug, Clone)]
pub struct OperatingAngleHertzLaw {
    /// K_H at the free contact angle α0, N/m^1.5.
    pub stiffness: f64,
    /// Chebyshev coefficients of ln(K_H/K_H(α0)) in cos α (dimensionless).
    coef: Arc<[f64]>,
    /// Coefficients of its derivative with respect to cos α.
    dcoef: Arc<[f64]>,
}

/// Σ' a_k T_k(x) by Clenshaw's recurrence (first term halved).
fn clenshaw(a: &[f64], x: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &ak in a.iter().skip(1).rev() {
        let b0 = 2.0 * x * b1 - b2 + ak;
        b2 = b1;
        b1 = b0;
    }
    x * b1 - b2 + 0.5 * a[0]
}

impl OperatingAngleHertzLaw {
    /// The law of `race` of `bearing` (materials and geometry validated by the caller).
    pub fn new(bearing: &Bearing, race: Race) -> Result<Self, BearingError> {
        let a0 = bearing.geometry.free_contact_angle;
        let k0 = bearing.hertz(race, a0)?.stiffness;
        let exact = |c: f64| -> Result<f64, BearingError> {
            Ok((bearing.hertz(race, c.clamp(-1.0, 1.0).acos())?.stiffness / k0).ln())
        };
        let mut n = 16;
        loop {
            // Chebyshev nodes of the first kind and the interpolating coefficients.
            let nodes: Vec<f64> = (0..n)
                .map(|k| (PI * (k as f64 + 0.5) / n as f64).cos())
                .collect();
            let vals = nodes
                .iter()
                .map(|&c| exact(c))
                .collect::<Result<Vec<_>, _>>()?;
            let coef: Vec<f64> = (0..n)
                .map(|j| {
                    2.0 / n as f64
                        * (0..n)
                            .map(|k| vals[k] * (PI * j as f64 * (k as f64 + 0.5) / n as f64).cos())
                            .sum::<f64>()
                })
                .collect();
            // Check between the nodes (and at the ends and the free angle).
            let mut worst = 0.0_f64;
            let checks =
                (0..n - 1)
                    .map(|k| 0.5 * (nodes[k] + nodes[k + 1]))
                    .chain([-1.0, 1.0, a0.cos()]);
            for c in checks {
                worst = worst.max((clenshaw(&coef, c) - exact(c)?).abs());
            }
            if worst <= FIT_TOLERANCE {
                // Derivative series: c'_{k−1} = c'_{k+1} + 2k·a_k.
                let mut d = vec![0.0; n + 1];
                for k in (1..n).rev() {
                    d[k - 1] = d[k + 1] + 2.0 * k as f64 * coef[k];
                }
                d.truncate(n.max(1));
                return Ok(OperatingAngleHertzLaw {
                    stiffness: k0,
                    coef: coef.into(),
                    dcoef: d.into(),
                });
            }
            if n >= 256 {
                return Err(BearingError::HertzSeries {
                    race,
                    tolerance: FIT_TOLERANCE,
                    worst,
                    terms: n,
                });
            }
            n *= 2;
        }
    }

    /// K_H(α)/K_H(α0) (dimensionless) and its derivative with respect to α (1/rad).
    pub fn factor(&self, contact_angle: f64) -> (f64, f64) {
        let (s, c) = contact_angle.sin_cos();
        let f = clenshaw(&self.coef, c).exp();
        (f, -f * clenshaw(&self.dcoef, c) * s)
    }
}

impl OperatingAngleHertzLaw {
    /// The plain Hertz law with this law's constant at its reference angle.
    fn at_reference(&self) -> HertzLaw {
        HertzLaw {
            stiffness: self.stiffness,
        }
    }
}

impl ContactLaw for OperatingAngleHertzLaw {
    /// The dry Hertz law at the reference angle ([`HertzLaw`]); the angle enters through
    /// [`ContactLaw::angle_factor`].
    fn force(&self, approach: f64) -> (f64, f64) {
        self.at_reference().force(approach)
    }

    fn approach_at(&self, load: f64) -> Option<f64> {
        self.at_reference().approach_at(load)
    }

    fn angle_factor(&self, contact_angle: f64) -> Option<(f64, f64)> {
        Some(self.factor(contact_angle))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearing::geometry::BearingGeometry;
    use crate::material::Solid;

    fn bearing(d: f64, dm: f64, fi: f64, fo: f64, a0: f64) -> Bearing {
        Bearing {
            geometry: BearingGeometry::new(3, d, dm, fi, fo, a0.to_radians()).unwrap(),
            ball_material: Solid::AISI_52100,
            ring_material: Solid::AISI_52100,
        }
    }

    #[test]
    fn factor_matches_exact_hertz_constants_and_their_derivative() {
        // The seed 7006, the 218 of Harris' high-speed example and an extreme geometry (ball
        // almost the pitch circle, f_o near its limit where Ry ≈ Rx at the outer race).
        // Derivative tolerance: the interpolant's derivative errs by up to ~n² times its value
        // error (Markov's inequality); the extreme geometry (Ry/Rx ≈ 3000 at the inner race) needs
        // the most terms, hence its looser bound. The Jacobian of the bearing model is exact for
        // the interpolant either way.
        for (b, dtol) in [
            (bearing(7e-3, 42.5e-3, 0.51, 0.54, 15.0), 1e-8),
            (bearing(22.23e-3, 125.26e-3, 0.5232, 0.5232, 40.0), 1e-8),
            (
                bearing(20e-3, 25e-3 / (PI / 3.0).sin() * 1.0001, 0.5005, 4.9, 30.0),
                1e-6,
            ),
        ] {
            for race in [Race::Inner, Race::Outer] {
                let law = OperatingAngleHertzLaw::new(&b, race).unwrap();
                let k0 = b
                    .hertz(race, b.geometry.free_contact_angle)
                    .unwrap()
                    .stiffness;
                assert_eq!(law.stiffness, k0);
                for deg in [-89.0, -30.0, 0.0, 7.3, 15.0, 33.3, 40.0, 61.0, 89.9] {
                    let a: f64 = f64::to_radians(deg);
                    let exact = b.hertz(race, a).unwrap().stiffness / k0;
                    let (f, df) = law.factor(a);
                    assert!(
                        (f / exact - 1.0).abs() < 1e-11,
                        "{race:?} {deg}: {f} vs {exact}"
                    );
                    // Central difference of the exact constants, h = 1e-5 rad: truncation
                    // ~h²·f‴ ≈ 1e-10, round-off ~1e-16/h ≈ 1e-11.
                    let h = 1e-5;
                    let fd = (b.hertz(race, a + h).unwrap().stiffness
                        - b.hertz(race, a - h).unwrap().stiffness)
                        / (2.0 * h * k0);
                    assert!(
                        (df - fd).abs() < dtol * (1.0 + fd.abs()),
                        "{:?} {race:?} {deg}: {df} vs {fd}",
                        b.geometry
                    );
                }
            }
        }
    }
}
