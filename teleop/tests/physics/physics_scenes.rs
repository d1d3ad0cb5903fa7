//! Every one of the 18 project scenes in real MuJoCo: the task's progress joint moved by script
//! through its progress states gives the paper's correctness (V: notches/6; H1–H3: curves
//! cleared/total; H4, H5: mm/200; C: degrees/360; G: 0, 0.5, 1), read by the same tracker the
//! simulated robot runs and scored by `scoring::correctness`. A lab's own MJCF, written here
//! with the lab's joint names, loads by path and its progress is read. (`physics` feature.)

use nalgebra::Isometry3;
use retarget::HandModel;
use scoring::{CorrectnessKind, Mark, PhysicsMapping, TaskCatalog, correctness};
use simulation::progress::{ProgressTracker, Reading};
use teleop::physics::engine::PhysicsEngine;
use teleop::physics::setup::{SceneSource, SimulatedTask, load_task};

/// The arm's default start pose (flange down, above the table).
fn arm_start() -> Isometry3<f64> {
    station::StationConfig::default()
        .arm
        .start_pose_isometry()
        .unwrap()
}

/// How far through its progress a script takes a task.
#[derive(Debug, Clone, Copy)]
enum Script {
    /// Notches or curves: pass the first `n` marks.
    Marks(usize),
    /// Rotation or distance: this fraction of the full amount.
    Fraction(f64),
    /// Grasp: leave the object where it is.
    NotLifted,
    /// Grasp: lift it, set it down beside the target.
    Dropped,
    /// Grasp: lift it, set it down in the target.
    Relocated,
}

/// Move `joint` through the script's states, feeding the tracker; the trial's marks.
fn play(
    engine: &mut PhysicsEngine,
    kind: &CorrectnessKind,
    mapping: &PhysicsMapping,
    script: Script,
) -> Vec<(i64, Mark)> {
    let initial = engine.reading(&mapping.joint).expect("progress joint");
    let mut tracker = ProgressTracker::new(kind, mapping, initial).unwrap();
    let mut marks = Vec::new();
    let mut t = 0.0;
    let states = states(kind, mapping, initial, script);
    let last = states.len() - 1;
    for (i, state) in states.into_iter().enumerate() {
        engine.set_joint(&mapping.joint, &state).unwrap();
        // A grasped object is set down from 2 cm up and left to the physics to settle.
        let settle = matches!(initial, Reading::Body { .. }) && i == last;
        for _ in 0..if settle { 40 } else { 4 } {
            if settle {
                engine.advance(0.05);
                t += 0.05;
            } else {
                t += 0.1;
            }
            let reading = engine.reading(&mapping.joint).unwrap();
            marks.extend(
                tracker
                    .update(reading, t)
                    .into_iter()
                    .map(|e| ((t * 1e9) as i64, e.mark())),
            );
        }
    }
    marks
}

/// The joint coordinates the script passes through.
fn states(
    kind: &CorrectnessKind,
    mapping: &PhysicsMapping,
    initial: Reading,
    script: Script,
) -> Vec<Vec<f64>> {
    let sign = mapping.direction.sign();
    match (script, initial) {
        (Script::Marks(n), Reading::Joint(_)) => {
            let beyond = 3.0
                * mapping.mark_band
                * if mapping.marks.len() > 1 && mapping.marks[1] < mapping.marks[0] {
                    -1.0
                } else {
                    1.0
                };
            mapping.marks[..n]
                .iter()
                .map(|m| vec![m + beyond])
                .collect()
        }
        (Script::Fraction(f), Reading::Joint(q0)) => {
            let full = match kind {
                CorrectnessKind::Rotation { full_deg } => full_deg.to_radians(),
                CorrectnessKind::Distance { full_mm } => full_mm / 1000.0,
                _ => panic!("fraction script for {kind:?}"),
            };
            // In quarter steps, so a hinge is unwrapped as it turns; a hair over, as a
            // ratchet counts whole units.
            (1..=4)
                .map(|k| vec![q0 + sign * (f * full * k as f64 / 4.0 + 1e-4)])
                .collect()
        }
        (grasp, Reading::Body { position_m: p, .. }) => grasp_states(mapping, p, grasp),
        (script, reading) => panic!("script {script:?} does not fit {reading:?}"),
    }
}

fn grasp_states(mapping: &PhysicsMapping, start: [f64; 3], script: Script) -> Vec<Vec<f64>> {
    let grasp = mapping.grasp.as_ref().expect("grasp mapping");
    let pose = |p: [f64; 3]| vec![p[0], p[1], p[2], 1.0, 0.0, 0.0, 0.0];
    let lifted = [start[0], start[1], start[2] + grasp.lift_m + 0.05];
    let centre: Vec<f64> = (0..3)
        .map(|i| 0.5 * (grasp.target_min_m[i] + grasp.target_max_m[i]))
        .collect();
    let in_target = [centre[0], centre[1], start[2] + 0.02];
    let beside = [start[0], start[1] - 0.08, start[2] + 0.02];
    match script {
        Script::NotLifted => vec![pose(start)],
        Script::Dropped => vec![pose(lifted), pose(beside)],
        Script::Relocated => vec![
            pose(lifted),
            pose([in_target[0], in_target[1], lifted[2]]),
            pose(in_target),
        ],
        other => panic!("{other:?} is not a grasp script"),
    }
}

/// Play `script` on `loaded`'s progress joint and check the correctness it scores.
fn assert_scores(
    id: &str,
    task: &scoring::TaskSpec,
    loaded: &mut SimulatedTask,
    script: Script,
    expected: f64,
) {
    let marks = play(
        &mut loaded.engine,
        &task.correctness,
        &loaded.progress,
        script,
    );
    let c = correctness(&task.correctness, &marks, None).unwrap();
    assert!(
        (c.value - expected).abs() < 0.01,
        "{id} {script:?}: correctness {} (expected {expected}), marks {marks:?}",
        c.value
    );
}

#[test]
fn every_scene_scores_its_scripted_progress_as_the_paper_does() {
    let catalog = TaskCatalog::builtin();
    let model = HandModel::orca_v1_right();
    let table: &[(&str, Script, f64)] = &[
        ("V1", Script::Marks(6), 1.0),
        ("V2", Script::Marks(3), 0.5),
        ("V3", Script::Marks(2), 2.0 / 6.0),
        ("H1", Script::Marks(6), 1.0),
        ("H2", Script::Marks(1), 1.0 / 3.0),
        ("H3", Script::Marks(3), 0.75),
        ("H4", Script::Fraction(0.5), 0.5),
        ("H5", Script::Fraction(1.0), 1.0),
        ("C1", Script::Fraction(1.0), 1.0),
        ("C2", Script::Fraction(0.25), 0.25),
        ("C3", Script::Fraction(0.5), 0.5),
        ("C4", Script::Fraction(1.0), 1.0),
        ("G1", Script::Relocated, 1.0),
        ("G2", Script::Dropped, 0.5),
        ("G3", Script::NotLifted, 0.0),
        ("G4", Script::Relocated, 1.0),
        ("G5", Script::Dropped, 0.5),
        ("G6", Script::Relocated, 1.0),
    ];
    let ids: Vec<&str> = table.iter().map(|row| row.0).collect();
    assert_eq!(ids.len(), 18);
    for &(id, script, expected) in table {
        let task = catalog.get(id).unwrap();
        let mut loaded = load_task(
            task,
            &model,
            SceneSource::Project(Default::default()),
            arm_start(),
        )
        .unwrap();
        assert_scores(id, task, &mut loaded, script, expected);
    }
}

/// A lab's own task file as it might be: its own scaffold with the lab's joint names
/// (`disk_rod_slide_joint`, `bolt_hinge`), the hand (here the project's, written with the
/// URDF's names) under a mocap body named `pomdar_arm_mount`.
fn lab_task_file(dir: &std::path::Path) -> std::path::PathBuf {
    use simulation::hand_mjcf::{HandMjcfOptions, hand_mjcf};
    let hand = hand_mjcf(&HandModel::orca_v1_right(), &HandMjcfOptions::default());
    let xml = format!(
        r#"<mujoco model="lab_tasks">
  <compiler angle="radian" autolimits="true"/>
  <default>{defaults}</default>
  <worldbody>
    <geom name="table" type="plane" size="1 1 0.01"/>
    <body name="pomdar_arm_mount" mocap="true" pos="0.45 0 0.6" quat="0 1 0 0">{body}</body>
    <body name="rod" pos="0.6 0.2 0">
      <geom type="cylinder" size="0.004 0.12" pos="0 0 0.12"/>
      <body name="disk" pos="0 0 0.01">
        <joint name="disk_rod_slide_joint" type="slide" axis="0 0 1" range="0 0.22"/>
        <geom type="cylinder" size="0.03 0.004" mass="0.03"/>
      </body>
    </body>
    <body name="bolt" pos="0.6 -0.2 0.05">
      <joint name="bolt_hinge" type="hinge" axis="0 0 1" range="-62.83 0"/>
      <geom type="cylinder" size="0.012 0.01" mass="0.02"/>
    </body>
  </worldbody>
  <actuator>{actuators}</actuator>
  <equality>{equalities}</equality>
</mujoco>"#,
        defaults = hand.defaults,
        body = hand.body,
        actuators = hand.actuators,
        equalities = hand.equalities,
    );
    let path = dir.join("lab_tasks.xml");
    std::fs::write(&path, xml).unwrap();
    path
}

#[test]
fn a_labs_own_file_loads_by_path_and_its_progress_is_read() {
    let dir = std::env::temp_dir().join(format!("pomdar-lab-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = lab_task_file(&dir);
    let catalog = TaskCatalog::builtin();
    let model = HandModel::orca_v1_right();
    for (id, script, expected) in [
        ("V1", Script::Marks(6), 1.0),
        ("V2", Script::Marks(3), 0.5),
        ("C1", Script::Fraction(0.5), 0.5),
    ] {
        let task = catalog.get(id).unwrap();
        let mapping = task
            .physics
            .as_ref()
            .expect("the catalog maps the lab's joint");
        let mut loaded = load_task(task, &model, SceneSource::LabFile(&path), arm_start()).unwrap();
        assert_eq!(&loaded.progress, mapping);
        assert_scores(id, task, &mut loaded, script, expected);
    }
    // A task the catalog does not map is refused with what to add.
    let h1 = catalog.get("H1").unwrap();
    let error = load_task(h1, &model, SceneSource::LabFile(&path), arm_start())
        .err()
        .unwrap();
    assert!(error.to_string().contains("physics"), "{error}");
    std::fs::remove_dir_all(&dir).ok();
}
