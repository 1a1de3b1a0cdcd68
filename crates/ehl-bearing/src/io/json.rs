//! JSON results in SI units.

use crate::bearing::{ContactState, Equilibrium};
use serde_json::{json, Value};

fn contact(c: &ContactState) -> Value {
    json!({
        "load": c.load,
        "contact_angle": c.contact_angle,
        "deflection": c.deflection,
        "semi_major": c.semi_major,
        "semi_minor": c.semi_minor,
        "max_pressure": c.max_pressure,
        "rx": c.rx,
        "ry": c.ry,
        "sum_velocity": c.sum_velocity,
    })
}

/// The equilibrium as JSON (SI: m, rad, N, N·m, Pa, rad/s, m/s):
/// `{"converged","iterations","displacement":{"x","y","z","theta_y","theta_z"},
/// "reaction":{"force_x","force_y","force_z","moment_y","moment_z"},"stiffness":[[5×5]],
/// "balls":[{"azimuth","orbital_speed","spin_speed","inner":CONTACT,"outer":CONTACT}]}`,
/// plus `"residual"`, `"warnings"` and per-ball `"pitch_angle"`, `"kinematic_angle"`,
/// `"centrifugal_force"`, `"gyroscopic_moment"`, `"inner_friction"`, `"outer_friction"`.
/// `"spin_speed"` is the ball's signed roll speed ω_R about its rolling axis, relative to the cage.
pub fn equilibrium_json(e: &Equilibrium) -> Value {
    let q = &e.displacement;
    let f = &e.reaction;
    json!({
        "converged": e.converged,
        "iterations": e.iterations,
        "residual": e.residual,
        "displacement": {"x": q[0], "y": q[1], "z": q[2], "theta_y": q[3], "theta_z": q[4]},
        "reaction": {"force_x": f[0], "force_y": f[1], "force_z": f[2], "moment_y": f[3], "moment_z": f[4]},
        "stiffness": e.stiffness,
        "warnings": e.warnings,
        "balls": e.balls.iter().map(|b| json!({
            "azimuth": b.azimuth,
            "orbital_speed": b.orbital_speed,
            "spin_speed": b.spin_speed,
            "pitch_angle": b.pitch_angle,
            "kinematic_angle": b.kinematic_angle,
            "centrifugal_force": b.centrifugal_force,
            "gyroscopic_moment": b.gyroscopic_moment,
            "inner_friction": b.inner_friction,
            "outer_friction": b.outer_friction,
            "inner": contact(&b.inner),
            "outer": contact(&b.outer),
        })).collect::<Vec<_>>(),
    })
}
