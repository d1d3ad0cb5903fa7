//! The simulated glove node: publishes the lab's `/ingress/mano` (Float32MultiArray, N × 3
//! metres) and `/ingress/wrist` (PoseStamped, frame `coil`) from the parametric human hand
//! model at a fixed rate, optionally with keypoint noise and timing jitter. The hand plays a
//! periodic motion with the wrist in place, or a task script ([`GloveScript`]: a wrist path and
//! hand poses as keyframes, played once from the glove's time origin and then held while the
//! glove keeps publishing at its rate).

use std::collections::BTreeMap;
use std::time::Duration;

use msgs::{Float32MultiArray, PoseStamped, StringMsg};
use retarget::KeypointLayout;
use retarget::human_hand::{GloveScript, HumanHandShape, Motion, MotionKind, SimGlove};
use serde::{Deserialize, Serialize};
use tokio::sync::watch;

use crate::clock::StationClock;
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use crate::stand_ins::error::SimError;
use station::convert::{header, isometry_to_pose};

/// How long the glove waits for a subscriber before publishing anyway.
const MATCH_WAIT: Duration = Duration::from_secs(5);

/// The simulated glove's settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimGloveConfig {
    /// Publishing rate, Hz.
    pub rate_hz: f64,
    /// Scripted motion.
    pub motion: MotionKind,
    /// Motion period, seconds (per pinch for `pinches`).
    pub period_s: f64,
    /// Hand size relative to the average adult hand.
    pub hand_scale: f64,
    /// Keypoint noise, standard deviation, metres.
    pub jitter_m: f64,
    /// Layout published.
    pub layout: KeypointLayout,
    /// Keypoint topic.
    pub keypoints_topic: String,
    /// Wrist pose topic.
    pub wrist_topic: String,
    /// Status topic (`std_msgs/String`, JSON once a second naming the source as `simulated`,
    /// as an ingress does; the station records it in each trial log).
    pub status_topic: String,
    /// Seed of the noise.
    pub seed: u64,
    /// A task script to play instead of `motion` (its wrist path moves the published wrist
    /// pose); `None`: the periodic motion with the wrist in place.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub script: Option<GloveScript>,
}

impl Default for SimGloveConfig {
    fn default() -> Self {
        SimGloveConfig {
            rate_hz: 100.0,
            motion: MotionKind::TaskLike,
            period_s: MotionKind::TaskLike.default_period_s(),
            hand_scale: 1.0,
            jitter_m: 0.001,
            layout: KeypointLayout::Lab22,
            keypoints_topic: "/ingress/mano".into(),
            wrist_topic: "/ingress/wrist".into(),
            status_topic: "/ingress/status".into(),
            seed: 1,
            script: None,
        }
    }
}

impl SimGloveConfig {
    /// The glove model for this configuration (performing the script if there is one).
    pub fn glove(&self) -> Result<SimGlove, SimError> {
        let shape = HumanHandShape::average().scaled(self.hand_scale);
        let glove = Motion::new(self.motion, self.period_s, &shape)
            .and_then(|motion| SimGlove::new(shape, motion, self.layout))
            .and_then(|g| g.with_jitter(self.jitter_m, self.seed))
            .and_then(|g| match &self.script {
                Some(script) => g.with_script(script),
                None => Ok(g),
            })
            .map_err(|source| SimError::Glove { source })?;
        Ok(glove)
    }

    /// What the glove performs, for a console line: the script's length or the motion.
    pub fn describe_performance(&self) -> String {
        match &self.script {
            Some(script) => format!(
                "task script of {} keyframes, {:.1} s",
                script.keyframes.len(),
                script.duration_s()
            ),
            None => format!("{:?}", self.motion),
        }
    }
}

/// What a glove published.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SimGloveReport {
    /// Frames published (keypoints and wrist pose both sent).
    pub frames: u64,
    /// Messages whose publishing failed (not sent), by topic.
    pub publish_failed: BTreeMap<String, u64>,
    /// Station-clock times of the first and the last frame published: the glove's sending
    /// span, which excludes the wait for a subscriber before it and the shutdown after it.
    pub sending_ns: Option<(i64, i64)>,
}

impl SimGloveReport {
    /// Count a frame whose keypoints and wrist pose were (`true`) or were not sent.
    fn count(
        &mut self,
        config: &SimGloveConfig,
        now_ns: i64,
        keypoints_sent: bool,
        wrist_sent: bool,
    ) {
        for (topic, sent) in [
            (&config.keypoints_topic, keypoints_sent),
            (&config.wrist_topic, wrist_sent),
        ] {
            if !sent {
                *self.publish_failed.entry(topic.clone()).or_default() += 1;
            }
        }
        if keypoints_sent && wrist_sent {
            self.frames += 1;
            let first_ns = self.sending_ns.map_or(now_ns, |(first, _)| first);
            self.sending_ns = Some((first_ns, now_ns));
        }
    }

    /// Frames published per second over the sending span (between the first and the last
    /// frame); `None` before two frames.
    pub fn sending_rate_hz(&self) -> Option<f64> {
        let (first, last) = self.sending_ns?;
        (self.frames >= 2 && last > first)
            .then(|| (self.frames - 1) as f64 / ((last - first) as f64 * 1e-9))
    }

    /// Seconds between the first and the last frame published (0 before two frames).
    pub fn sending_span_s(&self) -> f64 {
        self.sending_ns
            .map_or(0.0, |(first, last)| (last - first) as f64 * 1e-9)
    }

    /// Count a message on `topic` that was not sent.
    fn count_failure(&mut self, topic: &str) {
        *self.publish_failed.entry(topic.to_string()).or_default() += 1;
    }

    /// Messages not sent, every topic.
    pub fn not_published(&self) -> u64 {
        self.publish_failed.values().sum()
    }
}

/// The glove's status: the source it is (`simulated`) and what it published.
fn glove_status(config: &SimGloveConfig, report: &SimGloveReport) -> StringMsg {
    let device = format!(
        "pomdar simulated glove ({}, {} Hz)",
        config.describe_performance(),
        config.rate_hz
    );
    let status = serde_json::json!({
        "node": "sim_glove",
        "source": {"kind": "simulated", "device": device},
        "published": report.frames,
    });
    StringMsg {
        data: status.to_string(),
    }
}

/// Keypoint noise of a glove at rest before its shared time origin, metres (standard
/// deviation per axis), when the glove itself has none: a worn glove is never perfectly still,
/// and the station takes identical frames for a stalled stream.
pub const REST_JITTER_M: f64 = 0.0005;

/// Where a published glove's motion time starts.
#[derive(Debug, Clone)]
pub enum GloveOrigin {
    /// When the first subscriber matched (or after a bounded wait).
    FirstSubscriber,
    /// A time origin (station-clock ns) shared with another node, e.g. a calibration
    /// session's or a trial's start; until it is known the glove holds the motion's first
    /// posture (with [`REST_JITTER_M`] of noise if it has none of its own).
    Shared(watch::Receiver<Option<i64>>),
}

/// Publish until `shutdown`; returns what was published. The motion's (or the script's) time
/// starts when the first subscriber matched (or after a bounded wait).
pub async fn run_sim_glove(
    config: SimGloveConfig,
    network: NetworkConfig,
    clock: StationClock,
    shutdown: watch::Receiver<bool>,
) -> Result<SimGloveReport, SimError> {
    let glove = config.glove()?;
    publish_glove(
        glove,
        &config,
        network,
        clock,
        GloveOrigin::FirstSubscriber,
        shutdown,
    )
    .await
}

/// Publish `glove`'s frames on `config`'s topics at its rate until `shutdown`, its motion time
/// starting at `origin`; returns what was published.
pub async fn publish_glove(
    glove: SimGlove,
    config: &SimGloveConfig,
    network: NetworkConfig,
    clock: StationClock,
    origin: GloveOrigin,
    mut shutdown: watch::Receiver<bool>,
) -> Result<SimGloveReport, SimError> {
    let mut node = RosNode::join(&network, "/", "pomdar_sim_glove")?;
    let qos = QosConfig::best_effort(400);
    let keypoints_pub = node.publisher::<Float32MultiArray>(&config.keypoints_topic, qos)?;
    let wrist_pub = node.publisher::<PoseStamped>(&config.wrist_topic, qos)?;
    let status_pub = node.publisher::<StringMsg>(&config.status_topic, QosConfig::reliable(10))?;
    let mut status_tick = tokio::time::interval(Duration::from_secs(1));
    // Start once a station listens (bounded), so no frame is lost to discovery.
    let waiting_since = std::time::Instant::now();
    while node.matched_subscriptions(&keypoints_pub) == 0 && waiting_since.elapsed() < MATCH_WAIT {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { return Ok(SimGloveReport::default()) },
            _ = tokio::time::sleep(Duration::from_millis(10)) => {}
        }
    }
    let first_subscriber_ns = clock.now_ns();
    // Before its shared origin the glove holds the first posture with noise keyed by the
    // (negative) time: its own noise, else a hand's at rest. Never identical frames, which
    // the station takes for a stalled glove.
    let resting = match &origin {
        GloveOrigin::Shared(_) if glove.jitter_sd_m() == 0.0 => Some(
            glove
                .clone()
                .with_jitter(REST_JITTER_M, config.seed)
                .map_err(|source| SimError::Glove { source })?,
        ),
        GloveOrigin::Shared(_) => Some(glove.clone()),
        GloveOrigin::FirstSubscriber => None,
    };
    let start_ns = || match &origin {
        GloveOrigin::FirstSubscriber => Some(first_subscriber_ns),
        GloveOrigin::Shared(rx) => *rx.borrow(),
    };
    let mut interval = tokio::time::interval(Duration::from_secs_f64(1.0 / config.rate_hz));
    interval.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut report = SimGloveReport::default();
    // Subscriptions of the status the glove has published to, looked at every 100 ms: a
    // station that has just matched hears it then, not up to a second later (a trial started
    // meanwhile would record its keypoint source as unknown).
    let mut status_heard_by = 0;
    let mut match_tick = tokio::time::interval(Duration::from_millis(100));
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break },
            _ = status_tick.tick() => {
                if status_pub.async_publish(glove_status(config, &report)).await.is_err() {
                    report.count_failure(&config.status_topic);
                }
            }
            _ = match_tick.tick() => {
                let matched = node.matched_subscriptions(&status_pub);
                if matched > status_heard_by
                    && status_pub.async_publish(glove_status(config, &report)).await.is_err()
                {
                    report.count_failure(&config.status_topic);
                }
                status_heard_by = matched;
            }
            _ = interval.tick() => {
                let now = clock.now_ns();
                // A script's dropout: nothing is sent.
                if start_ns().is_some_and(|start| !glove.sends_at((now - start) as f64 * 1e-9)) {
                    continue;
                }
                let (points, wrist) = match (start_ns(), &resting) {
                    (Some(start), _) => glove.frame((now - start) as f64 * 1e-9),
                    // A script holds its first keyframe before its time 0; the noise is keyed
                    // by the (negative) time, so every frame differs.
                    (None, Some(rest)) => {
                        rest.frame(-1e-3 - (now - first_subscriber_ns) as f64 * 1e-9)
                    }
                    (None, None) => glove.frame(0.0),
                };
                let rows: Vec<[f32; 3]> = points.iter().map(|p| [p.x as f32, p.y as f32, p.z as f32]).collect();
                let array = Float32MultiArray::from_points(&rows)?;
                let keypoints_sent = keypoints_pub.async_publish(array).await.is_ok();
                let pose = PoseStamped { header: header(now, "coil"), pose: isometry_to_pose(&wrist) };
                let wrist_sent = wrist_pub.async_publish(pose).await.is_ok();
                report.count(config, now, keypoints_sent, wrist_sent);
            }
        }
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;
    use retarget::human_hand::{HumanHandPose, ScriptKeyframe, ScriptPose};

    use super::*;

    fn script() -> GloveScript {
        GloveScript {
            keyframes: vec![
                ScriptKeyframe::new(0.0, [0.0; 3], ScriptPose::Open),
                ScriptKeyframe::new(2.0, [0.0, 0.0, -0.25], ScriptPose::CylinderGrasp),
                ScriptKeyframe::new(4.0, [0.0, 0.18, -0.15], ScriptPose::CylinderGrasp),
            ],
            dropouts: Vec::new(),
        }
    }

    #[test]
    fn the_glove_of_a_scripted_config_follows_the_script_and_holds_its_end() {
        let config = SimGloveConfig {
            script: Some(script()),
            jitter_m: 0.0,
            ..SimGloveConfig::default()
        };
        let glove = config.glove().unwrap();
        let wrist = |t: f64| glove.frame(t).1.translation.vector;
        assert_eq!(wrist(0.0), Vector3::zeros());
        assert!((wrist(2.0) - Vector3::new(0.0, 0.0, -0.25)).norm() < 1e-15);
        assert!((wrist(3.0) - Vector3::new(0.0, 0.09, -0.2)).norm() < 1e-12);
        for t in [4.0, 10.0, 3600.0] {
            assert!((wrist(t) - Vector3::new(0.0, 0.18, -0.15)).norm() < 1e-15);
            assert_eq!(glove.pose_at(t), HumanHandPose::cylinder_grasp());
        }
        let (points, _) = glove.frame(3.0);
        let layout_wrist = points[config.layout.wrist()].coords;
        assert!(
            (layout_wrist - wrist(3.0)).norm() < 1e-12,
            "keypoints move with it"
        );
        assert!(config.describe_performance().contains("3 keyframes, 4.0 s"));
    }

    #[test]
    fn without_a_script_the_wrist_stays_and_the_config_reads_as_before() {
        let glove = SimGloveConfig::default().glove().unwrap();
        assert_eq!(glove.frame(3.0).1.translation.vector, Vector3::zeros());
        let text = toml::to_string(&SimGloveConfig::default()).unwrap();
        assert!(!text.contains("script"), "{text}");
        let read: SimGloveConfig = toml::from_str(&text).unwrap();
        assert_eq!(read, SimGloveConfig::default());
        let scripted = SimGloveConfig {
            script: Some(script()),
            ..SimGloveConfig::default()
        };
        let text = toml::to_string(&scripted).unwrap();
        assert_eq!(toml::from_str::<SimGloveConfig>(&text).unwrap(), scripted);
    }

    #[test]
    fn an_invalid_script_is_a_glove_error() {
        let config = SimGloveConfig {
            script: Some(GloveScript {
                keyframes: vec![],
                dropouts: Vec::new(),
            }),
            ..SimGloveConfig::default()
        };
        let err = config.glove().unwrap_err().to_string();
        assert!(err.contains("keyframes"), "{err}");
    }
}
