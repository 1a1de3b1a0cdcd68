//! Empirical film-thickness formulas, for sanity checks of the numerical solver.
//!
//! Dimensionless groups (Moes; Venner & Lubrecht 2000): W = w/(E′Rx²), U = η0·u_s/(E′Rx) with the
//! SUM velocity u_s = u1 + u2, G = αE′, M = W·U^(−3/4), L = G·U^(1/4), H_Moes = (h/Rx)·U^(−1/2).

/// Hamrock & Dowson (1977) central film, h_c/Rx, dimensionless.
///
/// `u_sum` = η0·u_s/(E′Rx) with the sum velocity (the formula's own U uses the mean velocity
/// u_s/2; the conversion is done here), `g` = αE′, `w` = load/(E′Rx²), `k` = a/b ellipticity
/// (transverse over rolling semi-axis). Scatter against full numerical solutions: ±10–20 %.
pub fn hamrock_dowson_central(u_sum: f64, g: f64, w: f64, k: f64) -> f64 {
    let u = 0.5 * u_sum;
    2.69 * u.powf(0.67) * g.powf(0.53) * w.powf(-0.067) * (1.0 - 0.61 * (-0.73 * k).exp())
}

/// Hamrock & Dowson (1977) minimum film, h_min/Rx, dimensionless; arguments as in
/// [`hamrock_dowson_central`].
pub fn hamrock_dowson_min(u_sum: f64, g: f64, w: f64, k: f64) -> f64 {
    let u = 0.5 * u_sum;
    3.63 * u.powf(0.68) * g.powf(0.49) * w.powf(-0.073) * (1.0 - (-0.68 * k).exp())
}

/// The four asymptotes of the Nijenbanning–Venner–Moes formula and its exponent s, in Moes
/// scaling: (H_RI, H_EI, H_RP, H_EP, s, H00).
pub fn nijenbanning_asymptotes(m: f64, l: f64, rx_over_ry: f64) -> [f64; 6] {
    let d = rx_over_ry;
    let ld = d.ln();
    let h_ri = 145.0 * (1.0 + 0.796 * d.powf(14.0 / 15.0)).powf(-15.0 / 7.0) / d / (m * m);
    let h_ei = 3.18
        * (1.0 + 0.006 * ld + 0.63 * d.powf(4.0 / 7.0)).powf(-14.0 / 25.0)
        * d.powf(-1.0 / 15.0)
        * m.powf(-2.0 / 15.0);
    let h_rp = 1.29 * (1.0 + 0.691 * d).powf(-2.0 / 3.0) * l.powf(2.0 / 3.0);
    let h_ep = 1.48
        * (1.0 + 0.006 * ld + 0.63 * d.powf(4.0 / 7.0)).powf(-7.0 / 20.0)
        * d.powf(-1.0 / 24.0)
        * m.powf(-1.0 / 12.0)
        * l.powf(0.75);
    let s = 1.5 * (1.0 + (-1.2 * h_ei / h_ri).exp());
    let h00 = 1.8 / d;
    [h_ri, h_ei, h_rp, h_ep, s, h00]
}

/// Nijenbanning, Venner & Moes (1994, Wear 176:217) central film thickness for elliptical
/// contacts, in Moes scaling H_c = (h_c/Rx)·U^(−1/2); `rx_over_ry` = D = Rx/Ry ≤ 1.
///
/// Combination rule (one consistent reading of the four asymptotes, checked in the tests against
/// them; docs/ehl.md §5.4): H_c = {[H_RI^(3/2) + (H_EI^(−4) + H00^(−4))^(−3/8)]^(2s/3)
/// + (H_RP^(−8) + H_EP^(−8))^(−s/8)}^(1/s). A fit to numerical solutions: expect a few percent.
pub fn nijenbanning_central(m: f64, l: f64, rx_over_ry: f64) -> f64 {
    let [h_ri, h_ei, h_rp, h_ep, s, h00] = nijenbanning_asymptotes(m, l, rx_over_ry);
    let iso =
        (h_ri.powf(1.5) + (h_ei.powf(-4.0) + h00.powf(-4.0)).powf(-3.0 / 8.0)).powf(2.0 * s / 3.0);
    let piezo = (h_rp.powf(-8.0) + h_ep.powf(-8.0)).powf(-s / 8.0);
    (iso + piezo).powf(1.0 / s)
}
