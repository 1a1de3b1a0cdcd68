//! Helpers shared by the bearing-model tests (included with `mod`).

use ehl_bearing::bearing::BearingModel;

/// Central finite differences of the reactions at `q`: steps 0.1 nm for x, y, z and `tilt_step`
/// (rad) for θy, θz.
pub fn fd_jacobian(model: &BearingModel, q: &[f64; 5], tilt_step: f64) -> [[f64; 5]; 5] {
    let mut jac = [[0.0; 5]; 5];
    for c in 0..5 {
        let h = if c < 3 { 1e-10 } else { tilt_step };
        let mut qp = *q;
        let mut qm = *q;
        qp[c] += h;
        qm[c] -= h;
        let fp = model.evaluate(&qp).unwrap().reaction;
        let fm = model.evaluate(&qm).unwrap().reaction;
        for (row, (p, m)) in jac.iter_mut().zip(fp.iter().zip(&fm)) {
            row[c] = (p - m) / (2.0 * h);
        }
    }
    jac
}
