//! The Foxglove layouts shipped in `launch_configs/foxglove/` bind their panels to topics the
//! station really has, with the types those panels need.
//!
//! Every layout is read as the Foxglove app imports it (`configById`, the `layout` tree,
//! `globalVariables`, `userNodes`, `playbackConfig`) and every topic a panel names is collected:
//! the 3D panel's topic settings (and the frame it follows), plot series and state-transition
//! paths, the raw-message path, the diagnostics panels' topic. Each must be one the station
//! offers where the layout is used — `pomdar_live*.json` on the live view (`--view`),
//! `pomdar_trial*.json` on a trial log — as listed by `teleop::station_topics` for the default
//! `StationConfig` (and for every preset in `launch_configs/station/`), with a type the panel can draw: a 3D topic a MarkerArray (or a pose, or
//! the URDF text on the robot-description topic), a diagnostics topic a DiagnosticArray, and a
//! message path must resolve through the topic's own `ros2msg` schema to a single number
//! (plots) or a single value (state transitions). A plot series labelled with a joint must
//! read that joint's index of the station's published joint names.
//!
//! The checker is shown to catch a misspelt topic, a wrong type, a log-only topic on the live
//! layout, a mislabelled joint and an unknown panel on edited copies of the shipped layouts;
//! and a demo run (in process: the simulated glove, the station, the mock hand and arm on
//! loopback DDS) shows that the list is what a station serves live and records: exactly those
//! topics and types on its tap (what `--view` turns into channels) and in its log.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::time::Duration;

use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{files_with_extension, scratch_dir, workspace_root};
use retarget::HandModel;
use serde_json::Value;
use station::StationConfig;
use station::ros_tools::{HandTf, published_joint_names};
use teleop::demo::{DemoOptions, run_demo};
use teleop::mcap_log::TrialReader;
use teleop::stand_ins::sim_glove_node::SimGloveConfig;
use teleop::station_node::tap::Tap;
use teleop::station_topics::{StationTopic, station_topics};
use tokio::sync::broadcast::error::{RecvError, TryRecvError};

const MARKER_ARRAY: &str = "visualization_msgs/msg/MarkerArray";
const DIAGNOSTIC_ARRAY: &str = "diagnostic_msgs/msg/DiagnosticArray";
const STRING: &str = "std_msgs/msg/String";
/// What a 3D panel draws from a topic's settings (besides the URDF text).
const SCENE_TYPES: [&str; 4] = [
    MARKER_ARRAY,
    "visualization_msgs/msg/Marker",
    "geometry_msgs/msg/PoseStamped",
    "geometry_msgs/msg/PoseArray",
];

/// Where a layout is used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Source {
    /// The live view (`--view`): what the station publishes.
    Live,
    /// A trial log: what the station records.
    Log,
}

impl Source {
    /// By the file's name: `…live….json` or `…trial….json`.
    fn of(path: &Path) -> Source {
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        match (stem.contains("live"), stem.contains("trial")) {
            (true, false) => Source::Live,
            (false, true) => Source::Log,
            _ => panic!(
                "{}: name a layout pomdar_live*.json or pomdar_trial*.json, so the check knows \
                 whether it is for the live view or a trial log",
                path.display()
            ),
        }
    }

    fn offers(self, topic: &StationTopic) -> bool {
        match self {
            Source::Live => topic.live,
            Source::Log => topic.recorded,
        }
    }
}

/// What the station offers a viewer, from the project's code.
struct Offered {
    topics: Vec<StationTopic>,
    /// The frame of the hand's root on `/tf` (markers are drawn in it).
    root_frame: String,
    /// The topic carrying the URDF text.
    robot_description_topic: String,
    /// The joint names the station publishes (its joint targets; the mock hand's state too).
    joint_names: Vec<String>,
}

impl Offered {
    fn of(config: &StationConfig) -> Offered {
        let model = HandModel::orca_v1_right();
        Offered {
            topics: station_topics(config),
            root_frame: HandTf::new(&model, &config.ros_tools)
                .root_frame()
                .to_string(),
            robot_description_topic: config.ros_tools.robot_description_topic.clone(),
            joint_names: published_joint_names(&model, config.output.joint_name_prefix.as_deref()),
        }
    }

    fn default_station() -> Offered {
        Offered::of(&StationConfig::default())
    }
}

/// What a panel does with a topic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Need {
    /// A 3D panel's topic setting: something it draws.
    Scene,
    /// A plot series: one number per message.
    Plot,
    /// A state-transitions path: one value per message.
    States,
    /// A raw-message path: anything that resolves.
    Raw,
    /// A diagnostics panel's topic: a DiagnosticArray.
    Diagnostics,
}

/// One topic (or message path) a panel names.
#[derive(Debug, Clone)]
struct Binding {
    panel: String,
    need: Need,
    path: String,
    label: Option<String>,
}

// ---- message paths through the topics' ros2msg schemas ---------------------------------------

/// One step of a message path after its topic.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Step {
    Field(String),
    /// `[3]` (or a variable, `[$i]`: `None`).
    Index(Option<usize>),
    /// `[:]`, `[1:3]`: several values.
    Slice,
    /// `{name=="x"}`.
    Filter,
    /// `.@derivative` and the like.
    Modifier,
}

/// Split a Foxglove message path (`/topic.field[2].sub`) into its topic and steps.
fn parse_path(path: &str) -> Result<(String, Vec<Step>), String> {
    if !path.starts_with('/') {
        return Err(format!("'{path}' does not start with a topic"));
    }
    let end = path.find(['.', '[', '{']).unwrap_or(path.len());
    let topic = path[..end].to_string();
    let rest: Vec<char> = path[end..].chars().collect();
    let mut steps = Vec::new();
    let mut i = 0;
    let word = |i: &mut usize| -> String {
        let start = *i;
        while *i < rest.len() && (rest[*i].is_alphanumeric() || rest[*i] == '_') {
            *i += 1;
        }
        rest[start..*i].iter().collect()
    };
    let until = |i: &mut usize, close: char| -> Result<String, String> {
        let start = *i + 1;
        let Some(offset) = rest[start..].iter().position(|c| *c == close) else {
            return Err(format!("'{path}': no closing '{close}'"));
        };
        *i = start + offset + 1;
        Ok(rest[start..start + offset].iter().collect())
    };
    while i < rest.len() {
        match rest[i] {
            '.' if rest.get(i + 1) == Some(&'@') => {
                i += 2;
                word(&mut i);
                steps.push(Step::Modifier);
            }
            '.' => {
                i += 1;
                let name = word(&mut i);
                if name.is_empty() {
                    return Err(format!("'{path}': an empty field name"));
                }
                steps.push(Step::Field(name));
            }
            '[' => {
                let inside = until(&mut i, ']')?;
                let inside = inside.trim();
                steps.push(if inside.contains(':') {
                    Step::Slice
                } else if inside.starts_with('$') {
                    Step::Index(None)
                } else {
                    let index = inside
                        .parse()
                        .map_err(|_| format!("'{path}': '[{inside}]' is not an index"))?;
                    Step::Index(Some(index))
                });
            }
            '{' => {
                until(&mut i, '}')?;
                steps.push(Step::Filter);
            }
            other => return Err(format!("'{path}': unexpected '{other}'")),
        }
    }
    Ok((topic, steps))
}

/// A field of a message type.
#[derive(Debug, Clone)]
struct Field {
    name: String,
    /// A primitive (`float64`, `string`, …) or a message type as `pkg/Type`.
    base: String,
    array: bool,
}

const PRIMITIVES: [&str; 15] = [
    "bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32",
    "uint32", "int64", "uint64", "string", "wstring",
];

fn is_primitive(base: &str) -> bool {
    PRIMITIVES.contains(&base)
}

fn is_number(base: &str) -> bool {
    is_primitive(base) && base != "string" && base != "wstring"
}

/// `pkg/msg/Type` → `pkg/Type` (the form a schema's own references take).
fn short_type(ros_type: &str) -> String {
    ros_type.replacen("/msg/", "/", 1)
}

/// The message types of a `ros2msg` schema text (the root type first, then each dependency
/// after its `MSG: pkg/Type` line), field by field; constants are left out.
fn parse_schema(ros_type: &str, text: &str) -> BTreeMap<String, Vec<Field>> {
    let mut types: BTreeMap<String, Vec<Field>> = BTreeMap::new();
    let mut current = short_type(ros_type);
    types.entry(current.clone()).or_default();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() || line.starts_with("===") {
            continue;
        }
        if let Some(name) = line.strip_prefix("MSG: ") {
            current = short_type(name.trim());
            types.entry(current.clone()).or_default();
            continue;
        }
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let [kind, name, rest @ ..] = tokens.as_slice() else {
            continue;
        };
        if name.contains('=') || rest.first().is_some_and(|r| r.starts_with('=')) {
            continue; // a constant
        }
        let array = kind.contains('[');
        let base = kind.split(['[', '<']).next().unwrap_or(kind);
        let package = current.split('/').next().unwrap_or("");
        let base = if is_primitive(base) || base.contains('/') {
            base.to_string()
        } else if base == "Header" {
            "std_msgs/Header".to_string()
        } else {
            format!("{package}/{base}")
        };
        if let Some(fields) = types.get_mut(&current) {
            fields.push(Field {
                name: name.to_string(),
                base,
                array,
            });
        }
    }
    types
}

/// Where a path ends in its topic's type.
#[derive(Debug, Clone)]
struct Resolved {
    base: String,
    array: bool,
    /// A slice on the way: several values per message.
    several: bool,
}

/// Follow `steps` through the schema of `topic`.
fn resolve(topic: &StationTopic, steps: &[Step]) -> Result<Resolved, String> {
    let types = parse_schema(&topic.ros_type, &topic.schema_text);
    let mut at = Resolved {
        base: short_type(&topic.ros_type),
        array: false,
        several: false,
    };
    for step in steps {
        match step {
            Step::Field(name) => {
                let fields = types
                    .get(&at.base)
                    .filter(|_| !at.array)
                    .ok_or_else(|| format!("'{name}' asked of {} (no fields there)", at.base))?;
                let field = fields.iter().find(|f| &f.name == name).ok_or_else(|| {
                    let known: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
                    format!(
                        "{} has no field '{name}' (it has: {})",
                        at.base,
                        known.join(", ")
                    )
                })?;
                at.base.clone_from(&field.base);
                at.array = field.array;
            }
            Step::Index(_) | Step::Slice => {
                if !at.array {
                    return Err(format!("an index into {}, which is no array", at.base));
                }
                at.array = false;
                at.several |= *step == Step::Slice;
            }
            Step::Filter if at.array || is_primitive(&at.base) => {
                return Err(format!("a filter on {}, not a message", at.base));
            }
            Step::Filter | Step::Modifier => {}
        }
    }
    Ok(at)
}

// ---- the layout ------------------------------------------------------------------------------

/// The panel ids at the leaves of a layout tree.
fn leaves(node: &Value, out: &mut Vec<String>, problems: &mut Vec<String>) {
    match node {
        Value::String(id) => out.push(id.clone()),
        Value::Object(split) => {
            for side in ["first", "second"] {
                match split.get(side) {
                    Some(child) => leaves(child, out, problems),
                    None => problems.push(format!("a layout split without '{side}'")),
                }
            }
        }
        other => problems.push(format!(
            "a layout node that is neither a panel nor a split: {other}"
        )),
    }
}

fn string_at<'a>(config: &'a Value, key: &str) -> Option<&'a str> {
    config.get(key).and_then(Value::as_str)
}

/// The layout's panels by id, after checking its shape: the keys of Foxglove's layout file,
/// and every panel of the tree configured and every configured panel in the tree.
fn panels<'a>(
    layout: &'a Value,
    problems: &mut Vec<String>,
) -> Option<&'a serde_json::Map<String, Value>> {
    for key in [
        "configById",
        "globalVariables",
        "userNodes",
        "playbackConfig",
    ] {
        if !layout.get(key).is_some_and(Value::is_object) {
            problems.push(format!(
                "no '{key}' object (Foxglove's layout file has one)"
            ));
        }
    }
    let panels = layout.get("configById").and_then(Value::as_object)?;
    let mut placed = Vec::new();
    match layout.get("layout") {
        Some(tree) => leaves(tree, &mut placed, problems),
        None => problems.push("no 'layout' tree".into()),
    }
    let placed: BTreeSet<&String> = placed.iter().collect();
    let configured: BTreeSet<&String> = panels.keys().collect();
    for id in placed.difference(&configured) {
        problems.push(format!(
            "panel {id} is in the layout tree but has no configuration"
        ));
    }
    for id in configured.difference(&placed) {
        problems.push(format!(
            "panel {id} is configured but not in the layout tree"
        ));
    }
    Some(panels)
}

/// A plot's or state-transitions panel's series: (path, label).
fn series(config: &Value) -> Vec<(String, Option<String>)> {
    let paths = config.get("paths").and_then(Value::as_array);
    paths
        .into_iter()
        .flatten()
        .map(|p| {
            (
                string_at(p, "value").unwrap_or("").to_string(),
                string_at(p, "label").map(str::to_string),
            )
        })
        .collect()
}

/// Every topic (or path) the panels name; the problems of the layout's shape on the way.
fn bindings(layout: &Value, offered: &Offered, problems: &mut Vec<String>) -> Vec<Binding> {
    let mut out = Vec::new();
    for (id, config) in panels(layout, problems).into_iter().flatten() {
        let kind = id.split('!').next().unwrap_or("");
        let mut bind = |need: Need, path: &str, label: Option<&str>| {
            out.push(Binding {
                panel: id.clone(),
                need,
                path: path.to_string(),
                label: label.map(str::to_string),
            });
        };
        match kind {
            "3D" => {
                let topics = config.get("topics").and_then(Value::as_object);
                for topic in topics.into_iter().flat_map(|t| t.keys()) {
                    bind(Need::Scene, topic, None);
                }
                match string_at(config, "followTf") {
                    Some(frame) if frame == offered.root_frame => {}
                    other => problems.push(format!(
                        "panel {id} follows frame {other:?}; the hand's root on /tf is '{}'",
                        offered.root_frame
                    )),
                }
            }
            "Plot" | "StateTransitions" => {
                let need = if kind == "Plot" {
                    Need::Plot
                } else {
                    Need::States
                };
                let series = series(config);
                if series.is_empty() {
                    problems.push(format!("panel {id} has no paths"));
                }
                for (path, label) in series {
                    bind(need, &path, label.as_deref());
                }
            }
            "RawMessages" => bind(
                Need::Raw,
                string_at(config, "topicPath").unwrap_or(""),
                None,
            ),
            "DiagnosticSummary" | "DiagnosticStatusPanel" => bind(
                Need::Diagnostics,
                string_at(config, "topicToRender").unwrap_or(""),
                None,
            ),
            _ => problems.push(format!(
                "panel {id}: a panel type this check does not know (teach it which topics the \
                 panel names)"
            )),
        }
    }
    out
}

/// Whether `binding` names a topic `source` offers, with a type its panel can use.
fn check_binding(binding: &Binding, source: Source, offered: &Offered) -> Result<(), String> {
    let (panel, path) = (&binding.panel, &binding.path);
    let (name, steps) = parse_path(path).map_err(|e| format!("panel {panel}: {e}"))?;
    let Some(topic) = offered.topics.iter().find(|t| t.topic == name) else {
        let known: Vec<&str> = offered
            .topics
            .iter()
            .filter(|t| source.offers(t))
            .map(|t| t.topic.as_str())
            .collect();
        return Err(format!(
            "panel {panel}: {name} is not a topic of the station (it offers {})",
            known.join(", ")
        ));
    };
    if !source.offers(topic) {
        return Err(format!(
            "panel {panel}: {name} is not served live (it is only in the logs); the live view \
             serves what the station publishes"
        ));
    }
    let ty = &topic.ros_type;
    match binding.need {
        Need::Scene => {
            let urdf = ty == STRING && name == offered.robot_description_topic;
            if !steps.is_empty() || !(SCENE_TYPES.contains(&ty.as_str()) || urdf) {
                return Err(format!(
                    "panel {panel}: the 3D panel cannot draw {path} ({ty}); it takes {} or the \
                     URDF text on {}",
                    SCENE_TYPES.join(", "),
                    offered.robot_description_topic
                ));
            }
        }
        Need::Diagnostics => {
            if !steps.is_empty() || ty != DIAGNOSTIC_ARRAY {
                return Err(format!(
                    "panel {panel}: {path} is {ty}, the diagnostics panels read {DIAGNOSTIC_ARRAY}"
                ));
            }
        }
        Need::Plot | Need::States | Need::Raw => {
            let at = resolve(topic, &steps).map_err(|e| format!("panel {panel}: {path}: {e}"))?;
            let single = !at.array && !at.several;
            match binding.need {
                Need::Plot if !(single && is_number(&at.base)) => {
                    return Err(format!(
                        "panel {panel}: {path} ({ty}) is not one number per message but {}{}",
                        at.base,
                        if single { "" } else { " (several)" }
                    ));
                }
                Need::States if !(single && is_primitive(&at.base)) => {
                    return Err(format!(
                        "panel {panel}: {path} ({ty}) is not one value per message but {}{}",
                        at.base,
                        if single { "" } else { " (several)" }
                    ));
                }
                _ => {}
            }
            check_joint_label(binding, topic, &steps, offered)?;
        }
    }
    Ok(())
}

/// A series labelled `JOINT …` on `.position[i]` of a JointState reads that joint: the
/// station's `i`-th published joint name ends with `JOINT`.
fn check_joint_label(
    binding: &Binding,
    topic: &StationTopic,
    steps: &[Step],
    offered: &Offered,
) -> Result<(), String> {
    let (Some(label), [Step::Field(field), Step::Index(Some(index))]) = (&binding.label, steps)
    else {
        return Ok(());
    };
    if topic.ros_type != "sensor_msgs/msg/JointState" || field != "position" {
        return Ok(());
    }
    let joint = label.split_whitespace().next().unwrap_or("");
    match offered.joint_names.get(*index) {
        Some(name) if name.ends_with(joint) => Ok(()),
        other => Err(format!(
            "panel {}: series '{label}' reads {} (joint {other:?}), not {joint}",
            binding.panel, binding.path
        )),
    }
}

/// Every problem of `layout` used on `source`.
fn check_layout(layout: &Value, source: Source, offered: &Offered) -> Vec<String> {
    let mut problems = Vec::new();
    let found = bindings(layout, offered, &mut problems);
    if found.is_empty() {
        problems.push("no panel names a topic".into());
    }
    for binding in &found {
        if let Err(problem) = check_binding(binding, source, offered) {
            problems.push(problem);
        }
    }
    problems
}

fn shipped_layouts() -> Vec<(PathBuf, Value)> {
    let dir = workspace_root().join("launch_configs").join("foxglove");
    let paths = files_with_extension(&dir, "json").unwrap();
    assert!(paths.len() >= 2, "layouts in {}: {paths:?}", dir.display());
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).unwrap();
            let layout = serde_json::from_str(&text)
                .unwrap_or_else(|e| panic!("{}: not JSON: {e}", path.display()));
            (path, layout)
        })
        .collect()
}

fn shipped(name: &str) -> Value {
    shipped_layouts()
        .into_iter()
        .find(|(path, _)| path.file_name().is_some_and(|n| n == name))
        .map(|(_, layout)| layout)
        .unwrap_or_else(|| panic!("no launch_configs/foxglove/{name}"))
}

// ---- the tests -------------------------------------------------------------------------------

#[test]
fn every_shipped_layout_binds_its_panels_to_the_stations_topics_and_types() {
    let offered = Offered::default_station();
    for (path, layout) in shipped_layouts() {
        let source = Source::of(&path);
        let found = bindings(&layout, &offered, &mut Vec::new());
        let problems = check_layout(&layout, source, &offered);
        println!("{} ({source:?}):", path.display());
        for b in &found {
            println!("  {:32} {:?} {}", b.panel, b.need, b.path);
        }
        assert!(
            problems.is_empty(),
            "{}:\n  {}",
            path.display(),
            problems.join("\n  ")
        );
        // Each layout has its panels: the hand in 3D, joints, diagnostics, the status.
        let needs: BTreeSet<String> = found.iter().map(|b| format!("{:?}", b.need)).collect();
        for need in ["Scene", "Plot", "Diagnostics", "Raw"] {
            assert!(needs.contains(need), "{}: no {need} panel", path.display());
        }
        if source == Source::Log {
            assert!(
                needs.contains("States"),
                "{}: no trial events",
                path.display()
            );
        }
    }
}

#[test]
fn the_layouts_fit_every_shipped_station_preset() {
    let dir = workspace_root().join("launch_configs").join("station");
    let presets = files_with_extension(&dir, "toml").unwrap();
    assert!(!presets.is_empty());
    for preset in presets {
        let text = std::fs::read_to_string(&preset).unwrap();
        let config = StationConfig::from_toml_str(&text)
            .unwrap_or_else(|e| panic!("{}: {e}", preset.display()));
        let offered = Offered::of(&config);
        for (path, layout) in shipped_layouts() {
            let problems = check_layout(&layout, Source::of(&path), &offered);
            assert!(
                problems.is_empty(),
                "{} with {}:\n  {}",
                path.display(),
                preset.display(),
                problems.join("\n  ")
            );
        }
    }
}

/// `(pointer to a string in the layout, its replacement, what the report must say)`.
type Edit = (&'static str, &'static str, &'static [&'static str]);

#[test]
fn a_misspelt_topic_a_wrong_type_or_a_log_only_topic_is_reported() {
    let offered = Offered::default_station();
    let trial = shipped("pomdar_trial.json");
    assert_eq!(
        check_layout(&trial, Source::Log, &offered),
        Vec::<String>::new()
    );

    let edits: [Edit; 6] = [
        // A misspelt topic in a plot series.
        (
            "/configById/Plot!thumb_index/paths/1/value",
            "/pomdar/hand/joint_state.position[0]",
            &[
                "Plot!thumb_index",
                "/pomdar/hand/joint_state is not a topic",
            ],
        ),
        // A plot path on a topic whose type has no such field.
        (
            "/configById/Plot!thumb_index/paths/1/value",
            "/pomdar/status.position[0]",
            &["std_msgs/String has no field 'position'"],
        ),
        // A whole array plotted as one series.
        (
            "/configById/Plot!middle_wrist/paths/0/value",
            "/pomdar/hand/joint_targets.position",
            &["not one number per message but float64"],
        ),
        // Diagnostics on a JointState.
        (
            "/configById/DiagnosticSummary!station/topicToRender",
            "/pomdar/hand/joint_targets",
            &["DiagnosticSummary!station", DIAGNOSTIC_ARRAY],
        ),
        // State transitions on an array's `.data` (Float32MultiArray) instead of a String's.
        (
            "/configById/StateTransitions!trial_events/paths/0/value",
            "/hand/policy_output.data",
            &["not one value per message but float32 (several)"],
        ),
        // A series labelled with a joint it does not read.
        (
            "/configById/Plot!thumb_index/paths/0/value",
            "/pomdar/hand/joint_targets.position[1]",
            &["thumb_mcp commanded", "right_thumb_abd"],
        ),
    ];
    for (pointer, replacement, expected) in edits {
        let mut edited = trial.clone();
        *edited
            .pointer_mut(pointer)
            .unwrap_or_else(|| panic!("no {pointer}")) = Value::from(replacement);
        let problems = check_layout(&edited, Source::Log, &offered);
        println!("{pointer} = {replacement}:\n  {}", problems.join("\n  "));
        assert_eq!(problems.len(), 1, "{problems:?}");
        for part in expected {
            assert!(problems[0].contains(part), "'{part}' not in {problems:?}");
        }
    }

    // A misspelt 3D topic, and a String that is not the URDF.
    for (topic, expected) in [
        ("/pomdar/marker/keypoints", "is not a topic of the station"),
        ("/pomdar/status", "the 3D panel cannot draw /pomdar/status"),
    ] {
        let mut edited = trial.clone();
        let topics = edited
            .pointer_mut("/configById/3D!hand/topics")
            .and_then(Value::as_object_mut)
            .unwrap();
        let setting = topics.remove("/pomdar/markers/keypoints").unwrap();
        topics.insert(topic.to_string(), setting);
        let problems = check_layout(&edited, Source::Log, &offered);
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert!(problems[0].contains(expected), "{problems:?}");
    }

    // The 3D panel following a frame the station does not publish.
    let mut edited = trial.clone();
    edited["configById"]["3D!hand"]["followTf"] = "base_link".into();
    let problems = check_layout(&edited, Source::Log, &offered);
    assert!(
        problems.len() == 1 && problems[0].contains("the hand's root on /tf is 'world'"),
        "{problems:?}"
    );

    // An unknown panel, and a panel left out of the tree.
    let mut edited = trial.clone();
    edited["configById"]["Gauge!x"] = serde_json::json!({"path": "/pomdar/status.data"});
    let problems = check_layout(&edited, Source::Log, &offered).join("\n");
    assert!(
        problems.contains("Gauge!x: a panel type this check does not know"),
        "{problems}"
    );
    assert!(
        problems.contains("Gauge!x is configured but not in the layout tree"),
        "{problems}"
    );

    // The trial layout on the live view: the measured state and the trial events are only in
    // the logs.
    let problems = check_layout(&trial, Source::Live, &offered);
    assert_eq!(problems.len(), 5, "{problems:?}");
    for problem in &problems {
        assert!(problem.contains("is not served live"), "{problem}");
    }
    assert!(problems.iter().any(|p| p.contains("/pomdar/trial_events")));
}

/// Runs the demo in process for `seconds` with a tap and a log; what went through the tap
/// (topic, type) and the log's path.
async fn demo_run(config: &StationConfig, seconds: f64) -> (BTreeSet<(String, String)>, PathBuf) {
    let tap = Tap::new(4096);
    let mut tapped = tap.subscribe();
    let (stop, mut stopped) = tokio::sync::oneshot::channel::<()>();
    let collector = tokio::spawn(async move {
        let mut seen = BTreeSet::new();
        let mut keep = |m: teleop::station_node::tap::TappedMessage| {
            seen.insert((m.topic, m.ros_type_name));
        };
        loop {
            tokio::select! {
                received = tapped.recv() => match received {
                    Ok(message) => keep(message),
                    Err(RecvError::Lagged(_)) => {}
                    Err(RecvError::Closed) => break,
                },
                _ = &mut stopped => {
                    loop {
                        match tapped.try_recv() {
                            Ok(message) => keep(message),
                            Err(TryRecvError::Lagged(_)) => {}
                            Err(_) => break,
                        }
                    }
                    break;
                }
            }
        }
        seen
    });
    let dir = scratch_dir("foxglove-layout");
    let outcome = run_demo(DemoOptions {
        duration_s: seconds,
        domain_id: test_domain(),
        station: config.clone(),
        glove: SimGloveConfig::default(),
        live: false,
        out: Some(dir),
        tap: Some(tap),
        physics: None,
    })
    .await
    .unwrap();
    stop.send(()).ok();
    let served = tokio::time::timeout(Duration::from_secs(10), collector)
        .await
        .expect("the tap's reader stops")
        .unwrap();
    (served, outcome.recorded.expect("the demo recorded its run"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_demo_run_serves_live_and_records_exactly_the_listed_topics() {
    let config = StationConfig::default();
    let offered = Offered::of(&config);
    let (served, log_path) = demo_run(&config, 2.0).await;

    // Without a URDF there is no /robot_description; everything else of the list is there.
    let listed = |keep: fn(&StationTopic) -> bool| -> BTreeSet<(String, String)> {
        offered
            .topics
            .iter()
            .filter(|t| keep(t) && !t.needs_urdf)
            .map(|t| (t.topic.clone(), t.ros_type.clone()))
            .collect()
    };
    assert_eq!(served, listed(|t| t.live), "the live view's topics");
    let log = TrialReader::open(&log_path).unwrap();
    let recorded: BTreeSet<(String, String)> = log
        .topics()
        .iter()
        .map(|t| (t.topic.clone(), t.type_name.clone()))
        .collect();
    assert_eq!(recorded, listed(|t| t.recorded), "the log's channels");
    for channel in log.topics() {
        let topic = offered
            .topics
            .iter()
            .find(|t| t.topic == channel.topic)
            .unwrap();
        assert_eq!(channel.schema_text, topic.schema_text, "{}", channel.topic);
        assert!(channel.message_count > 0, "{}", channel.topic);
    }

    // The plots' joint indices hold on the data: commands and the hand's state carry the
    // station's published names in its order.
    for topic in ["/pomdar/hand/joint_targets", "/pomdar/hand/joint_states"] {
        let states = log.decode_topic::<msgs::JointState>(topic).unwrap();
        assert!(!states.is_empty(), "{topic}");
        assert_eq!(states[0].name, offered.joint_names, "{topic}");
    }

    // And the shipped layouts name only topics this run had.
    for (path, layout) in shipped_layouts() {
        let source = Source::of(&path);
        let mut problems = Vec::new();
        for binding in bindings(&layout, &offered, &mut problems) {
            let (topic, _) = parse_path(&binding.path).unwrap();
            let had = match source {
                Source::Live => served.iter().any(|(t, _)| *t == topic),
                Source::Log => log.topic(&topic).is_some(),
            };
            if !had && topic != offered.robot_description_topic {
                problems.push(format!("{}: {topic} not in the run", binding.panel));
            }
        }
        assert!(problems.is_empty(), "{}: {problems:?}", path.display());
    }
    std::fs::remove_dir_all(log_path.parent().unwrap()).ok();
}

#[test]
fn message_paths_resolve_through_the_schemas() {
    let offered = Offered::default_station();
    let topic = |name: &str| offered.topics.iter().find(|t| t.topic == name).unwrap();
    let resolved = |name: &str, path: &str| {
        let (_, steps) = parse_path(path).unwrap();
        resolve(topic(name), &steps)
    };
    let at = resolved("/pomdar/hand/joint_targets", "/t.header.stamp.sec").unwrap();
    assert_eq!((at.base.as_str(), at.array), ("int32", false));
    let at = resolved("/diagnostics", "/t.status[:]{level==2}.message").unwrap();
    assert_eq!((at.base.as_str(), at.several), ("string", true));
    let at = resolved(
        "/franka/end_effector_pose_cmd",
        "/t.pose.position.x.@derivative",
    )
    .unwrap();
    assert_eq!(at.base, "float64");
    let at = resolved("/pomdar/markers/keypoints", "/t.markers[0].points").unwrap();
    assert_eq!((at.base.as_str(), at.array), ("geometry_msgs/Point", true));
    // DiagnosticStatus's constants (`byte OK=0`) are no fields.
    let error = resolved("/diagnostics", "/t.status[0].OK").unwrap_err();
    assert!(error.contains("has no field 'OK'"), "{error}");
    assert!(parse_path("pomdar/status").is_err());
    assert!(parse_path("/pomdar/status.data[x]").is_err());
}
