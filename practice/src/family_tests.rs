use retarget::human_hand::{GloveScript, ScriptKeyframe, ScriptPose};

use super::*;
use crate::search::Candidate;

fn script() -> GloveScript {
    let mut closed = ScriptKeyframe::new(2.0, [0.1, 0.0, -0.1], ScriptPose::Fist);
    closed.closure = 0.9;
    GloveScript {
        keyframes: vec![
            ScriptKeyframe::new(0.0, [0.0; 3], ScriptPose::Open),
            closed,
            ScriptKeyframe::new(3.0, [0.1, 0.0, 0.0], ScriptPose::Open),
        ],
        dropouts: Vec::new(),
    }
}

fn family() -> StrategyFamily {
    StrategyFamily {
        task: "G4".into(),
        script: script(),
        grips: vec![ScriptPose::PinchIndex],
        bounds: StrategyBounds::DEFAULT,
    }
}

#[test]
fn the_script_as_written_is_the_member_as_written_and_the_start_point() {
    let family = family();
    let strategy = family.strategy(&StrategyParams::AS_WRITTEN);
    assert_eq!(strategy.script, script());
    assert_eq!(strategy.start_offset_m, [0.0; 3]);
    let space = family.space();
    let start = Candidate {
        x: space.dimensions.iter().map(|d| d.start).collect(),
        category: 0,
    };
    assert_eq!(family.params(&start), StrategyParams::AS_WRITTEN);
    assert_eq!(space.categories, 2);
}

#[test]
fn each_parameter_changes_what_it_names_and_nothing_else() {
    let family = family();
    let params = StrategyParams {
        start_offset_mm: [5.0, -3.0, 2.0],
        approach_yaw_deg: 90.0,
        reach_scale: 0.5,
        grip: Grip::Pose(ScriptPose::PinchIndex),
        closure_scale: 1.5,
        time_scale: 0.5,
    };
    let s = family.strategy(&params);
    assert_eq!(s.start_offset_m, [0.005, -0.003, 0.002]);
    let k = &s.script.keyframes;
    assert_eq!(
        k.iter().map(|k| k.t_s).collect::<Vec<_>>(),
        vec![0.0, 1.0, 1.5]
    );
    // 0.1 m along x, halved and turned 90° about the vertical: 0.05 m along y.
    assert!((k[1].wrist_m[0]).abs() < 1e-12 && (k[1].wrist_m[1] - 0.05).abs() < 1e-12);
    assert!(
        (k[1].wrist_m[2] + 0.05).abs() < 1e-12,
        "the vertical is only scaled"
    );
    assert_eq!(
        (k[1].pose, k[1].closure),
        (ScriptPose::PinchIndex, 1.0),
        "closure capped at 1"
    );
    assert_eq!(
        (k[0].pose, k[0].closure),
        (ScriptPose::Open, 1.0),
        "open poses stay"
    );
    assert!(s.script.validate().is_ok());
}

#[test]
fn the_bounds_must_contain_the_script_as_written() {
    assert!(StrategyBounds::DEFAULT.validate().is_ok());
    let mut b = StrategyBounds::DEFAULT;
    b.time_scale = [1.1, 1.3];
    assert!(
        b.validate()
            .unwrap_err()
            .to_string()
            .starts_with("bounds.time_scale")
    );
    let mut b = StrategyBounds::DEFAULT;
    b.start_offset_mm = f64::NAN;
    assert!(b.validate().is_err());
}
