//! `pomdar calibrate --simulate`: a whole session on loopback DDS with a synthetic user
//! ([`calibration::SyntheticUser`]: hand size, glove misalignment, 2 mm keypoint noise) whose
//! simulated glove copies the poses on the session's schedule, its motion time starting at the
//! session's start. The fit then runs on the recording exactly as `--from` would, and the
//! recovered transform can be compared with the user's true one.

use std::time::Duration;

use anyhow::{Context as _, bail};
use calibration::{
    CalibrationSettings, CaptureSchedule, FitInputs, PoseSet, Study, SyntheticUser, human_copies,
};
use retarget::{CalibrationTransform, EmbodimentCatalog, HandModel};
use tokio::sync::watch;

use crate::calibrate::session_node::{SessionOptions, SessionReport, run_session};
use crate::clock::StationClock;
use crate::ros::NetworkConfig;
use crate::sim::sim_glove_node::{GloveOrigin, SimGloveConfig, publish_glove};
use crate::station::station_config::{KeypointFormat, StationConfig};

/// Keypoint noise of a simulated user, metres (standard deviation per axis).
pub const SIMULATED_NOISE_M: f64 = 0.002;
/// Publishing rate of the simulated glove, Hz.
pub const SIMULATED_GLOVE_RATE_HZ: f64 = 100.0;

/// A synthetic user with the flags' values.
pub fn synthetic_user(
    hand_scale: f64,
    glove_rpy_deg: [f64; 3],
    seed: u64,
) -> anyhow::Result<SyntheticUser> {
    if !(hand_scale.is_finite() && (0.5..=2.0).contains(&hand_scale)) {
        bail!("--hand-scale {hand_scale} must be in [0.5, 2]");
    }
    if let Some(a) = glove_rpy_deg
        .iter()
        .find(|a| !(a.is_finite() && a.abs() <= 45.0))
    {
        bail!("--glove-rpy angle {a}° must be in [-45, 45] degrees");
    }
    Ok(SyntheticUser {
        hand_scale,
        glove_rpy_rad: glove_rpy_deg.map(f64::to_radians),
        noise_sd_m: SIMULATED_NOISE_M,
        seed,
    })
}

/// The transform that calibrates `user`: the user's hand size and glove misalignment
/// composed with the reference calibration — the average hand in an aligned glove without
/// noise, fitted with a generous budget ([`calibration::Study`], as in the acceptance test).
pub fn true_transform(
    user: &SyntheticUser,
    station: &StationConfig,
    settings: &CalibrationSettings,
) -> anyhow::Result<CalibrationTransform> {
    let model = HandModel::orca_v1_right();
    let catalog = EmbodimentCatalog::builtin();
    let poses = PoseSet::orca_v1();
    let study = Study::new(FitInputs {
        model: &model,
        config: &station.retarget,
        catalog: &catalog,
        poses: &poses,
        settings,
    })
    .context("calibrating the reference hand")?;
    Ok(user.true_transform(study.reference()))
}

/// Record a session of `user` on loopback DDS (`session.station.network` is replaced by
/// loopback on `domain_id`).
pub async fn record_simulated_session(
    user: SyntheticUser,
    mut session: SessionOptions,
    domain_id: u16,
    shutdown: watch::Receiver<bool>,
) -> anyhow::Result<SessionReport> {
    let network = NetworkConfig {
        domain_id: Some(domain_id),
        interfaces: vec![std::net::IpAddr::from([127, 0, 0, 1])],
    };
    session.station.network = network.clone();
    if session.station.input.keypoints_format != KeypointFormat::Float32MultiArray {
        bail!(
            "--simulate publishes Float32MultiArray keypoints: the station configuration must use input.keypoints_format = \"float32_multi_array\""
        );
    }
    let model = HandModel::orca_v1_right();
    let schedule: CaptureSchedule = session.schedule;
    let layout = session.station.retarget.layout;
    let copies = human_copies(&model, &PoseSet::orca_v1())
        .map_err(|e| anyhow::anyhow!("the human copies of the poses: {e}"))?;
    let glove = user
        .glove(layout, &schedule, &copies)
        .map_err(|e| anyhow::anyhow!("simulated glove: {e}"))?;
    let glove_config = SimGloveConfig {
        rate_hz: SIMULATED_GLOVE_RATE_HZ,
        layout,
        keypoints_topic: session.station.input.keypoints_topic.clone(),
        wrist_topic: session.station.input.wrist_topic.clone(),
        ..SimGloveConfig::default()
    };
    let clock = StationClock::new();
    let (origin_tx, origin_rx) = watch::channel(None);
    let (stop_tx, stop_rx) = watch::channel(false);
    let glove_task = tokio::spawn(async move {
        publish_glove(
            glove,
            &glove_config,
            network,
            clock,
            GloveOrigin::Shared(origin_rx),
            stop_rx,
        )
        .await
    });
    session.glove_wait = session.glove_wait.max(Duration::from_secs(10));
    let report = run_session(session, &model, clock, Some(origin_tx), shutdown).await;
    stop_tx.send(true).ok();
    glove_task.await.context("simulated glove task")??;
    report
}
