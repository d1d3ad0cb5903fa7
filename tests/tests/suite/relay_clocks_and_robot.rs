//! A station behind `pomdar relay`, every part its own `pomdar` process on loopback DDS as a
//! lab runs them: `pomdar sim-glove`, the operator console (`pomdar trial`), `pomdar relay`
//! with its clock 80 ms ahead of the station's (the test knob `POMDAR_TEST_CLOCK_OFFSET_MS`:
//! two computers out of step, on one), and `pomdar mock-hand` as the robot's driver on the
//! robot's topic.
//!
//! - The relay warns, naming the offset, and the station's status carries its estimate.
//! - The station sees the robot's driver through the relay: one hand listening; with the
//!   driver stopped, none, and the console warns at the next trial's start that no hand is
//!   listening (and did not at the first).

use std::time::{Duration, Instant};

use futures::StreamExt as _;
use msgs::StringMsg;
use pomdar_tests::line_console::LineConsole;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::{lab_tool_node, test_domain};
use serde_json::Value;
use station::StationConfig;
use teleop::ros::{QosConfig, RosNode};

const OFFSET_MS: i64 = 80;

/// The station's configuration: the defaults, its commands through a relay.
fn relayed_config(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("relayed.toml");
    std::fs::write(
        &path,
        "[robot_link]\nrelay_prefix = \"/pomdar/link\"\nmax_age_ms = 100\n",
    )
    .unwrap();
    path
}

/// `pomdar ARGS --interface 127.0.0.1 --domain-id DOMAIN`.
fn args(args: &[&str], domain: u16) -> Vec<String> {
    let mut all: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    all.extend(["--interface", "127.0.0.1", "--domain-id"].map(String::from));
    all.push(domain.to_string());
    all
}

/// Statuses of the station, as a lab tool reads them (on its own runtime).
struct StatusWatch {
    runtime: tokio::runtime::Runtime,
    node: Option<RosNode>,
    subscription: Option<ros2_client::Subscription<StringMsg>>,
}

impl StatusWatch {
    fn open(domain: u16) -> StatusWatch {
        let (runtime, mut node) = lab_tool_node(domain, "status_watch", 1);
        let topic = StationConfig::default().output.status_topic;
        let subscription = node
            .subscription::<StringMsg>(&topic, QosConfig::reliable(10))
            .unwrap();
        StatusWatch {
            runtime,
            node: Some(node),
            subscription: Some(subscription),
        }
    }

    /// The first status `accept` takes within `timeout`, else a panic naming `what` and the
    /// last status seen.
    fn wait_for(&self, what: &str, timeout: Duration, accept: impl Fn(&Value) -> bool) -> Value {
        let subscription = self.subscription.as_ref().unwrap();
        self.runtime.block_on(async {
            let mut stream = Box::pin(subscription.async_stream());
            let deadline = Instant::now() + timeout;
            let mut last = Value::Null;
            while let Some(left) = deadline.checked_duration_since(Instant::now()) {
                let Ok(Some(Ok((message, _)))) = tokio::time::timeout(left, stream.next()).await
                else {
                    continue;
                };
                last = serde_json::from_str(&message.data).unwrap_or(Value::Null);
                if accept(&last) {
                    return last;
                }
            }
            panic!("no station status with {what} in {timeout:?}; the last:\n{last:#}");
        })
    }
}

impl Drop for StatusWatch {
    fn drop(&mut self) {
        // The endpoints before their node, the node before its runtime.
        self.subscription.take();
        self.node.take();
    }
}

fn hand_listeners(status: &Value) -> Option<u64> {
    status.pointer("/listeners/hand").and_then(Value::as_u64)
}

#[test]
fn behind_a_relay_the_clock_offset_is_named_and_a_stopped_driver_is_no_hand_listening() {
    let dir = scratch_dir("relay_clocks_and_robot");
    let domain = test_domain();
    let config = relayed_config(&dir);
    let config = config.to_str().unwrap();
    let offset = OFFSET_MS.to_string();
    let relay = LineConsole::start_with_env(
        &args(&["relay", "--config", config], domain),
        &[("POMDAR_TEST_CLOCK_OFFSET_MS", &offset)],
    );
    let mut driver = LineConsole::start(&args(&["mock-hand"], domain));
    let _glove = LineConsole::start(&args(&["sim-glove", "--rate-hz", "100"], domain));
    let out = dir.join("trials").display().to_string();
    let mut console = LineConsole::start(&args(
        &[
            "trial",
            "--config",
            config,
            "--task",
            "V1",
            "--user",
            "relay",
            "--operator",
            "ci",
            "--practice",
            "0",
            "--trials",
            "2",
            "--plain",
            "--countdown",
            "0.3",
            "--out",
            &out,
        ],
        domain,
    ));
    let watch = StatusWatch::open(domain);
    console.wait_for("WAITING FOR ENGAGE", 60.0);
    console.say("engage");
    console.wait_for("READY", 30.0);

    // Commands flow through the relay: its offset estimate reaches the station's status.
    let status = watch.wait_for(
        "the relay's clock offset and one hand listening",
        Duration::from_secs(30),
        |s| {
            s.pointer("/listeners/relay/status/clock_offset_ms")
                .is_some_and(|v| !v.is_null())
                && hand_listeners(s) == Some(1)
        },
    );
    let estimate = status
        .pointer("/listeners/relay/status/clock_offset_ms")
        .and_then(Value::as_f64)
        .unwrap();
    assert!(
        (OFFSET_MS as f64..OFFSET_MS as f64 + 10.0).contains(&estimate),
        "the relay's estimate {estimate} ms for a {OFFSET_MS} ms offset"
    );
    relay.wait_for(
        "the station's clock is about 80 ms behind this computer's",
        15.0,
    );

    // A trial with the driver listening: no warning.
    console.say("start");
    console.wait_for("RUNNING · trial 1/2", 30.0);
    console.say("stop");
    console.wait_for("last trial 1", 30.0);
    let warning = "no robot hand is listening";
    assert_eq!(console.count(warning), 0, "{}", console.printed());

    // The robot's driver stops: the station sees no hand behind the relay.
    assert_eq!(driver.interrupt(), Some(0), "{}", driver.printed());
    watch.wait_for("no hand listening", Duration::from_secs(15), |s| {
        hand_listeners(s) == Some(0)
    });
    console.say("start");
    console.wait_for(warning, 30.0);
    console.wait_for("RUNNING · trial 2/2", 30.0);
    console.say("stop");
    console.wait_for("last trial 2", 30.0);
}
