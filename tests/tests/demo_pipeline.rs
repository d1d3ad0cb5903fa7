//! The demo pipeline end to end over loopback DDS: the simulated glove node → the station →
//! the mock ORCA hand and mock Franka nodes, each on its own participant, as `pomdar demo`
//! runs them.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

use pomdar_tests::station_harness::test_domain;
use teleop::arm::Constraint;
use teleop::demo::{DemoOptions, run_demo};
use teleop::sim::sim_glove_node::SimGloveConfig;
use teleop::station::station_config::StationConfig;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sim_glove_station_mock_hand_and_arm() {
    let mut station = StationConfig::default();
    station.arm.constraint = Constraint::HorizontalAxis;
    let arm = station.arm.clone();
    let outcome = run_demo(DemoOptions {
        duration_s: 3.0,
        domain_id: test_domain(6),
        station,
        glove: SimGloveConfig::default(),
        live: false,
    })
    .await
    .unwrap();
    let s = &outcome.summary;
    println!("{}", serde_json::to_string(s).unwrap());
    assert!(s.input_rate_hz > 80.0, "glove at {} Hz", s.input_rate_hz);
    assert!(
        (20.0..=30.0).contains(&s.output_rate_hz),
        "joint targets at {} Hz (25 configured)",
        s.output_rate_hz
    );
    assert_eq!(s.rejected_frames, 0);
    assert_eq!(outcome.hand.rejected, 0);
    assert!(outcome.hand.last_target.is_some());

    // The mock arm's targets: on the horizontal axis line through the first, inside the box,
    // within the step caps.
    let targets = &outcome.arm.targets;
    assert!(targets.len() > 40, "{} arm targets", targets.len());
    let first = targets[0].translation.vector;
    for (i, t) in targets.iter().enumerate() {
        let p = t.translation.vector;
        assert!(
            (p.y - first.y).abs() < 1e-9 && (p.z - first.z).abs() < 1e-9,
            "target {i} off the x axis: {p}"
        );
        for k in 0..3 {
            assert!(p[k] >= arm.workspace_min_m[k] - 1e-9 && p[k] <= arm.workspace_max_m[k] + 1e-9);
        }
        if i > 0 {
            assert!(
                (p - targets[i - 1].translation.vector).norm() <= arm.max_translation_step_m + 1e-9
            );
            assert!(
                t.rotation.angle_to(&targets[i - 1].rotation) <= arm.max_rotation_step_rad + 1e-9
            );
        }
    }
}
