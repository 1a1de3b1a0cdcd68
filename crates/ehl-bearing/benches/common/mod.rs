//! Set-up shared by the benchmarks.

use ehl_bearing::bearing::{Bearing, Race};
use ehl_bearing::fit::FittedLaw;
use ehl_bearing::hertz::HertzGeometry;

/// Fitted-looking laws with damping, the magnitudes of the seed's (tests/force_element.rs): per
/// contact K from the Hertz constant at α0 so that K·δ^1.45 = K_H·δ^1.5 at δ = 5 µm, d = 1.45,
/// ΔF = 20 N, c = 150 N·s/m, fitted range 1–12 µm; contact order ball 0 inner, ball 0 outer, …
pub fn seed_fitted_laws(b: &Bearing) -> Vec<FittedLaw> {
    let a0 = b.geometry.free_contact_angle;
    let mut laws = Vec::new();
    for _ in 0..b.geometry.ball_count {
        for race in [Race::Inner, Race::Outer] {
            let (rx, ry) = b.geometry.curvature_radii(race, a0);
            let kh = HertzGeometry::new(rx, ry, b.reduced_modulus())
                .unwrap()
                .stiffness;
            laws.push(
                FittedLaw::new(kh * 5e-6_f64.powf(0.05), 1.45, 20.0, 1e-6, 12e-6)
                    .unwrap()
                    .with_damping(150.0)
                    .unwrap(),
            );
        }
    }
    laws
}
