//! MuJoCo behind a small, safe surface: a loaded scene, the hand's actuators bound by name, the
//! arm's mocap mount, and readings of any joint or body. Everything the simulated benchmark
//! does to the physics goes through here.
//!
//! Speed limit: MuJoCo's position actuators have no speed limit of their own, so the control
//! each actuator gets moves toward the commanded target by at most `max_speed_rad_s · dt` per
//! physics step, as the real hand's servos slew.

use std::path::Path;

use mujoco_rs::prelude::*;
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};
use simulation::progress::Reading;

use super::error::PhysicsError;

/// Which scene elements drive and carry the hand.
#[derive(Debug, Clone, PartialEq)]
pub struct HandBinding {
    /// MuJoCo joint per degree of freedom (the station's order).
    pub dof_joints: Vec<String>,
    /// MuJoCo actuator per degree of freedom.
    pub dof_actuators: Vec<String>,
    /// The mocap body the arm target moves.
    pub mount_body: String,
    /// The servos' speed limit, rad/s.
    pub max_speed_rad_s: f64,
    /// Per degree of freedom, MuJoCo's `qpos` minus the URDF angle (a manufacturer model's
    /// joint `ref`); everything this engine takes and gives is in URDF angles.
    pub zero_offsets_rad: Vec<f64>,
}

/// A joint of the scene, resolved.
#[derive(Debug, Clone, Copy)]
struct JointAddress {
    qpos: usize,
    qvel: usize,
    width: usize,
}

/// One scene parsed at a time: MuJoCo's XML parser keeps state of its own, and `pomdar
/// sim-bench` loads scenes from several threads.
static XML_PARSER: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// A loaded, bound scene.
pub struct PhysicsEngine {
    data: MjData<Box<MjModel>>,
    joints: Vec<JointAddress>,
    actuators: Vec<usize>,
    ctrl_ranges: Vec<[f64; 2]>,
    mocap: usize,
    /// Targets in URDF angles.
    targets: Vec<f64>,
    max_speed_rad_s: f64,
    /// `qpos` − URDF angle per degree of freedom.
    offsets: Vec<f64>,
}

impl PhysicsEngine {
    /// Load a scene from MJCF text (`origin` names it in errors) and bind the hand.
    pub fn from_xml_str(
        xml: &str,
        origin: &str,
        binding: &HandBinding,
    ) -> Result<Self, PhysicsError> {
        let model = {
            let _parsing = XML_PARSER.lock();
            MjModel::from_xml_string(xml)
        }
        .map_err(|e| PhysicsError::Load {
            origin: origin.to_string(),
            message: format!("{e:?}"),
        })?;
        Self::bind(Box::new(model), origin, binding)
    }

    /// Load a scene from an MJCF file (its meshes and includes relative to it) and bind the hand.
    pub fn from_file(path: &Path, binding: &HandBinding) -> Result<Self, PhysicsError> {
        let origin = path.display().to_string();
        let model = {
            let _parsing = XML_PARSER.lock();
            MjModel::from_xml(path)
        }
        .map_err(|e| PhysicsError::Load {
            origin: origin.clone(),
            message: format!("{e:?}"),
        })?;
        Self::bind(Box::new(model), &origin, binding)
    }

    fn bind(
        model: Box<MjModel>,
        origin: &str,
        binding: &HandBinding,
    ) -> Result<Self, PhysicsError> {
        let missing = |kind: &'static str, names: Vec<String>| PhysicsError::Missing {
            origin: origin.to_string(),
            kind,
            names,
        };
        let joints = resolve(&binding.dof_joints, |n| joint_address(&model, n));
        let joints = joints.map_err(|names| missing("joint", names))?;
        let actuators = resolve(&binding.dof_actuators, |n| {
            model.name_to_id(MjtObjBase::mjOBJ_ACTUATOR, n)
        });
        let actuators = actuators.map_err(|names| missing("actuator", names))?;
        let mocap = model
            .name_to_id(MjtObjBase::mjOBJ_BODY, &binding.mount_body)
            .and_then(|body| usize::try_from(model.body_mocapid()[body]).ok())
            .ok_or_else(|| missing("mocap body", vec![binding.mount_body.clone()]))?;
        let offsets = if binding.zero_offsets_rad.is_empty() {
            vec![0.0; joints.len()]
        } else {
            binding.zero_offsets_rad.clone()
        };
        // Control ranges in URDF angles.
        let ctrl_ranges = actuators
            .iter()
            .zip(&offsets)
            .map(|(&a, o)| model.actuator_ctrlrange()[a].map(|v| v - o))
            .collect();
        let mut data = MjData::new(model);
        data.forward();
        let targets = joints
            .iter()
            .zip(&offsets)
            .map(|(j, o)| data.qpos()[j.qpos] - o)
            .collect();
        let mut engine = PhysicsEngine {
            data,
            joints,
            actuators,
            ctrl_ranges,
            mocap,
            targets,
            max_speed_rad_s: binding.max_speed_rad_s,
            offsets,
        };
        engine.hold_controls_at_targets();
        Ok(engine)
    }

    /// The physics time step, seconds.
    pub fn timestep_s(&self) -> f64 {
        self.data.model().ffi().opt.timestep
    }

    /// Simulated time, seconds.
    pub fn time_s(&self) -> f64 {
        self.data.ffi().time
    }

    /// Command the hand: one target per degree of freedom, URDF angles in radians (clamped to
    /// the actuator's control range). Wrong lengths and non-finite values are refused.
    pub fn set_hand_targets(&mut self, targets: &[f64]) -> Result<(), PhysicsError> {
        if targets.len() != self.targets.len() || targets.iter().any(|t| !t.is_finite()) {
            return Err(PhysicsError::BadTargets {
                expected: self.targets.len(),
                got: targets.len(),
            });
        }
        for ((t, new), range) in self.targets.iter_mut().zip(targets).zip(&self.ctrl_ranges) {
            *t = new.clamp(range[0], range[1]);
        }
        Ok(())
    }

    /// The hand's targets in force, radians, per degree of freedom.
    pub fn hand_targets(&self) -> &[f64] {
        &self.targets
    }

    /// Move the arm's mount (the mocap body) to `pose`, world frame.
    pub fn set_mount_pose(&mut self, pose: &Isometry3<f64>) {
        let p = pose.translation.vector;
        let q = pose.rotation.quaternion();
        self.data.mocap_pos_mut()[self.mocap] = [p.x, p.y, p.z];
        self.data.mocap_quat_mut()[self.mocap] = [q.w, q.i, q.j, q.k];
    }

    /// Step the physics by `duration_s` (whole steps; at least one), the controls slewing
    /// toward the targets at the speed limit.
    pub fn advance(&mut self, duration_s: f64) {
        let dt = self.timestep_s();
        let steps = (duration_s / dt).round().max(1.0) as usize;
        let max_move = self.max_speed_rad_s * dt;
        for _ in 0..steps {
            for (i, &a) in self.actuators.iter().enumerate() {
                let target = self.targets[i] + self.offsets[i];
                let ctrl = &mut self.data.ctrl_mut()[a];
                *ctrl += (target - *ctrl).clamp(-max_move, max_move);
            }
            self.data.step();
        }
    }

    /// The hand's measured joint positions, URDF angles in radians, per degree of freedom.
    pub fn hand_positions(&self) -> Vec<f64> {
        self.joints
            .iter()
            .zip(&self.offsets)
            .map(|(j, o)| self.data.qpos()[j.qpos] - o)
            .collect()
    }

    /// Put the hand at `angles` (URDF angles, one per degree of freedom), at rest, its targets
    /// there too, and recompute the kinematics (poses in tests and tools).
    pub fn set_hand_positions(&mut self, angles: &[f64]) -> Result<(), PhysicsError> {
        self.set_hand_targets(angles)?;
        for ((j, o), angle) in self.joints.iter().zip(&self.offsets).zip(angles) {
            self.data.qpos_mut()[j.qpos] = angle + o;
            self.data.qvel_mut()[j.qvel] = 0.0;
        }
        self.hold_controls_at_targets();
        self.data.forward();
        Ok(())
    }

    /// The hand's measured joint speeds, rad/s, per degree of freedom.
    pub fn hand_velocities(&self) -> Vec<f64> {
        self.joints
            .iter()
            .map(|j| self.data.qvel()[j.qvel])
            .collect()
    }

    /// A joint's position (the first coordinate of a multi-coordinate joint), or `None`.
    pub fn joint_position(&self, name: &str) -> Option<f64> {
        let j = joint_address(self.data.model(), name)?;
        Some(self.data.qpos()[j.qpos])
    }

    /// A progress reading of joint `name`: a slide or hinge joint's position, or a free
    /// joint's body position and speed.
    pub fn reading(&self, name: &str) -> Option<Reading> {
        let j = joint_address(self.data.model(), name)?;
        let qpos = self.data.qpos();
        Some(match j.width {
            7 => {
                let v = &self.data.qvel()[j.qvel..j.qvel + 3];
                Reading::Body {
                    position_m: [qpos[j.qpos], qpos[j.qpos + 1], qpos[j.qpos + 2]],
                    speed_m_s: Vector3::new(v[0], v[1], v[2]).norm(),
                }
            }
            _ => Reading::Joint(qpos[j.qpos]),
        })
    }

    /// Set joint `name`'s coordinates (a free joint: x y z qw qx qy qz), zero its speed and
    /// recompute the kinematics (scripted moves in tests and tools).
    pub fn set_joint(&mut self, name: &str, values: &[f64]) -> Result<(), PhysicsError> {
        let j = joint_address(self.data.model(), name).ok_or_else(|| PhysicsError::Missing {
            origin: "scene".into(),
            kind: "joint",
            names: vec![name.to_string()],
        })?;
        if values.len() != j.width {
            return Err(PhysicsError::BadTargets {
                expected: j.width,
                got: values.len(),
            });
        }
        self.data.qpos_mut()[j.qpos..j.qpos + j.width].copy_from_slice(values);
        let dofs = if j.width == 7 { 6 } else { j.width };
        self.data.qvel_mut()[j.qvel..j.qvel + dofs].fill(0.0);
        self.data.forward();
        Ok(())
    }

    /// The name of the body joint `name` moves, or `None`.
    pub fn body_of_joint(&self, name: &str) -> Option<String> {
        let model = self.data.model();
        let joint = model.name_to_id(MjtObjBase::mjOBJ_JOINT, name)?;
        let body = usize::try_from(model.jnt_bodyid()[joint]).ok()?;
        model
            .id_to_name(MjtObjBase::mjOBJ_BODY, body)
            .map(str::to_string)
    }

    /// Body `name`'s pose in the world, or `None`.
    pub fn body_pose(&self, name: &str) -> Option<Isometry3<f64>> {
        let id = self.data.model().name_to_id(MjtObjBase::mjOBJ_BODY, name)?;
        let p = self.data.xpos()[id];
        let q = self.data.xquat()[id];
        Some(Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3])),
        ))
    }

    /// Back to the scene's initial state (MuJoCo's reset: `qpos0`, zero speeds, time 0), the
    /// hand's targets its initial positions.
    pub fn reset(&mut self) {
        self.data.reset();
        self.data.forward();
        self.targets = self.hand_positions();
        self.hold_controls_at_targets();
    }

    /// Recompute the kinematics after poses were set (no time passes).
    pub fn settle(&mut self) {
        self.data.forward();
    }

    fn hold_controls_at_targets(&mut self) {
        for (i, &a) in self.actuators.iter().enumerate() {
            let range = self.ctrl_ranges[i];
            self.data.ctrl_mut()[a] = self.targets[i].clamp(range[0], range[1]) + self.offsets[i];
        }
    }
}

/// Every name resolved, or the names that were not.
fn resolve<T>(names: &[String], find: impl Fn(&str) -> Option<T>) -> Result<Vec<T>, Vec<String>> {
    let found: Vec<Option<T>> = names.iter().map(|n| find(n)).collect();
    let missing: Vec<String> = names
        .iter()
        .zip(&found)
        .filter(|(_, f)| f.is_none())
        .map(|(n, _)| n.clone())
        .collect();
    if missing.is_empty() {
        Ok(found.into_iter().flatten().collect())
    } else {
        Err(missing)
    }
}

fn joint_address(model: &MjModel, name: &str) -> Option<JointAddress> {
    let id = model.name_to_id(MjtObjBase::mjOBJ_JOINT, name)?;
    let width = match model.jnt_type()[id] {
        MjtJoint::mjJNT_FREE => 7,
        MjtJoint::mjJNT_BALL => 4,
        _ => 1,
    };
    Some(JointAddress {
        qpos: model.jnt_qposadr()[id] as usize,
        qvel: model.jnt_dofadr()[id] as usize,
        width,
    })
}
