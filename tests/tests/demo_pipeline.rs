//! The demo pipeline end to end over loopback DDS: the simulated glove node → the station →
//! the mock ORCA hand and mock Franka nodes, each on its own participant, as `pomdar demo`
//! runs them.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

use pomdar_tests::station_harness::{check_arm_targets, test_domain};
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
    assert!(
        outcome.arm.targets.len() > 40,
        "{} arm targets",
        outcome.arm.targets.len()
    );
    check_arm_targets(&outcome.arm.targets, &arm, Some(arm.horizontal_axis));
}
