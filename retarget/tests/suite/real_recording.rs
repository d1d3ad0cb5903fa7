//! Real data: every distinct frame of the lab's 30 s Rokoko recording (22-point layout)
//! retargets to the ORCA v1 hand with the default configuration, without a failure.

use crate::common;

use common::recording::{RECORDING, distinct_mano_frames};
use retarget::{EmbodimentCatalog, HandModel, QpMethod, RetargetConfig, Retargeter, SolveStatus};

/// Longest time step the rate limit credits (default `solver.max_rate_dt_s`) times the default
/// joint speed limit: no command may move a joint further in one frame.
fn max_step_rad(config: &RetargetConfig) -> f64 {
    config.solver.max_joint_speed_rad_s * config.solver.max_rate_dt_s
}

#[test]
fn every_frame_of_the_reference_recording_retargets() {
    let Some(path) = common::reference_file("real_recording", RECORDING) else {
        return;
    };
    let (frames, messages) = distinct_mano_frames(&path);
    let config = RetargetConfig::default();
    let step_bound = max_step_rad(&config);
    let model = HandModel::orca_v1_right();
    let mut retargeter =
        Retargeter::new(model.clone(), config, &EmbodimentCatalog::builtin()).unwrap();

    let mut previous = retargeter.command().to_vec();
    let mut previous_t = None;
    let (mut tip_error_sum, mut max_step, mut not_converged) = (0.0, 0.0_f64, 0);
    for frame in &frames {
        let dt = previous_t.map_or(0.04, |t| frame.t_s - t);
        previous_t = Some(frame.t_s);
        let solution = retargeter
            .retarget(&frame.points, dt)
            .unwrap_or_else(|e| panic!("frame at {:.3} s rejected: {e}", frame.t_s));
        assert!(
            !matches!(solution.status, SolveStatus::QpFailed(_)),
            "frame at {:.3} s: {:?}",
            frame.t_s,
            solution.status
        );
        assert!(
            model.within_limits(&solution.q),
            "frame at {:.3} s outside limits",
            frame.t_s
        );
        not_converged += usize::from(solution.status == SolveStatus::StepLimit);
        tip_error_sum += solution.tip_error_m;
        for (a, b) in solution.q.iter().zip(&previous) {
            max_step = max_step.max((a - b).abs());
        }
        previous = solution.q;
    }
    let mean_tip_error = tip_error_sum / frames.len() as f64;
    println!(
        "{RECORDING}: {messages} messages, {} distinct frames; mean key-vector (palm→tip) error \
         {:.1} mm at scale 1, max joint step {:.3} rad, {not_converged} frames ended on the step \
         budget",
        frames.len(),
        mean_tip_error * 1e3,
        max_step
    );
    // The recording holds ~24 glove frames a second for 30 s.
    assert!(frames.len() > 600, "only {} distinct frames", frames.len());
    // Uncalibrated (scale 1), a human hand and the ORCA hand differ by about a centimetre per
    // fingertip vector; 40 mm mean would mean the fit is failing, not the sizes differing.
    assert!(mean_tip_error < 0.04, "mean tip error {mean_tip_error} m");
    // The rate limit holds on real data.
    assert!(
        max_step <= step_bound + 1e-9,
        "max step {max_step} rad > {step_bound}"
    );
}

/// The two QP methods solve the same QPs: on every frame of the recording, retargeted frame
/// after frame (so a difference would also carry forward), the commands agree to 1e-4 rad
/// (Clarabel stops at its interior-point tolerance; measured: 1.2e-5 rad at most).
#[test]
fn active_set_and_clarabel_give_the_same_commands() {
    let Some(path) = common::reference_file("real_recording", RECORDING) else {
        return;
    };
    let (frames, _) = distinct_mano_frames(&path);
    let retargeter = |method| {
        let mut config = RetargetConfig::default();
        config.solver.qp_method = method;
        Retargeter::new(
            HandModel::orca_v1_right(),
            config,
            &EmbodimentCatalog::builtin(),
        )
        .unwrap()
    };
    let mut active_set = retargeter(QpMethod::ActiveSet);
    let mut clarabel = retargeter(QpMethod::Clarabel);
    let (mut worst, mut interior_point_iterations) = (0.0_f64, [0u64; 2]);
    for frame in &frames {
        let a = active_set.retarget(&frame.points, 0.04).unwrap();
        let c = clarabel.retarget(&frame.points, 0.04).unwrap();
        interior_point_iterations[0] += u64::from(a.qp_iterations);
        interior_point_iterations[1] += u64::from(c.qp_iterations);
        for (x, y) in a.q.iter().zip(&c.q) {
            worst = worst.max((x - y).abs());
        }
    }
    println!(
        "largest command difference {worst:.2e} rad; interior-point iterations: active set \
         {}, Clarabel {}",
        interior_point_iterations[0], interior_point_iterations[1]
    );
    assert!(worst < 1e-4, "the methods differ by {worst} rad");
    assert!(
        interior_point_iterations[1] > 0,
        "the Clarabel method must run Clarabel"
    );
}
