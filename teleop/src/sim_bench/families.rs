//! The strategy families of a benchmark run: the practice file with its scripts and station
//! files, built in (the project's `launch_configs/sim/practice.toml` and what it names,
//! embedded in the binary) or read from a lab's own file (paths relative to it).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use practice::{PracticeFile, StrategyFamily};
use retarget::human_hand::GloveScript;
use station::StationConfig;

use super::error::BenchError;

/// The project's practice file and every file it names, by their paths relative to it.
const BUILTIN: [(&str, &str); 20] = [
    (
        "practice.toml",
        include_str!("../../../launch_configs/sim/practice.toml"),
    ),
    (
        "grasp_place.toml",
        include_str!("../../../launch_configs/sim/grasp_place.toml"),
    ),
    (
        "tasks/V1.toml",
        include_str!("../../../launch_configs/sim/tasks/V1.toml"),
    ),
    (
        "tasks/V2.toml",
        include_str!("../../../launch_configs/sim/tasks/V2.toml"),
    ),
    (
        "tasks/V3.toml",
        include_str!("../../../launch_configs/sim/tasks/V3.toml"),
    ),
    (
        "tasks/H1.toml",
        include_str!("../../../launch_configs/sim/tasks/H1.toml"),
    ),
    (
        "tasks/H2.toml",
        include_str!("../../../launch_configs/sim/tasks/H2.toml"),
    ),
    (
        "tasks/H3.toml",
        include_str!("../../../launch_configs/sim/tasks/H3.toml"),
    ),
    (
        "tasks/H4.toml",
        include_str!("../../../launch_configs/sim/tasks/H4.toml"),
    ),
    (
        "tasks/H5.toml",
        include_str!("../../../launch_configs/sim/tasks/H5.toml"),
    ),
    (
        "tasks/C1.toml",
        include_str!("../../../launch_configs/sim/tasks/C1.toml"),
    ),
    (
        "tasks/C2.toml",
        include_str!("../../../launch_configs/sim/tasks/C2.toml"),
    ),
    (
        "tasks/C3.toml",
        include_str!("../../../launch_configs/sim/tasks/C3.toml"),
    ),
    (
        "tasks/C4.toml",
        include_str!("../../../launch_configs/sim/tasks/C4.toml"),
    ),
    (
        "tasks/G1.toml",
        include_str!("../../../launch_configs/sim/tasks/G1.toml"),
    ),
    (
        "tasks/G2.toml",
        include_str!("../../../launch_configs/sim/tasks/G2.toml"),
    ),
    (
        "tasks/G3.toml",
        include_str!("../../../launch_configs/sim/tasks/G3.toml"),
    ),
    (
        "tasks/G5.toml",
        include_str!("../../../launch_configs/sim/tasks/G5.toml"),
    ),
    (
        "tasks/G6.toml",
        include_str!("../../../launch_configs/sim/tasks/G6.toml"),
    ),
    (
        "../station/twist_about_axis.toml",
        include_str!("../../../launch_configs/station/twist_about_axis.toml"),
    ),
];

/// Reads a file the practice file names, by its path relative to it.
type ReadFile = Box<dyn Fn(&str) -> Result<String, BenchError>>;

/// Where the practice file and its scripts come from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PracticeSource {
    /// The project's, built in.
    Builtin,
    /// A lab's file; the paths in it are relative to it.
    File(PathBuf),
}

/// One task's family and the station file it is played with.
#[derive(Debug, Clone)]
pub struct TaskFamily {
    /// The family.
    pub family: StrategyFamily,
    /// The station file's text, laid over the run's station configuration.
    pub station_overlay: Option<String>,
    /// Where the script came from (for messages and the strategies report).
    pub script_origin: String,
}

/// Every task's family, by task ID.
#[derive(Debug, Clone)]
pub struct Families {
    /// The families.
    pub tasks: BTreeMap<String, TaskFamily>,
    /// Where they came from.
    pub origin: String,
}

impl Families {
    /// Loads the practice file of `source` and everything it names; `known` are the catalog's
    /// task IDs. Errors name the file and the key.
    pub fn load(source: &PracticeSource, known: &[&str]) -> Result<Families, BenchError> {
        let (origin, read): (String, ReadFile) = match source {
            PracticeSource::Builtin => {
                ("the built-in practice file".into(), Box::new(read_builtin))
            }
            PracticeSource::File(path) => {
                let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
                let root = path.clone();
                (
                    path.display().to_string(),
                    Box::new(move |name: &str| {
                        let file = if name == "practice.toml" {
                            root.clone()
                        } else {
                            dir.join(name)
                        };
                        std::fs::read_to_string(&file)
                            .map_err(|source| BenchError::Read { path: file, source })
                    }),
                )
            }
        };
        let file =
            PracticeFile::from_toml_str(&read("practice.toml")?, known).map_err(|source| {
                BenchError::Practice {
                    origin: origin.clone(),
                    source,
                }
            })?;
        let mut tasks = BTreeMap::new();
        for entry in &file.tasks {
            let script_origin = format!("{} ({})", entry.script, origin);
            let script = GloveScript::from_toml_str(&read(&entry.script)?).map_err(|e| {
                BenchError::Script {
                    origin: script_origin.clone(),
                    reason: e.to_string(),
                }
            })?;
            let station_overlay = entry.station.as_deref().map(&read).transpose()?;
            let family = StrategyFamily {
                task: entry.id.clone(),
                script,
                grips: entry.grips.clone(),
                bounds: file.bounds,
            };
            tasks.insert(
                entry.id.clone(),
                TaskFamily {
                    family,
                    station_overlay,
                    script_origin,
                },
            );
        }
        Ok(Families { tasks, origin })
    }
}

fn read_builtin(name: &str) -> Result<String, BenchError> {
    BUILTIN
        .iter()
        .find(|(path, _)| *path == name)
        .map(|(_, text)| text.to_string())
        .ok_or_else(|| BenchError::Read {
            path: PathBuf::from(name),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "not built into this pomdar"),
        })
}

/// `base` with the settings of the station file `overlay` laid over it (tables merged key by
/// key, the overlay's values winning), checked as a whole.
pub fn overlay_station(base: &StationConfig, overlay: &str) -> Result<StationConfig, BenchError> {
    let bad = |reason: String| BenchError::Station { reason };
    let mut merged = toml::Value::try_from(base).map_err(|e| bad(e.to_string()))?;
    let top: toml::Value = toml::from_str(overlay).map_err(|e| bad(e.to_string()))?;
    merge(&mut merged, top);
    let text = toml::to_string(&merged).map_err(|e| bad(e.to_string()))?;
    StationConfig::from_toml_str(&text).map_err(|e| bad(e.to_string()))
}

fn merge(base: &mut toml::Value, top: toml::Value) {
    match (base, top) {
        (toml::Value::Table(b), toml::Value::Table(t)) => {
            for (key, value) in t {
                match b.get_mut(&key) {
                    Some(existing) => merge(existing, value),
                    None => {
                        b.insert(key, value);
                    }
                }
            }
        }
        (b, t) => *b = t,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_builtin_families_cover_the_catalog_and_parse() {
        let catalog = scoring::TaskCatalog::builtin();
        let known: Vec<&str> = catalog.tasks.iter().map(|t| t.id.as_str()).collect();
        let families = Families::load(&PracticeSource::Builtin, &known).unwrap();
        assert_eq!(families.tasks.len(), 18);
        for id in known {
            assert!(families.tasks.contains_key(id), "{id}");
        }
        assert!(families.tasks["V1"].station_overlay.is_some());
        assert!(families.tasks["G4"].station_overlay.is_none());
    }

    #[test]
    fn a_station_overlay_changes_only_what_it_names() {
        let base = StationConfig::default();
        let text = BUILTIN
            .iter()
            .find(|(p, _)| p.ends_with("twist_about_axis.toml"))
            .unwrap()
            .1;
        let merged = overlay_station(&base, text).unwrap();
        assert_ne!(merged.arm, base.arm);
        let mut back = merged.clone();
        back.arm = base.arm.clone();
        assert_eq!(back, base);
        let error = overlay_station(&base, "[arm]\norientation = \"sideways\"\n").unwrap_err();
        assert!(error.to_string().contains("orientation"), "{error}");
    }
}
