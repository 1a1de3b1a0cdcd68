//! The FMU's variables in one table: value references, names (SI units in the name), causality,
//! units and descriptions. `modelDescription.xml` is written from this table
//! ([`model_description`]), so the value references the C functions use and the ones the importer
//! reads cannot drift apart.

use std::fmt::Write as _;
use std::sync::OnceLock;

/// The model identifier: the name of the shared library in `binaries/<platform>/` and the prefix
/// of nothing (the functions are exported with their plain `fmi2…` names).
pub const MODEL_IDENTIFIER: &str = "ehl_bearing_fmi";

/// Real value references of the inputs: displacements q (5).
pub const VR_Q: u32 = 0;
/// Rates q̇ (5).
pub const VR_V: u32 = 5;
/// Inner-ring speed.
pub const VR_INNER_SPEED: u32 = 10;
/// Outer-ring speed.
pub const VR_OUTER_SPEED: u32 = 11;
/// Cage angle.
pub const VR_CAGE_ANGLE: u32 = 12;
/// Number of Real inputs (value references 0..N_INPUTS).
pub const N_INPUTS: u32 = 13;
/// Reactions (5).
pub const VR_REACTION: u32 = 13;
/// Stiffness ∂F/∂q, row-major 5×5.
pub const VR_K: u32 = 18;
/// Damping ∂F/∂q̇, row-major 5×5.
pub const VR_C: u32 = 43;
/// Cage speed under pure rolling.
pub const VR_CAGE_SPEED: u32 = 68;
/// Largest inner-race contact load.
pub const VR_MAX_LOAD_INNER: u32 = 69;
/// Largest outer-race contact load.
pub const VR_MAX_LOAD_OUTER: u32 = 70;
/// Number of overloaded contacts.
pub const VR_OVERLOADED: u32 = 71;
/// Number of loaded contacts outside their law's range.
pub const VR_OUTSIDE_RANGE: u32 = 72;
/// 1 when the speed lies outside the trends' speed range.
pub const VR_SPEED_OUTSIDE: u32 = 73;
/// Number of Real variables (value references 0..N_REAL).
pub const N_REAL: u32 = 74;

/// Integer value reference: which element the resources define (0 dry Hertz, 1 fitted laws,
/// 2 trends).
pub const VR_ELEMENT_KIND: u32 = 0;
/// Integer value reference: number of balls Z.
pub const VR_BALL_COUNT: u32 = 1;
/// Number of Integer variables.
pub const N_INTEGER: u32 = 2;

/// Boolean value reference: warm starts between calls.
pub const VR_WARM_START: u32 = 0;
/// Number of Boolean variables.
pub const N_BOOLEAN: u32 = 1;

/// Names of the displacement inputs q.
pub const Q_NAMES: [&str; 5] = ["q_x_m", "q_y_m", "q_z_m", "q_thy_rad", "q_thz_rad"];
/// Names of the rate inputs q̇.
pub const V_NAMES: [&str; 5] = [
    "v_x_m_s",
    "v_y_m_s",
    "v_z_m_s",
    "v_thy_rad_s",
    "v_thz_rad_s",
];
/// Names of the reaction outputs.
pub const REACTION_NAMES: [&str; 5] = [
    "reaction_Fx_N",
    "reaction_Fy_N",
    "reaction_Fz_N",
    "reaction_My_Nm",
    "reaction_Mz_Nm",
];
const ROWS: [&str; 5] = ["Fx", "Fy", "Fz", "My", "Mz"];
const COLS: [&str; 5] = ["x", "y", "z", "thy", "thz"];

/// Causality and variability of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// A fixed parameter with a start value.
    Parameter,
    /// A fixed value the FMU computes at initialization.
    CalculatedParameter,
    /// A continuous input with a start value.
    Input,
    /// A continuous output, algebraic in the inputs.
    Output,
}

/// The type and type attributes of a variable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// Real with its unit (a name of `UnitDefinitions`) and start value (inputs only).
    Real {
        /// Unit name.
        unit: &'static str,
        /// Start value (inputs only).
        start: Option<f64>,
    },
    /// Integer.
    Integer,
    /// Boolean with its start value (parameters only).
    Boolean {
        /// Start value.
        start: bool,
    },
}

/// One scalar variable.
#[derive(Debug, Clone)]
pub struct Variable {
    /// Name (SI unit in the name).
    pub name: String,
    /// Value reference within its type.
    pub vr: u32,
    /// Causality.
    pub causality: Causality,
    /// Type.
    pub kind: Kind,
    /// Description.
    pub description: String,
}

/// Units used by the variables with their SI base-unit exponents (kg, m, s, rad).
const UNITS: [(&str, [i32; 4]); 13] = [
    ("m", [0, 1, 0, 0]),
    ("rad", [0, 0, 0, 1]),
    ("m/s", [0, 1, -1, 0]),
    ("rad/s", [0, 0, -1, 1]),
    ("N", [1, 1, -2, 0]),
    ("N.m", [1, 2, -2, 0]),
    ("N/m", [1, 0, -2, 0]),
    ("N/rad", [1, 1, -2, -1]),
    ("N.m/rad", [1, 2, -2, -1]),
    ("N.s/m", [1, 0, -1, 0]),
    ("N.s/rad", [1, 1, -1, -1]),
    ("N.s", [1, 1, -1, 0]),
    ("N.m.s/rad", [1, 2, -1, -1]),
];

fn real(
    name: &str,
    vr: u32,
    causality: Causality,
    unit: &'static str,
    description: &str,
) -> Variable {
    Variable {
        name: name.into(),
        vr,
        causality,
        kind: Kind::Real {
            unit,
            start: (causality == Causality::Input).then_some(0.0),
        },
        description: description.into(),
    }
}

/// Every variable, in the order of `ModelVariables` (index = position + 1).
pub fn variables() -> &'static [Variable] {
    static TABLE: OnceLock<Vec<Variable>> = OnceLock::new();
    TABLE.get_or_init(build)
}

/// The table in the order of `ModelVariables`: inputs, reactions, stiffness, damping, the
/// status outputs, then the parameters.
fn build() -> Vec<Variable> {
    let mut v = Vec::new();
    inputs(&mut v);
    reactions(&mut v);
    matrix_outputs(&mut v, MatrixOutput::Stiffness);
    matrix_outputs(&mut v, MatrixOutput::Damping);
    status_outputs(&mut v);
    parameters(&mut v);
    v
}

/// What each displacement input q_k is, in words.
const Q_WHAT: [&str; 5] = [
    "axial displacement x",
    "radial displacement y",
    "radial displacement z",
    "tilt about +y",
    "tilt about +z",
];

/// The 13 Real inputs: displacements q (m, rad), their rates (m/s, rad/s), the ring speeds
/// (rad/s) and the cage angle (rad).
fn inputs(v: &mut Vec<Variable>) {
    use Causality::Input;
    for k in 0..5 {
        let unit = if k < 3 { "m" } else { "rad" };
        v.push(real(
            Q_NAMES[k],
            VR_Q + k as u32,
            Input,
            unit,
            &format!(
                "Inner-ring {} relative to the outer ring, {unit}",
                Q_WHAT[k]
            ),
        ));
    }
    for k in 0..5 {
        let unit = if k < 3 { "m/s" } else { "rad/s" };
        v.push(real(
            V_NAMES[k],
            VR_V + k as u32,
            Input,
            unit,
            &format!("Rate of the inner-ring {}, {unit}", Q_WHAT[k]),
        ));
    }
    v.push(real(
        "inner_speed_rad_s",
        VR_INNER_SPEED,
        Input,
        "rad/s",
        "Inner-ring speed about +x, rad/s",
    ));
    v.push(real(
        "outer_speed_rad_s",
        VR_OUTER_SPEED,
        Input,
        "rad/s",
        "Outer-ring speed about +x, rad/s",
    ));
    v.push(real(
        "cage_angle_rad",
        VR_CAGE_ANGLE,
        Input,
        "rad",
        "Cage angle, rad: ball j at azimuth 2*pi*j/Z + cage angle from +y toward +z (integrate cage_speed_rad_s for the varying-compliance excitation, or hold fixed)",
    ));
}

/// The five reaction outputs (N, N·m).
fn reactions(v: &mut Vec<Variable>) {
    let r_what = [
        "axial force Fx, N",
        "radial force Fy, N",
        "radial force Fz, N",
        "moment My, N.m",
        "moment Mz, N.m",
    ];
    for k in 0..5 {
        v.push(real(
            REACTION_NAMES[k],
            VR_REACTION + k as u32,
            Causality::Output,
            if k < 3 { "N" } else { "N.m" },
            &format!(
                "Load on the inner ring in equilibrium with the balls (damping term included): {} (the bearing acts on the shaft with the opposite)",
                r_what[k]
            ),
        ));
    }
}

/// The two 5×5 matrix outputs.
#[derive(Clone, Copy)]
enum MatrixOutput {
    /// ∂F/∂q.
    Stiffness,
    /// ∂F/∂q̇.
    Damping,
}

/// The 25 outputs of a 5×5 matrix, row-major, each named by its row (force or moment), its
/// column (displacement or rate) and its unit.
fn matrix_outputs(v: &mut Vec<Variable>, which: MatrixOutput) {
    for (i, row) in ROWS.iter().enumerate() {
        for j in 0..5 {
            let (name, vr, unit, description) = match which {
                MatrixOutput::Stiffness => {
                    let (suffix, unit) = match (i < 3, j < 3) {
                        (true, true) => ("N_m", "N/m"),
                        (true, false) => ("N_rad", "N/rad"),
                        (false, true) => ("Nm_m", "N"),
                        (false, false) => ("Nm_rad", "N.m/rad"),
                    };
                    (
                        format!("K_{row}_{}_{suffix}", COLS[j]),
                        VR_K,
                        unit,
                        format!("Stiffness d{row}/d{} ({unit}; not symmetrized)", Q_NAMES[j]),
                    )
                }
                MatrixOutput::Damping => {
                    let (suffix, unit) = match (i < 3, j < 3) {
                        (true, true) => ("Ns_m", "N.s/m"),
                        (true, false) => ("Ns_rad", "N.s/rad"),
                        (false, true) => ("Nms_m", "N.s"),
                        (false, false) => ("Nms_rad", "N.m.s/rad"),
                    };
                    (
                        format!("C_{row}_{}_{suffix}", COLS[j]),
                        VR_C,
                        unit,
                        format!(
                            "Damping d{row}/d{} ({unit}; zero for laws without damping terms)",
                            V_NAMES[j]
                        ),
                    )
                }
            };
            v.push(real(
                &name,
                vr + (5 * i + j) as u32,
                Causality::Output,
                unit,
                &description,
            ));
        }
    }
}

/// A Real output counting something (unit "1", no start value).
fn count(name: &str, vr: u32, description: &str) -> Variable {
    Variable {
        name: name.into(),
        vr,
        causality: Causality::Output,
        kind: Kind::Real {
            unit: "1",
            start: None,
        },
        description: description.into(),
    }
}

/// The status outputs: the cage speed (rad/s), the largest contact loads (N) and the counts of
/// contacts beyond their limits.
fn status_outputs(v: &mut Vec<Variable>) {
    use Causality::Output;
    v.push(real(
        "cage_speed_rad_s",
        VR_CAGE_SPEED,
        Output,
        "rad/s",
        "Cage speed at the operating state, rad/s: the load-weighted mean of the balls' orbital speeds of the bearing model (the rate of cage_angle_rad)",
    ));
    v.push(real(
        "max_ball_load_inner_N",
        VR_MAX_LOAD_INNER,
        Output,
        "N",
        "Largest inner-race contact load (without the damping term), N",
    ));
    v.push(real(
        "max_ball_load_outer_N",
        VR_MAX_LOAD_OUTER,
        Output,
        "N",
        "Largest outer-race contact load (without the damping term), N",
    ));
    v.push(count(
        "overloaded_contacts",
        VR_OVERLOADED,
        "Number of contacts whose approach exceeds 2 percent of the ball diameter (no bearing survives; numbers returned as computed)",
    ));
    v.push(count(
        "outside_range_contacts",
        VR_OUTSIDE_RANGE,
        "Number of loaded contacts outside the range their law was fitted on (trends: outside the trends' load range)",
    ));
    v.push(count(
        "speed_outside",
        VR_SPEED_OUTSIDE,
        "1 when the speed lies outside the trends' speed range (laws at the nearest end), else 0",
    ));
}

/// The Boolean parameter (warm starts) and the Integer calculated parameters (element kind,
/// ball count).
fn parameters(v: &mut Vec<Variable>) {
    v.push(Variable {
        name: "warm_start".into(),
        vr: VR_WARM_START,
        causality: Causality::Parameter,
        kind: Kind::Boolean { start: true },
        description: "Warm-start each call from the previous one (results differ only within the solvers' tolerances); false: every call from scratch, reproducible bit for bit".into(),
    });
    v.push(Variable {
        name: "element_kind".into(),
        vr: VR_ELEMENT_KIND,
        causality: Causality::CalculatedParameter,
        kind: Kind::Integer,
        description: "The element the resources define: 0 dry Hertz (case.toml), 1 fitted laws (case.toml + characterization.json), 2 trends (trends.json)".into(),
    });
    v.push(Variable {
        name: "ball_count".into(),
        vr: VR_BALL_COUNT,
        causality: Causality::CalculatedParameter,
        kind: Kind::Integer,
        description: "Number of balls Z".into(),
    });
}

/// The Real variable with value reference `vr`, if any.
pub fn real_variable(vr: u32) -> Option<&'static Variable> {
    variables()
        .iter()
        .find(|v| v.vr == vr && matches!(v.kind, Kind::Real { .. }))
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// FNV-1a, 64 bit, from `seed`.
fn fnv(bytes: &[u8], seed: u64) -> u64 {
    let mut h = seed;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The GUID: a hash of the model description without it (and of the crate version), so that any
/// change of the variables changes it.
pub fn guid() -> &'static str {
    static GUID: OnceLock<String> = OnceLock::new();
    GUID.get_or_init(|| {
        let body = body();
        let a = fnv(body.as_bytes(), 0xcbf2_9ce4_8422_2325);
        let b = fnv(body.as_bytes(), 0x8422_2325_cbf2_9ce4);
        format!(
            "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
            a >> 32,
            (a >> 16) & 0xffff,
            a & 0xffff,
            b >> 48,
            b & 0xffff_ffff_ffff
        )
    })
}

/// Everything of the model description after the root element's attributes.
fn body() -> String {
    let mut x = String::new();
    let _ = writeln!(
        x,
        "  <ModelExchange modelIdentifier=\"{MODEL_IDENTIFIER}\" canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"false\" canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\" completedIntegratorStepNotNeeded=\"true\"/>"
    );
    x.push_str("  <UnitDefinitions>\n");
    for (name, [kg, m, s, rad]) in UNITS {
        let mut attrs = String::new();
        for (k, e) in [("kg", kg), ("m", m), ("s", s), ("rad", rad)] {
            if e != 0 {
                let _ = write!(attrs, " {k}=\"{e}\"");
            }
        }
        let _ = writeln!(
            x,
            "    <Unit name=\"{name}\">\n      <BaseUnit{attrs}/>\n    </Unit>"
        );
    }
    x.push_str("    <Unit name=\"1\">\n      <BaseUnit/>\n    </Unit>\n");
    x.push_str("  </UnitDefinitions>\n");
    x.push_str("  <LogCategories>\n    <Category name=\"logStatusError\" description=\"Errors: invalid inputs, failed evaluations, bad resources\"/>\n    <Category name=\"logStatusWarning\" description=\"Overloaded contacts\"/>\n    <Category name=\"logAll\" description=\"Instantiation and the element read from the resources\"/>\n  </LogCategories>\n");
    x.push_str("  <DefaultExperiment startTime=\"0\" stopTime=\"0.01\"/>\n");
    x.push_str("  <ModelVariables>\n");
    for (i, v) in variables().iter().enumerate() {
        let (causality, variability, initial) = match v.causality {
            Causality::Parameter => ("parameter", "fixed", ""),
            Causality::CalculatedParameter => {
                ("calculatedParameter", "fixed", " initial=\"calculated\"")
            }
            Causality::Input => ("input", "continuous", ""),
            Causality::Output => (
                "output",
                if matches!(v.kind, Kind::Real { .. }) {
                    "continuous"
                } else {
                    "discrete"
                },
                " initial=\"calculated\"",
            ),
        };
        let _ = writeln!(
            x,
            "    <!-- index {} -->\n    <ScalarVariable name=\"{}\" valueReference=\"{}\" causality=\"{causality}\" variability=\"{variability}\"{initial} description=\"{}\">",
            i + 1,
            v.name,
            v.vr,
            xml_escape(&v.description)
        );
        match v.kind {
            Kind::Real { unit, start } => {
                let start = start
                    .map(|s| format!(" start=\"{s:?}\""))
                    .unwrap_or_default();
                let _ = writeln!(x, "      <Real unit=\"{unit}\"{start}/>");
            }
            Kind::Integer => x.push_str("      <Integer/>\n"),
            Kind::Boolean { start } => {
                let _ = writeln!(x, "      <Boolean start=\"{start}\"/>");
            }
        }
        x.push_str("    </ScalarVariable>\n");
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n");
    let index = |c: Causality| {
        variables()
            .iter()
            .enumerate()
            .filter(move |(_, v)| v.causality == c)
            .map(|(i, _)| i + 1)
    };
    // No `dependencies` attribute: every output depends on every input (direct feedthrough).
    for i in index(Causality::Output) {
        let _ = writeln!(x, "      <Unknown index=\"{i}\"/>");
    }
    x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    let mut initial: Vec<usize> = index(Causality::Output)
        .chain(index(Causality::CalculatedParameter))
        .collect();
    initial.sort_unstable();
    for i in initial {
        let _ = writeln!(x, "      <Unknown index=\"{i}\"/>");
    }
    x.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// `modelDescription.xml` (FMI 2.0, model exchange).
pub fn model_description() -> String {
    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"ehl_bearing\" guid=\"{}\" description=\"Angular-contact ball bearing as a nonlinear force element (ehl-bearing {}): ring displacements, rates, speeds and cage angle in; reactions, stiffness K and damping C out. The element (dry Hertz, fitted laws or trends) is read from the files in resources/.\" author=\"ehl-bearing\" version=\"{}\" generationTool=\"ehl-bearing-fmu {}\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"0\">",
        guid(),
        env!("CARGO_PKG_VERSION"),
        env!("CARGO_PKG_VERSION"),
        env!("CARGO_PKG_VERSION"),
    );
    x.push_str(&body());
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_references_are_unique_dense_and_match_the_constants() {
        let vars = variables();
        let mut reals: Vec<u32> = vars
            .iter()
            .filter(|v| matches!(v.kind, Kind::Real { .. }))
            .map(|v| v.vr)
            .collect();
        reals.sort_unstable();
        assert_eq!(reals, (0..N_REAL).collect::<Vec<_>>());
        let ints = vars.iter().filter(|v| v.kind == Kind::Integer).count();
        assert_eq!(ints as u32, N_INTEGER);
        let bools = vars
            .iter()
            .filter(|v| matches!(v.kind, Kind::Boolean { .. }))
            .count();
        assert_eq!(bools as u32, N_BOOLEAN);
        let mut names: Vec<&str> = vars.iter().map(|v| v.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), vars.len(), "variable names are unique");
        assert_eq!(real_variable(VR_Q + 1).unwrap().name, "q_y_m");
        assert_eq!(real_variable(VR_CAGE_ANGLE).unwrap().name, "cage_angle_rad");
        assert_eq!(
            real_variable(VR_REACTION + 3).unwrap().name,
            "reaction_My_Nm"
        );
        assert_eq!(real_variable(VR_K + 6).unwrap().name, "K_Fy_y_N_m");
        assert_eq!(real_variable(VR_K + 24).unwrap().name, "K_Mz_thz_Nm_rad");
        assert_eq!(real_variable(VR_C + 3).unwrap().name, "C_Fx_thy_Ns_rad");
        assert_eq!(
            real_variable(VR_SPEED_OUTSIDE).unwrap().name,
            "speed_outside"
        );
        for v in vars {
            if let Kind::Real { unit, .. } = v.kind {
                assert!(
                    unit == "1" || UNITS.iter().any(|(u, _)| *u == unit),
                    "{}: unit {unit} defined",
                    v.name
                );
            }
            let inputs = v.causality == Causality::Input;
            assert_eq!(
                v.vr < N_INPUTS && matches!(v.kind, Kind::Real { .. }),
                inputs
            );
        }
    }

    #[test]
    fn model_description_is_well_formed_enough() {
        let x = model_description();
        assert_eq!(x.matches("<ScalarVariable ").count(), variables().len());
        assert_eq!(x.matches("</ScalarVariable>").count(), variables().len());
        assert!(x.contains(guid()));
        assert!(x.contains("modelIdentifier=\"ehl_bearing_fmi\""));
        assert!(!x.contains("&&") && !x.contains(" < "));
        assert_eq!(guid().len(), 38);
    }
}
