//! The small map spec of the map machinery's tests (`law_map.rs`: its `map` and `sparse`
//! modules).
#![allow(dead_code)]

use ehl_bearing::law_map::{Group, LawMapSpec, MapAxis};
use ehl_bearing::material::{DensityModel, ViscosityModel};

/// A 3 × 3 × 3 tensor map on grid 33 (seconds): the machinery, not the accuracy. M 300–1000
/// (log), L 20–24, Ry/Rx 10–20 (log), the seed's oil.
pub fn small() -> LawMapSpec {
    let axis = |group, min, max, log| MapAxis {
        group,
        min,
        max,
        nodes: 3,
        log,
    };
    LawMapSpec {
        viscosity_model: ViscosityModel::Roelands,
        density_model: DensityModel::DowsonHigginson,
        m: None,
        l: None,
        ry_over_rx: None,
        alpha_p0: Some(4.312),
        ln_eta0_ratio: Some(0.04_f64.ln() + 9.67),
        axes: vec![
            axis(Group::M, 300.0, 1000.0, true),
            axis(Group::L, 20.0, 24.0, false),
            axis(Group::RyOverRx, 10.0, 20.0, true),
        ],
        amplitude: 0.2,
        points: Some(7),
        grid: 33,
        law: Default::default(),
        frequency_fraction: None,
        tolerance_factor: 1.0,
        sparse_level: None,
    }
}
