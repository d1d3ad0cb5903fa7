//! The task catalog: the benchmark's tasks as data, validated on load.
//!
//! The built-in catalog is `scoring/data/tasks_pomdar.toml` (the 18 POMDAR tasks, each with
//! its provenance); a lab can load its own corrected copy with [`TaskCatalog::from_toml_str`].
//! A task may say where its progress is read in a simulated scene ([`PhysicsMapping`],
//! `physics_mapping.rs`), for a lab's own task files.

mod physics_mapping;

use serde::{Deserialize, Serialize};

use crate::error::ScoringError;

pub use physics_mapping::{
    DEFAULT_LIFT_M, DEFAULT_MARK_BAND, DEFAULT_REST_SPEED_M_S, DEFAULT_REST_TIME_S, Direction,
    GraspMapping, InvalidMapping, PhysicsMapping,
};

/// The built-in catalog's text (the 18 POMDAR tasks).
pub const POMDAR_TASKS_TOML: &str = include_str!("../data/tasks_pomdar.toml");

/// Origin string of the built-in catalog in errors and reports.
pub const BUILTIN_CATALOG_ORIGIN: &str = "built-in task catalog, scoring/data/tasks_pomdar.toml";

/// The benchmark configuration a task belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Configuration {
    /// Vertical board (V1–V3): notches.
    Vertical,
    /// Horizontal board (H1–H5): curves, rod slides.
    Horizontal,
    /// Continuous rotation (C1–C4).
    Continuous,
    /// Grasp and relocate (G1–G6).
    Grasp,
}

impl Configuration {
    /// Whether the task is one of the grasping tasks (the 6-task radar) rather than a
    /// manipulation task (the 12-task radar).
    pub fn is_grasp(self) -> bool {
        self == Configuration::Grasp
    }
}

/// How the arm may move during a task (POMDAR: `fixed` for C4/H4/H5, `vertical_axis` for
/// V1–V3 and C1–C3, `horizontal_axis` for H1–H3, `free` for the grasp tasks G1–G6); the
/// station's arm mapping applies it (`station::arm::Constraint` is this type).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArmConstraint {
    /// Position and orientation stay at the pose latched at engage.
    Fixed,
    /// Translation only along the station's `vertical_axis` through the latched position.
    VerticalAxis,
    /// Translation only along the station's `horizontal_axis` through the latched position.
    HorizontalAxis,
    /// The full relative pose (orientation per the station's orientation policy).
    Free,
}

/// How a trial's progress events become its correctness in [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CorrectnessKind {
    /// Notches passed (progress values are whole numbers of notches) out of `count`.
    Notches {
        /// Notches in the task.
        count: u32,
    },
    /// Curves cleared (progress values are whole numbers of curves) out of `count`.
    Curves {
        /// Curves in the task.
        count: u32,
    },
    /// Rotation achieved (progress values are degrees turned) out of `full_deg`.
    Rotation {
        /// The rotation that counts as complete, degrees (360 in the paper).
        full_deg: f64,
    },
    /// Grasp level: progress values are levels, 0 not lifted, 0.5 lifted then dropped,
    /// 1 relocated; a `drop` event sets 0.5. (A struct variant so that unknown keys are
    /// refused, as for the other kinds.)
    Grasp {},
    /// Distance slid (progress values are millimetres) out of `full_mm`.
    Distance {
        /// The slide that counts as complete, mm.
        full_mm: f64,
    },
}

impl CorrectnessKind {
    /// Short description for reports (`6 notches`, `rotation / 360°`).
    pub fn describe(&self) -> String {
        match self {
            CorrectnessKind::Notches { count } => format!("{count} notches"),
            CorrectnessKind::Curves { count } => format!("{count} curves"),
            CorrectnessKind::Rotation { full_deg } => format!("rotation / {full_deg}°"),
            CorrectnessKind::Grasp {} => "grasp level 0 / 0.5 / 1".to_string(),
            CorrectnessKind::Distance { full_mm } => format!("distance / {full_mm} mm"),
        }
    }

    /// The unit of a progress value (`notches`, `deg`, `mm`, `level`).
    pub fn progress_unit(&self) -> &'static str {
        match self {
            CorrectnessKind::Notches { .. } => "notches",
            CorrectnessKind::Curves { .. } => "curves",
            CorrectnessKind::Rotation { .. } => "deg",
            CorrectnessKind::Grasp {} => "level",
            CorrectnessKind::Distance { .. } => "mm",
        }
    }
}

/// One task of the catalog.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskSpec {
    /// Short ID, as in trial metadata (`V1`).
    pub id: String,
    /// The object or action (`Wheel`).
    pub name: String,
    /// The benchmark configuration.
    pub configuration: Configuration,
    /// The arm constraint.
    pub arm: ArmConstraint,
    /// How correctness is computed.
    pub correctness: CorrectnessKind,
    /// Where the entry comes from, and what about it is unverified.
    pub provenance: String,
    /// Where the task's progress is read in a simulated scene (the lab's own task file's
    /// joints); `None` when the catalog does not say.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub physics: Option<PhysicsMapping>,
}

/// The catalog's header.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CatalogHeader {
    /// The benchmark's name and reference.
    pub name: String,
    /// Where the catalog as a whole comes from.
    pub provenance: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CatalogFile {
    catalog: CatalogHeader,
    task: Vec<TaskSpec>,
}

/// A validated task catalog.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskCatalog {
    /// Where it was loaded from (a path, or [`BUILTIN_CATALOG_ORIGIN`]).
    pub origin: String,
    /// The header.
    pub header: CatalogHeader,
    /// The tasks, in file order (the order of every report).
    pub tasks: Vec<TaskSpec>,
}

impl TaskCatalog {
    /// The built-in POMDAR catalog (18 tasks).
    pub fn builtin() -> TaskCatalog {
        #[allow(clippy::expect_used)] // the embedded file is validated by a unit test
        TaskCatalog::from_toml_str(POMDAR_TASKS_TOML, BUILTIN_CATALOG_ORIGIN)
            .expect("built-in catalog is valid")
    }

    /// Parses and validates a catalog; `origin` names the file in errors.
    ///
    /// Checks: at least one task; IDs non-empty, made of letters, digits, `_` or `-`, and
    /// unique; names and provenance non-empty; counts ≥ 1; `full_deg` and `full_mm` finite
    /// and > 0; a `physics` mapping fits the task's kind ([`PhysicsMapping::validate`]).
    pub fn from_toml_str(text: &str, origin: &str) -> Result<TaskCatalog, ScoringError> {
        let file: CatalogFile =
            toml::from_str(text).map_err(|e| ScoringError::syntax(origin, &e))?;
        if file.task.is_empty() {
            return Err(ScoringError::invalid(
                origin,
                "task",
                "[]",
                "at least one [[task]]",
            ));
        }
        for (i, task) in file.task.iter().enumerate() {
            validate_task(origin, i, task)?;
            if file.task[..i].iter().any(|t| t.id == task.id) {
                return Err(ScoringError::invalid(
                    origin,
                    format!("task[{i}].id"),
                    format!("{:?}", task.id),
                    "a task ID used once (it is defined twice)",
                ));
            }
        }
        Ok(TaskCatalog {
            origin: origin.to_string(),
            header: file.catalog,
            tasks: file.task,
        })
    }

    /// The task with ID `id`.
    pub fn get(&self, id: &str) -> Option<&TaskSpec> {
        self.tasks.iter().find(|t| t.id == id)
    }

    /// Position of task `id` in the catalog.
    pub fn position(&self, id: &str) -> Option<usize> {
        self.tasks.iter().position(|t| t.id == id)
    }

    /// Number of tasks.
    pub fn len(&self) -> usize {
        self.tasks.len()
    }

    /// Whether the catalog has no tasks (never true for a validated catalog).
    pub fn is_empty(&self) -> bool {
        self.tasks.is_empty()
    }

    /// The task IDs joined for messages (`V1, V2, ...`).
    pub fn ids(&self) -> String {
        self.tasks
            .iter()
            .map(|t| t.id.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

fn validate_task(origin: &str, i: usize, task: &TaskSpec) -> Result<(), ScoringError> {
    let key = |k: &str| {
        if task.id.is_empty() {
            format!("task[{i}].{k}")
        } else {
            format!("task {}: {k}", task.id)
        }
    };
    let id_ok = !task.id.is_empty()
        && task
            .id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if !id_ok {
        return Err(ScoringError::invalid(
            origin,
            format!("task[{i}].id"),
            format!("{:?}", task.id),
            "a non-empty ID of letters, digits, '_' or '-'",
        ));
    }
    if task.name.trim().is_empty() {
        return Err(ScoringError::invalid(
            origin,
            key("name"),
            "\"\"",
            "a non-empty name",
        ));
    }
    if task.provenance.trim().is_empty() {
        return Err(ScoringError::invalid(
            origin,
            key("provenance"),
            "\"\"",
            "a note saying where the entry comes from",
        ));
    }
    validate_kind(origin, task)?;
    match &task.physics {
        Some(physics) => physics.validate(&task.correctness).map_err(|e| {
            ScoringError::invalid(
                origin,
                key(&format!("physics.{}", e.field)),
                e.value,
                e.allowed,
            )
        }),
        None => Ok(()),
    }
}

fn validate_kind(origin: &str, task: &TaskSpec) -> Result<(), ScoringError> {
    let key = |k: &str| format!("task {}: {k}", task.id);
    match task.correctness {
        CorrectnessKind::Notches { count } | CorrectnessKind::Curves { count } if count == 0 => {
            Err(ScoringError::invalid(
                origin,
                key("correctness.count"),
                count,
                "a whole number ≥ 1",
            ))
        }
        CorrectnessKind::Rotation { full_deg } if !(full_deg.is_finite() && full_deg > 0.0) => {
            Err(ScoringError::invalid(
                origin,
                key("correctness.full_deg"),
                full_deg,
                "degrees, finite and > 0 (360 in the paper)",
            ))
        }
        CorrectnessKind::Distance { full_mm } if !(full_mm.is_finite() && full_mm > 0.0) => {
            Err(ScoringError::invalid(
                origin,
                key("correctness.full_mm"),
                full_mm,
                "millimetres, finite and > 0",
            ))
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_builtin_catalog_has_the_18_pomdar_tasks() {
        let catalog = TaskCatalog::builtin();
        assert_eq!(
            catalog.ids(),
            "V1, V2, V3, H1, H2, H3, H4, H5, C1, C2, C3, C4, G1, G2, G3, G4, G5, G6"
        );
        let grasp = catalog
            .tasks
            .iter()
            .filter(|t| t.configuration.is_grasp())
            .count();
        assert_eq!(grasp, 6);
        assert_eq!(
            catalog.get("H2").map(|t| t.correctness),
            Some(CorrectnessKind::Curves { count: 3 })
        );
        assert_eq!(catalog.get("C4").map(|t| t.arm), Some(ArmConstraint::Fixed));
    }

    #[test]
    fn the_builtin_catalog_maps_only_the_tasks_whose_lab_joints_are_known() {
        let catalog = TaskCatalog::builtin();
        let mapped: Vec<&str> = catalog
            .tasks
            .iter()
            .filter(|t| t.physics.is_some())
            .map(|t| t.id.as_str())
            .collect();
        assert_eq!(mapped, ["V1", "V2", "V3", "C1"]);
        let c1 = catalog.get("C1").and_then(|t| t.physics.clone());
        assert_eq!(c1.map(|p| p.direction), Some(Direction::Decreasing));
    }

    #[test]
    fn a_physics_mapping_that_does_not_fit_its_task_names_the_task_and_key() {
        let text = "[catalog]\nname = \"lab\"\nprovenance = \"ours\"\n\n[[task]]\nid = \"V1\"\n\
            name = \"Wheel\"\nconfiguration = \"vertical\"\narm = \"vertical_axis\"\n\
            correctness = { kind = \"notches\", count = 2 }\nprovenance = \"ours\"\n\
            physics = { joint = \"slide\", marks = [0.02, 0.01] }\n";
        let error = TaskCatalog::from_toml_str(text, "lab.toml").unwrap_err();
        let message = error.to_string();
        assert!(
            message.starts_with(
                "lab.toml: task V1: physics.marks = [0.02, 0.01]: strictly increasing"
            ),
            "{message}"
        );
        let fixed = text.replace("[0.02, 0.01]", "[0.01, 0.02]");
        let catalog = TaskCatalog::from_toml_str(&fixed, "lab.toml").unwrap();
        assert_eq!(
            catalog.tasks[0].physics.as_ref().map(|p| p.marks.clone()),
            Some(vec![0.01, 0.02])
        );
    }
}
