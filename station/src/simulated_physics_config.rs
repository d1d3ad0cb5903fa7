//! `[simulated_physics]`: the simulated benchmark's contact, actuator and mount settings. Only
//! the simulator reads them. Every key is optional: unset is the twin's default (README, "The
//! simulated benchmark", lists them with the measurement that chose them).

use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;

/// Overrides of the twin's physics settings; `None` keeps the twin's default.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimulatedPhysicsConfig {
    /// MuJoCo `solref` of the hand's contacts: time constant (s), damping ratio.
    pub contact_solref: Option<[f64; 2]>,
    /// MuJoCo `solimp` of the hand's contacts: impedance at zero and at full penetration, and
    /// the width (m) between them.
    pub contact_solimp: Option<[f64; 3]>,
    /// Distance at which a hand contact becomes active, m.
    pub contact_margin_m: Option<f64>,
    /// Friction of the hand's pads: sliding, torsional (m), rolling (m).
    pub contact_friction: Option<[f64; 3]>,
    /// MuJoCo `impratio`: friction's stiffness over the normal force's, elliptic cones.
    pub impratio: Option<f64>,
    /// `solref` of the weld holding the hand to the arm's mocap body.
    pub mount_solref: Option<[f64; 2]>,
    /// `solimp` of that weld.
    pub mount_solimp: Option<[f64; 3]>,
    /// Stiffness of the project's hand's position servos, N·m/rad (a lab's MJCF keeps its own).
    pub actuator_kp: Option<f64>,
    /// Largest torque of the project's hand's servos, N·m (a lab's MJCF keeps its own).
    pub actuator_max_torque_nm: Option<f64>,
    /// Viscous damping of the project's hand's hinges, N·m·s/rad.
    pub joint_damping: Option<f64>,
    /// Reflected rotor inertia on the project's hand's hinges, kg·m².
    pub joint_armature: Option<f64>,
}

impl Default for SimulatedPhysicsConfig {
    fn default() -> Self {
        SimulatedPhysicsConfig::DEFAULTS
    }
}

impl SimulatedPhysicsConfig {
    /// Nothing set: every setting the twin's default.
    pub const DEFAULTS: SimulatedPhysicsConfig = SimulatedPhysicsConfig {
        contact_solref: None,
        contact_solimp: None,
        contact_margin_m: None,
        contact_friction: None,
        impratio: None,
        mount_solref: None,
        mount_solimp: None,
        actuator_kp: None,
        actuator_max_torque_nm: None,
        joint_damping: None,
        joint_armature: None,
    };

    /// Check every value that is set.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_solref("contact_solref", self.contact_solref)?;
        check_solimp("contact_solimp", self.contact_solimp)?;
        check_solref("mount_solref", self.mount_solref)?;
        check_solimp("mount_solimp", self.mount_solimp)?;
        let friction = self.contact_friction;
        let sliding = friction.map(|f| f[0]);
        check(
            "contact_friction",
            sliding,
            |x| x > 0.0 && x <= 5.0,
            "sliding friction in (0, 5]",
        )?;
        let torsional = friction.map(|f| f[1]);
        check(
            "contact_friction",
            torsional,
            |x| x <= 1.0,
            "torsional friction in [0, 1] m",
        )?;
        let rolling = friction.map(|f| f[2]);
        check(
            "contact_friction",
            rolling,
            |x| x <= 1.0,
            "rolling friction in [0, 1] m",
        )?;
        check(
            "contact_margin_m",
            self.contact_margin_m,
            |x| x <= 0.01,
            "in [0, 0.01] m",
        )?;
        check(
            "impratio",
            self.impratio,
            |x| (1.0..=1000.0).contains(&x),
            "in [1, 1000]",
        )?;
        let kp = self.actuator_kp;
        check(
            "actuator_kp",
            kp,
            |x| x > 0.0 && x <= 1000.0,
            "in (0, 1000] N·m/rad",
        )?;
        let torque = self.actuator_max_torque_nm;
        check(
            "actuator_max_torque_nm",
            torque,
            |x| x > 0.0 && x <= 100.0,
            "in (0, 100] N·m",
        )?;
        let damping = self.joint_damping;
        check(
            "joint_damping",
            damping,
            |x| x <= 100.0,
            "in [0, 100] N·m·s/rad",
        )?;
        check(
            "joint_armature",
            self.joint_armature,
            |x| x <= 1.0,
            "in [0, 1] kg·m²",
        )?;
        self.check_solimp_order()
    }

    /// A `solimp`'s impedance at zero penetration may not exceed the one at full penetration.
    fn check_solimp_order(&self) -> Result<(), ConfigError> {
        for (key, value) in [
            ("contact_solimp", self.contact_solimp),
            ("mount_solimp", self.mount_solimp),
        ] {
            if let Some([dmin, dmax, _]) = value
                && dmin > dmax
            {
                return Err(ConfigError::out_of_range(
                    format!("simulated_physics.{key}"),
                    format!("[{dmin}, {dmax}, …]"),
                    "with the first impedance at most the second",
                ));
            }
        }
        Ok(())
    }
}

/// `simulated_physics.{key}` when `value` is set and not a finite, non-negative number that
/// `allowed` accepts; `range` says what is.
fn check(
    key: &str,
    value: Option<f64>,
    allowed: impl Fn(f64) -> bool,
    range: &str,
) -> Result<(), ConfigError> {
    match value {
        Some(x) if !(x.is_finite() && x >= 0.0 && allowed(x)) => Err(ConfigError::out_of_range(
            format!("simulated_physics.{key}"),
            x,
            range,
        )),
        _ => Ok(()),
    }
}

/// A `solref`: a time constant and a damping ratio.
fn check_solref(key: &str, value: Option<[f64; 2]>) -> Result<(), ConfigError> {
    let time = value.map(|v| v[0]);
    check(
        key,
        time,
        |x| x > 0.0 && x <= 1.0,
        "a time constant in (0, 1] s",
    )?;
    let ratio = value.map(|v| v[1]);
    check(
        key,
        ratio,
        |x| x > 0.0 && x <= 10.0,
        "a damping ratio in (0, 10]",
    )
}

/// A `solimp`: two impedances and a width.
fn check_solimp(key: &str, value: Option<[f64; 3]>) -> Result<(), ConfigError> {
    for impedance in value.map(|v| [v[0], v[1]]).into_iter().flatten() {
        check(
            key,
            Some(impedance),
            |x| x > 0.0 && x < 1.0,
            "impedances in (0, 1)",
        )?;
    }
    let width = value.map(|v| v[2]);
    check(key, width, |x| x > 0.0 && x <= 0.1, "a width in (0, 0.1] m")
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use crate::StationConfig;

    #[test]
    fn settings_are_read_and_unset_ones_stay_unset() {
        let config = StationConfig::from_toml_str(
            "[simulated_physics]\ncontact_solref = [0.01, 1]\nimpratio = 100\n",
        )
        .unwrap();
        let physics = config.simulated_physics;
        assert_eq!(physics.contact_solref, Some([0.01, 1.0]));
        assert_eq!(physics.impratio, Some(100.0));
        assert_eq!(physics.mount_solref, None);
    }

    #[test]
    fn errors_name_the_key_and_the_range() {
        for (text, key, range) in [
            ("contact_solref = [0, 1]", "contact_solref", "(0, 1] s"),
            (
                "mount_solimp = [0.99, 0.97, 0.0005]",
                "mount_solimp",
                "at most the second",
            ),
            (
                "contact_solimp = [0.5, 1.2, 0.001]",
                "contact_solimp",
                "(0, 1)",
            ),
            (
                "contact_friction = [1, 0.01, -1]",
                "contact_friction",
                "rolling",
            ),
            ("impratio = 0.5", "impratio", "[1, 1000]"),
            ("actuator_kp = -2", "actuator_kp", "(0, 1000]"),
        ] {
            let err = StationConfig::from_toml_str(&format!("[simulated_physics]\n{text}\n"))
                .unwrap_err()
                .to_string();
            assert!(err.contains(&format!("simulated_physics.{key}")), "{err}");
            assert!(err.contains(range), "{text}: {err}");
        }
        let err = StationConfig::from_toml_str("[simulated_physics]\nfriction = [1, 0, 0]\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("friction"), "{err}");
    }
}
