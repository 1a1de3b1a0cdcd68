//! The envelope of the law map's groups that real angular-contact ball bearings produce, and what
//! part of it the embedded maps hold.
//!
//! Nine bearings from an instrument bearing (1.6 mm balls) to a turbine main-shaft bearing
//! (20.6 mm balls), each at speeds d_m·n from 0.05e6 to its class's limit (mm·rpm), at axial
//! loads that give a Hertz pressure of 0.8–2.5 GPa on the inner raceway (with a radial load of
//! 0.3 times the axial one, so the balls' loads spread), lubricated by ISO VG 10–220 mineral oils
//! (VI 100) at 40, 70 and 100 °C. Each case is solved by the dry quasi-static model (Hertz
//! contacts, centrifugal and gyroscopic terms); every contact carrying at least 1 % of the
//! largest load gives its groups (M, L, Ry/Rx, α·p0, ln(η0/η∞); Roelands and Dowson–Higginson)
//! and is looked up in the embedded maps. Prints the range of every group per bearing, the
//! share of contacts the maps hold, and the contacts by (L, M) cell (docs/law_map.md §5) — for
//! every combination, and for the cases run as ISO 281 advises (viscosity ratio κ = ν/ν1 from 1
//! to 4: ν the oil's kinematic viscosity at the operating temperature, ν1 ISO 281's rated
//! viscosity at the speed and pitch diameter).
//!
//! ```sh
//! cargo run --release -p ehl-bearing --example law_map_envelope [CSV]   # CSV: one row per contact
//! ```
//! Geometries are representative of the catalogue series (ball and pitch diameters, ball
//! counts, conformities 0.52/0.53), not a manufacturer's data.

use ehl_bearing::bearing::{solve_equilibrium, ContactLaws, Race};
use ehl_bearing::ehl::EhlContact;
use ehl_bearing::io::parse_case;
use ehl_bearing::law_map::{mass_group, LawGroups, LawMap};
use ehl_bearing::lubrication::rated_viscosity_mm2_s;
use std::fmt::Write as _;

/// One bearing of the ladder: name, balls, ball and pitch diameters (mm), contact angle
/// (deg), largest d_m·n of its kind (mm·rpm).
struct Size {
    name: &'static str,
    balls: u32,
    ball_mm: f64,
    pitch_mm: f64,
    angle_deg: f64,
    dmn_max: f64,
}

const SIZES: [Size; 9] = [
    Size {
        name: "instrument 3×10",
        balls: 7,
        ball_mm: 1.588,
        pitch_mm: 6.5,
        angle_deg: 15.0,
        dmn_max: 0.5e6,
    },
    Size {
        name: "7000 10×26",
        balls: 10,
        ball_mm: 4.762,
        pitch_mm: 18.0,
        angle_deg: 15.0,
        dmn_max: 1.2e6,
    },
    Size {
        name: "7006 30×55 (seed)",
        balls: 11,
        ball_mm: 7.0,
        pitch_mm: 42.5,
        angle_deg: 15.0,
        dmn_max: 1.2e6,
    },
    Size {
        name: "7205 25×52",
        balls: 12,
        ball_mm: 7.938,
        pitch_mm: 38.5,
        angle_deg: 25.0,
        dmn_max: 1.2e6,
    },
    Size {
        name: "7210 50×90",
        balls: 16,
        ball_mm: 12.7,
        pitch_mm: 70.0,
        angle_deg: 15.0,
        dmn_max: 1.5e6,
    },
    Size {
        name: "7014 70×110 spindle",
        balls: 18,
        ball_mm: 11.1125,
        pitch_mm: 90.0,
        angle_deg: 15.0,
        dmn_max: 2.0e6,
    },
    Size {
        name: "218 90×160",
        balls: 16,
        ball_mm: 22.23,
        pitch_mm: 125.26,
        angle_deg: 40.0,
        dmn_max: 2.0e6,
    },
    Size {
        name: "7220 100×180",
        balls: 14,
        ball_mm: 25.4,
        pitch_mm: 140.0,
        angle_deg: 25.0,
        dmn_max: 1.5e6,
    },
    Size {
        name: "turbine 150×225",
        balls: 24,
        ball_mm: 20.6,
        pitch_mm: 187.5,
        angle_deg: 25.0,
        dmn_max: 2.0e6,
    },
];

const DMN: [f64; 5] = [0.05e6, 0.25e6, 0.6e6, 1.2e6, 2.0e6];
const PRESSURE_GPA: [f64; 5] = [0.8, 1.2, 1.6, 2.0, 2.5];
const GRADES: [u32; 4] = [10, 32, 68, 220];
const TEMPERATURES_C: [f64; 3] = [40.0, 70.0, 100.0];

fn case_text(s: &Size, rpm: f64, axial_n: f64, grade: u32, t_c: f64) -> String {
    format!(
        "[bearing]\nball_count = {}\nball_diameter_mm = {}\npitch_diameter_mm = {}\n\
         inner_conformity = 0.52\nouter_conformity = 0.53\ncontact_angle_deg = {}\n\
         [ball_material]\nyoungs_modulus_gpa = 208.0\npoisson_ratio = 0.3\ndensity_kg_m3 = 7850.0\n\
         [ring_material]\nyoungs_modulus_gpa = 208.0\npoisson_ratio = 0.3\ndensity_kg_m3 = 7850.0\n\
         [lubricant]\niso_vg = {grade}\nviscosity_index = 100.0\nbase_oil = \"mineral\"\n\
         density_15c_kg_m3 = 870.0\nviscosity_model = \"roelands\"\ndensity_model = \"dowson-higginson\"\n\
         [operating]\ninner_speed_rpm = {rpm}\nouter_speed_rpm = 0.0\nforce_axial_n = {axial_n}\n\
         force_y_n = {}\nforce_z_n = 0.0\nrace_control = \"outer\"\ntemperature_c = {t_c}\n",
        s.balls,
        s.ball_mm,
        s.pitch_mm,
        s.angle_deg,
        0.3 * axial_n
    )
}

/// The axial load that gives inner-raceway Hertz pressure `p_gpa` at rest (every ball loaded
/// alike at the free contact angle; the radial load and the speed then move it).
fn axial_load(s: &Size, p_gpa: f64) -> Result<f64, Box<dyn std::error::Error>> {
    let case = parse_case(&case_text(s, 1000.0, 1000.0, 32, 40.0), "size")?;
    let alpha = s.angle_deg.to_radians();
    let h = case.bearing.hertz(Race::Inner, alpha)?;
    let q1 = 100.0;
    let p1 = h.contact(q1).max_pressure;
    let q = q1 * (p_gpa * 1e9 / p1).powi(3);
    Ok(q * f64::from(s.balls) * alpha.sin())
}

/// Bins of the (L, M) table.
const L_EDGES: [f64; 7] = [0.0, 8.0, 12.5, 19.0, 26.0, 34.0, f64::INFINITY];
const M_EDGES: [f64; 8] = [
    0.0,
    30.0,
    100.0,
    300.0,
    1000.0,
    3000.0,
    10000.0,
    f64::INFINITY,
];

fn bin(edges: &[f64], v: f64) -> usize {
    edges
        .windows(2)
        .position(|w| v >= w[0] && v < w[1])
        .unwrap_or(0)
}

/// Cases of one size: (solved, not converged).
type CaseCount = (usize, usize);

/// One loaded contact of one case.
struct Row {
    size: usize,
    /// ISO 281 viscosity ratio κ of the case.
    kappa: f64,
    /// M, L, Ry/Rx, α·p0, ln(η0/η∞).
    groups: [f64; 5],
    /// Whether an embedded map holds it.
    covered: bool,
    /// The harmonic law's mass group Ψ_H = (b/u_s)·√(w0/(δ_H·m)) with the ball's mass.
    psi_h: f64,
    /// Whether an embedded harmonic map holds it (groups and Ψ_H).
    covered_harmonic: bool,
}

/// Solves every case and returns its loaded contacts, the number of cases per size and how many
/// of them did not converge; writes one CSV row per contact into `csv`.
fn contacts(csv: &mut String) -> Result<(Vec<Row>, Vec<CaseCount>), Box<dyn std::error::Error>> {
    csv.push_str("bearing,rpm,axial_n,iso_vg,temperature_c,kappa,race,load_n,m,l,ry_over_rx,alpha_p0,ln_eta0_ratio,covered,psi_h,covered_harmonic\n");
    let mut rows = Vec::new();
    let mut counts = Vec::new();
    for (k, s) in SIZES.iter().enumerate() {
        let (mut cases, mut failed) = (0, 0);
        for dmn in DMN.iter().filter(|&&x| x <= s.dmn_max) {
            let rpm = dmn / s.pitch_mm;
            for &p in &PRESSURE_GPA {
                let fa = axial_load(s, p)?;
                for grade in GRADES {
                    for t_c in TEMPERATURES_C {
                        cases += 1;
                        let case = parse_case(&case_text(s, rpm, fa, grade, t_c), s.name)?;
                        let nu = case
                            .oil
                            .as_ref()
                            .map_or(f64::NAN, |o| o.kinematic_viscosity_mm2_s);
                        let kappa =
                            rated_viscosity_mm2_s(rpm, s.pitch_mm).map_or(f64::NAN, |nu1| nu / nu1);
                        let laws = ContactLaws::hertz(&case.bearing)?;
                        let Ok(eq) = solve_equilibrium(
                            &case.bearing,
                            &laws,
                            &case.operating,
                            &case.settings,
                        ) else {
                            failed += 1;
                            continue;
                        };
                        let states = eq.contact_states();
                        let qmax = states.iter().map(|(_, _, c)| c.load).fold(0.0, f64::max);
                        for (_, race, c) in states {
                            if c.load.is_nan() || c.load < 0.01 * qmax {
                                continue;
                            }
                            let ehl = EhlContact {
                                load: c.load,
                                rx: c.rx,
                                ry: c.ry,
                                sum_velocity: c.sum_velocity,
                                e_reduced: case.bearing.reduced_modulus(),
                                lubricant: case.lubricant_of(race),
                            };
                            let g = LawGroups::of(&ehl)?;
                            let psi_h = mass_group(&ehl, case.bearing.ball_mass())?;
                            let covered_harmonic =
                                LawMap::query_embedded_harmonic(&g, psi_h).is_ok();
                            let groups = [
                                g.m,
                                g.l,
                                g.ry_over_rx,
                                g.alpha_p0.unwrap_or(f64::NAN),
                                g.ln_eta0_ratio.unwrap_or(f64::NAN),
                            ];
                            let covered = LawMap::query_embedded(&g).is_ok();
                            let [m, l, r, a, e] = groups;
                            let _ = writeln!(
                                csv,
                                "{},{rpm:.1},{fa:.2},{grade},{t_c},{kappa:.4},{race:?},{:.4},{m:.6e},{l:.5},{r:.4},{a:.5},{e:.5},{covered},{psi_h:.5},{covered_harmonic}",
                                s.name, c.load
                            );
                            rows.push(Row {
                                size: k,
                                kappa,
                                groups,
                                covered,
                                psi_h,
                                covered_harmonic,
                            });
                        }
                    }
                }
            }
        }
        counts.push((cases, failed));
    }
    Ok((rows, counts))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut csv = String::new();
    let (rows, counts) = contacts(&mut csv)?;
    let designed = |r: &&Row| (1.0..=4.0).contains(&r.kappa);
    for (title, pick) in [
        ("All cases", &(|_: &&Row| true) as &dyn Fn(&&Row) -> bool),
        ("The cases with κ from 1 to 4 (ISO 281's advice)", &designed),
    ] {
        println!("{title}:\n");
        println!("| bearing | cases (not converged) | contacts | M | L | Ry/Rx | α·p0 | ln(η0/η∞) | in a map |");
        println!("|---|---:|---:|---|---|---|---|---|---:|");
        for (k, s) in SIZES.iter().enumerate() {
            let of_size: Vec<&Row> = rows.iter().filter(|r| r.size == k).filter(pick).collect();
            let (cases, failed) = counts[k];
            println!("| {} | {cases} ({failed}) | {} |", s.name, ranges(&of_size));
        }
        let picked: Vec<&Row> = rows.iter().filter(pick).collect();
        let (cases, failed) = counts.iter().fold((0, 0), |a, c| (a.0 + c.0, a.1 + c.1));
        println!("| all | {cases} ({failed}) | {} |", ranges(&picked));
        println!("\nContacts by cell (L rows, M columns): count, and in brackets the share an embedded map holds.\n");
        cell_table(&picked);
        println!();
        println!("The harmonic law's mass group Ψ_H = (b/u_s)·√(w0/(δ_H·m)) (m the ball's mass, steel):\n");
        println!(
            "| bearing | contacts | Ψ_H min | 5 % | median | 95 % | max | in a harmonic map |"
        );
        println!("|---|---:|---:|---:|---:|---:|---:|---:|");
        for (k, s) in SIZES.iter().enumerate() {
            let of_size: Vec<&Row> = rows.iter().filter(|r| r.size == k).filter(pick).collect();
            println!("| {} | {} |", s.name, psi_ranges(&of_size));
        }
        println!("| all | {} |\n", psi_ranges(&picked));
    }
    if let Some(p) = std::env::args().nth(1) {
        std::fs::write(&p, csv)?;
        println!("wrote {p}");
    }
    Ok(())
}

/// "contacts | ranges of the five groups | share in a map" of `rows`.
fn ranges(rows: &[&Row]) -> String {
    if rows.is_empty() {
        return "0 | | | | | | |".into();
    }
    let mut out = format!("{} |", rows.len());
    for (k, digits) in [3, 1, 1, 2, 2].into_iter().enumerate() {
        let lo = rows
            .iter()
            .map(|r| r.groups[k])
            .fold(f64::INFINITY, f64::min);
        let hi = rows
            .iter()
            .map(|r| r.groups[k])
            .fold(f64::NEG_INFINITY, f64::max);
        let _ = write!(out, " {lo:.digits$}–{hi:.digits$} |");
    }
    let covered = rows.iter().filter(|r| r.covered).count();
    let _ = write!(out, " {:.1} %", 100.0 * covered as f64 / rows.len() as f64);
    out
}

/// "contacts | Ψ_H min, 5 %, median, 95 %, max | share in a harmonic map" of `rows`.
fn psi_ranges(rows: &[&Row]) -> String {
    if rows.is_empty() {
        return "0 | | | | | | |".into();
    }
    let mut v: Vec<f64> = rows.iter().map(|r| r.psi_h).collect();
    v.sort_by(f64::total_cmp);
    let q = |p: f64| v[((v.len() - 1) as f64 * p).round() as usize];
    let covered = rows.iter().filter(|r| r.covered_harmonic).count();
    format!(
        "{} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.1} %",
        v.len(),
        q(0.0),
        q(0.05),
        q(0.5),
        q(0.95),
        q(1.0),
        100.0 * covered as f64 / rows.len() as f64
    )
}

fn cell_table(rows: &[&Row]) {
    let mut head = String::from("| L \\ M |");
    for w in M_EDGES.windows(2) {
        let _ = write!(head, " {}–{} |", w[0], w[1]);
    }
    println!("{head}");
    println!("|---|{}", "---:|".repeat(M_EDGES.len() - 1));
    for (i, lw) in L_EDGES.windows(2).enumerate() {
        let mut line = format!("| {}–{} |", lw[0], lw[1]);
        for j in 0..M_EDGES.len() - 1 {
            let here: Vec<&&Row> = rows
                .iter()
                .filter(|r| bin(&L_EDGES, r.groups[1]) == i && bin(&M_EDGES, r.groups[0]) == j)
                .collect();
            if here.is_empty() {
                line.push_str(" · |");
            } else {
                let c = here.iter().filter(|r| r.covered).count();
                let _ = write!(
                    line,
                    " {} ({:.0} %) |",
                    here.len(),
                    100.0 * c as f64 / here.len() as f64
                );
            }
        }
        println!("{line}");
    }
}
