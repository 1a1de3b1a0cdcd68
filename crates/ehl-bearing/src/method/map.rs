//! The `map` characterization method: the quasi-static law of a contact from the embedded maps
//! of the dimensionless law, with the map's error estimate, or — outside the maps' envelopes — an
//! error naming the group, or with `fallback` the quasi-static method itself. With `law =
//! "harmonic"` the harmonic law (with the damping c) from the embedded harmonic map at the
//! contact's groups and mass group Ψ_H, the fallback being the harmonic method at that map's
//! settings.

use super::{
    predict_steady, CharacterizedContact, ContactCharacterizer, ContactConditions,
    HarmonicCharacterizer, LoadPredictor, MapSettings, Method, PredictedLaw,
    QuasiStaticCharacterizer,
};
use crate::budget::Deadline;
use crate::contact::{HarmonicSettings, QuasiStaticSettings};
use crate::ehl::{film_resolution, EhlContact, EhlSettings, FILM_RESOLUTION_MIN};
use crate::hertz::HertzGeometry;
use crate::law_map::{
    damping_scale, hertz_deflection, mass_group, LawGroups, LawKind, LawMap, LawMapError, MapQuery,
};
use crate::ContactLaw;
use std::time::Instant;

/// The map method as a [`ContactCharacterizer`] (with the embedded maps,
/// [`LawMap::embedded_maps`]; they share the quasi-static settings of the fallback).
///
/// Inside the envelope the result is the map's law made dimensional for the contact: K, d, ΔF
/// and the fitted range as the map gives them, `max_residual` the map's error estimate of the
/// force at the nominal approach plus the nodes' own fit residual (N), `std_errors` the error
/// estimates of (K, d, ΔF) (the difference of the two interpolants, not standard errors),
/// `rms_residual` and `r_squared` those of the nearest nodes' fits, `samples` 0, `method`
/// "map" (with the harmonic map, `c_std_error` its error estimate of c). Outside it, with
/// `fallback`, the quasi-static method with the first map's settings (on 257² where 129² does
/// not resolve the contact's film, [`fallback_settings`]) characterizes the contact and its
/// `method` reads "quasi-static (outside the map: …)" with the reason (and the grid, where
/// refined); without, the error names the group, its value and the envelope.
///
/// With `law = "harmonic"` ([`MapSettings::law`]) the same from the embedded harmonic map at
/// the contact's groups and Ψ_H ([`crate::law_map::mass_group`] with the ball's mass): the law
/// carries the damping c = ĉ·w0·b/(δ_H·u_s), `method` reads "map (harmonic)", and outside the
/// map the harmonic method at the map's settings (Ω = 0.005·ω_n, its amplitude and grid, refined
/// where 129² does not resolve the film, [`harmonic_fallback_settings`]) characterizes the
/// contact ("harmonic (outside the map: …)").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MapCharacterizer {
    /// Settings of the method.
    pub settings: MapSettings,
}

impl ContactCharacterizer for MapCharacterizer {
    fn characterize(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<CharacterizedContact, crate::Error> {
        let t0 = Instant::now();
        let ehl = c.ehl_contact();
        let groups = LawGroups::of(&ehl)?;
        if self.settings.law == LawKind::Harmonic {
            return self.characterize_harmonic(c, &groups, deadline, t0);
        }
        let q = match LawMap::query_embedded(&groups) {
            Ok((q, _)) => q,
            Err(e) if self.settings.fallback => {
                let settings = fallback_settings(&ehl);
                let mut r = QuasiStaticCharacterizer { settings }.characterize(c, deadline)?;
                r.method =
                    fallback_method("quasi-static", settings.ehl.grid, LawMap::embedded(), &e);
                return Ok(r);
            }
            Err(e) => return Err(e.into()),
        };
        Self::from_query(c, &q, "map".into(), t0)
    }

    fn method(&self) -> Method {
        Method::Map(self.settings)
    }

    fn predictor(&self) -> Option<&dyn LoadPredictor> {
        Some(self)
    }
}

/// The `method` of a contact the fallback characterized by `name` on `grid` points a side,
/// outside every map for `reason`: it names the grid where it is not the fallback's `map`'s
/// (refined to resolve the film).
fn fallback_method(name: &str, grid: usize, map: &LawMap, reason: &LawMapError) -> String {
    if grid == map.spec.grid {
        format!("{name} (outside the map: {reason})")
    } else {
        format!("{name} on {grid} × {grid} to resolve the film (outside the map: {reason})")
    }
}

/// The first embedded map of the harmonic law (the harmonic fallback's settings).
fn harmonic_map() -> Result<&'static LawMap, LawMapError> {
    LawMap::embedded_first(LawKind::Harmonic).ok_or_else(|| LawMapError::OutsideEveryMap {
        reasons: "no embedded map of the harmonic law".into(),
        method: "harmonic",
    })
}

impl MapCharacterizer {
    /// The harmonic law from the embedded harmonic map at the contact's groups and its mass
    /// group Ψ_H (the ball's mass); outside it, with `fallback`, the harmonic method at the
    /// map's settings, its `method` reading "harmonic (outside the map: …)".
    fn characterize_harmonic(
        &self,
        c: &ContactConditions,
        groups: &LawGroups,
        deadline: Option<Deadline>,
        t0: Instant,
    ) -> Result<CharacterizedContact, crate::Error> {
        let ehl = c.ehl_contact();
        let psi_h = mass_group(&ehl, c.ball_mass)?;
        match LawMap::query_embedded_harmonic(groups, psi_h) {
            Ok((q, _)) => Self::from_query(c, &q, "map (harmonic)".into(), t0),
            Err(e) if self.settings.fallback => {
                let settings = harmonic_fallback_settings(&ehl)?;
                let mut r = HarmonicCharacterizer { settings }.characterize(c, deadline)?;
                r.method = fallback_method("harmonic", settings.ehl.grid, harmonic_map()?, &e);
                Ok(r)
            }
            Err(e) => Err(e.into()),
        }
    }

    /// The contact's law from a map query, with the map's error estimate.
    fn from_query(
        c: &ContactConditions,
        q: &MapQuery,
        method: String,
        t0: Instant,
    ) -> Result<CharacterizedContact, crate::Error> {
        let ehl = c.ehl_contact();
        let law = q.law.law(&ehl)?;
        let dh = hertz_deflection(&ehl)?;
        let w0 = c.load;
        let approach = law.approach_at(w0).unwrap_or(q.law.approach_hat * dh);
        let moes = c.moes();
        Ok(CharacterizedContact {
            law,
            k: law.k(),
            d: law.d(),
            delta_f: law.delta_f(),
            load: w0,
            approach,
            moes_m: moes.m,
            moes_l: moes.l,
            ry_over_rx: c.ry_over_rx(),
            r_squared: q.node_r_squared,
            rms_residual: q.node_rms_hat * w0,
            max_residual: (q.force_error + q.node_rms_hat) * w0,
            std_errors: [
                q.error.k_hat * w0 / dh.powf(q.law.d),
                q.error.d,
                q.error.delta_f_hat * w0,
            ],
            c_std_error: match q.error.c_hat {
                Some(e) if law.c().is_some() => Some(e * damping_scale(&ehl)?),
                _ => None,
            },
            converged: q.nodes_converged,
            method,
            seconds: t0.elapsed().as_secs_f64(),
            samples: 0,
        })
    }
}

impl LoadPredictor for MapCharacterizer {
    /// Inside a map, the map's own law: h = δ_Hertz(w0) − δ_map(w0), no EHL solution (so the
    /// loop starts from nearly the lubricated loads, as the EHL methods' predictor makes it do;
    /// from the dry loads a light contact can start where the fallback's family reaches the
    /// hydrodynamic regime, docs/law_map.md §8). Outside every map, with `fallback`, the
    /// quasi-static method's predictor (one loosely converged steady EHL solution,
    /// [`predict_steady`]) at the fallback's settings, [`fallback_settings`] (the harmonic map:
    /// [`harmonic_fallback_settings`]), so the loop starts where the fallback's method would
    /// start it (a start from a coarser grid's prediction put the seed's light inner contact at
    /// half load 2 % lighter, where the fallback's ±20 % family reached the hydrodynamic
    /// regime); without, the map's error (the loop keeps that contact's
    /// dry law for the start).
    fn predict(
        &self,
        c: &ContactConditions,
        deadline: Option<Deadline>,
    ) -> Result<PredictedLaw, crate::Error> {
        let ehl = c.ehl_contact();
        let groups = LawGroups::of(&ehl)?;
        let query = match self.settings.law {
            LawKind::QuasiStatic => LawMap::query_embedded(&groups),
            LawKind::Harmonic => {
                LawMap::query_embedded_harmonic(&groups, mass_group(&ehl, c.ball_mass)?)
            }
        };
        match query {
            Ok((q, _)) => {
                let law = q.law.law(&ehl)?;
                let h = HertzGeometry::new(c.rx, c.ry, c.e_reduced)?;
                let dh = h.contact(c.load).deflection;
                let approach = law.approach_at(c.load).unwrap_or(q.law.approach_hat * dh);
                Ok(PredictedLaw::new(
                    h.stiffness,
                    dh - approach,
                    q.nodes_converged,
                )?)
            }
            Err(_) if self.settings.fallback => {
                let settings = match self.settings.law {
                    LawKind::QuasiStatic => fallback_settings(&ehl).ehl,
                    LawKind::Harmonic => harmonic_fallback_settings(&ehl)?.ehl,
                };
                predict_steady(c, &settings, deadline)
            }
            Err(e) => Err(e.into()),
        }
    }
}

/// The fallback's settings for contact `c`: the first embedded map's (grid 129²), or the same
/// on 257² where 129² does not resolve the contact's film ([`film_resolution`] below
/// [`FILM_RESOLUTION_MIN`]: there a grid gives limit cycles or negative films and a fitted ΔF
/// several percent off, docs/ehl.md §5.9). 257² is kept even if it is still short of the
/// threshold (the finest grid the fallback uses).
pub fn fallback_settings(c: &EhlContact) -> QuasiStaticSettings {
    refined(c, LawMap::embedded().spec.settings())
}

/// `s` on 129² or, failing that, 257² where its grid does not resolve the film of `c`.
fn refined(c: &EhlContact, mut s: QuasiStaticSettings) -> QuasiStaticSettings {
    s.ehl = refined_ehl(c, s.ehl);
    s
}

/// `ehl` on 129² or, failing that, 257² where its grid does not resolve the film of `c`.
fn refined_ehl(c: &EhlContact, mut ehl: EhlSettings) -> EhlSettings {
    for grid in [129, 257] {
        if ehl.grid >= grid {
            continue;
        }
        match film_resolution(c, &ehl) {
            Ok(r) if r < FILM_RESOLUTION_MIN => ehl.grid = grid,
            _ => break,
        }
    }
    ehl
}

/// The harmonic fallback's settings for contact `c`: the harmonic map's (grid 129²,
/// Ω = 0.005·ω_n), on 257² where 129² does not resolve the contact's film (as
/// [`fallback_settings`]; from any grid of the map's, the first that resolves it).
pub fn harmonic_fallback_settings(c: &EhlContact) -> Result<HarmonicSettings, LawMapError> {
    let mut s = harmonic_map()?.spec.harmonic_settings();
    s.ehl = refined_ehl(c, s.ehl);
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law_map::LawGroups;
    use crate::material::{DensityModel, ViscosityModel};

    fn contact(m: f64, l: f64) -> EhlContact {
        LawGroups {
            m,
            l,
            ry_over_rx: 10.0,
            alpha_p0: Some(3.5),
            ln_eta0_ratio: Some(5.0),
            viscosity: ViscosityModel::Roelands,
            density: DensityModel::DowsonHigginson,
        }
        .contact(5e-3, 2.286e11)
        .unwrap()
    }

    /// The fallbacks keep the maps' 129² (the harmonic map's too) where it resolves the film and
    /// refine where it does not. Each chosen grid is the first with the film at ≥ 10 ΔX² (257²
    /// the last resort), and only the grid changes.
    #[test]
    fn the_fallbacks_refine_the_grid_where_theirs_does_not_resolve_the_film() {
        let ratio = |c: &EhlContact, grid: usize| {
            let mut s = LawMap::embedded().spec.settings().ehl;
            s.grid = grid;
            film_resolution(c, &s).unwrap()
        };
        assert_eq!(LawMap::embedded().spec.grid, 129);
        for (m, l, grid) in [(300.0, 20.0, 129), (3000.0, 10.0, 129), (20000.0, 8.0, 257)] {
            let c = contact(m, l);
            let quasi_static = LawMap::embedded().spec.settings().ehl;
            let harmonic = harmonic_map().unwrap().spec.harmonic_settings().ehl;
            assert_eq!(harmonic.grid, 129);
            for (s, base) in [
                (fallback_settings(&c).ehl, quasi_static),
                (harmonic_fallback_settings(&c).unwrap().ehl, harmonic),
            ] {
                assert_eq!(s.grid, grid, "M {m}, L {l}: {}", ratio(&c, s.grid));
                if grid > base.grid {
                    assert!(ratio(&c, grid / 2 + 1) < FILM_RESOLUTION_MIN);
                }
                if grid < 257 {
                    assert!(ratio(&c, grid) >= FILM_RESOLUTION_MIN);
                }
                // Only the grid changes.
                assert_eq!(
                    EhlSettings {
                        grid: base.grid,
                        ..s
                    },
                    base
                );
            }
        }
    }
}
