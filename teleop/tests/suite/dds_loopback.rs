//! Real DDS on loopback: a `msgs` JointState published by one node arrives intact at another,
//! on a test-unique domain id and loopback-only discovery.

use std::time::Duration;

use msgs::{Header, JointState, Time};
use teleop::ros::NetworkContext as _;
use teleop::ros::domain_lease::{TEST_DOMAINS, lease_domain};
use teleop::ros::{NetworkConfig, QosConfig, RosNode};

fn loopback(domain: u16) -> NetworkConfig {
    NetworkConfig {
        domain_id: Some(domain),
        interfaces: vec!["127.0.0.1".parse().unwrap()],
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn joint_states_cross_loopback_dds_intact() {
    let domain = lease_domain(TEST_DOMAINS).unwrap();
    let talker_context = loopback(domain).context().unwrap();
    let listener_context = loopback(domain).context().unwrap();
    let mut talker = RosNode::new(&talker_context, "/pomdar_test", "talker").unwrap();
    let mut listener = RosNode::new(&listener_context, "/pomdar_test", "listener").unwrap();
    let publisher = talker
        .publisher::<JointState>("/test/joint_states", QosConfig::reliable(50))
        .unwrap();
    let subscription = listener
        .subscription::<JointState>("/test/joint_states", QosConfig::reliable(50))
        .unwrap();

    // Wait for the match (never a fixed sleep), bounded.
    let start = std::time::Instant::now();
    while publisher.get_subscription_count(talker.node()) == 0 {
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "no match in 10 s"
        );
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    println!("matched after {:?}", start.elapsed());

    let sent: Vec<JointState> = (0..20)
        .map(|i| JointState {
            header: Header {
                stamp: Time::from_nanos(1_000_000_000 + i),
                frame_id: "orca".into(),
            },
            name: vec!["index_mcp".into(), "index_pip".into()],
            position: vec![0.1 * i as f64, -0.2],
            velocity: vec![],
            effort: vec![],
        })
        .collect();
    for message in &sent {
        publisher.async_publish(message.clone()).await.unwrap();
        tokio::time::sleep(Duration::from_millis(2)).await;
    }
    let mut received = Vec::new();
    while received.len() < sent.len() {
        let (message, _info) =
            tokio::time::timeout(Duration::from_secs(5), subscription.async_take())
                .await
                .expect("timed out waiting for a joint state")
                .unwrap();
        received.push(message);
    }
    assert_eq!(received, sent);
}
