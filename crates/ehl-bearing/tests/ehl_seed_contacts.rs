//! The seed bearing's contacts (examples/7006.toml, 11 balls × inner/outer race, 3000, 4000 and
//! 5000 rpm, dry Hertz equilibrium loads; list in `benches/seed_contacts.csv`) solved by the
//! steady EHL solver at its defaults.
//!
//! Fast check (default run): the contacts of one speed at 65² converge in their first start.
//! Table (ignored; grid from `EHL_SEED_GRID`, default 257; `EHL_SEED_RPM` to pick one speed):
//!
//!     cargo test --release -p ehl-bearing --test ehl_seed_contacts -- --ignored --nocapture

use ehl_bearing::ehl::{
    solve_steady, solve_steady_starts, start_order, AttemptOutcome, EhlContact, EhlSettings,
    StartStrategy,
};
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};

/// (rpm, ball, race, contact) of every row of `benches/seed_contacts.csv`.
fn seed_contacts() -> Vec<(u32, usize, String, EhlContact)> {
    let text = include_str!("../benches/seed_contacts.csv");
    let e = reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100);
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("rpm"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |i: usize| f[i].parse::<f64>().expect("number");
            (
                f[0].parse().expect("rpm"),
                f[1].parse().expect("ball"),
                f[2].to_string(),
                EhlContact {
                    load: num(3),
                    rx: num(4),
                    ry: num(5),
                    sum_velocity: num(6),
                    e_reduced: e,
                    lubricant: Lubricant::DEFAULT_MINERAL_OIL,
                },
            )
        })
        .collect()
}

#[test]
fn seed_contact_list_is_complete() {
    let c = seed_contacts();
    assert_eq!(c.len(), 66, "22 contacts at each of 3 speeds");
    for rpm in [3000, 4000, 5000] {
        assert_eq!(c.iter().filter(|x| x.0 == rpm).count(), 22);
    }
}

#[test]
fn seed_contacts_converge_in_their_first_start_on_65() {
    let s = EhlSettings {
        grid: 65,
        ..Default::default()
    };
    let mut conservative = 0;
    for (rpm, ball, race, c) in seed_contacts().into_iter().filter(|x| x.0 == 5000) {
        let r = solve_steady(&c, &s).expect("solves");
        assert!(r.converged, "{rpm} rpm ball {ball} {race}: not converged");
        // The start tried is the first of the contact's start order, and it converged.
        let order = start_order(&c, &s).expect("valid");
        assert_eq!(r.attempt_log[0].strategy, order[0]);
        assert_eq!(r.attempt_log[0].outcome, AttemptOutcome::Converged);
        assert_eq!(r.attempt_log[0].cycles, r.cycles);
        if order[0] == StartStrategy::Conservative {
            conservative += 1;
            assert_eq!(r.attempts, 5);
        }
        assert_eq!(
            r.attempt_log.len(),
            1,
            "{rpm} rpm ball {ball} {race}: starts tried {:?}",
            r.attempt_log
        );
    }
    // At 5000 rpm (L = 23.4–25.3) the inner contacts with M ≤ 1100 (balls 4–9) and the outer
    // one with M ≤ 100 (ball 7) start with the conservative settings (docs/ehl.md §2).
    assert_eq!(conservative, 7);
}

#[test]
#[ignore]
fn seed_contact_table() {
    let grid: usize = std::env::var("EHL_SEED_GRID")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(257);
    let rpm_only: Option<u32> = std::env::var("EHL_SEED_RPM")
        .ok()
        .and_then(|v| v.parse().ok());
    // EHL_SEED_START=k: only start k (1–9) of the ladder, to see which start converges.
    let only: Option<usize> = std::env::var("EHL_SEED_START")
        .ok()
        .and_then(|v| v.parse().ok());
    // EHL_SEED_FILTER=rpm:ball:race,... to pick contacts.
    let filter: Option<String> = std::env::var("EHL_SEED_FILTER").ok();
    let s = EhlSettings {
        grid,
        ..Default::default()
    };
    println!("rpm ball race load_N M L Ry/Rx conv start cycles s H_c_moes delta_um");
    let mut total = 0.0;
    let mut worst: f64 = 0.0;
    let mut not_first = 0;
    let mut n = 0;
    for (rpm, ball, race, c) in seed_contacts() {
        if rpm_only.is_some_and(|r| r != rpm) {
            continue;
        }
        if let Some(f) = &filter {
            if !f.split(',').any(|x| x == format!("{rpm}:{ball}:{race}")) {
                continue;
            }
        }
        let r = match only {
            Some(k) => match solve_steady_starts(&c, &s, &[StartStrategy::LADDER[k - 1]], None) {
                Ok(r) => r,
                Err(e) => {
                    println!("{rpm} {ball} {race} start {k}: {e}");
                    continue;
                }
            },
            None => solve_steady(&c, &s).expect("solves"),
        };
        println!(
            "{rpm} {ball} {race} {:.1} {:.1} {:.2} {:.1} {} {} {} {:.3} {:.5} {:.5}",
            c.load,
            r.moes_m,
            r.moes_l,
            r.ry_over_rx,
            r.converged,
            r.attempts,
            r.cycles,
            r.seconds,
            r.h_central_moes,
            r.approach * 1e6
        );
        total += r.seconds;
        worst = worst.max(r.seconds);
        n += 1;
        if r.attempt_log.len() != 1 {
            not_first += 1;
        }
        if only.is_none() {
            assert!(r.converged);
        }
    }
    println!(
        "{n} contacts at {grid}²: total {total:.2} s, mean {:.3} s, worst {worst:.3} s, {not_first} not in their first start",
        total / n as f64
    );
}
