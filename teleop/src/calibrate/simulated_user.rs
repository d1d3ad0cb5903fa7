//! `pomdar calibrate --simulate`: a whole session on loopback DDS with a synthetic user
//! ([`calibration::SyntheticUser`]: hand size, glove misalignment, 1.5 mm keypoint noise) whose
//! simulated glove copies the pose the session is at: it moves to each pose when the hand is
//! sent there and holds it for as long as the session stays (settling, capturing, review,
//! retries). With `--simulate-bad-pose`, the first capture of that pose is taken with a
//! shaking hand ([`SHAKING_NOISE_M`]), so the console flags it and the pose is captured again.
//! With `--simulate-wrong-pose`, the user stays in the previous pose through that pose's first
//! capture: a steady capture of the wrong pose, which the fit cannot match, so the console
//! names the pose after the fit and offers to capture it again ([`SimulatedMistakes`]).
//! The fit then runs on the recording exactly as `--from` would, and the recovered transform
//! can be compared with the user's true one.

use std::time::Duration;

use calibration::{
    CalibrationSettings, CaptureSchedule, FitInputs, PoseSet, Study, SyntheticUser, human_copies,
};
use msgs::{Float32MultiArray, PoseStamped};
use retarget::human_hand::{HandVariation, SplitMix64, VariationRanges};
use retarget::{CalibrationTransform, EmbodimentCatalog, HandModel};
use tokio::sync::watch;

use crate::calibrate::CalibrateError;
use crate::calibrate::session_node::PoseCue;
use crate::clock::StationClock;
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use station::convert::{header, isometry_to_pose};
use station::{KeypointFormat, StationConfig};

/// Keypoint noise of a simulated user, metres (standard deviation per axis): a steady user,
/// whose captures are judged good with a margin. At 2 mm the open hand of a 1.15× hand
/// measured 8.6–10.2 mm of palm-frame jitter (the palm frame's own noise swings the
/// fingertips), against the 10.2 mm from which a capture is poor (85 % of the 12 mm limit):
/// about one session in ten then stopped at an unexpected review.
pub const SIMULATED_NOISE_M: f64 = 0.0015;
/// Publishing rate of the simulated glove, Hz.
pub const SIMULATED_GLOVE_RATE_HZ: f64 = 100.0;

/// A synthetic user with the flags' values: hand size, glove misalignment, noise seed and the
/// hand's proportions ([`HandVariation::NONE`]: a scaled copy of the average hand).
pub fn synthetic_user(
    hand_scale: f64,
    glove_rpy_deg: [f64; 3],
    seed: u64,
    variation: HandVariation,
) -> Result<SyntheticUser, CalibrateError> {
    if !(hand_scale.is_finite() && (0.5..=2.0).contains(&hand_scale)) {
        return Err(CalibrateError::HandScale { hand_scale });
    }
    if let Some(&angle) = glove_rpy_deg
        .iter()
        .find(|a| !(a.is_finite() && a.abs() <= 45.0))
    {
        return Err(CalibrateError::GloveAngle { angle });
    }
    Ok(SyntheticUser {
        hand_scale,
        glove_rpy_rad: glove_rpy_deg.map(f64::to_radians),
        noise_sd_m: SIMULATED_NOISE_M,
        seed,
        variation,
    })
}

/// Allowed range of a named proportion of `--simulate-hand`.
pub const SIMULATED_PROPORTION_RANGE: (f64, f64) = (0.7, 1.3);

/// The proportions of `--simulate-hand`: `random:SEED` draws a hand within the ranges of
/// [`VariationRanges::DEFAULT`] (thumb ±15 %, index and middle ±10 %, palm breadth ±10 %,
/// thumb base ±5 mm and ±5°, tip markers ±5 mm); `thumb=F,index=F,middle=F,palm=F` (any of
/// them, factors 0.7–1.3) names them, the rest average.
pub fn parse_simulated_hand(text: &str) -> Result<HandVariation, String> {
    let text = text.trim();
    if let Some(seed) = text.strip_prefix("random:") {
        let seed: u64 = seed
            .trim()
            .parse()
            .map_err(|e| format!("'{text}': the seed after random: is not a whole number ({e})"))?;
        let mut rng = SplitMix64::new(seed);
        return Ok(HandVariation::draw(&mut rng, &VariationRanges::DEFAULT));
    }
    let mut hand = HandVariation::NONE;
    for item in text.split(',') {
        let (name, value) = item.split_once('=').ok_or_else(|| {
            format!(
                "'{item}': expected NAME=FACTOR (thumb, index, middle, palm) or random:SEED, \
                 e.g. thumb=1.12,index=0.95"
            )
        })?;
        let (low, high) = SIMULATED_PROPORTION_RANGE;
        let factor: f64 = value
            .trim()
            .parse()
            .ok()
            .filter(|f: &f64| f.is_finite() && (low..=high).contains(f))
            .ok_or_else(|| format!("'{item}': the factor must be a number in {low}–{high}"))?;
        let slot = match name.trim() {
            "thumb" => &mut hand.thumb_length,
            "index" => &mut hand.index_length,
            "middle" => &mut hand.middle_length,
            "palm" => &mut hand.palm_breadth,
            other => {
                return Err(format!(
                    "'{other}': unknown proportion (known: thumb, index, middle, palm)"
                ));
            }
        };
        *slot = factor;
    }
    Ok(hand)
}

/// The transform that calibrates `user`: the user's hand size and glove misalignment
/// composed with the reference calibration — the average hand in an aligned glove without
/// noise, fitted with a generous budget ([`calibration::Study`], as in the acceptance test).
pub fn true_transform(
    user: &SyntheticUser,
    station: &StationConfig,
    settings: &CalibrationSettings,
) -> Result<CalibrationTransform, CalibrateError> {
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
    .map_err(|source| CalibrateError::ReferenceHand { source })?;
    Ok(user.true_transform(study.reference()))
}

/// Keypoint noise of the simulated user's bad capture (`--simulate-bad-pose`): a shaking hand,
/// metres per axis (jitter over 30 mm in the palm frame, far above the 12 mm limit).
pub const SHAKING_NOISE_M: f64 = 0.008;

/// What the simulated user gets wrong on purpose, so a lab can rehearse the console's answers.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SimulatedMistakes {
    /// `--simulate-bad-pose`: the user shakes through this pose's first capture.
    pub shaking: Option<usize>,
    /// `--simulate-wrong-pose`: the user holds [`calibration::wrongly_held_pose`] of this pose
    /// through its first capture.
    pub wrong: Option<usize>,
}

/// The motion's pose and whether it starts in the hold, for `cue`: a wrongly held pose shows
/// the pose held instead, from its hold (the user stays where they were).
fn shown_pose(cue: PoseCue, mistakes: SimulatedMistakes) -> (PoseCue, bool) {
    if mistakes.wrong == Some(cue.pose) && cue.attempt == 1 {
        let pose = calibration::wrongly_held_pose(cue.pose);
        (PoseCue { pose, ..cue }, true)
    } else {
        (cue, cue.attempt > 1)
    }
}

/// Fraction of a pose's slot the simulated hand takes to move to the pose (the
/// calibration-poses motion: move 35 %, hold the rest); the hold starts a little later.
const HOLD_FROM: f64 = 0.4;

/// The simulated glove's motion time for `cue`, `elapsed_s` after the cue began: the motion of
/// the pose's slot from its start (moving from the previous pose), then its hold repeated for
/// as long as the session stays on the pose (a retry or a review holds the pose).
pub fn motion_time_s(slot_s: f64, cue: PoseCue, elapsed_s: f64, retried: bool) -> f64 {
    let start = cue.pose as f64 * slot_s;
    let hold_start = start + HOLD_FROM * slot_s;
    let hold_len = (1.0 - HOLD_FROM) * slot_s - 0.05;
    let t = if retried {
        hold_start + elapsed_s
    } else {
        start + elapsed_s
    };
    if t < hold_start {
        t
    } else {
        hold_start + (t - hold_start).rem_euclid(hold_len)
    }
}

/// The loopback network a simulated session runs on.
pub fn loopback(domain_id: u16) -> NetworkConfig {
    NetworkConfig {
        domain_id: Some(domain_id),
        interfaces: vec![std::net::IpAddr::from([127, 0, 0, 1])],
    }
}

/// What the simulated glove published.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SimulatedGloveReport {
    /// Frames (keypoints and wrist pose) made.
    pub frames: u64,
    /// Frames of which the keypoints or the wrist pose could not be published.
    pub not_published: u64,
}

/// Publish `user`'s glove on the station's keypoint and wrist topics at 100 Hz, copying the
/// pose the session is at (`cue`), with the `mistakes` asked for. Until the session starts
/// the hand holds the motion's first posture.
/// Returns what was published, after `stop`.
pub async fn publish_simulated_user(
    user: SyntheticUser,
    mistakes: SimulatedMistakes,
    station: StationConfig,
    network: NetworkConfig,
    clock: StationClock,
    mut cue: watch::Receiver<Option<PoseCue>>,
    mut stop: watch::Receiver<bool>,
) -> Result<SimulatedGloveReport, CalibrateError> {
    if station.input.keypoints_format != KeypointFormat::Float32MultiArray {
        return Err(CalibrateError::SimulateNeedsArray);
    }
    let model = HandModel::orca_v1_right();
    let schedule = CaptureSchedule::default();
    let layout = station.retarget.layout;
    let copies = human_copies(&model, &PoseSet::orca_v1())
        .map_err(|source| CalibrateError::HumanCopies { source })?;
    let glove = user
        .glove(layout, &schedule, &copies)
        .map_err(|source| CalibrateError::SimulatedGlove { source })?;
    let shaking = SyntheticUser {
        noise_sd_m: SHAKING_NOISE_M,
        ..user
    }
    .glove(layout, &schedule, &copies)
    .map_err(|source| CalibrateError::SimulatedGlove { source })?;
    let mut node = RosNode::join(&network, "/", "pomdar_simulated_user")?;
    let qos = QosConfig::best_effort(400);
    let keypoints_pub = node.publisher::<Float32MultiArray>(&station.input.keypoints_topic, qos)?;
    let wrist_pub = node.publisher::<PoseStamped>(&station.input.wrist_topic, qos)?;
    let mut interval =
        tokio::time::interval(Duration::from_secs_f64(1.0 / SIMULATED_GLOVE_RATE_HZ));
    interval.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut since: Option<(PoseCue, i64)> = None;
    let mut report = SimulatedGloveReport::default();
    loop {
        tokio::select! {
            changed = stop.changed() => if changed.is_err() || *stop.borrow() { break },
            Ok(()) = cue.changed() => {
                if let Some(c) = *cue.borrow_and_update() {
                    since = Some((c, clock.now_ns()));
                }
            }
            _ = interval.tick() => {
                let now = clock.now_ns();
                let (glove, t_s) = match since {
                    Some((c, at_ns)) => {
                        let elapsed_s = (now - at_ns) as f64 * 1e-9;
                        let (shown, from_hold) = shown_pose(c, mistakes);
                        let t = motion_time_s(schedule.slot_s, shown, elapsed_s, from_hold);
                        let shakes = mistakes.shaking == Some(c.pose) && c.attempt == 1;
                        (if shakes { &shaking } else { &glove }, t)
                    }
                    // Before the session starts: the first posture, its noise varying.
                    None => (&glove, (report.frames % 100) as f64 * 1e-6),
                };
                let (points, wrist) = glove.frame(t_s);
                let rows: Vec<[f32; 3]> = points.iter().map(|p| [p.x as f32, p.y as f32, p.z as f32]).collect();
                let keypoints = Float32MultiArray::from_points(&rows)
                    .map_err(|source| CalibrateError::KeypointMessage { source })?;
                let pose = PoseStamped { header: header(now, "coil"), pose: isometry_to_pose(&wrist) };
                let sent = keypoints_pub.async_publish(keypoints).await.is_ok();
                let sent = wrist_pub.async_publish(pose).await.is_ok() && sent;
                report.frames += 1;
                if !sent {
                    report.not_published += 1;
                }
            }
        }
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_simulated_hand_is_named_by_its_proportions_or_drawn_from_a_seed() {
        let named = parse_simulated_hand("thumb=1.12, index=0.95").unwrap();
        assert_eq!((named.thumb_length, named.index_length), (1.12, 0.95));
        assert_eq!((named.middle_length, named.palm_breadth), (1.0, 1.0));
        let drawn = parse_simulated_hand("random:7").unwrap();
        assert_eq!(drawn, parse_simulated_hand("random:7").unwrap());
        assert_ne!(drawn, parse_simulated_hand("random:8").unwrap());
        assert_ne!(drawn, HandVariation::NONE);
        for (bad, named) in [
            ("thumb=1.5", "0.7–1.3"),
            ("wrist=1.1", "unknown proportion"),
            ("thumb", "NAME=FACTOR"),
            ("random:x", "whole number"),
        ] {
            let error = parse_simulated_hand(bad).unwrap_err();
            assert!(error.contains(named), "{bad}: {error}");
        }
    }

    #[test]
    fn a_wrongly_held_pose_shows_the_previous_one_at_its_first_capture_only() {
        let mistakes = SimulatedMistakes {
            shaking: None,
            wrong: Some(2),
        };
        let cue = |pose, attempt| PoseCue { pose, attempt };
        assert_eq!(shown_pose(cue(2, 1), mistakes), (cue(1, 1), true));
        assert_eq!(shown_pose(cue(2, 2), mistakes), (cue(2, 2), true));
        assert_eq!(shown_pose(cue(3, 1), mistakes), (cue(3, 1), false));
        assert_eq!(
            calibration::POSE_NAMES[calibration::wrongly_held_pose(0)],
            "open"
        );
    }

    #[test]
    fn the_motion_moves_to_the_pose_then_holds_it_for_as_long_as_needed() {
        let cue = PoseCue {
            pose: 2,
            attempt: 1,
        };
        let slot = 2.5;
        assert_eq!(motion_time_s(slot, cue, 0.0, false), 5.0);
        assert_eq!(motion_time_s(slot, cue, 0.5, false), 5.5);
        let hold = (6.0, 7.45);
        for elapsed in [1.0, 2.0, 3.3, 10.0, 100.0] {
            let t = motion_time_s(slot, cue, elapsed, false);
            assert!(t >= hold.0 && t < hold.1, "{elapsed}: {t}");
        }
        // A retry starts in the hold.
        let t = motion_time_s(
            slot,
            PoseCue {
                pose: 2,
                attempt: 2,
            },
            0.0,
            true,
        );
        assert_eq!(t, 6.0);
    }
}
