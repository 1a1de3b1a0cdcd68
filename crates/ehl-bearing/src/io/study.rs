//! Study files (TOML): a case, inner-ring speeds, load scales, the method and the loop settings,
//! read into a validated [`Study`].

use super::case::{method_input_error, parse_case, read_case};
use crate::case::{Case, InputError};
use crate::characterize::{CharacterizeError, CharacterizeSettings};
use crate::method::Method;
use crate::study::Study;
use serde::Deserialize;
use std::f64::consts::PI;
use std::path::Path;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    case: Option<toml::Value>,
    method: Option<String>,
    method_options: Option<toml::Table>,
    inner_speeds_rpm: Option<Vec<f64>>,
    load_scales: Option<Vec<f64>>,
    characterize: Option<RawCharacterize>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCharacterize {
    tolerance: Option<f64>,
    max_iterations: Option<i64>,
    cache_tolerance: Option<f64>,
    min_load_fraction: Option<f64>,
    load_reuse_tolerance: Option<f64>,
    predict_loads: Option<bool>,
}

/// Read a study file; a relative `case` path is resolved against the study file's folder.
pub fn read_study(path: &Path) -> Result<Study, InputError> {
    let text = super::read_text(path)?;
    let base = path.parent().unwrap_or(Path::new("."));
    parse_study(&text, &path.display().to_string(), base)
}

/// Parse and validate study-file text (`origin` names it in messages, `base_dir` resolves a
/// relative case path).
///
/// ```toml
/// case = "7006.toml"                    # path relative to the study file, or an inline [case]
/// method = "quasi-static"               # or "harmonic", "hertz" (Method::NAMES); default quasi-static
/// inner_speeds_rpm = [3000, 4000, 5000] # each > 0 and ≤ 1e6, distinct, 1 to 1000 values
/// load_scales = [0.5, 1.0, 1.5, 2.0]    # each > 0 and ≤ 100, distinct, 1 to 1000 values
///
/// [characterize]                        # optional, defaults of CharacterizeSettings
/// tolerance = 1e-3                      # 0 < tol < 1
/// max_iterations = 20                   # 1 to 1000
/// cache_tolerance = 1e-3                # 0 to 0.1
/// min_load_fraction = 0.01              # 0 < f < 1
/// load_reuse_tolerance = 0.01           # 0 to 0.5; reuse a law while the load moved less than this
/// predict_loads = true                  # start from predicted lubricated loads (quasi-static)
///
/// [method_options]                      # optional, the method's options (Method::parse), e.g.
///                                       # quasi-static: amplitude, points, grid; hertz: samples, amplitude
/// ```
pub fn parse_study(text: &str, origin: &str, base_dir: &Path) -> Result<Study, InputError> {
    let raw: RawStudy = super::from_toml(text, origin)?;
    let (case, case_origin) = study_case(raw.case, origin, base_dir)?;
    let name = raw.method.unwrap_or_else(|| Method::NAMES[0].into());
    let method = Method::parse(&name, raw.method_options.as_ref()).map_err(method_input_error)?;
    let method_options = raw.method_options;
    let inner_speeds_rpm = positive_list(
        raw.inner_speeds_rpm,
        "inner_speeds_rpm",
        vec![case.operating.inner_speed * 30.0 / PI],
        1e6,
        "a speed in rpm",
    )?;
    let load_scales = positive_list(
        raw.load_scales,
        "load_scales",
        vec![1.0],
        100.0,
        "a load factor",
    )?;
    let settings = characterize_settings(raw.characterize)?;
    Ok(Study {
        case,
        case_origin,
        method,
        method_options,
        inner_speeds_rpm,
        load_scales,
        settings,
    })
}

/// The study's case and where it came from (the path as written, or "inline"): a case file
/// path relative to `base_dir`, or an inline `[case]` table.
fn study_case(
    raw: Option<toml::Value>,
    origin: &str,
    base_dir: &Path,
) -> Result<(Case, String), InputError> {
    match raw {
        None => Err(InputError::Missing {
            field: "case".into(),
            hint: "a case file path relative to the study file, or an inline [case] table".into(),
        }),
        Some(toml::Value::String(p)) => {
            let path = base_dir.join(&p);
            Ok((read_case(&path)?, p))
        }
        Some(toml::Value::Table(t)) => {
            let text = toml::to_string(&t).map_err(|e| InputError::Syntax {
                path: format!("{origin} [case]"),
                message: e.to_string(),
            })?;
            Ok((
                parse_case(&text, &format!("{origin} [case]"))?,
                "inline".into(),
            ))
        }
        Some(other) => Err(InputError::field(
            "case",
            other.to_string(),
            "a file path (string) or an inline [case] table",
        )),
    }
}

/// The list under `key` (`default` when absent): 1 to 1000 distinct values, each greater than
/// 0 and at most `max` (`what` names a value in messages).
fn positive_list(
    v: Option<Vec<f64>>,
    key: &str,
    default: Vec<f64>,
    max: f64,
    what: &str,
) -> Result<Vec<f64>, InputError> {
    let v = v.unwrap_or(default);
    if v.is_empty() || v.len() > 1000 {
        return Err(InputError::field(
            key,
            format!("{} values", v.len()),
            "a list of 1 to 1000 values",
        ));
    }
    for (i, &x) in v.iter().enumerate() {
        if !(x.is_finite() && x > 0.0 && x <= max) {
            return Err(InputError::field(
                &format!("{key}[{i}]"),
                x,
                format!("{what} greater than 0 and at most {max}"),
            ));
        }
        if v[..i].contains(&x) {
            return Err(InputError::field(
                &format!("{key}[{i}]"),
                x,
                "distinct values (this one is repeated)",
            ));
        }
    }
    Ok(v)
}

/// The loop settings: the defaults of [`CharacterizeSettings`] overridden by the `[characterize]`
/// table, validated (a message names the key as `characterize.<key>`).
fn characterize_settings(raw: Option<RawCharacterize>) -> Result<CharacterizeSettings, InputError> {
    let mut settings = CharacterizeSettings::default();
    if let Some(c) = raw {
        if let Some(v) = c.tolerance {
            settings.tolerance = v;
        }
        if let Some(v) = c.max_iterations {
            if !(1..=1000).contains(&v) {
                return Err(InputError::field(
                    "characterize.max_iterations",
                    v,
                    "an integer from 1 to 1000",
                ));
            }
            settings.max_iterations = v as usize;
        }
        if let Some(v) = c.cache_tolerance {
            settings.cache_tolerance = v;
        }
        if let Some(v) = c.min_load_fraction {
            settings.min_load_fraction = v;
        }
        if let Some(v) = c.load_reuse_tolerance {
            settings.load_reuse_tolerance = v;
        }
        if let Some(v) = c.predict_loads {
            settings.predict_loads = v;
        }
    }
    if let Err(CharacterizeError::Setting {
        field,
        value,
        expected,
    }) = settings.validate()
    {
        return Err(InputError::Field {
            field: format!("characterize.{field}"),
            value,
            expected,
        });
    }
    Ok(settings)
}
