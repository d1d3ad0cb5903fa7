//! The operator console driven through its ROS services, as a lab's own tool would: a
//! `pomdar trial --simulate` console (simulated glove and mock robot on loopback DDS) is
//! engaged, its trial started and stopped by `std_srvs/srv/Trigger` calls from a ros2-client
//! node, and the console carries them out as its own keys (the trial is recorded and scored as a
//! finished one).
//!
//! The tool retries a call whose answer did not come: DDS discovery is not symmetric, and
//! ros2-client's `wait_for_service` says only that this side has discovered the service's
//! endpoints; until the console's response writer has discovered this tool's response reader,
//! an answer is sent to no one (seen on a 2-core machine with two busy CPU hogs: an engage
//! unanswered for 10 s). Before a retry the tool checks on the console whether the call was
//! carried out (an answer lost, not a request), as a lab's tool would look at the station.

use std::time::Duration;

use pomdar_tests::line_console::LineConsole;
use pomdar_tests::station_harness::{lab_tool_node, test_domain};
use pomdar_tests::{scratch_dir, session_trial_statuses};
use ros2_client::ServiceMapping;
use station::StationConfig;
use teleop::ros::{RosNode, TriggerRequest};

/// The console's arguments (the start gate's defaults).
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

/// How a call ended.
enum Called {
    /// The service answered.
    Answered(msgs::TriggerResponse),
    /// No answer, but the console shows the call carried out (the answer was lost).
    CarriedOut,
}

/// Call `service` until it answers (5 s per attempt, 6 attempts), unless the console prints
/// `done` first: then its answer was lost, and the call is not repeated.
async fn call(node: &mut RosNode, service: &str, console: &LineConsole, done: &str) -> Called {
    let client = node
        .trigger_client(service, ServiceMapping::Enhanced)
        .unwrap();
    tokio::time::timeout(
        Duration::from_secs(30),
        client.wait_for_service(node.node()),
    )
    .await
    .unwrap_or_else(|_| panic!("{service} did not match in 30 s"));
    for attempt in 1..=6 {
        let answer = tokio::time::timeout(
            Duration::from_secs(5),
            client.async_call_service(TriggerRequest::default()),
        )
        .await;
        match answer {
            Ok(answer) => {
                let answer = answer.unwrap_or_else(|e| panic!("{service}: {e:?}"));
                return Called::Answered(answer.0);
            }
            Err(_) if console.printed().contains(done) => return Called::CarriedOut,
            Err(_) => eprintln!("{service}: no answer in 5 s (attempt {attempt}); calling again"),
        }
    }
    panic!("{service}: no answer to 6 calls, and the console did not carry it out");
}

/// The answer, if any, says the console carried the call out.
fn assert_by_console(called: &Called) {
    if let Called::Answered(answer) = called {
        assert!(
            answer.success && answer.message.contains("console"),
            "{answer:?}"
        );
    }
}

/// The lab tool's node runs on its own runtime's workers; this thread only blocks on the
/// console's output between calls (blocking a worker instead could stall the node's spinner,
/// and with it discovery and the answers, behind the wait).
#[test]
fn services_engage_start_and_stop_a_trial_as_the_operators_keys_do() {
    let root = scratch_dir("console_services");
    let domain = test_domain();
    let console = LineConsole::start(&console_args(&root, domain));
    console.wait_for("WAITING FOR ENGAGE", 60.0);
    let (runtime, mut node) = lab_tool_node(domain, "pomdar_lab_tool", 2);
    let services = StationConfig::default().ros_tools.services;

    let engaged = runtime.block_on(call(&mut node, &services.engage, &console, "READY"));
    assert_by_console(&engaged);
    console.wait_for("READY", 30.0);

    let running = "RUNNING · trial 1/2";
    let started = runtime.block_on(call(&mut node, &services.trial_start, &console, running));
    assert_by_console(&started);
    console.wait_for(running, 30.0);
    std::thread::sleep(Duration::from_millis(800));

    let done = "last trial 1: completed";
    if let Called::Answered(answer) =
        runtime.block_on(call(&mut node, &services.trial_stop, &console, done))
    {
        assert!(answer.success, "{answer:?}");
    }
    console.wait_for(done, 30.0);
    drop(console);

    let statuses = session_trial_statuses(&root.join("svc/orca_full/V1"));
    // The trial the services started and stopped was logged and scored as a finished one.
    assert_eq!(
        statuses,
        [("V1-t01.mcap".to_string(), "scored".to_string())]
    );
    // The node's endpoints before its runtime (its spinner task holds the context).
    drop(node);
}
