//! Lubricant by description: ISO 3448 viscosity grade (or ν at 40 °C and 100 °C, or ν at 40 °C
//! and the viscosity index), base-oil type, density at 15 °C and an operating temperature, turned
//! into the constants the EHL models use (η0 in Pa·s, α in 1/Pa, ρ0 in kg/m³), each with its
//! source.
//!
//! Units: kinematic viscosities in mm²/s (cSt) and temperatures in °C or K as the names say, as
//! the standards write them; every constant handed to the models is SI.
//!
//! The correlations (docs/lubricant.md):
//! - ν(T): ASTM D341 (Walther, as in ASTM D341-09): log10 log10 Z = A − B·log10 T, T in K,
//!   Z = ν + 0.7 + exp(−1.47 − 1.84ν − 0.51ν²), ν in mm²/s; the inverse
//!   ν = Z − 0.7 − exp(−0.7487 − 3.295(Z−0.7) + 0.6119(Z−0.7)² − 0.3193(Z−0.7)³). For ν ≥ 2 mm²/s
//!   the exponential terms are below 1e-3 mm²/s and Z = ν + 0.7 (the classical Walther form).
//! - viscosity index ↔ ν at 100 °C: ASTM D2270 / ISO 2909 (Table 1 for 2 ≤ ν100 ≤ 70 mm²/s with
//!   linear interpolation, the standard's formulas above 70; procedure A for VI ≤ 100,
//!   procedure B above).
//! - ρ(T): the lubricating-oil group of API MPMS 11.1 / ASTM D1250 (Table 54D):
//!   ρ(T) = ρ15·exp[−a·ΔT·(1 + 0.8·a·ΔT)], a = K1/ρ15 with K1 = 0.34878 kg/(m³·°F) = 0.62780
//!   kg/(m³·K), ΔT = T − 15 °C (the standard's base is 60 °F = 15.56 °C; taking 15 °C changes ρ by
//!   less than 0.05 %).
//! - α(T): Roelands (1966) with a constant pressure–viscosity index Z, α = Z·(ln η0 + 9.67)/p0,
//!   p0 = 1.96e8 Pa (Roelands found Z nearly independent of temperature). For mineral oils
//!   Z = [`MINERAL_OIL_Z`] = 0.72, the median of the 38 values implied by the ASME
//!   Pressure–Viscosity Report data for 13 mineral oils at 30, 60 and 100 °C (as tabulated in
//!   Stachowiak & Batchelor, Engineering Tribology, Table 2.3); the scatter of those data about it
//!   is 9.7 % (one standard deviation), −13 % to +22 % at worst: the stated accuracy. For PAO, ester
//!   and other base oils no correlation whose coefficients we could verify was found (Gold et al.
//!   2001 and So & Klaus 1980 were not reachable): give Z or α for them.
//! - thermal conductivity, for the inlet shear-heating estimate: 0.1 W/(m·K) unless given ("most
//!   mineral oils have approximately the same thermal conductivity of near 0.1 W/(m·°C)", Panther
//!   Lubes technical library, measured by ASTM D2717; a low value overestimates the heating, i.e.
//!   the estimate errs on the safe side).

use serde::{Deserialize, Serialize};

/// Kelvin at 0 °C.
pub const KELVIN: f64 = 273.15;
/// Roelands' pressure–viscosity index Z for mineral oils (dimensionless): median of the ASME
/// Pressure–Viscosity Report data (module documentation); scatter 9.7 % (1σ).
pub const MINERAL_OIL_Z: f64 = 0.72;
/// Default thermal conductivity of a lubricating oil, W/(m·K) (module documentation).
pub const DEFAULT_THERMAL_CONDUCTIVITY: f64 = 0.1;
/// API MPMS 11.1 lubricating-oil constant K1 per kelvin, kg/(m³·K) (0.34878 per °F × 1.8).
pub const API_LUBE_K1_PER_K: f64 = 0.34878 * 1.8;

/// ISO 3448 viscosity grades: (grade, midpoint kinematic viscosity at 40 °C in mm²/s). The limits
/// are ±10 % of the midpoint (grades 2–1500 checked against a published copy of the table in
/// tests/lubricant.rs).
pub const ISO_VG: [(u32, f64); 20] = [
    (2, 2.2),
    (3, 3.2),
    (5, 4.6),
    (7, 6.8),
    (10, 10.0),
    (15, 15.0),
    (22, 22.0),
    (32, 32.0),
    (46, 46.0),
    (68, 68.0),
    (100, 100.0),
    (150, 150.0),
    (220, 220.0),
    (320, 320.0),
    (460, 460.0),
    (680, 680.0),
    (1000, 1000.0),
    (1500, 1500.0),
    (2200, 2200.0),
    (3200, 3200.0),
];

/// The ISO 3448 midpoint ν40 of a grade, mm²/s (None for a number that is not a grade).
pub fn iso_vg_midpoint(grade: u32) -> Option<f64> {
    ISO_VG.iter().find(|(g, _)| *g == grade).map(|(_, v)| *v)
}

/// ASTM D2270 Table 1: (ν100, L, H) in mm²/s for 2 ≤ ν100 ≤ 70 mm²/s. L and H are the 40 °C
/// kinematic viscosities of the oils of VI 0 and VI 100 with the same ν100.
#[rustfmt::skip]
const D2270_TABLE: [(f64, f64, f64); 311] = [
    (2.00, 7.994, 6.394), (2.10, 8.640, 6.894), (2.20, 9.309, 7.410), (2.30, 10.00, 7.944),
    (2.40, 10.71, 8.496), (2.50, 11.45, 9.063), (2.60, 12.21, 9.647), (2.70, 13.00, 10.25),
    (2.80, 13.80, 10.87), (2.90, 14.63, 11.50), (3.00, 15.49, 12.15), (3.10, 16.36, 12.82),
    (3.20, 17.26, 13.51), (3.30, 18.18, 14.21), (3.40, 19.12, 14.93), (3.50, 20.09, 15.66),
    (3.60, 21.08, 16.42), (3.70, 22.09, 17.19), (3.80, 23.13, 17.97), (3.90, 24.19, 18.77),
    (4.00, 25.32, 19.56), (4.10, 26.50, 20.37), (4.20, 27.75, 21.21), (4.30, 29.07, 22.05),
    (4.40, 30.48, 22.92), (4.50, 31.96, 23.81), (4.60, 33.52, 24.71), (4.70, 35.13, 25.63),
    (4.80, 36.79, 26.57), (4.90, 38.50, 27.53), (5.00, 40.23, 28.49), (5.10, 41.99, 29.46),
    (5.20, 43.76, 30.43), (5.30, 45.53, 31.40), (5.40, 47.31, 32.37), (5.50, 49.09, 33.34),
    (5.60, 50.87, 34.32), (5.70, 52.64, 35.29), (5.80, 54.42, 36.26), (5.90, 56.20, 37.23),
    (6.00, 57.97, 38.19), (6.10, 59.74, 39.17), (6.20, 61.52, 40.15), (6.30, 63.32, 41.13),
    (6.40, 65.18, 42.14), (6.50, 67.12, 43.18), (6.60, 69.16, 44.24), (6.70, 71.29, 45.33),
    (6.80, 73.48, 46.44), (6.90, 75.72, 47.51), (7.00, 78.00, 48.57), (7.10, 80.25, 49.61),
    (7.20, 82.39, 50.69), (7.30, 84.53, 51.78), (7.40, 86.66, 52.88), (7.50, 88.85, 53.98),
    (7.60, 91.04, 55.09), (7.70, 93.20, 56.20), (7.80, 95.43, 57.31), (7.90, 97.72, 58.45),
    (8.00, 100.0, 59.60), (8.10, 102.3, 60.74), (8.20, 104.6, 61.89), (8.30, 106.9, 63.05),
    (8.40, 109.2, 64.18), (8.50, 111.5, 65.32), (8.60, 113.9, 66.48), (8.70, 116.2, 67.64),
    (8.80, 118.5, 68.79), (8.90, 120.9, 69.94), (9.00, 123.3, 71.10), (9.10, 125.7, 72.27),
    (9.20, 128.0, 73.42), (9.30, 130.4, 74.57), (9.40, 132.8, 75.73), (9.50, 135.3, 76.91),
    (9.60, 137.7, 78.08), (9.70, 140.1, 79.27), (9.80, 142.7, 80.46), (9.90, 145.2, 81.67),
    (10.0, 147.7, 82.87), (10.1, 150.3, 84.08), (10.2, 152.9, 85.30), (10.3, 155.4, 86.51),
    (10.4, 158.0, 87.72), (10.5, 160.6, 88.95), (10.6, 163.2, 90.19), (10.7, 165.8, 91.40),
    (10.8, 168.5, 92.65), (10.9, 171.2, 93.92), (11.0, 173.9, 95.19), (11.1, 176.6, 96.45),
    (11.2, 179.4, 97.71), (11.3, 182.1, 98.97), (11.4, 184.9, 100.2), (11.5, 187.6, 101.5),
    (11.6, 190.4, 102.8), (11.7, 193.3, 104.1), (11.8, 196.2, 105.4), (11.9, 199.0, 106.7),
    (12.0, 201.9, 108.0), (12.1, 204.8, 109.4), (12.2, 207.8, 110.7), (12.3, 210.7, 112.0),
    (12.4, 213.6, 113.3), (12.5, 216.6, 114.7), (12.6, 219.6, 116.0), (12.7, 222.6, 117.4),
    (12.8, 225.7, 118.7), (12.9, 228.8, 120.1), (13.0, 231.9, 121.5), (13.1, 235.0, 122.9),
    (13.2, 238.1, 124.2), (13.3, 241.2, 125.6), (13.4, 244.3, 127.0), (13.5, 247.4, 128.4),
    (13.6, 250.6, 129.8), (13.7, 253.8, 131.2), (13.8, 257.0, 132.6), (13.9, 260.1, 134.0),
    (14.0, 263.3, 135.4), (14.1, 266.6, 136.8), (14.2, 269.8, 138.2), (14.3, 273.0, 139.6),
    (14.4, 276.3, 141.0), (14.5, 279.6, 142.4), (14.6, 283.0, 143.9), (14.7, 286.4, 145.3),
    (14.8, 289.7, 146.8), (14.9, 293.0, 148.2), (15.0, 296.5, 149.7), (15.1, 300.0, 151.2),
    (15.2, 303.4, 152.6), (15.3, 306.9, 154.1), (15.4, 310.3, 155.6), (15.5, 313.9, 157.0),
    (15.6, 317.5, 158.6), (15.7, 321.1, 160.1), (15.8, 324.6, 161.6), (15.9, 328.3, 163.1),
    (16.0, 331.9, 164.6), (16.1, 335.5, 166.1), (16.2, 339.2, 167.7), (16.3, 342.9, 169.2),
    (16.4, 346.6, 170.7), (16.5, 350.3, 172.3), (16.6, 354.1, 173.8), (16.7, 358.0, 175.4),
    (16.8, 361.7, 177.0), (16.9, 365.6, 178.6), (17.0, 369.4, 180.2), (17.1, 373.3, 181.7),
    (17.2, 377.1, 183.3), (17.3, 381.0, 184.9), (17.4, 384.9, 186.5), (17.5, 388.9, 188.1),
    (17.6, 392.7, 189.7), (17.7, 396.7, 191.3), (17.8, 400.7, 192.9), (17.9, 404.6, 194.6),
    (18.0, 408.6, 196.2), (18.1, 412.6, 197.8), (18.2, 416.7, 199.4), (18.3, 420.7, 201.0),
    (18.4, 424.9, 202.6), (18.5, 429.0, 204.3), (18.6, 433.2, 205.9), (18.7, 437.3, 207.6),
    (18.8, 441.5, 209.3), (18.9, 445.7, 211.0), (19.0, 449.9, 212.7), (19.1, 454.2, 214.4),
    (19.2, 458.4, 216.1), (19.3, 462.7, 217.7), (19.4, 467.0, 219.4), (19.5, 471.3, 221.1),
    (19.6, 475.7, 222.8), (19.7, 479.7, 224.5), (19.8, 483.9, 226.2), (19.9, 488.6, 227.7),
    (20.0, 493.2, 229.5), (20.2, 501.5, 233.0), (20.4, 510.8, 236.4), (20.6, 519.9, 240.1),
    (20.8, 528.8, 243.5), (21.0, 538.4, 247.1), (21.2, 547.5, 250.7), (21.4, 556.7, 254.2),
    (21.6, 566.4, 257.8), (21.8, 575.6, 261.5), (22.0, 585.2, 264.9), (22.2, 595.0, 268.6),
    (22.4, 604.3, 272.3), (22.6, 614.2, 275.8), (22.8, 624.1, 279.6), (23.0, 633.6, 283.3),
    (23.2, 643.4, 286.8), (23.4, 653.8, 290.5), (23.6, 663.3, 294.4), (23.8, 673.7, 297.9),
    (24.0, 683.9, 301.8), (24.2, 694.5, 305.6), (24.4, 704.2, 309.4), (24.6, 714.9, 313.0),
    (24.8, 725.7, 317.0), (25.0, 736.5, 320.9), (25.2, 747.2, 324.9), (25.4, 758.2, 328.8),
    (25.6, 769.3, 332.7), (25.8, 779.7, 336.7), (26.0, 790.4, 340.5), (26.2, 801.6, 344.4),
    (26.4, 812.8, 348.4), (26.6, 824.1, 352.3), (26.8, 835.5, 356.4), (27.0, 847.0, 360.5),
    (27.2, 857.5, 364.6), (27.4, 869.0, 368.3), (27.6, 880.6, 372.3), (27.8, 892.3, 376.4),
    (28.0, 904.1, 380.6), (28.2, 915.8, 384.6), (28.4, 927.6, 388.8), (28.6, 938.6, 393.0),
    (28.8, 951.2, 396.6), (29.0, 963.4, 401.1), (29.2, 975.4, 405.3), (29.4, 987.1, 409.5),
    (29.6, 998.9, 413.5), (29.8, 1011.0, 417.6), (30.0, 1023.0, 421.7), (30.5, 1055.0, 432.4),
    (31.0, 1086.0, 443.2), (31.5, 1119.0, 454.0), (32.0, 1151.0, 464.9), (32.5, 1184.0, 475.9),
    (33.0, 1217.0, 487.0), (33.5, 1251.0, 498.1), (34.0, 1286.0, 509.6), (34.5, 1321.0, 521.1),
    (35.0, 1356.0, 532.5), (35.5, 1391.0, 544.0), (36.0, 1427.0, 555.6), (36.5, 1464.0, 567.1),
    (37.0, 1501.0, 579.3), (37.5, 1538.0, 591.3), (38.0, 1575.0, 603.1), (38.5, 1613.0, 615.0),
    (39.0, 1651.0, 627.1), (39.5, 1691.0, 639.2), (40.0, 1730.0, 651.8), (40.5, 1770.0, 664.2),
    (41.0, 1810.0, 676.6), (41.5, 1851.0, 689.1), (42.0, 1892.0, 701.9), (42.5, 1935.0, 714.9),
    (43.0, 1978.0, 728.2), (43.5, 2021.0, 741.3), (44.0, 2064.0, 754.4), (44.5, 2108.0, 767.6),
    (45.0, 2152.0, 780.9), (45.5, 2197.0, 794.5), (46.0, 2243.0, 808.2), (46.5, 2288.0, 821.9),
    (47.0, 2333.0, 835.5), (47.5, 2380.0, 849.2), (48.0, 2426.0, 863.0), (48.5, 2473.0, 876.9),
    (49.0, 2521.0, 890.9), (49.5, 2570.0, 905.3), (50.0, 2618.0, 919.6), (50.5, 2667.0, 933.6),
    (51.0, 2717.0, 948.2), (51.5, 2767.0, 962.9), (52.0, 2817.0, 977.5), (52.5, 2867.0, 992.1),
    (53.0, 2918.0, 1007.0), (53.5, 2969.0, 1021.0), (54.0, 3020.0, 1036.0), (54.5, 3073.0, 1051.0),
    (55.0, 3126.0, 1066.0), (55.5, 3180.0, 1082.0), (56.0, 3233.0, 1097.0), (56.5, 3286.0, 1112.0),
    (57.0, 3340.0, 1127.0), (57.5, 3396.0, 1143.0), (58.0, 3452.0, 1159.0), (58.5, 3507.0, 1175.0),
    (59.0, 3563.0, 1190.0), (59.5, 3619.0, 1206.0), (60.0, 3676.0, 1222.0), (60.5, 3734.0, 1238.0),
    (61.0, 3792.0, 1254.0), (61.5, 3850.0, 1270.0), (62.0, 3908.0, 1286.0), (62.5, 3966.0, 1303.0),
    (63.0, 4026.0, 1319.0), (63.5, 4087.0, 1336.0), (64.0, 4147.0, 1352.0), (64.5, 4207.0, 1369.0),
    (65.0, 4268.0, 1386.0), (65.5, 4329.0, 1402.0), (66.0, 4392.0, 1419.0), (66.5, 4455.0, 1436.0),
    (67.0, 4517.0, 1454.0), (67.5, 4580.0, 1471.0), (68.0, 4645.0, 1488.0), (68.5, 4709.0, 1506.0),
    (69.0, 4773.0, 1523.0), (69.5, 4839.0, 1541.0), (70.0, 4905.0, 1558.0),
];

/// An input outside the range a correlation describes.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OilError {
    /// A quantity outside its valid range.
    #[error("{quantity} = {value}: expected {expected}")]
    Range {
        /// What the value is (the case-file key where there is one).
        quantity: String,
        /// The value.
        value: f64,
        /// The valid range.
        expected: String,
    },
    /// A quantity the description needs and does not give.
    #[error("{quantity} is missing: {hint}")]
    Missing {
        /// The case-file key.
        quantity: String,
        /// What to give.
        hint: String,
    },
}

fn range(quantity: &str, value: f64, expected: impl Into<String>) -> OilError {
    OilError::Range {
        quantity: quantity.into(),
        value,
        expected: expected.into(),
    }
}

/// ASTM D341's Z of a kinematic viscosity ν in mm²/s: Z = ν + 0.7 + exp(−1.47 − 1.84ν − 0.51ν²).
pub fn walther_z(nu_mm2_s: f64) -> f64 {
    let n = nu_mm2_s;
    n + 0.7 + (-1.47 - 1.84 * n - 0.51 * n * n).exp()
}

/// ASTM D341's inverse: the kinematic viscosity in mm²/s of Z,
/// ν = Z − 0.7 − exp(−0.7487 − 3.295(Z−0.7) + 0.6119(Z−0.7)² − 0.3193(Z−0.7)³).
pub fn walther_nu(z: f64) -> f64 {
    let x = z - 0.7;
    z - 0.7 - (-0.7487 - 3.295 * x + 0.6119 * x * x - 0.3193 * x * x * x).exp()
}

/// The ASTM D341 (Walther) line log10 log10 Z = A − B·log10 T, T in K.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Walther {
    /// A (dimensionless).
    pub a: f64,
    /// B (dimensionless, the slope; 3–4.5 for mineral oils).
    pub b: f64,
}

impl Walther {
    /// The line through two kinematic viscosities (mm²/s) at two temperatures (°C), the first
    /// colder and more viscous.
    pub fn through(t1_c: f64, nu1: f64, t2_c: f64, nu2: f64) -> Result<Walther, OilError> {
        if !(nu2.is_finite() && nu2 > 0.0) {
            return Err(range(
                "kinematic viscosity",
                nu2,
                "a positive value in mm²/s",
            ));
        }
        if !(nu1.is_finite() && nu1 > nu2) {
            return Err(range(
                "kinematic viscosity",
                nu1,
                format!(
                    "more than the {nu2} mm²/s at {t2_c} °C (viscosity falls with temperature)"
                ),
            ));
        }
        let y = |nu: f64| walther_z(nu).log10().log10();
        let x = |t: f64| (t + KELVIN).log10();
        let b = (y(nu1) - y(nu2)) / (x(t2_c) - x(t1_c));
        Ok(Walther {
            a: y(nu1) + b * x(t1_c),
            b,
        })
    }

    /// Kinematic viscosity at `t_c` °C, mm²/s.
    pub fn nu_at(&self, t_c: f64) -> f64 {
        let loglog = self.a - self.b * (t_c + KELVIN).log10();
        walther_nu(10f64.powf(10f64.powf(loglog)))
    }
}

/// L and H of ASTM D2270 (mm²/s) for ν100 = `nu100` mm²/s ≥ 2: Table 1 with linear
/// interpolation up to 70 mm²/s, the standard's formulas above
/// (L = 0.8353Y² + 14.67Y − 216, H = 0.1684Y² + 11.85Y − 97).
pub fn d2270_l_h(nu100: f64) -> Result<(f64, f64), OilError> {
    if !(nu100.is_finite() && nu100 >= 2.0) {
        return Err(range(
            "viscosity_100c_mm2_s",
            nu100,
            "at least 2 mm²/s (ASTM D2270 defines no viscosity index below)",
        ));
    }
    if nu100 > 70.0 {
        let y = nu100;
        return Ok((
            0.8353 * y * y + 14.67 * y - 216.0,
            0.1684 * y * y + 11.85 * y - 97.0,
        ));
    }
    let i = D2270_TABLE.partition_point(|r| r.0 <= nu100);
    let (y0, l0, h0) = D2270_TABLE[i - 1];
    if i == D2270_TABLE.len() || y0 == nu100 {
        return Ok((l0, h0));
    }
    let (y1, l1, h1) = D2270_TABLE[i];
    let f = (nu100 - y0) / (y1 - y0);
    Ok((l0 + f * (l1 - l0), h0 + f * (h1 - h0)))
}

/// Viscosity index (ASTM D2270 / ISO 2909, unrounded) of an oil with ν40 and ν100 in mm²/s.
pub fn viscosity_index(nu40: f64, nu100: f64) -> Result<f64, OilError> {
    let (l, h) = d2270_l_h(nu100)?;
    if !(nu40.is_finite() && nu40 > nu100) {
        return Err(range(
            "viscosity_40c_mm2_s",
            nu40,
            format!("more than viscosity_100c_mm2_s = {nu100}"),
        ));
    }
    if nu40 >= h {
        // Procedure A (VI ≤ 100).
        Ok((l - nu40) / (l - h) * 100.0)
    } else {
        // Procedure B (VI > 100).
        let n = (h.log10() - nu40.log10()) / nu100.log10();
        Ok((10f64.powf(n) - 1.0) / 0.00715 + 100.0)
    }
}

/// ν100 in mm²/s of an oil with ν40 in mm²/s and viscosity index `vi` (the inverse of
/// [`viscosity_index`], by bisection to 1e-12 relative).
pub fn nu100_from_vi(nu40: f64, vi: f64) -> Result<f64, OilError> {
    if !(nu40.is_finite() && nu40 > 2.0) {
        return Err(range(
            "viscosity_40c_mm2_s",
            nu40,
            "more than 2 mm²/s (ASTM D2270 needs ν100 ≥ 2 mm²/s)",
        ));
    }
    let f = |y: f64| viscosity_index(nu40, y).map(|v| v - vi);
    let (mut lo, mut hi) = (2.0, nu40 * (1.0 - 1e-9));
    let (flo, fhi) = (f(lo)?, f(hi)?);
    if !(vi.is_finite() && flo <= 0.0 && fhi >= 0.0) {
        return Err(range(
            "viscosity_index",
            vi,
            format!(
                "a viscosity index an oil of ν40 = {nu40} mm²/s can have: {:.0} to {:.0}",
                flo + vi,
                fhi + vi
            ),
        ));
    }
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if f(mid)? < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi / lo - 1.0 < 1e-12 {
            break;
        }
    }
    Ok((lo * hi).sqrt())
}

/// Density at `t_c` °C of an oil of density `rho15` kg/m³ at 15 °C, kg/m³ (API MPMS 11.1
/// lubricating-oil group; module documentation).
pub fn density_at(rho15: f64, t_c: f64) -> f64 {
    let a = API_LUBE_K1_PER_K / rho15;
    let dt = t_c - 15.0;
    rho15 * (-a * dt * (1.0 + 0.8 * a * dt)).exp()
}

/// Base-oil type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BaseOil {
    /// Mineral oil (paraffinic or naphthenic): α from Roelands with [`MINERAL_OIL_Z`].
    Mineral,
    /// Polyalphaolefin: give Z or α.
    Pao,
    /// Ester: give Z or α.
    Ester,
    /// Other: give Z or α.
    Other,
}

impl BaseOil {
    /// The case-file names.
    pub const NAMES: [&'static str; 4] = ["mineral", "pao", "ester", "other"];

    /// Its case-file name.
    pub fn name(&self) -> &'static str {
        match self {
            BaseOil::Mineral => "mineral",
            BaseOil::Pao => "pao",
            BaseOil::Ester => "ester",
            BaseOil::Other => "other",
        }
    }

    /// From its case-file name.
    pub fn parse(s: &str) -> Option<BaseOil> {
        match s {
            "mineral" => Some(BaseOil::Mineral),
            "pao" => Some(BaseOil::Pao),
            "ester" => Some(BaseOil::Ester),
            "other" => Some(BaseOil::Other),
            _ => None,
        }
    }
}

/// A lubricant described as a practitioner knows it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OilDescription {
    /// ISO 3448 grade, when given by grade.
    pub iso_vg: Option<u32>,
    /// Kinematic viscosity at 40 °C, mm²/s.
    pub viscosity_40c_mm2_s: f64,
    /// Kinematic viscosity at 100 °C, mm²/s (given, or from the viscosity index).
    pub viscosity_100c_mm2_s: f64,
    /// Base-oil type.
    pub base_oil: BaseOil,
    /// Density at 15 °C, kg/m³.
    pub density_15c_kg_m3: f64,
    /// Roelands' pressure–viscosity index Z, when given (dimensionless).
    pub pressure_viscosity_index_z: Option<f64>,
    /// Pressure–viscosity coefficient at the operating temperature, when given, 1/Pa.
    pub pressure_viscosity_1_pa: Option<f64>,
    /// Thermal conductivity, W/(m·K).
    pub thermal_conductivity_w_m_k: f64,
}

/// A derived constant's source.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Source {
    /// The field of [`OilProperties`].
    pub quantity: String,
    /// Where it comes from.
    pub source: String,
}

/// The constants of a described oil at its operating temperature, each with its source.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OilProperties {
    /// Operating temperature, °C.
    pub temperature_c: f64,
    /// ISO 3448 grade, if given by grade.
    pub iso_vg: Option<u32>,
    /// Base-oil type.
    pub base_oil: BaseOil,
    /// Kinematic viscosity at 40 °C, mm²/s.
    pub viscosity_40c_mm2_s: f64,
    /// Kinematic viscosity at 100 °C, mm²/s.
    pub viscosity_100c_mm2_s: f64,
    /// Viscosity index (ASTM D2270, unrounded).
    pub viscosity_index: f64,
    /// ASTM D341 line: log10 log10 Z = A − B·log10 T (T in K).
    pub walther: Walther,
    /// Kinematic viscosity at the operating temperature, mm²/s.
    pub kinematic_viscosity_mm2_s: f64,
    /// Density at 15 °C, kg/m³.
    pub density_15c_kg_m3: f64,
    /// Density at the operating temperature, kg/m³.
    pub density_kg_m3: f64,
    /// Dynamic viscosity η0 = ρν at the operating temperature, Pa·s.
    pub viscosity_pa_s: f64,
    /// Temperature–viscosity coefficient β = −(1/η0)·dη0/dT at the operating temperature, 1/K.
    pub temperature_viscosity_1_k: f64,
    /// Roelands' pressure–viscosity index Z (dimensionless).
    pub roelands_z: f64,
    /// Pressure–viscosity coefficient α at the operating temperature, 1/Pa.
    pub pressure_viscosity_1_pa: f64,
    /// Thermal conductivity, W/(m·K).
    pub thermal_conductivity_w_m_k: f64,
    /// The source of every derived constant.
    pub sources: Vec<Source>,
}

/// The constants of `oil` at `t_c` °C.
pub fn derive(oil: &OilDescription, t_c: f64) -> Result<OilProperties, OilError> {
    if !(t_c.is_finite() && (-40.0..=200.0).contains(&t_c)) {
        return Err(range(
            "operating.temperature_c",
            t_c,
            "−40 to 200 °C (liquid lubricating oils; ASTM D341 extrapolated beyond)",
        ));
    }
    let (nu40, nu100) = (oil.viscosity_40c_mm2_s, oil.viscosity_100c_mm2_s);
    let walther = Walther::through(40.0, nu40, 100.0, nu100)?;
    let vi = viscosity_index(nu40, nu100)?;
    let rho15 = oil.density_15c_kg_m3;
    let eta = |t: f64| density_at(rho15, t) * walther.nu_at(t) * 1e-6;
    let nu = walther.nu_at(t_c);
    let rho = density_at(rho15, t_c);
    let eta0 = rho * nu * 1e-6;
    let ln_c = eta0.ln() + crate::material::ROELANDS_LN_ETA_INF;
    if !(nu.is_finite() && nu >= 1.0 && ln_c > 0.5) {
        return Err(range(
            "operating.temperature_c",
            t_c,
            format!(
                "a temperature at which this oil keeps ν ≥ 1 mm²/s (ASTM D341 gives {nu:.3} mm²/s)"
            ),
        ));
    }
    let h = 0.05;
    let beta = -(eta(t_c + h) - eta(t_c - h)) / (2.0 * h) / eta0;
    let mut sources = viscosity_sources(oil);
    let (z, alpha) = pressure_viscosity(oil, ln_c, &mut sources)?;
    sources.push(conductivity_source(oil));
    Ok(OilProperties {
        temperature_c: t_c,
        iso_vg: oil.iso_vg,
        base_oil: oil.base_oil,
        viscosity_40c_mm2_s: nu40,
        viscosity_100c_mm2_s: nu100,
        viscosity_index: vi,
        walther,
        kinematic_viscosity_mm2_s: nu,
        density_15c_kg_m3: rho15,
        density_kg_m3: rho,
        viscosity_pa_s: eta0,
        temperature_viscosity_1_k: beta,
        roelands_z: z,
        pressure_viscosity_1_pa: alpha,
        thermal_conductivity_w_m_k: oil.thermal_conductivity_w_m_k,
        sources,
    })
}

/// The sources of the viscosity, density and temperature coefficient of a described oil.
fn viscosity_sources(oil: &OilDescription) -> Vec<Source> {
    vec![
        Source {
            quantity: "viscosity_40c_mm2_s".into(),
            source: match oil.iso_vg {
                Some(g) => format!("ISO 3448 midpoint of ISO VG {g}"),
                None => "given".into(),
            },
        },
        Source {
            quantity: "viscosity_100c_mm2_s".into(),
            source: "given, or from the viscosity index by ASTM D2270 / ISO 2909 (inverted)".into(),
        },
        Source {
            quantity: "viscosity_index".into(),
            source: "ASTM D2270 / ISO 2909 from ν40 and ν100 (unrounded)".into(),
        },
        Source {
            quantity: "kinematic_viscosity_mm2_s".into(),
            source: "ASTM D341 (Walther) line through ν40 and ν100".into(),
        },
        Source {
            quantity: "density_kg_m3".into(),
            source: "API MPMS 11.1 / ASTM D1250 lubricating-oil group (K1 = 0.34878 per °F) from \
                     the density at 15 °C"
                .into(),
        },
        Source {
            quantity: "viscosity_pa_s".into(),
            source: "η0 = ρ·ν at the operating temperature".into(),
        },
        Source {
            quantity: "temperature_viscosity_1_k".into(),
            source: "−(1/η0)·dη0/dT of ρ(T)·ν(T) above (central difference, ±0.05 K)".into(),
        },
    ]
}

/// Roelands' Z and α at the operating temperature (`ln_c` = ln η0 + 9.67, η0 in Pa·s): the
/// given α or Z, else the mineral-oil Z; their sources appended to `sources`. Other base oils
/// need Z or α given.
fn pressure_viscosity(
    oil: &OilDescription,
    ln_c: f64,
    sources: &mut Vec<Source>,
) -> Result<(f64, f64), OilError> {
    let p0 = crate::material::ROELANDS_P0;
    let za = match (oil.pressure_viscosity_1_pa, oil.pressure_viscosity_index_z) {
        (Some(a), _) => {
            sources.push(Source {
                quantity: "pressure_viscosity_1_pa".into(),
                source: "given (at the operating temperature)".into(),
            });
            sources.push(Source {
                quantity: "roelands_z".into(),
                source: "Z = α·p0/(ln η0 + 9.67), Roelands (1966)".into(),
            });
            (a * p0 / ln_c, a)
        }
        (None, Some(z)) => {
            sources.push(Source {
                quantity: "roelands_z".into(),
                source: "given".into(),
            });
            sources.push(Source {
                quantity: "pressure_viscosity_1_pa".into(),
                source: "α = Z·(ln η0 + 9.67)/p0, Roelands (1966), Z constant with temperature"
                    .into(),
            });
            (z, z * ln_c / p0)
        }
        (None, None) => match oil.base_oil {
            BaseOil::Mineral => {
                sources.push(Source {
                    quantity: "roelands_z".into(),
                    source: "mineral oils: 0.72, median of the ASME Pressure–Viscosity Report \
                             data for 13 mineral oils (Stachowiak & Batchelor, Table 2.3); \
                             scatter 9.7 % (1σ), −13 % to +22 %"
                        .into(),
                });
                sources.push(Source {
                    quantity: "pressure_viscosity_1_pa".into(),
                    source: "α = Z·(ln η0 + 9.67)/p0, Roelands (1966), Z constant with \
                             temperature; ±10 % (1σ) against the ASME data"
                        .into(),
                });
                (MINERAL_OIL_Z, MINERAL_OIL_Z * ln_c / p0)
            }
            other => {
                return Err(OilError::Missing {
                    quantity: "lubricant.pressure_viscosity_index_z".into(),
                    hint: format!(
                        "no verified pressure–viscosity correlation for {} base oils is \
                         built in (only mineral): give Roelands' Z or \
                         lubricant.pressure_viscosity_1_pa at the operating temperature",
                        other.name()
                    ),
                })
            }
        },
    };
    Ok(za)
}

/// The source of the thermal conductivity (the default, or given).
fn conductivity_source(oil: &OilDescription) -> Source {
    Source {
        quantity: "thermal_conductivity_w_m_k".into(),
        source: if oil.thermal_conductivity_w_m_k == DEFAULT_THERMAL_CONDUCTIVITY {
            "default 0.1 W/(m·K), typical of mineral oils (Panther Lubes technical library, \
             ASTM D2717); low values overestimate inlet heating"
                .into()
        } else {
            "given".into()
        },
    }
}
