//! The practice file: per task, the glove script its family grows from, the station settings
//! it is played with, and the poses practice may close with instead; one set of ranges for all
//! (`launch_configs/sim/practice.toml` is the project's).
//!
//! ```toml
//! [bounds]                      # optional; the defaults of StrategyBounds::DEFAULT
//! start_offset_mm = 10.0
//! approach_yaw_deg = 15.0
//! reach_scale = [0.9, 1.1]
//! closure_scale = [0.85, 1.1]
//! time_scale = [0.7, 1.2]
//!
//! [[task]]
//! id = "G4"                     # a task of the catalog
//! script = "grasp_place.toml"   # relative to the practice file
//! station = "../station/twist_about_axis.toml"   # optional station file, relative too
//! grips = ["cylinder_grasp", "pinch_index"]      # optional
//! ```

use retarget::human_hand::ScriptPose;
use serde::{Deserialize, Serialize};

use crate::error::PracticeError;
use crate::family::{StrategyBounds, closes};

/// One task's entry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskPractice {
    /// The task's ID.
    pub id: String,
    /// The glove script, relative to the practice file.
    pub script: String,
    /// A station file whose settings the task is played with, relative to the practice file.
    #[serde(default)]
    pub station: Option<String>,
    /// Closing poses practice may use in place of the script's.
    #[serde(default)]
    pub grips: Vec<ScriptPose>,
}

/// The whole file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PracticeFile {
    /// The parameters' ranges.
    #[serde(default)]
    pub bounds: StrategyBounds,
    /// The tasks, in file order.
    #[serde(rename = "task")]
    pub tasks: Vec<TaskPractice>,
}

impl PracticeFile {
    /// Parses and checks: valid ranges, each task once, with a script, grips that close the
    /// hand and are listed once, and (if `known` is not empty) only tasks in `known`.
    pub fn from_toml_str(text: &str, known: &[&str]) -> Result<PracticeFile, PracticeError> {
        let file: PracticeFile = toml::from_str(text).map_err(|e| PracticeError::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        file.bounds.validate()?;
        for (i, task) in file.tasks.iter().enumerate() {
            let bad = |field: &str, value: String, allowed: String| PracticeError::Range {
                key: format!("task[{i}].{field}"),
                value,
                allowed,
            };
            if !known.is_empty() && !known.contains(&task.id.as_str()) {
                return Err(bad(
                    "id",
                    task.id.clone(),
                    format!("a task of the catalog: {}", known.join(", ")),
                ));
            }
            if file.tasks[..i].iter().any(|t| t.id == task.id) {
                return Err(bad("id", task.id.clone(), "each task once".into()));
            }
            if task.script.trim().is_empty() {
                return Err(bad("script", "\"\"".into(), "a glove script file".into()));
            }
            for (k, grip) in task.grips.iter().enumerate() {
                if !closes(*grip) || task.grips[..k].contains(grip) {
                    return Err(bad(
                        "grips",
                        format!("{grip:?}"),
                        "closing poses (fist, cylinder_grasp, pinch_*), each once".into(),
                    ));
                }
            }
        }
        Ok(file)
    }

    /// The entry of task `id`.
    pub fn task(&self, id: &str) -> Option<&TaskPractice> {
        self.tasks.iter().find(|t| t.id == id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = r#"
[bounds]
start_offset_mm = 5.0
approach_yaw_deg = 10.0
reach_scale = [0.95, 1.05]
closure_scale = [0.9, 1.0]
time_scale = [0.8, 1.0]

[[task]]
id = "G4"
script = "grasp_place.toml"
grips = ["cylinder_grasp", "pinch_index"]

[[task]]
id = "C1"
script = "tasks/C1.toml"
station = "../station/twist_about_axis.toml"
"#;

    #[test]
    fn reads_the_tasks_and_the_ranges() {
        let file = PracticeFile::from_toml_str(FILE, &["G4", "C1"]).unwrap();
        assert_eq!(file.bounds.time_scale, [0.8, 1.0]);
        assert_eq!(
            file.task("G4").unwrap().grips,
            vec![ScriptPose::CylinderGrasp, ScriptPose::PinchIndex]
        );
        assert_eq!(
            file.task("C1").unwrap().station.as_deref(),
            Some("../station/twist_about_axis.toml")
        );
        let defaults =
            PracticeFile::from_toml_str("[[task]]\nid = \"G4\"\nscript = \"a.toml\"\n", &[])
                .unwrap();
        assert_eq!(defaults.bounds, StrategyBounds::DEFAULT);
    }

    #[test]
    fn errors_name_the_key_and_what_is_allowed() {
        let cases = [
            (
                FILE.replace("[0.8, 1.0]", "[1.1, 1.2]"),
                "bounds.time_scale",
            ),
            (FILE.replace("id = \"C1\"", "id = \"G4\""), "task[1].id"),
            (FILE.replace("\"pinch_index\"", "\"open\""), "task[0].grips"),
            (FILE.replace("tasks/C1.toml", " "), "task[1].script"),
        ];
        for (text, key) in cases {
            let error = PracticeFile::from_toml_str(&text, &["G4", "C1"])
                .unwrap_err()
                .to_string();
            assert!(error.starts_with(key), "{key}: {error}");
        }
        let error = PracticeFile::from_toml_str(FILE, &["G4"])
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("task[1].id = C1") && error.contains("G4"),
            "{error}"
        );
        assert!(PracticeFile::from_toml_str("[[task]]\nid = 1", &[]).is_err());
    }
}
