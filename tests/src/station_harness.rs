//! A station under test on real loopback DDS: the station node runs as in production, and a
//! test node plays the glove and listens to every output, recording what arrives and when.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::{Float32MultiArray, JointState, PoseStamped, RosMessage, StringMsg};
use nalgebra::{Isometry3, Point3};
use retarget::HandModel;
use station::StationConfig;
use station::convert::{header, isometry_to_pose};
use teleop::clock::StationClock;
use teleop::ros::NetworkContext as _;
use teleop::ros::{NetworkConfig, QosConfig, RosNode};
use teleop::station_node::operator::StationHooks;
use teleop::station_node::recorder::RecordingOptions;
use teleop::station_node::ros_node::{OperatorCommand, StationSummary, run_station_observed};
use tokio::sync::{mpsc, watch};
use tokio::task::JoinHandle;

/// A ROS domain id of the calling test's own: leased on this machine for as long as the test
/// process lives ([`teleop::ros::domain_lease`]), so that tests running side by side, in one
/// test binary or in several processes, never hear each other. Each call leases a new id.
///
/// # Panics
/// When no id can be leased (a test's failure report).
pub fn test_domain() -> u16 {
    use teleop::ros::domain_lease::{TEST_DOMAINS, lease_domain};
    lease_domain(TEST_DOMAINS).unwrap_or_else(|e| panic!("{e}"))
}

/// Loopback-only network on `domain`.
pub fn loopback(domain: u16) -> NetworkConfig {
    NetworkConfig {
        domain_id: Some(domain),
        interfaces: vec![std::net::IpAddr::from([127, 0, 0, 1])],
    }
}

/// A node named `name` on loopback `domain`, as a lab's own tool runs one: on a runtime of its
/// own with `workers` threads, so a test thread that blocks between calls (on a console's
/// output) never stalls the node's spinner, and with it discovery. Drop the node's endpoints,
/// then the node, then the runtime.
///
/// # Panics
/// When the runtime or the node cannot be built (a test's failure report).
pub fn lab_tool_node(
    domain: u16,
    name: &str,
    workers: usize,
) -> (tokio::runtime::Runtime, RosNode) {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(workers)
        .enable_all()
        .build()
        .unwrap_or_else(|e| panic!("runtime: {e}"));
    let context = loopback(domain)
        .context()
        .unwrap_or_else(|e| panic!("DDS context: {e}"));
    let node = runtime
        .block_on(async { RosNode::new(&context, "/", name) })
        .unwrap_or_else(|e| panic!("node {name}: {e}"));
    (runtime, node)
}

/// A station configuration whose joint targets do not depend on when frames arrive: every
/// frame is retargeted, the joint-speed limit never binds, the input filter (whose history is
/// the frames the station took, fewer when a burst is coalesced), the smoothing's release
/// by its speed estimate and by a pinch's approach (whose history is the same frames) are off, the station engages on fresh input and stays engaged through
/// 5 s without a changed frame (a noise-free simulated hand that holds still sends exact
/// repeats, which refresh nothing), and inputs and outputs are reliable with deep queues. Its targets equal an in-process retargeter's (or
/// re-simulation's) fed the same frames, or started from the command before.
pub fn timing_independent_config() -> StationConfig {
    let mut config = StationConfig::default();
    config.control.mode = station::ControlMode::OnArrival;
    config.control.auto_engage = true;
    config.input.qos = QosConfig::reliable(2000);
    config.output.qos = QosConfig::reliable(2000);
    config.retarget.solver.max_joint_speed_rad_s = 100.0;
    config.retarget.solver.max_rate_dt_s = 1.0;
    config.retarget.input_filter.min_cutoff_hz = 0.0;
    config.retarget.smoothing.release_speed_m_s = 0.0;
    config.retarget.smoothing.approach_speed_m_s = 0.0;
    config.watchdog.disengage_timeout_ms = 5000;
    config
}

/// Everything the test node heard, with receive times (station clock, ns).
#[derive(Debug, Default)]
pub struct Heard {
    /// Joint targets.
    pub targets: Vec<(i64, JointState)>,
    /// Arm targets.
    pub arm: Vec<(i64, PoseStamped)>,
    /// Status documents.
    pub status: Vec<(i64, serde_json::Value)>,
}

/// The running station and the test's glove/listener node.
pub struct Harness {
    /// The clock shared with the station.
    pub clock: StationClock,
    /// What was heard so far.
    pub heard: Arc<Mutex<Heard>>,
    shutdown: watch::Sender<bool>,
    operator: mpsc::UnboundedSender<OperatorCommand>,
    station: JoinHandle<Result<StationSummary, teleop::station_node::NodeError>>,
    /// The test node (keep alive).
    pub node: RosNode,
    keypoints: ros2_client::Publisher<Float32MultiArray>,
    wrist: ros2_client::Publisher<PoseStamped>,
    /// The network the station runs on.
    pub network: NetworkConfig,
    listeners: Vec<JoinHandle<()>>,
}

fn collect<M, F>(
    sub: ros2_client::Subscription<M>,
    clock: StationClock,
    heard: Arc<Mutex<Heard>>,
    push: F,
) -> JoinHandle<()>
where
    M: serde::de::DeserializeOwned + Send + Sync + 'static,
    F: Fn(&mut Heard, i64, M) + Send + 'static,
{
    tokio::spawn(async move {
        let mut stream = Box::pin(sub.async_stream());
        while let Some(item) = stream.next().await {
            if let Ok((message, _)) = item {
                let now = clock.now_ns();
                if let Ok(mut heard) = heard.lock() {
                    push(&mut heard, now, message);
                }
            }
        }
    })
}

impl Harness {
    /// The joint positions of every joint target heard so far, in arrival order.
    #[allow(clippy::unwrap_used)] // a poisoned lock means a test thread already panicked
    pub fn target_positions(&self) -> Vec<Vec<f64>> {
        self.heard
            .lock()
            .unwrap()
            .targets
            .iter()
            .map(|(_, m)| m.position.clone())
            .collect()
    }

    /// Start a station with `config` (its network replaced by loopback on `domain`) and a test
    /// node, and wait until the glove topics and outputs are matched.
    pub async fn start(config: StationConfig, domain: u16) -> anyhow::Result<Harness> {
        Harness::start_recording(config, domain, None).await
    }

    /// [`Harness::start`], the station recording its run to `recording` (finished when the
    /// harness stops).
    pub async fn start_recording(
        config: StationConfig,
        domain: u16,
        recording: Option<RecordingOptions>,
    ) -> anyhow::Result<Harness> {
        let model = HandModel::orca_v1_right();
        Harness::start_with(config, model, StationHooks::default(), domain, recording).await
    }

    /// [`Harness::start_recording`] with a hand `model` of the test's choice and the
    /// station's `hooks` (e.g. a robot description to publish).
    pub async fn start_with(
        mut config: StationConfig,
        model: HandModel,
        hooks: StationHooks,
        domain: u16,
        recording: Option<RecordingOptions>,
    ) -> anyhow::Result<Harness> {
        let network = loopback(domain);
        config.network = network.clone();
        config.validate()?;
        let clock = StationClock::new();
        let (shutdown, shutdown_rx) = watch::channel(false);
        let (operator, operator_rx) = mpsc::unbounded_channel();
        let station = tokio::spawn(run_station_observed(
            config.clone(),
            model,
            clock,
            shutdown_rx,
            operator_rx,
            recording,
            hooks,
        ));

        let context = network.context()?;
        let mut node = RosNode::new(&context, "/", "pomdar_test")?;
        let keypoints = node.publisher::<Float32MultiArray>(
            &config.input.keypoints_topic,
            QosConfig::reliable(1000),
        )?;
        let wrist =
            node.publisher::<PoseStamped>(&config.input.wrist_topic, QosConfig::reliable(1000))?;
        let heard = Arc::new(Mutex::new(Heard::default()));
        let targets = node.subscription::<JointState>(
            &config.output.joint_targets_topic,
            QosConfig::reliable(1000),
        )?;
        let arm = node.subscription::<PoseStamped>(
            &config.output.arm_target_topic,
            QosConfig::reliable(1000),
        )?;
        let status =
            node.subscription::<StringMsg>(&config.output.status_topic, QosConfig::reliable(100))?;
        let listeners = vec![
            collect(targets, clock, heard.clone(), |h, t, m| {
                h.targets.push((t, m))
            }),
            collect(arm, clock, heard.clone(), |h, t, m| h.arm.push((t, m))),
            collect(status, clock, heard.clone(), |h, t, m: StringMsg| {
                if let Ok(v) = serde_json::from_str(&m.data) {
                    h.status.push((t, v));
                }
            }),
        ];
        let harness = Harness {
            clock,
            heard,
            shutdown,
            operator,
            station,
            node,
            keypoints,
            wrist,
            network,
            listeners,
        };
        harness.wait_for_match().await?;
        Ok(harness)
    }

    async fn wait_for_match(&self) -> anyhow::Result<()> {
        let start = Instant::now();
        while self.keypoints.get_subscription_count(self.node.node()) == 0
            || self.wrist.get_subscription_count(self.node.node()) == 0
        {
            anyhow::ensure!(
                start.elapsed() < Duration::from_secs(15),
                "station did not match the glove topics in 15 s"
            );
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
        // Outputs: wait for the first status document.
        self.wait_until(Duration::from_secs(15), |h| !h.status.is_empty())
            .await
    }

    /// Publish one glove frame (keypoints as f32, and the wrist pose).
    pub async fn publish(
        &self,
        points: &[Point3<f64>],
        wrist: &Isometry3<f64>,
    ) -> anyhow::Result<()> {
        let rows: Vec<[f32; 3]> = points
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        self.publish_rows(&rows).await?;
        let pose = PoseStamped {
            header: header(self.clock.now_ns(), "coil"),
            pose: isometry_to_pose(wrist),
        };
        self.wrist
            .async_publish(pose)
            .await
            .map_err(|e| anyhow::anyhow!("{e:?}"))?;
        Ok(())
    }

    /// Publish raw keypoint rows (possibly malformed).
    pub async fn publish_rows(&self, rows: &[[f32; 3]]) -> anyhow::Result<()> {
        let array = Float32MultiArray::from_points(rows)?;
        self.keypoints
            .async_publish(array)
            .await
            .map_err(|e| anyhow::anyhow!("{e:?}"))?;
        Ok(())
    }

    /// Send an operator command.
    pub fn operator(&self, command: OperatorCommand) {
        self.operator.send(command).ok();
    }

    /// Wait until `condition` holds on what was heard, at most `timeout`.
    pub async fn wait_until(
        &self,
        timeout: Duration,
        condition: impl Fn(&Heard) -> bool,
    ) -> anyhow::Result<()> {
        let start = Instant::now();
        loop {
            if self.heard.lock().map(|h| condition(&h)).unwrap_or(false) {
                return Ok(());
            }
            anyhow::ensure!(
                start.elapsed() < timeout,
                "condition not met within {timeout:?}"
            );
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
    }

    /// The latest status document.
    pub fn last_status(&self) -> Option<serde_json::Value> {
        self.heard
            .lock()
            .ok()
            .and_then(|h| h.status.last().map(|(_, v)| v.clone()))
    }

    /// Listen to `M` on `topic` with `qos` until the harness stops.
    pub fn listen<M>(&mut self, topic: &str, qos: QosConfig) -> anyhow::Result<Inbox<M>>
    where
        M: RosMessage + serde::de::DeserializeOwned + Send + Sync + 'static,
    {
        let subscription = self.node.subscription::<M>(topic, qos)?;
        Ok(self.keep(subscription))
    }

    /// Listen to `M` on the latched (transient-local) `topic`: also what was published before
    /// the test node joined.
    pub fn listen_latched<M>(&mut self, topic: &str) -> anyhow::Result<Inbox<M>>
    where
        M: RosMessage + serde::de::DeserializeOwned + Send + Sync + 'static,
    {
        let subscription = self.node.latched_subscription::<M>(topic, 10)?;
        Ok(self.keep(subscription))
    }

    fn keep<M>(&mut self, subscription: ros2_client::Subscription<M>) -> Inbox<M>
    where
        M: serde::de::DeserializeOwned + Send + Sync + 'static,
    {
        let inbox = Inbox(Arc::new(Mutex::new(Vec::new())));
        let (clock, sink) = (self.clock, inbox.clone());
        self.listeners.push(tokio::spawn(async move {
            let mut stream = Box::pin(subscription.async_stream());
            while let Some(item) = stream.next().await {
                if let (Ok((message, _)), Ok(mut messages)) = (item, sink.0.lock()) {
                    messages.push((clock.now_ns(), message));
                }
            }
        }));
        inbox
    }

    /// Stop the station and the listeners; returns the station's summary.
    pub async fn stop(self) -> anyhow::Result<StationSummary> {
        self.shutdown.send(true).ok();
        let summary = self.station.await??;
        for l in self.listeners {
            l.abort();
        }
        Ok(summary)
    }
}

/// The messages of one topic the test node heard, with receive times (station clock, ns).
#[derive(Debug)]
pub struct Inbox<M>(Arc<Mutex<Vec<(i64, M)>>>);

impl<M> Clone for Inbox<M> {
    fn clone(&self) -> Self {
        Inbox(Arc::clone(&self.0))
    }
}

impl<M: Clone> Inbox<M> {
    /// Everything heard so far, in arrival order.
    #[allow(clippy::unwrap_used)] // a poisoned lock means a test thread already panicked
    pub fn all(&self) -> Vec<(i64, M)> {
        self.0.lock().unwrap().clone()
    }

    /// The last message heard.
    #[allow(clippy::unwrap_used)] // as above
    pub fn last(&self) -> Option<M> {
        self.0.lock().unwrap().last().map(|(_, m)| m.clone())
    }

    /// How many messages were heard.
    #[allow(clippy::unwrap_used)] // as above
    pub fn len(&self) -> usize {
        self.0.lock().unwrap().len()
    }

    /// Whether nothing was heard.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Wait until `condition` holds on what was heard, at most `timeout`.
    pub async fn wait_until(
        &self,
        timeout: Duration,
        condition: impl Fn(&[(i64, M)]) -> bool,
    ) -> anyhow::Result<()> {
        let start = Instant::now();
        loop {
            if self.0.lock().map(|m| condition(&m)).unwrap_or(false) {
                return Ok(());
            }
            anyhow::ensure!(
                start.elapsed() < timeout,
                "condition not met within {timeout:?}"
            );
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
    }
}

/// Check a sequence of arm targets against the arm configuration: on the line along `axis`
/// through the first target (if given), inside the workspace box, within the step caps.
/// Panics naming the first target that breaks a rule.
pub fn check_arm_targets(
    targets: &[Isometry3<f64>],
    arm: &station::arm::ArmConfig,
    axis: Option<[f64; 3]>,
) {
    let Some(first) = targets.first().map(|t| t.translation.vector) else {
        return;
    };
    for (i, target) in targets.iter().enumerate() {
        let p = target.translation.vector;
        if let Some(a) = axis {
            let a = nalgebra::Vector3::from(a).normalize();
            let d = p - first;
            let off = (d - a * a.dot(&d)).norm();
            assert!(
                off < 1e-9,
                "arm target {i} is {off} m off the constraint axis"
            );
        }
        for k in 0..3 {
            assert!(
                p[k] >= arm.workspace_min_m[k] - 1e-9 && p[k] <= arm.workspace_max_m[k] + 1e-9,
                "arm target {i} outside the workspace box: {p}"
            );
        }
        if i > 0 {
            let previous = &targets[i - 1];
            let step = (p - previous.translation.vector).norm();
            assert!(
                step <= arm.max_translation_step_m + 1e-9,
                "arm translation step {step} m at {i}"
            );
            let turn = target.rotation.angle_to(&previous.rotation);
            assert!(
                turn <= arm.max_rotation_step_rad + 1e-9,
                "arm rotation step {turn} rad at {i}"
            );
        }
    }
}
