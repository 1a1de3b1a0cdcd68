//! Bearing geometry and materials (SI units).

use super::BearingError;
use crate::hertz::HertzGeometry;
use crate::material::{reduced_modulus, Solid};
use serde::Serialize;
use std::f64::consts::PI;

/// Internal geometry of an angular-contact ball bearing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct BearingGeometry {
    /// Number of balls Z (≥ 3).
    pub ball_count: usize,
    /// Ball diameter D, m.
    pub ball_diameter: f64,
    /// Pitch diameter d_m, m.
    pub pitch_diameter: f64,
    /// Inner raceway conformity f_i = r_i/D (groove radius over ball diameter), > 0.5.
    pub inner_conformity: f64,
    /// Outer raceway conformity f_o = r_o/D, > 0.5.
    pub outer_conformity: f64,
    /// Free (unloaded) contact angle α0, rad, in [0, π/2).
    pub free_contact_angle: f64,
}

/// Which raceway a contact is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Race {
    /// The inner ring's raceway.
    Inner,
    /// The outer ring's raceway.
    Outer,
}

impl BearingGeometry {
    /// Validated geometry. Errors name the field (SI), its value and the valid range.
    pub fn new(
        ball_count: usize,
        ball_diameter: f64,
        pitch_diameter: f64,
        inner_conformity: f64,
        outer_conformity: f64,
        free_contact_angle: f64,
    ) -> Result<Self, BearingError> {
        let g = BearingGeometry {
            ball_count,
            ball_diameter,
            pitch_diameter,
            inner_conformity,
            outer_conformity,
            free_contact_angle,
        };
        g.validate()?;
        Ok(g)
    }

    /// Free contact angle from the diametral clearance P_d (m): cos α0 = 1 − P_d/(2(f_i + f_o − 1)D).
    pub fn contact_angle_from_clearance(
        ball_diameter: f64,
        inner_conformity: f64,
        outer_conformity: f64,
        diametral_clearance: f64,
    ) -> Result<f64, BearingError> {
        let a = (inner_conformity + outer_conformity - 1.0) * ball_diameter;
        let c = 1.0 - diametral_clearance / (2.0 * a);
        if !(diametral_clearance.is_finite() && diametral_clearance >= 0.0 && a > 0.0 && c > 0.0) {
            return Err(BearingError::invalid(
                "diametral_clearance",
                diametral_clearance,
                format!("0 ≤ P_d < 2(f_i + f_o − 1)D = {:.6e} m", 2.0 * a),
            ));
        }
        Ok(c.acos())
    }

    /// Check every field; see [`BearingGeometry::new`].
    pub fn validate(&self) -> Result<(), BearingError> {
        let finite_pos = |name: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(BearingError::invalid(name, v, "a positive finite number"))
            }
        };
        if self.ball_count < 3 {
            return Err(BearingError::invalid(
                "ball_count",
                self.ball_count as f64,
                "at least 3",
            ));
        }
        finite_pos("ball_diameter", self.ball_diameter)?;
        finite_pos("pitch_diameter", self.pitch_diameter)?;
        if self.ball_diameter >= self.pitch_diameter {
            return Err(BearingError::invalid(
                "ball_diameter",
                self.ball_diameter,
                format!(
                    "less than the pitch diameter {} m (ball and pitch diameter swapped?)",
                    self.pitch_diameter
                ),
            ));
        }
        for (name, f) in [
            ("inner_conformity", self.inner_conformity),
            ("outer_conformity", self.outer_conformity),
        ] {
            if !(f.is_finite() && f > 0.5 && f < 5.0) {
                return Err(BearingError::invalid(
                    name,
                    f,
                    "groove radius over ball diameter, > 0.5 (a groove wider than the ball) and < 5",
                ));
            }
        }
        if !(self.free_contact_angle.is_finite()
            && self.free_contact_angle >= 0.0
            && self.free_contact_angle < 0.49 * PI)
        {
            return Err(BearingError::invalid(
                "free_contact_angle",
                self.free_contact_angle,
                "0 ≤ α0 < 88.2° (in rad)",
            ));
        }
        // Balls must fit on the pitch circle: chord between neighbours 2·(dm/2)·sin(π/Z) > D.
        let chord = self.pitch_diameter * (PI / self.ball_count as f64).sin();
        if chord <= self.ball_diameter {
            return Err(BearingError::invalid(
                "ball_count",
                self.ball_count as f64,
                format!(
                    "at most {} balls of diameter {} m fit on pitch diameter {} m",
                    max_balls(self.ball_diameter, self.pitch_diameter),
                    self.ball_diameter,
                    self.pitch_diameter
                ),
            ));
        }
        Ok(())
    }

    /// Distance between the inner and outer groove curvature centres when unloaded,
    /// A = (f_i + f_o − 1)·D, m.
    pub fn center_distance(&self) -> f64 {
        (self.inner_conformity + self.outer_conformity - 1.0) * self.ball_diameter
    }

    /// Radius of the locus of inner groove curvature centres, ℜ_i = d_m/2 + (f_i − 0.5)·D·cos α0, m.
    pub fn inner_groove_center_radius(&self) -> f64 {
        0.5 * self.pitch_diameter
            + (self.inner_conformity - 0.5) * self.ball_diameter * self.free_contact_angle.cos()
    }

    /// Conformity of a race.
    pub fn conformity(&self, race: Race) -> f64 {
        match race {
            Race::Inner => self.inner_conformity,
            Race::Outer => self.outer_conformity,
        }
    }

    /// Curvature radii (Rx, Ry) in m of a contact at contact angle `alpha` (rad): x is the rolling
    /// direction. Inner: Rx = D(d_m − D cos α)/(2 d_m); outer: Rx = D(d_m + D cos α)/(2 d_m);
    /// Ry = f·D/(2f − 1).
    pub fn curvature_radii(&self, race: Race, alpha: f64) -> (f64, f64) {
        let d = self.ball_diameter;
        let dm = self.pitch_diameter;
        let f = self.conformity(race);
        let rx = match race {
            Race::Inner => d * (dm - d * alpha.cos()) / (2.0 * dm),
            Race::Outer => d * (dm + d * alpha.cos()) / (2.0 * dm),
        };
        (rx, f * d / (2.0 * f - 1.0))
    }
}

/// Largest number of balls of diameter `d` that fit on pitch diameter `dm`.
fn max_balls(d: f64, dm: f64) -> usize {
    let mut z = 3usize;
    while dm * (PI / (z + 1) as f64).sin() > d && z < 10_000 {
        z += 1;
    }
    z
}

/// A bearing: geometry and materials.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct Bearing {
    /// Internal geometry.
    pub geometry: BearingGeometry,
    /// Ball material.
    pub ball_material: Solid,
    /// Ring material (both rings).
    pub ring_material: Solid,
}

impl Bearing {
    /// Reduced modulus E′ of the ball/ring pair, Pa.
    pub fn reduced_modulus(&self) -> f64 {
        reduced_modulus(&self.ball_material, &self.ring_material)
    }

    /// Ball mass m = ρ·πD³/6, kg.
    pub fn ball_mass(&self) -> f64 {
        self.ball_material.density * PI * self.geometry.ball_diameter.powi(3) / 6.0
    }

    /// Ball polar moment of inertia J = m·D²/10, kg·m².
    pub fn ball_inertia(&self) -> f64 {
        self.ball_mass() * self.geometry.ball_diameter.powi(2) / 10.0
    }

    /// Hertz constants of a contact at contact angle `alpha` (rad).
    pub fn hertz(&self, race: Race, alpha: f64) -> Result<HertzGeometry, BearingError> {
        let (rx, ry) = self.geometry.curvature_radii(race, alpha);
        Ok(HertzGeometry::new(rx, ry, self.reduced_modulus())?)
    }

    /// Validate geometry and materials.
    pub fn validate(&self) -> Result<(), BearingError> {
        self.geometry.validate()?;
        for (name, s) in [
            ("ball_material", &self.ball_material),
            ("ring_material", &self.ring_material),
        ] {
            if !(s.youngs_modulus.is_finite() && s.youngs_modulus > 0.0) {
                return Err(BearingError::invalid(
                    leak(format!("{name}.youngs_modulus")),
                    s.youngs_modulus,
                    "a positive finite number (Pa)",
                ));
            }
            if !(s.poisson_ratio.is_finite() && s.poisson_ratio > -1.0 && s.poisson_ratio < 0.5) {
                return Err(BearingError::invalid(
                    leak(format!("{name}.poisson_ratio")),
                    s.poisson_ratio,
                    "−1 < ν < 0.5",
                ));
            }
            if !(s.density.is_finite() && s.density > 0.0) {
                return Err(BearingError::invalid(
                    leak(format!("{name}.density")),
                    s.density,
                    "a positive finite number (kg/m³)",
                ));
            }
        }
        Ok(())
    }
}

fn leak(s: String) -> &'static str {
    // Field names are few and error paths rare; a leaked short string keeps the error type simple.
    Box::leak(s.into_boxed_str())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g7006() -> BearingGeometry {
        BearingGeometry::new(11, 7e-3, 42.5e-3, 0.51, 0.54, 15f64.to_radians()).unwrap()
    }

    #[test]
    fn seed_curvature_ratios() {
        // docs/design.md §2: Ry/Rx ≈ 61 at the inner race and ≈ 12 at the outer for the 7006.
        let g = g7006();
        let (rx, ry) = g.curvature_radii(Race::Inner, g.free_contact_angle);
        assert!((ry / rx - 60.65).abs() < 0.1, "{}", ry / rx);
        let (rx, ry) = g.curvature_radii(Race::Outer, g.free_contact_angle);
        assert!((ry / rx - 11.65).abs() < 0.1, "{}", ry / rx);
    }

    #[test]
    fn clearance_gives_contact_angle() {
        // cos α0 = 1 − P_d/(2A): A = 0.05·7 mm = 0.35 mm; P_d = 0.0238 mm → cos α0 = 0.966
        let a = BearingGeometry::contact_angle_from_clearance(7e-3, 0.51, 0.54, 2.38e-5).unwrap();
        assert!((a.cos() - (1.0 - 2.38e-5 / 0.7e-3)).abs() < 1e-12);
        assert!(BearingGeometry::contact_angle_from_clearance(7e-3, 0.51, 0.54, 1e-3).is_err());
    }

    #[test]
    fn rejects_bad_geometry() {
        let ok = g7006();
        let bad = |g: BearingGeometry, field: &str| {
            let e = g.validate().unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        };
        bad(
            BearingGeometry {
                ball_diameter: 42.5e-3,
                pitch_diameter: 7e-3,
                ..ok
            },
            "ball_diameter",
        );
        bad(
            BearingGeometry {
                inner_conformity: 0.5,
                ..ok
            },
            "inner_conformity",
        );
        bad(
            BearingGeometry {
                ball_count: 2,
                ..ok
            },
            "ball_count",
        );
        bad(
            BearingGeometry {
                ball_count: 20,
                ..ok
            },
            "ball_count",
        );
        bad(
            BearingGeometry {
                free_contact_angle: f64::NAN,
                ..ok
            },
            "free_contact_angle",
        );
    }
}
