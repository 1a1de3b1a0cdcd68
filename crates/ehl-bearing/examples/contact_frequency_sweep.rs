//! Contact dynamics over frequency: the harmonic method at a sweep of Ω/ω_n on seed contacts
//! (dry-Hertz loads of `benches/seed_contacts.csv`), with the quasi-static limit beside it.
//!
//! Per contact and speed, one quasi-static characterization and one harmonic characterization per
//! Ω/ω_n (harmonic defaults but up to 4 settling periods). Each row gives the fitted law (K, d, ΔF,
//! c) and the first-harmonic complex stiffness of the recorded period
//! (`ContactFit::dynamic_stiffness`), k*(Ω) = F₁/δ₁ = k' + i·Ω·c_eq (F₁, δ₁ the first Fourier
//! coefficients of the film force ∬p dA and of the approach over the recorded period), so k' (N/m)
//! is the dynamic stiffness and c_eq (N·s/m) the equivalent viscous damping. The quasi-static row has k' = the
//! law's tangent K·d·δ0^(d−1) at w0 and no damping. Writes `sweep.csv` and `sweep.svg` (k'/k_qs,
//! c_eq and c, d, ΔF against Ω/ω_n, log scale, the rotor band shaded) into OUT.
//!
//! `cargo run --release -p ehl-bearing --example contact_frequency_sweep -- [OPTIONS]`
//!
//! - `--out DIR` (default `docs/figures/contact_frequency`)
//! - `--grid N` EHL grid of every solution (default 129, the methods' default)
//! - `--steps N` steps per period (default 64)
//! - `--rpm 3000,4000,5000` speeds of `seed_contacts.csv`
//! - `--contacts 1i,1o,5i` ball number and race initial (default: the heaviest inner and outer
//!   contacts, ball 1, and a light inner one, ball 5)
//! - `--ratios 0.002,0.005,…` Ω/ω_n (default 0.002 0.005 0.01 0.02 0.05 0.1 0.2 0.3 0.5 1)
//! - `--plot` only redraw `OUT/sweep.svg` from `OUT/sweep.csv`
use ehl_bearing::contact::{
    ball_mass, characterize_harmonic, characterize_quasi_static, Excitation, ExcitationFrequency,
    HarmonicSettings, QuasiStaticSettings,
};
use ehl_bearing::ehl::EhlSettings;
use ehl_bearing::material::Solid;
use std::fmt::Write as _;
use std::path::PathBuf;

#[path = "../benches/common/seed_contacts.rs"]
mod seed_contacts;

/// Runs whose periodicity exceeds this are not plotted: not a periodic state (at Ω/ω_n = 0.5 the
/// seed contacts reach 7.6e-3 to 2.3e-2 in 4 settling periods; up to 0.3 they stay below 1.3e-3).
const MAX_PLOTTED_PERIODICITY: f64 = 5e-3;

/// Rotor band of shaft and whirl frequencies, Hz (the band the force elements are used in).
const ROTOR_BAND_HZ: [f64; 2] = [100.0, 400.0];

const HEADER: &str = "rpm,ball,race,load_n,method,ratio,omega_rad_s,omega_n_rad_s,k_lin_n_m,\
k,d,delta_f_n,c_n_s_m,approach_m,k_law_n_m,k_dyn_n_m,c_eq_n_s_m,r_squared,rms_residual_n,\
periodicity,settled,steps_not_converged,converged,seconds,error";

fn arg<'a>(args: &'a [String], key: &str) -> Option<&'a str> {
    args.iter()
        .position(|a| a == key)
        .and_then(|i| args.get(i + 1))
        .map(String::as_str)
}

fn list(s: &str) -> Vec<String> {
    s.split(',').map(|x| x.trim().to_string()).collect()
}

/// An error message as one CSV field.
fn clean(err: &dyn std::fmt::Display) -> String {
    err.to_string().replace([',', '\n'], ";")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = PathBuf::from(arg(&args, "--out").unwrap_or("docs/figures/contact_frequency"));
    std::fs::create_dir_all(&out).expect("output directory");
    if args.iter().any(|a| a == "--plot") {
        let csv = std::fs::read_to_string(out.join("sweep.csv")).expect("sweep.csv");
        std::fs::write(out.join("sweep.svg"), plot(&csv)).expect("write svg");
        return;
    }
    let grid: usize = arg(&args, "--grid").map_or(129, |x| x.parse().expect("grid"));
    let steps: usize = arg(&args, "--steps").map_or(64, |x| x.parse().expect("steps"));
    let rpms = list(arg(&args, "--rpm").unwrap_or("3000,4000,5000"));
    let contacts = list(arg(&args, "--contacts").unwrap_or("1i,1o,5i"));
    let ratios: Vec<f64> =
        list(arg(&args, "--ratios").unwrap_or("0.002,0.005,0.01,0.02,0.05,0.1,0.2,0.3,0.5,1"))
            .iter()
            .map(|x| x.parse().expect("ratio"))
            .collect();
    let m = ball_mass(7e-3, Solid::AISI_52100.density);
    let ehl = EhlSettings {
        grid,
        discretization_fraction: 0.0,
        ..EhlSettings::default()
    };
    let qs = QuasiStaticSettings {
        ehl,
        ..QuasiStaticSettings::default()
    };
    let mut csv = String::from(HEADER);
    csv.push('\n');
    let t_all = std::time::Instant::now();
    for row in seed_contacts::seed_contacts() {
        if !rpms.contains(&row.rpm) || !contacts.contains(&row.id()) {
            continue;
        }
        let c = row.contact;
        let id = format!("{},{},{},{:.3}", row.rpm, row.ball, row.race, c.load);
        match characterize_quasi_static(&c, &qs) {
            Ok(q) => {
                let k_law = q.k * q.d * q.approach.powf(q.d - 1.0);
                let _ =
                    writeln!(
                    csv,
                    "{id},quasi-static,0,0,,,{:e},{:.6},{:.4},,{:e},{:e},{:e},,{:.8},{:.4e},,,,\
                     {},{:.2},",
                    q.k, q.d, q.delta_f, q.approach, k_law, k_law, q.r_squared, q.rms_residual,
                    q.converged, q.seconds
                );
                eprintln!(
                    "{id} quasi-static: d {:.4} dF {:.2} N k {:.4e} N/m {:.1} s",
                    q.d, q.delta_f, k_law, q.seconds
                );
            }
            Err(err) => {
                eprintln!("{id} quasi-static: error {err}");
                let _ = writeln!(csv, "{id},quasi-static,0{}{}", ",".repeat(19), clean(&err));
            }
        }
        for &r in &ratios {
            let s = HarmonicSettings {
                frequency: ExcitationFrequency::FractionOfNatural(r),
                steps_per_period: steps,
                settling_periods: 4,
                ehl,
                ..HarmonicSettings::default()
            };
            match characterize_harmonic(&c, m, &s) {
                Ok(h) => {
                    let Excitation::Harmonic(x) = h.excitation else {
                        unreachable!("the harmonic method records a harmonic excitation")
                    };
                    let ds = h
                        .dynamic_stiffness()
                        .expect("a harmonic result has a recorded period");
                    let (om, k_dyn, c_eq) =
                        (ds.frequency_rad_s, ds.stiffness_n_m, ds.damping_n_s_m);
                    let cc = h.c.unwrap_or(f64::NAN);
                    let k_law = h.k * h.d * h.approach.powf(h.d - 1.0);
                    let _ = writeln!(
                        csv,
                        "{id},harmonic,{r},{om:e},{:e},{:e},{:e},{:.6},{:.4},{cc:.4},{:.6e},{:.6e},\
                         {:.6e},{:.4},{:.8},{:.4e},{:.2e},{},{},{},{:.2},",
                        x.natural_frequency_rad_s,
                        x.linearized_stiffness_n_m,
                        h.k,
                        h.d,
                        h.delta_f,
                        h.approach,
                        k_law,
                        k_dyn,
                        c_eq,
                        h.r_squared,
                        h.rms_residual,
                        x.periodicity,
                        x.settled,
                        x.steps_not_converged,
                        h.converged,
                        h.seconds
                    );
                    eprintln!(
                        "{id} Ω/ω_n {r}: d {:.4} dF {:.2} N c {cc:.2} | k' {k_dyn:.4e} N/m \
                         c_eq {:.2} N·s/m | periodicity {:.1e} {:.1} s",
                        h.d, h.delta_f, c_eq, x.periodicity, h.seconds
                    );
                }
                Err(err) => {
                    eprintln!("{id} Ω/ω_n {r}: error {err}");
                    let _ = writeln!(csv, "{id},harmonic,{r}{}{}", ",".repeat(19), clean(&err));
                }
            }
        }
    }
    eprintln!("total {:.0} s", t_all.elapsed().as_secs_f64());
    std::fs::write(out.join("sweep.csv"), &csv).expect("write csv");
    std::fs::write(out.join("sweep.svg"), plot(&csv)).expect("write svg");
}

/// One plotted series: label and (Ω/ω_n, value) points.
type Series = (String, Vec<(f64, f64)>);

/// One panel: title, the series drawn as lines, series drawn as dots, and a dashed reference
/// value per series.
type Panel<'a> = (
    &'a str,
    &'a Vec<Series>,
    Option<&'a Vec<Series>>,
    Vec<Option<f64>>,
);

/// Colours of the contacts' series, in order.
const COLOURS: [&str; 9] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf", "#7f7f7f",
    "#bcbd22",
];

/// Panel size and margins, px: width, height, left margin, top margin.
const PANEL: (f64, f64, f64, f64) = (460.0, 300.0, 70.0, 40.0);

/// The sweep's CSV: its columns, its rows and the contacts' keys in order of appearance.
struct Sweep<'a> {
    head: Vec<&'a str>,
    rows: Vec<Vec<&'a str>>,
    keys: Vec<String>,
}

impl<'a> Sweep<'a> {
    fn parse(csv: &'a str) -> Self {
        let mut lines = csv.lines();
        let head: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        let mut keys: Vec<String> = Vec::new();
        for r in &rows {
            let k = Self::key(r);
            if !keys.contains(&k) {
                keys.push(k);
            }
        }
        Sweep { head, rows, keys }
    }

    /// A row's contact: speed, ball and raceway.
    fn key(r: &[&str]) -> String {
        format!("{} rpm, ball {} {}", r[0], r[1], r[2])
    }

    fn col(&self, name: &str) -> usize {
        self.head.iter().position(|h| *h == name).expect("column")
    }

    fn num(&self, r: &[&str], name: &str) -> Option<f64> {
        r[self.col(name)].parse::<f64>().ok()
    }

    /// Column `name` of contact `k`'s quasi-static row.
    fn qs(&self, k: &str, name: &str) -> Option<f64> {
        self.rows
            .iter()
            .find(|r| Self::key(r) == k && r[self.col("method")] == "quasi-static")
            .and_then(|r| self.num(r, name))
    }

    /// Per contact, the settled harmonic runs' (Ω/ω_n, f(row, contact)).
    fn series(&self, f: &dyn Fn(&[&str], &str) -> Option<f64>) -> Vec<Series> {
        self.keys
            .iter()
            .map(|k| {
                let pts = self
                    .rows
                    .iter()
                    .filter(|r| Self::key(r) == *k && r[self.col("method")] == "harmonic")
                    .filter(|r| {
                        self.num(r, "periodicity")
                            .is_some_and(|p| p <= MAX_PLOTTED_PERIODICITY)
                    })
                    .filter_map(|r| Some((self.num(r, "ratio")?, f(r, k)?)))
                    .filter(|p| p.1.is_finite())
                    .collect();
                (k.clone(), pts)
            })
            .collect()
    }

    /// Per contact, its quasi-static value of column `name`.
    fn qs_line(&self, name: &str) -> Vec<Option<f64>> {
        self.keys.iter().map(|k| self.qs(k, name)).collect()
    }

    /// The rotor band in Ω/ω_n over the contacts' ω_n: (lowest band frequency over the
    /// largest ω_n, highest over the smallest).
    fn band(&self) -> (f64, f64) {
        let wn: Vec<f64> = self
            .rows
            .iter()
            .filter_map(|r| self.num(r, "omega_n_rad_s"))
            .filter(|w| *w > 0.0)
            .collect();
        let tau = 2.0 * std::f64::consts::PI;
        (
            tau * ROTOR_BAND_HZ[0] / wn.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
            tau * ROTOR_BAND_HZ[1] / wn.iter().cloned().fold(f64::INFINITY, f64::min),
        )
    }
}

/// SVG of four panels against log Ω/ω_n from the CSV text: k'/k_qs, c_eq (lines) and the law's
/// c (dots), d, ΔF. The quasi-static values are drawn as dashed horizontal lines in the same
/// colour. The rotor band (100–400 Hz over the contacts' ω_n) is shaded.
fn plot(csv: &str) -> String {
    let sw = Sweep::parse(csv);
    let k_rel = sw.series(&|r, k| Some(sw.num(r, "k_dyn_n_m")? / sw.qs(k, "k_law_n_m")?));
    let c_eq = sw.series(&|r, _| sw.num(r, "c_eq_n_s_m"));
    let c_law = sw.series(&|r, _| sw.num(r, "c_n_s_m"));
    let d = sw.series(&|r, _| sw.num(r, "d"));
    let df = sw.series(&|r, _| sw.num(r, "delta_f_n"));
    let band = sw.band();
    let (pw, ph, ml, mt) = PANEL;
    let (width, height) = (2.0 * (pw + ml + 20.0), 2.0 * (ph + mt + 50.0) + 30.0 * 3.0);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" \
         fill=\"white\"/>\n"
    );
    let panels: [Panel; 4] = [
        (
            "dynamic stiffness k'/k_qs (k_qs: quasi-static tangent)",
            &k_rel,
            None,
            sw.keys.iter().map(|_| Some(1.0)).collect(),
        ),
        (
            "damping: c_eq = Im k*/Ω (lines), fitted c (dots), N·s/m",
            &c_eq,
            Some(&c_law),
            sw.keys.iter().map(|_| None).collect(),
        ),
        ("index d (dashed: quasi-static)", &d, None, sw.qs_line("d")),
        (
            "offset ΔF, N (dashed: quasi-static)",
            &df,
            None,
            sw.qs_line("delta_f_n"),
        ),
    ];
    for (i, panel) in panels.iter().enumerate() {
        draw_panel(&mut svg, i, panel, band);
    }
    legend(&mut svg, &sw.keys);
    svg.push_str("</svg>\n");
    svg
}

/// Panel `i` (left to right, top to bottom): its scales, the shaded band, the frame and title,
/// the axes and the series.
fn draw_panel(svg: &mut String, i: usize, (title, main, dots, refs): &Panel, band: (f64, f64)) {
    let (pw, ph, ml, mt) = PANEL;
    let x0 = ml + (i % 2) as f64 * (pw + ml + 20.0);
    let y0 = mt + (i / 2) as f64 * (ph + mt + 50.0);
    let all: Vec<(f64, f64)> = main
        .iter()
        .chain(dots.iter().flat_map(|d| d.iter()))
        .flat_map(|s| s.1.iter().cloned())
        .chain(
            refs.iter()
                .flatten()
                .map(|&v| (band.0.max(1e-9), v))
                .collect::<Vec<_>>(),
        )
        .collect();
    if all.is_empty() {
        return;
    }
    let (xmin, xmax) = all.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
        (a.0.min(p.0), a.1.max(p.0))
    });
    let (xmin, xmax) = (xmin.min(band.0).log10(), xmax.log10());
    let (ymin, ymax) = all.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
        (a.0.min(p.1), a.1.max(p.1))
    });
    let pad = 0.05 * (ymax - ymin).max(1e-12);
    let (ymin, ymax) = (ymin - pad, ymax + pad);
    let frame = Frame {
        x0,
        y0,
        x: (xmin, xmax),
        y: (ymin, ymax),
    };
    let _ = writeln!(
        svg,
        "<rect x=\"{:.1}\" y=\"{y0}\" width=\"{:.1}\" height=\"{ph}\" fill=\"#eeeeee\"/>",
        frame.sx(band.0),
        frame.sx(band.1) - frame.sx(band.0)
    );
    let _ = writeln!(
        svg,
        "<rect x=\"{x0}\" y=\"{y0}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" \
         stroke=\"black\"/>\n<text x=\"{x0}\" y=\"{:.1}\">{title}</text>",
        y0 - 8.0
    );
    frame.axes(svg);
    for (k, (_, pts)) in main.iter().enumerate() {
        frame.series(
            svg,
            COLOURS[k % COLOURS.len()],
            pts,
            dots.map(|d| &d[k].1),
            refs[k],
        );
    }
}

/// A panel's position (top left, px) and its ranges: log10 Ω/ω_n and the value.
struct Frame {
    x0: f64,
    y0: f64,
    x: (f64, f64),
    y: (f64, f64),
}

impl Frame {
    fn sx(&self, x: f64) -> f64 {
        self.x0 + (x.log10() - self.x.0) / (self.x.1 - self.x.0) * PANEL.0
    }

    fn sy(&self, y: f64) -> f64 {
        self.y0 + PANEL.1 - (y - self.y.0) / (self.y.1 - self.y.0) * PANEL.1
    }

    /// Logarithmic x ticks (labels at 1, 2, 5), the x label, five y ticks.
    fn axes(&self, svg: &mut String) {
        let (pw, ph, x0, y0) = (PANEL.0, PANEL.1, self.x0, self.y0);
        let (xmin, xmax) = self.x;
        for e in (xmin.floor() as i32)..=(xmax.ceil() as i32) {
            for m in 1..10 {
                let x = m as f64 * 10f64.powi(e);
                if x.log10() < xmin - 1e-9 || x.log10() > xmax + 1e-9 {
                    continue;
                }
                let _ = writeln!(
                    svg,
                    "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{0:.1}\" y2=\"{2:.1}\" stroke=\"black\"/>",
                    self.sx(x),
                    y0 + ph,
                    y0 + ph + if m == 1 { 6.0 } else { 3.0 }
                );
                if m == 1 || m == 2 || m == 5 {
                    let _ = writeln!(
                        svg,
                        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
                        self.sx(x),
                        y0 + ph + 18.0,
                        x
                    );
                }
            }
        }
        let _ = writeln!(
            svg,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">Ω/ω_n</text>",
            x0 + pw / 2.0,
            y0 + ph + 34.0
        );
        let (ymin, ymax) = self.y;
        for j in 0..=4 {
            let y = ymin + (ymax - ymin) * j as f64 / 4.0;
            let _ = writeln!(
                svg,
                "<line x1=\"{a:.1}\" y1=\"{b:.1}\" x2=\"{x0}\" y2=\"{b:.1}\" stroke=\"black\"/>\
                 <text x=\"{c:.1}\" y=\"{e:.1}\" text-anchor=\"end\">{y:.4}</text>",
                a = x0 - 5.0,
                b = self.sy(y),
                c = x0 - 7.0,
                e = self.sy(y) + 4.0,
            );
        }
    }

    /// One contact's line with square markers, its dots (those inside the range) and its
    /// dashed reference value.
    fn series(
        &self,
        svg: &mut String,
        colour: &str,
        pts: &[(f64, f64)],
        dots: Option<&Vec<(f64, f64)>>,
        reference: Option<f64>,
    ) {
        let path: Vec<String> = pts
            .iter()
            .map(|&(x, y)| format!("{:.1},{:.1}", self.sx(x), self.sy(y)))
            .collect();
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"/>",
            path.join(" ")
        );
        for &(x, y) in pts {
            let _ = writeln!(
                svg,
                "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"5\" height=\"5\" fill=\"{colour}\"/>",
                self.sx(x) - 2.5,
                self.sy(y) - 2.5
            );
        }
        for &(x, y) in dots.into_iter().flatten() {
            if y >= self.y.0 && y <= self.y.1 {
                let _ = writeln!(
                    svg,
                    "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3\" fill=\"none\" \
                     stroke=\"{colour}\"/>",
                    self.sx(x),
                    self.sy(y)
                );
            }
        }
        if let Some(v) = reference {
            let x0 = self.x0;
            let _ = writeln!(
                svg,
                "<line x1=\"{x0}\" y1=\"{0:.1}\" x2=\"{1:.1}\" y2=\"{0:.1}\" \
                 stroke=\"{colour}\" stroke-dasharray=\"5,4\"/>",
                self.sy(v),
                x0 + PANEL.0,
            );
        }
    }
}

/// The contacts' colours under the panels and the note on the band and the omitted runs.
fn legend(svg: &mut String, keys: &[String]) {
    let (_, ph, ml, mt) = PANEL;
    let ly = 2.0 * (ph + mt + 50.0) + 5.0;
    for (k, name) in keys.iter().enumerate() {
        let (lx, lyy) = (
            ml + (k % 3) as f64 * 300.0,
            ly + (k / 3) as f64 * 20.0 + 10.0,
        );
        let _ = writeln!(
            svg,
            "<line x1=\"{lx}\" y1=\"{lyy}\" x2=\"{:.1}\" y2=\"{lyy}\" stroke=\"{}\" \
             stroke-width=\"2\"/><text x=\"{:.1}\" y=\"{:.1}\">{name}</text>",
            lx + 25.0,
            COLOURS[k % COLOURS.len()],
            lx + 30.0,
            lyy + 4.0
        );
    }
    let _ = writeln!(
        svg,
        "<text x=\"{ml}\" y=\"{:.1}\">grey: rotor band {}–{} Hz over the contacts' ω_n; runs \
         with periodicity above {MAX_PLOTTED_PERIODICITY:e} (not settled) and failed runs omitted</text>",
        ly + 70.0,
        ROTOR_BAND_HZ[0],
        ROTOR_BAND_HZ[1]
    );
}
