//! Retargeting quality on the lab's real glove recording with the shipped defaults, measured
//! as `pomdar eval` measures it (`retarget::quality`): every distinct frame through the
//! retargeter with the recording's time steps.
//!
//! **A regression guard, not evidence of generalisation**: the defaults were chosen by hand
//! while looking at this recording (and the two other shared ones), so its limits sit close to
//! what they measure here. The held-out figures are elsewhere: leave-one-source-out in
//! `retarget/tuning/tune.py`, and synthetic users of a seed no setting was chosen on, with
//! hands of their own proportions (`tests/tests/suite/eval_cli.rs`,
//! `held_out_users_with_their_own_proportions_close_their_pinches`).
//!
//! dex-retargeting 0.5.0 on the same 727 frames (vector optimiser, its teleop output filter
//! α 0.2): tip error mean 26.1 mm, 0 % of pinches closed, jerk 0.0026 rad, max step 0.18 rad;
//! without the filter 24.9 mm, 0.019 rad, 0.84 rad; DexPilot closes 100 % of pinches at
//! 26.4 mm (filtered) and exceeds the joint limits on most frames.

use crate::common;

use common::recording::{RECORDING, distinct_mano_frames};
use retarget::{EmbodimentCatalog, HandModel, QualityRecorder, RetargetConfig, Retargeter};

#[test]
fn the_defaults_on_the_reference_recording() {
    let Some(path) = common::reference_file("quality_reference", RECORDING) else {
        return;
    };
    let (frames, _) = distinct_mano_frames(&path);
    let config = RetargetConfig::default();
    let model = HandModel::orca_v1_right();
    let mut recorder = QualityRecorder::new(model.clone(), config.layout);
    let mut retargeter = Retargeter::new(model, config, &EmbodimentCatalog::builtin()).unwrap();
    let mut previous_t = None;
    for frame in &frames {
        let dt = previous_t.map_or(0.04, |t| frame.t_s - t);
        previous_t = Some(frame.t_s);
        let solution = retargeter.retarget(&frame.points, dt).unwrap();
        recorder.push(&frame.points, &solution.q).unwrap();
    }
    let q = recorder.report();
    println!("{q:#?}");
    assert_eq!(q.frames, 727);
    assert_eq!(q.limit_violation_frames, 0);
    // The retargeting quality targets on the shipped defaults.
    assert!(q.max_step_rad <= 0.3, "max step {} rad", q.max_step_rad);
    // Jerk: 0.028 rad without the smoothing and input filter, 0.0044 with them
    // (dex-retargeting: 0.019 unfiltered, 0.0026 with its output filter at 26.1 mm).
    assert!(q.jerk_rad <= 0.005, "jerk {} rad", q.jerk_rad);
    assert!(q.pinch_frames > 0);
    let closed = q.pinches_closed_pct.unwrap();
    assert!(closed >= 90.0, "{closed} % of pinches closed");
    // Better than dex-retargeting's 26.1 mm (vector, filtered) and 24.9 mm (unfiltered); 23.3
    // mm measured with the defaults (hand-chosen looking at this recording among others, so a
    // guard, not a held-out figure). The 22 mm target is not reached: the ORCA thumb cannot reach where the
    // glove's thumb tip is (its abduction and PIP sit on their limits; 44 mm at best at the
    // mean thumb target) and the glove's index tip points past the ORCA index abduction limit
    // (36 mm). Without the smoothing the defaults measure 22.1 mm at 0.025 rad of jerk: the
    // smoothing's lag costs middle, ring and little about 2 mm each. Guard against worse.
    assert!(
        q.tip_error_mean_mm <= 24.0,
        "tip error {} mm",
        q.tip_error_mean_mm
    );
}
