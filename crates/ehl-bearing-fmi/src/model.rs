//! The model behind the C functions: the element read from the FMU's resources, the values of the
//! variables and one evaluation of the force element per change of the inputs.

use crate::variables::*;
use ehl_bearing::characterize::CharacterizationReport;
use ehl_bearing::force_element::{
    ElementInput, ElementOutput, ElementState, ForceElement, LawElement, TrendForceElement,
};
use ehl_bearing::io::read_case;
use std::path::{Path, PathBuf};

/// Which element the resources define.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementKind {
    /// `case.toml` alone: dry Hertz laws.
    DryHertz = 0,
    /// `case.toml` + `characterization.json`: the fitted laws of the characterization.
    FittedLaws = 1,
    /// `trends.json`: a study's trend model (`case.toml`, if present, is not read).
    Trends = 2,
}

/// The element read from a resources folder.
pub struct Loaded {
    /// The force element.
    pub element: Box<dyn ForceElement>,
    /// Which one.
    pub kind: ElementKind,
    /// A one-line account of the files read, for the log.
    pub summary: String,
}

/// Resource file names.
pub const CASE_FILE: &str = "case.toml";
/// The characterization report (`ehl-bearing characterize --json`, `characterization.json`, a
/// study point file's record).
pub const CHARACTERIZATION_FILE: &str = "characterization.json";
/// A study's trend model.
pub const TRENDS_FILE: &str = "trends.json";

fn read(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// Read the element from the files in `dir`: `trends.json` → trend element; `case.toml` +
/// `characterization.json` → fitted laws; `case.toml` alone → dry Hertz.
pub fn load_resources(dir: &Path) -> Result<Loaded, String> {
    let case_path = dir.join(CASE_FILE);
    let ch_path = dir.join(CHARACTERIZATION_FILE);
    let trends_path = dir.join(TRENDS_FILE);
    match (case_path.is_file(), ch_path.is_file(), trends_path.is_file()) {
        (_, true, true) => Err(format!(
            "resources folder {} has both {CHARACTERIZATION_FILE} and {TRENDS_FILE}: keep one (fitted laws or trends)",
            dir.display()
        )),
        (_, false, true) => {
            let e = TrendForceElement::from_json(&read(&trends_path)?)
                .map_err(|e| format!("{}: {e}", trends_path.display()))?;
            Ok(Loaded {
                element: Box::new(e),
                kind: ElementKind::Trends,
                summary: format!("trend model from {}", trends_path.display()),
            })
        }
        (true, true, false) => {
            let case = read_case(&case_path).map_err(|e| format!("{}: {e}", case_path.display()))?;
            let text = read(&ch_path)?;
            let report: CharacterizationReport = serde_json::from_str(&text)
                .map_err(|e| format!("{}: not a characterization report: {e}", ch_path.display()))?;
            let e = LawElement::from_report(&case.bearing, case.operating.race_control, &report)
                .map_err(|e| format!("{}: {e}", ch_path.display()))?
                .with_kinematics(case.settings.kinematics);
            Ok(Loaded {
                summary: format!(
                    "fitted laws ({} damping terms) from {} for the bearing of {}",
                    if e.has_damping() { "with" } else { "without" },
                    ch_path.display(),
                    case_path.display()
                ),
                element: Box::new(e),
                kind: ElementKind::FittedLaws,
            })
        }
        (true, false, false) => {
            let case = read_case(&case_path).map_err(|e| format!("{}: {e}", case_path.display()))?;
            let e = LawElement::hertz_case(&case).map_err(|e| e.to_string())?;
            Ok(Loaded {
                element: Box::new(e),
                kind: ElementKind::DryHertz,
                summary: format!("dry Hertz laws for the bearing of {}", case_path.display()),
            })
        }
        (false, true, false) => Err(format!(
            "resources folder {} has {CHARACTERIZATION_FILE} but no {CASE_FILE} (the bearing the laws belong to)",
            dir.display()
        )),
        (false, false, false) => Err(format!(
            "resources folder {} has none of {CASE_FILE}, {TRENDS_FILE}: the FMU needs a case (dry Hertz), a case and {CHARACTERIZATION_FILE} (fitted laws) or {TRENDS_FILE} (trends)",
            dir.display()
        )),
    }
}

/// The local path of an `fmuResourceLocation` URI (`file:///a/b`, `file://localhost/a/b`,
/// `file:/a/b`; percent escapes decoded).
pub fn resource_path(uri: &str) -> Result<PathBuf, String> {
    let rest = uri
        .strip_prefix("file://localhost/")
        .map(|r| format!("/{r}"))
        .or_else(|| uri.strip_prefix("file:///").map(|r| format!("/{r}")))
        .or_else(|| uri.strip_prefix("file:/").map(|r| format!("/{r}")))
        .ok_or_else(|| {
            format!(
                "fmuResourceLocation = {uri:?}: expected a file URI (file:///path/to/resources)"
            )
        })?;
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok();
            if let Some(b) = hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                out.push(b);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    let s = String::from_utf8(out)
        .map_err(|_| format!("fmuResourceLocation = {uri:?}: not UTF-8 after decoding"))?;
    Ok(PathBuf::from(s))
}

/// The values of the variables and the element.
pub struct Model {
    /// The element and what it was read from.
    pub loaded: Loaded,
    state: ElementState,
    /// Real values by value reference (inputs as set, outputs as last computed).
    pub real: [f64; N_REAL as usize],
    /// Warm starts between calls.
    pub warm_start: bool,
    fresh: bool,
    last_overloaded: usize,
}

/// The outcome of an evaluation that succeeded.
pub enum Evaluated {
    /// Outputs up to date, nothing to report.
    Ok,
    /// Outputs up to date; the message is a warning (contacts became overloaded).
    Warning(String),
}

impl Model {
    /// A model with the inputs at their start values.
    pub fn new(loaded: Loaded) -> Self {
        let mut m = Model {
            loaded,
            state: ElementState::default(),
            real: [0.0; N_REAL as usize],
            warm_start: true,
            fresh: false,
            last_overloaded: 0,
        };
        m.reset();
        m
    }

    /// Back to the start values (inputs 0, warm starts on, cold state).
    pub fn reset(&mut self) {
        self.state = ElementState::default();
        self.real = [0.0; N_REAL as usize];
        for v in variables() {
            if let Kind::Real { start: Some(s), .. } = v.kind {
                self.real[v.vr as usize] = s;
            }
        }
        self.warm_start = true;
        self.fresh = false;
        self.last_overloaded = 0;
    }

    /// Set the Real input `vr` to `value`. Errors name the variable, the value and the range.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<(), String> {
        if vr < N_INPUTS && value.is_finite() {
            if self.real[vr as usize].to_bits() != value.to_bits() {
                self.real[vr as usize] = value;
                self.fresh = false;
            }
            return Ok(());
        }
        // An error: find the variable for the message.
        let var = real_variable(vr).ok_or_else(|| {
            format!(
                "value reference {vr} is not a Real variable of this FMU (0 to {})",
                N_REAL - 1
            )
        })?;
        if vr >= N_INPUTS {
            return Err(format!(
                "{} (value reference {vr}) is an output: only the inputs (value references 0 to {}) can be set",
                var.name,
                N_INPUTS - 1
            ));
        }
        let unit = match var.kind {
            Kind::Real { unit, .. } => unit,
            _ => "",
        };
        Err(format!(
            "{} = {value}: the input must be a finite number ({unit})",
            var.name
        ))
    }

    /// The Real variable `vr`, evaluating the element first if an output is asked for and the
    /// inputs changed since the last evaluation.
    pub fn get_real(&mut self, vr: u32) -> Result<(f64, Option<String>), String> {
        if vr >= N_REAL {
            return Err(format!(
                "value reference {vr} is not a Real variable of this FMU (0 to {})",
                N_REAL - 1
            ));
        }
        let mut warning = None;
        if vr >= N_INPUTS && !self.fresh {
            if let Evaluated::Warning(w) = self.evaluate()? {
                warning = Some(w);
            }
        }
        Ok((self.real[vr as usize], warning))
    }

    /// The element's inputs from the Real values.
    pub fn input(&self) -> ElementInput {
        let r = &self.real;
        let v5 = |k: u32| -> [f64; 5] {
            let k = k as usize;
            [r[k], r[k + 1], r[k + 2], r[k + 3], r[k + 4]]
        };
        ElementInput {
            displacement: v5(VR_Q),
            velocity: v5(VR_V),
            inner_speed: r[VR_INNER_SPEED as usize],
            outer_speed: r[VR_OUTER_SPEED as usize],
            cage_angle: r[VR_CAGE_ANGLE as usize],
        }
    }

    /// Evaluate the element at the current inputs and store the outputs.
    pub fn evaluate(&mut self) -> Result<Evaluated, String> {
        let input = self.input();
        let element = &self.loaded.element;
        let out = if self.warm_start {
            element.evaluate(&input, &mut self.state)
        } else {
            element.evaluate(&input, &mut ElementState::default())
        }
        .map_err(|e| {
            format!(
                "force element evaluation failed at q = {:?}, q_dot = {:?}, inner speed {} rad/s, outer speed {} rad/s, cage angle {} rad: {e}",
                input.displacement, input.velocity, input.inner_speed, input.outer_speed, input.cage_angle
            )
        })?;
        write_outputs(&mut self.real, &out);
        self.fresh = true;
        let n = out.overloaded.len();
        let was = std::mem::replace(&mut self.last_overloaded, n);
        if n > 0 && was == 0 {
            let (j, race) = out.overloaded[0];
            return Ok(Evaluated::Warning(format!(
                "{n} contact(s) beyond {} percent of the ball diameter (first: ball {j} {race:?}, approach {:.3e} m, load {:.4e} N) at q = {:?}: no bearing survives this; the outputs are returned as computed (overloaded_contacts counts them)",
                ehl_bearing::force_element::OVERLOAD_DEFLECTION_RATIO * 100.0,
                out.approaches[j][race as usize],
                out.loads[j][race as usize],
                input.displacement
            )));
        }
        Ok(Evaluated::Ok)
    }
}

/// The outputs of one evaluation into the Real values by value reference (shared with the
/// reference writer of the helper binary).
pub fn write_outputs(real: &mut [f64], out: &ElementOutput) {
    let base = VR_REACTION as usize;
    real[base..base + 5].copy_from_slice(&out.reaction);
    for i in 0..5 {
        for j in 0..5 {
            real[VR_K as usize + 5 * i + j] = out.stiffness[i][j];
            real[VR_C as usize + 5 * i + j] = out.damping[i][j];
        }
    }
    real[VR_CAGE_SPEED as usize] = out.cage_speed;
    let max = |k: usize| out.loads.iter().map(|l| l[k]).fold(0.0_f64, f64::max);
    real[VR_MAX_LOAD_INNER as usize] = max(0);
    real[VR_MAX_LOAD_OUTER as usize] = max(1);
    real[VR_OVERLOADED as usize] = out.overloaded.len() as f64;
    real[VR_OUTSIDE_RANGE as usize] = out.outside_range.len() as f64;
    real[VR_SPEED_OUTSIDE as usize] = if out.speed_outside { 1.0 } else { 0.0 };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resource_uris() {
        assert_eq!(
            resource_path("file:///tmp/a%20b/resources").unwrap(),
            PathBuf::from("/tmp/a b/resources")
        );
        assert_eq!(
            resource_path("file:/tmp/x").unwrap(),
            PathBuf::from("/tmp/x")
        );
        assert_eq!(
            resource_path("file://localhost/tmp/x/").unwrap(),
            PathBuf::from("/tmp/x/")
        );
        assert_eq!(resource_path("file:///a%2").unwrap(), PathBuf::from("/a%2"));
        let e = resource_path("http://x/y").unwrap_err();
        assert!(
            e.contains("fmuResourceLocation") && e.contains("http://x/y"),
            "{e}"
        );
    }
}
