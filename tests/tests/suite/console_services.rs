//! The operator console driven through its ROS services, as a lab's own tool would: a
//! `pomdar trial --simulate` console (simulated glove and mock robot on loopback DDS) is
//! engaged, its trial started and stopped by `std_srvs/srv/Trigger` calls from a ros2-client
//! node, and the console carries them out as its own keys (the trial is recorded and scored as a
//! finished one).

use std::time::Duration;

use pomdar_tests::line_console::LineConsole;
use pomdar_tests::station_harness::{loopback, test_domain};
use pomdar_tests::{scratch_dir, session_trial_statuses};
use ros2_client::ServiceMapping;
use station::StationConfig;
use teleop::ros::NetworkContext as _;
use teleop::ros::{RosNode, TriggerRequest};

/// The console's arguments. The start gate allows 1 s of glove input age: on a loaded 2-core
/// CI machine the in-process simulated glove once went 201 ms without a frame and cancelled
/// the countdown (the gate itself is tested in `console::health`; this test is about the
/// services).
fn console_args(dir: &std::path::Path, domain: u16) -> Vec<String> {
    let fixed = [
        "trial",
        "--task",
        "V1",
        "--user",
        "svc",
        "--operator",
        "ci",
        "--practice",
        "0",
        "--trials",
        "2",
        "--plain",
        "--simulate",
        "--countdown",
        "0.3",
        "--interface",
        "127.0.0.1",
        "--domain-id",
    ];
    fixed
        .iter()
        .map(|s| s.to_string())
        .chain([
            domain.to_string(),
            "--out".into(),
            dir.display().to_string(),
        ])
        .collect()
}

/// Call `service` once and return its answer.
async fn call(node: &mut RosNode, service: &str) -> msgs::TriggerResponse {
    let client = node
        .trigger_client(service, ServiceMapping::Enhanced)
        .unwrap();
    tokio::time::timeout(
        Duration::from_secs(30),
        client.wait_for_service(node.node()),
    )
    .await
    .unwrap_or_else(|_| panic!("{service} did not match in 30 s"));
    tokio::time::timeout(
        Duration::from_secs(10),
        client.async_call_service(TriggerRequest::default()),
    )
    .await
    .unwrap_or_else(|_| panic!("{service}: no answer in 10 s"))
    .unwrap_or_else(|e| panic!("{service}: {e:?}"))
    .0
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn services_engage_start_and_stop_a_trial_as_the_operators_keys_do() {
    let root = scratch_dir("console_services");
    let domain = test_domain();
    let console = LineConsole::start(&console_args(&root, domain));
    console.wait_for("WAITING FOR ENGAGE", 60.0);
    let context = loopback(domain).context().unwrap();
    let mut node = RosNode::new(&context, "/", "pomdar_lab_tool").unwrap();
    let services = StationConfig::default().ros_tools.services;

    let answer = call(&mut node, &services.engage).await;
    assert!(
        answer.success && answer.message.contains("console"),
        "{answer:?}"
    );
    console.wait_for("READY", 30.0);

    let answer = call(&mut node, &services.trial_start).await;
    assert!(
        answer.success && answer.message.contains("console"),
        "{answer:?}"
    );
    console.wait_for("RUNNING · trial 1/2", 30.0);
    std::thread::sleep(Duration::from_millis(800));

    let answer = call(&mut node, &services.trial_stop).await;
    assert!(answer.success, "{answer:?}");
    console.wait_for("last trial 1: completed", 30.0);
    drop(console);

    let statuses = session_trial_statuses(&root.join("svc/orca_full/V1"));
    // The trial the services started and stopped was logged and scored as a finished one.
    assert_eq!(
        statuses,
        [("V1-t01.mcap".to_string(), "scored".to_string())]
    );
}
