//! `pomdar relay`'s node on loopback DDS: commands on the relay topic, sent with chosen DDS
//! source timestamps and header stamps, reach the robot's topic when fresh and are dropped,
//! and counted, when older than `[robot_link] max_age_ms` by either time (one too old by its
//! header stamp only is counted as such), sent "in the future" by more than it, or
//! after.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use futures::StreamExt as _;
use msgs::JointState;
use pomdar_tests::stamped_glove::StampedWriter;
use pomdar_tests::station_harness::{loopback, test_domain};
use station::StationConfig;
use teleop::clock::{StationClock, WallClock};
use teleop::relay_node::{RelayReport, RelaySettings, run_relay};
use teleop::ros::{QosConfig, RosNode};
use tokio::sync::watch;

const MS: i64 = 1_000_000;

/// A joint target marked `marker`, its header stamp `stamp_ns` (0: unset).
fn command(marker: f64, stamp_ns: i64) -> JointState {
    JointState {
        header: station::convert::header(stamp_ns, ""),
        name: vec!["right_index_mcp".into()],
        position: vec![marker],
        ..JointState::default()
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_relay_forwards_fresh_commands_and_drops_old_and_future_ones() {
    let mut config = StationConfig::default();
    config.robot_link.relay_prefix = "/pomdar/link".into();
    let settings = RelaySettings::of(&config).expect("a relaying configuration");
    let route = settings.routes.joint_targets.clone().unwrap();
    assert_eq!(route.from, "/pomdar/link/pomdar/hand/joint_targets");
    let network = loopback(test_domain());
    let report = Arc::new(Mutex::new(RelayReport::default()));
    let (stop, shutdown) = watch::channel(false);
    let relay = {
        let (network, report) = (network.clone(), Arc::clone(&report));
        tokio::spawn(async move {
            run_relay(&settings, &network, WallClock::system(), &report, shutdown).await
        })
    };
    let mut robot = RosNode::join(&network, "/", "robot_driver").unwrap();
    let driver = robot
        .subscription::<JointState>(&route.to, QosConfig::reliable(50))
        .unwrap();
    let station =
        StampedWriter::<JointState>::new(&network, &route.from, QosConfig::best_effort(50))
            .unwrap();
    station
        .wait_for_reader(Duration::from_secs(10))
        .await
        .unwrap();
    // The relay's robot-side writer must have matched the driver before anything is sent.
    tokio::time::sleep(Duration::from_millis(500)).await;

    let clock = StationClock::new();
    // (marker, send time offset, header stamp's age when sent; None: unset)
    let sent = [
        (1.0, 0, None),
        (2.0, -5_000 * MS, None),
        (3.0, 5_000 * MS, None),
        (4.0, -101 * MS, None),
        (5.0, 0, Some(20 * MS)),
        (6.0, 0, Some(150 * MS)),
        (7.0, 0, None),
    ];
    for (marker, offset, stamp_age) in sent {
        let now = clock.now_ns();
        let stamp = stamp_age.map_or(0, |age| now - age);
        station
            .write(command(marker, stamp), now + offset)
            .await
            .unwrap();
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let mut heard = Vec::new();
    let mut stream = Box::pin(driver.async_stream());
    while heard.len() < 3 {
        let next = tokio::time::timeout(Duration::from_secs(10), stream.next()).await;
        let (message, _) = next
            .expect("the relay forwarded too little")
            .unwrap()
            .unwrap();
        heard.push(message.position[0]);
    }
    // Anything else would have arrived by now, in order, before the last fresh one.
    assert_eq!(heard, [1.0, 5.0, 7.0], "forwarded commands");
    stop.send(true).unwrap();
    relay.await.unwrap().unwrap();
    let report = report.lock().unwrap();
    let ages = &report.topics[&route.to].ages;
    assert_eq!(
        (
            ages.forwarded,
            ages.too_old,
            ages.too_old_by_stamp,
            ages.from_the_future
        ),
        (3, 3, 1, 1),
        "{report:?}"
    );
    assert!(ages.oldest_dropped_ns >= 5_000 * MS, "{report:?}");
}
