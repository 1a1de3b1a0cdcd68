//! Contact dynamics over frequency (docs/contact.md, "Contact dynamics over frequency"): on the
//! seed's heaviest inner contact at 3000 rpm (ball 1 of `benches/seed_contacts.csv`, dry-Hertz
//! load 561.1 N), the harmonic law tends to the quasi-static law as Ω/ω_n → 0, its offset ΔF
//! falls at Ω = 0.1·ω_n (the default before it was moved into the band), and the damping is flat
//! over the rotor band but not up to 0.1·ω_n; the default Ω lies in the band. 65² grid and 64
//! steps per period keep it to seconds.
//!
//! Measured values these bounds rest on (`contact_frequency_sweep` example, this contact):
//!
//! | quantity | 65² | 129² |
//! |---|---|---|
//! | ΔF quasi-static (N) | 30.68 | 30.28 |
//! | ΔF harmonic, Ω/ω_n = 0.002 / 0.005 (N) | 26.89 / 26.93 | 30.77 / 30.73 |
//! | ΔF harmonic, Ω/ω_n = 0.1 (N) | 6.58 | 11.00 |
//! | c_eq at 0.002 / 0.01 / 0.1 (N·s/m) | 172.8 / 170.5 / 113.3 | 150.7 / 148.8 / 98.3 |
//! | k'(0.002) / quasi-static tangent − 1 | 1.0 % | 0.08 % |

use ehl_bearing::contact::{
    ball_mass, characterize_harmonic, characterize_quasi_static, ContactFit, ExcitationFrequency,
    HarmonicSettings, QuasiStaticSettings,
};
use ehl_bearing::ehl::{EhlContact, EhlSettings};
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};

/// Ball 1, inner race, 3000 rpm, of `benches/seed_contacts.csv`.
fn heavy_inner_3000() -> EhlContact {
    EhlContact {
        load: 561.1020541505696,
        rx: 0.0029561756517531438,
        ry: 0.17849999999999985,
        sum_velocity: 6.514818289538437,
        e_reduced: reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100),
        lubricant: Lubricant::DEFAULT_MINERAL_OIL,
    }
}

fn ehl() -> EhlSettings {
    EhlSettings {
        grid: 65,
        discretization_fraction: 0.0,
        ..EhlSettings::default()
    }
}

fn harmonic(ratio: f64) -> ContactFit {
    let s = HarmonicSettings {
        frequency: ExcitationFrequency::FractionOfNatural(ratio),
        settling_periods: 4,
        ehl: ehl(),
        ..HarmonicSettings::default()
    };
    let fit = characterize_harmonic(
        &heavy_inner_3000(),
        ball_mass(7e-3, Solid::AISI_52100.density),
        &s,
    )
    .expect("harmonic characterization");
    assert!(fit.converged, "Ω/ω_n = {ratio}: not converged");
    fit
}

#[test]
fn harmonic_law_tends_to_quasi_static_and_damping_is_flat_in_the_rotor_band() {
    let qs = characterize_quasi_static(
        &heavy_inner_3000(),
        &QuasiStaticSettings {
            ehl: ehl(),
            ..QuasiStaticSettings::default()
        },
    )
    .expect("quasi-static characterization");
    assert!(qs.converged);
    let k_qs = qs.k * qs.d * qs.approach.powf(qs.d - 1.0);
    let (low, band_top, above) = (harmonic(0.002), harmonic(0.01), harmonic(0.1));
    let dyn_of = |f: &ContactFit| f.dynamic_stiffness().expect("recorded period");
    let (d_low, d_top, d_above) = (dyn_of(&low), dyn_of(&band_top), dyn_of(&above));

    // Low Ω: the offsets agree to the 65² grid's discretization error of the difference. The
    // harmonic ΔF at 0.002·ω_n moves by 3.9 N from 65² to 129² while the quasi-static one moves
    // by 0.4 N, and the two agree to 0.5 N on 129² and 0.6 N on 257², so on 65² they can be
    // compared to ≈ 4 N: bound 5 N.
    let gap_low = low.delta_f - qs.delta_f;
    assert!(
        gap_low.abs() <= 5.0,
        "ΔF harmonic(0.002·ω_n) {:.2} N against quasi-static {:.2} N",
        low.delta_f,
        qs.delta_f
    );
    // Ω = 0.1·ω_n lowers ΔF by far more than that bound (24 N on 65², 19 N on 129²): the 10 N
    // against 30 N of the two methods at the former default came from the excitation frequency.
    let gap_above = qs.delta_f - above.delta_f;
    assert!(
        gap_above >= 3.0 * 5.0,
        "ΔF harmonic(0.1·ω_n) {:.2} N, quasi-static {:.2} N",
        above.delta_f,
        qs.delta_f
    );
    // The dynamic stiffness at low Ω is the quasi-static tangent: 1.0 % apart on 65², 0.08 % on
    // 129²; bound 2 %.
    let rel = d_low.stiffness_n_m / k_qs - 1.0;
    assert!(rel.abs() <= 0.02, "k'(0.002·ω_n)/k_qs − 1 = {rel:.4}");
    // Damping over the rotor band (Ω/ω_n ≈ 0.002–0.01 on this contact for 100–400 Hz): within the
    // 5 % criterion (measured 1.3 % on 65² and 129², 0.06 % on 257²; on 65² the time-step error
    // of c_eq at 64 steps per period is 1.3 % against 256 steps, where the band change is 0.7 %).
    let spread = (d_low.damping_n_s_m - d_top.damping_n_s_m).abs() / d_low.damping_n_s_m;
    assert!(
        spread <= 0.05,
        "c_eq {:.2} → {:.2} N·s/m over the rotor band",
        d_low.damping_n_s_m,
        d_top.damping_n_s_m
    );
    // … but not up to 0.1·ω_n, where the squeeze film has relaxed (c_eq 1.52× lower on
    // both grids; bound 1.3×).
    assert!(
        d_low.damping_n_s_m >= 1.3 * d_above.damping_n_s_m,
        "c_eq {:.2} (0.002·ω_n) against {:.2} N·s/m (0.1·ω_n)",
        d_low.damping_n_s_m,
        d_above.damping_n_s_m
    );
    // The fitted c of the extended law and the first-harmonic c_eq describe the same loop (within
    // 1 % at every Ω of the sweep below 0.3·ω_n, on both grids; bound 2 %).
    for f in [&low, &band_top, &above] {
        let c = f.c.expect("damping term fitted");
        let c_eq = dyn_of(f).damping_n_s_m;
        assert!(
            (c / c_eq - 1.0).abs() <= 0.02,
            "c {c:.2} against c_eq {c_eq:.2}"
        );
    }
}

/// The harmonic method's default excitation lies inside the rotor band of the seed's contacts
/// (Ω/ω_n ≈ 0.0021–0.0112 for 100–400 Hz at ω_n/2π = 35.8–46.5 kHz, docs/contact.md), so that
/// the c a force element takes from a default characterization is the one the rotor sees.
#[test]
fn the_default_excitation_is_in_the_rotor_band() {
    let ExcitationFrequency::FractionOfNatural(f) = HarmonicSettings::default().frequency else {
        panic!("the default excitation is not a fraction of ω_n");
    };
    assert!((0.0021..=0.0112).contains(&f), "default Ω/ω_n = {f}");
}
