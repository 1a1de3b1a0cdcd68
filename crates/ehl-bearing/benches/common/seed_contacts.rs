//! The seed bearing's 22 contacts at 3000, 4000 and 5000 rpm (`seed_contacts.csv`: dry-Hertz
//! loads of examples/7006.toml, its lubricant, AISI 52100 on itself), read in one place for the
//! benches and examples that run them (`#[path = "…/benches/common/seed_contacts.rs"] mod
//! seed_contacts;`; in a subfolder, so that cargo does not take it for a bench of its own).
// Each user reads only some of the fields.
#![allow(dead_code)]

use ehl_bearing::ehl::EhlContact;
use ehl_bearing::material::{reduced_modulus, Lubricant, Solid};

/// One row of `seed_contacts.csv`.
pub struct SeedContact {
    /// Inner-ring speed as written in the file (`3000`, `4000`, `5000`), rpm.
    pub rpm: String,
    /// Ball number (0-based), as written.
    pub ball: String,
    /// `inner` or `outer`.
    pub race: String,
    /// The contact (SI).
    pub contact: EhlContact,
}

impl SeedContact {
    /// Ball number and race initial, as `7i` or `5o`.
    pub fn id(&self) -> String {
        format!("{}{}", self.ball, &self.race[..1])
    }
}

/// Every row, in the file's order.
pub fn seed_contacts() -> Vec<SeedContact> {
    let e = reduced_modulus(&Solid::AISI_52100, &Solid::AISI_52100);
    include_str!("../seed_contacts.csv")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("rpm"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let v: Vec<f64> = f[3..]
                .iter()
                .map(|x| x.parse().expect("seed_contacts.csv: a number"))
                .collect();
            SeedContact {
                rpm: f[0].to_string(),
                ball: f[1].to_string(),
                race: f[2].to_string(),
                contact: EhlContact {
                    load: v[0],
                    rx: v[1],
                    ry: v[2],
                    sum_velocity: v[3],
                    e_reduced: e,
                    lubricant: Lubricant::DEFAULT_MINERAL_OIL,
                },
            }
        })
        .collect()
}
