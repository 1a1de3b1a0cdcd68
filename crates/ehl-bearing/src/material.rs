//! Solids and lubricant rheology. SI units throughout (Pa, Pa·s, 1/Pa, kg/m³).

use serde::{Deserialize, Serialize};

/// An isotropic linear-elastic solid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Solid {
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, dimensionless, in (−1, 0.5).
    pub poisson_ratio: f64,
    /// Mass density, kg/m³.
    pub density: f64,
}

impl Solid {
    /// AISI 52100 bearing steel: E = 208 GPa, ν = 0.3, ρ = 7850 kg/m³ (the seed case's material,
    /// docs/paper.md).
    pub const AISI_52100: Solid = Solid {
        youngs_modulus: 208e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    };
}

impl Default for Solid {
    fn default() -> Self {
        Solid::AISI_52100
    }
}

/// Reduced modulus E′ in the EHL convention, Pa: 2/E′ = (1−ν1²)/E1 + (1−ν2²)/E2.
///
/// Note: Johnson's E* is E′/2.
pub fn reduced_modulus(a: &Solid, b: &Solid) -> f64 {
    2.0 / ((1.0 - a.poisson_ratio.powi(2)) / a.youngs_modulus
        + (1.0 - b.poisson_ratio.powi(2)) / b.youngs_modulus)
}

/// Pressure–viscosity relation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ViscosityModel {
    /// Roelands (1966): η = η0·exp{(ln η0 + 9.67)·[−1 + (1 + p/p0)^z]}, p0 = 1.96e8 Pa,
    /// z = α·p0/(ln η0 + 9.67).
    #[default]
    Roelands,
    /// Barus: η = η0·exp(α·p).
    Barus,
}

/// Pressure–density relation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum DensityModel {
    /// Dowson–Higginson (1977): ρ/ρ0 = (5.9e8 + 1.34·p)/(5.9e8 + p), p in Pa.
    #[default]
    DowsonHigginson,
    /// Constant density.
    Incompressible,
}

/// Roelands' reference pressure p0, Pa.
pub const ROELANDS_P0: f64 = 1.96e8;
/// Roelands' constant: ln η0 + 9.67 with η0 in Pa·s (η∞ = 6.31e-5 Pa·s).
pub const ROELANDS_LN_ETA_INF: f64 = 9.67;

/// A Newtonian, isothermal lubricant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Lubricant {
    /// Dynamic viscosity at ambient pressure η0, Pa·s.
    pub viscosity: f64,
    /// Pressure–viscosity coefficient α, 1/Pa.
    pub pressure_viscosity: f64,
    /// Density at ambient pressure ρ0, kg/m³.
    pub density: f64,
    /// Viscosity model.
    pub viscosity_model: ViscosityModel,
    /// Density model.
    pub density_model: DensityModel,
}

impl Lubricant {
    /// Default mineral oil (as in Hamrock's worked examples): η0 = 0.04 Pa·s, α = 2.2e-8 1/Pa,
    /// ρ0 = 870 kg/m³, Roelands and Dowson–Higginson. The seed paper gives no lubricant; this is
    /// the project's assumption (docs/paper.md).
    pub const DEFAULT_MINERAL_OIL: Lubricant = Lubricant {
        viscosity: 0.04,
        pressure_viscosity: 2.2e-8,
        density: 870.0,
        viscosity_model: ViscosityModel::Roelands,
        density_model: DensityModel::DowsonHigginson,
    };

    /// Roelands pressure–viscosity index z (dimensionless) matching α at p = 0.
    pub fn roelands_z(&self) -> f64 {
        self.pressure_viscosity * ROELANDS_P0 / (self.viscosity.ln() + ROELANDS_LN_ETA_INF)
    }

    /// Viscosity η(p), Pa·s, for gauge pressure p ≥ 0 in Pa.
    pub fn viscosity_at(&self, p: f64) -> f64 {
        self.viscosity * self.viscosity_ratio(p)
    }

    /// η(p)/η0, dimensionless.
    pub fn viscosity_ratio(&self, p: f64) -> f64 {
        match self.viscosity_model {
            ViscosityModel::Barus => (self.pressure_viscosity * p).exp(),
            ViscosityModel::Roelands => {
                let c = self.viscosity.ln() + ROELANDS_LN_ETA_INF;
                (c * (-1.0 + (1.0 + p / ROELANDS_P0).powf(self.roelands_z()))).exp()
            }
        }
    }

    /// ρ(p)/ρ0, dimensionless, for gauge pressure p ≥ 0 in Pa.
    pub fn density_ratio(&self, p: f64) -> f64 {
        match self.density_model {
            DensityModel::Incompressible => 1.0,
            DensityModel::DowsonHigginson => (5.9e8 + 1.34 * p) / (5.9e8 + p),
        }
    }
}

impl Default for Lubricant {
    fn default() -> Self {
        Lubricant::DEFAULT_MINERAL_OIL
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduced_modulus_of_equal_steels() {
        // 2/E' = 2(1-ν²)/E  =>  E' = E/(1-ν²) = 208e9/0.91
        let e = reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100);
        assert!((e - 208e9 / 0.91).abs() < 1e-3);
    }

    #[test]
    fn roelands_matches_barus_slope_at_zero_pressure() {
        // By construction of z, d ln η/dp at p = 0 equals α.
        let l = Lubricant::DEFAULT_MINERAL_OIL;
        let h = 1e3;
        let slope = (l.viscosity_ratio(h).ln() - l.viscosity_ratio(0.0).ln()) / h;
        assert!((slope / l.pressure_viscosity - 1.0).abs() < 1e-4, "{slope}");
        assert_eq!(l.viscosity_ratio(0.0), 1.0);
    }

    #[test]
    fn roelands_below_barus_at_high_pressure() {
        // Roelands' exponent z < 1 flattens the growth: η_R(1 GPa) < η_B(1 GPa).
        let r = Lubricant::DEFAULT_MINERAL_OIL;
        let b = Lubricant {
            viscosity_model: ViscosityModel::Barus,
            ..r
        };
        assert!(r.viscosity_ratio(1e9) < b.viscosity_ratio(1e9));
    }

    #[test]
    fn dowson_higginson_limits() {
        let l = Lubricant::DEFAULT_MINERAL_OIL;
        assert_eq!(l.density_ratio(0.0), 1.0);
        // (5.9e8 + 1.34e9)/(5.9e8 + 1e9) = 1.2138...
        assert!((l.density_ratio(1e9) - 1.93e9 / 1.59e9).abs() < 1e-12);
        // tends to 1.34 as p → ∞
        assert!((l.density_ratio(1e15) - 1.34).abs() < 1e-5);
    }
}
