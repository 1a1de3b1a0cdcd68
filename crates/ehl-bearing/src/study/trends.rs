//! A study's trend curves: the samples its rows give the trend fit ([`fit_trends`]), and how well
//! the trends reproduce a characterized point ([`trend_reaction_error`]). The trend model, its
//! fit and its evaluation live in [`crate::trends`].

use super::point::{PointRecord, ResultRow};
use super::spec::Study;
use crate::characterize::CharacterizeError;
use crate::force_element::TrendForceElement;
use crate::trends::{fit_model, RaceSamples, TrendError, TrendFitInput, TrendModel};
use std::f64::consts::PI;

/// Fit the trend curves of a study to its rows. Contacts whose load was floored (lightly loaded)
/// or whose fit did not converge are left out. K, d and ΔF are fitted against the load each law
/// was characterized at (`characterized_load_n`), the approach δ against the equilibrium load
/// (`load_n`); the two differ by at most the loop's load reuse tolerance. The speed n is the inner-ring speed relative to
/// the outer ring, rad/s.
pub fn fit_trends(study: &Study, rows: &[ResultRow]) -> Result<TrendModel, CharacterizeError> {
    let outer_speed = study.case.operating.outer_speed;
    let pick = |race: &str| {
        let mut s = RaceSamples::default();
        for r in rows {
            let c = &r.contact;
            if c.race == race && !c.load_floored && c.fit_converged && c.load_n > 0.0 {
                s.characterized_load_n.push(c.characterized_load_n);
                s.load_n.push(c.load_n);
                s.speed_rad_s
                    .push((r.inner_speed_rad_s - outer_speed).abs());
                s.k.push(c.k);
                s.d.push(c.d);
                s.delta_f_n.push(c.delta_f_n);
                s.approach_m.push(c.approach_m);
            }
        }
        s
    };
    Ok(fit_model(&TrendFitInput {
        method: study.method,
        bearing: &study.case.bearing,
        lubricant: study.case.lubricant,
        race_control: study.case.operating.race_control,
        inner: pick("inner"),
        outer: pick("outer"),
    })?)
}

/// Largest relative difference between the reactions F_x, F_y, F_z the trend force element gives
/// at a characterized point's displacement and speed and the point's own equilibrium reactions
/// (each relative to max(|F|, 1 N)): how well the trends reproduce the characterization.
pub fn trend_reaction_error(
    element: &TrendForceElement,
    point: &PointRecord,
) -> Result<f64, crate::Error> {
    let r = point
        .result
        .as_ref()
        .ok_or(CharacterizeError::Trend(TrendError::NoEquilibrium))?;
    let q = r.displacement.to_array();
    let inner = point.spec.inner_speed_rpm * PI / 30.0;
    let f = element.evaluate(&q, inner, point.spec.operating.outer_speed)?;
    let want = r.reaction.to_array();
    Ok(f.force.reaction[..3]
        .iter()
        .zip(&want[..3])
        .map(|(got, w)| (got - w).abs() / w.abs().max(1.0))
        .fold(0.0_f64, f64::max))
}
