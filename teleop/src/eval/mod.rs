//! Retargeting quality on a recording's glove frames (`pomdar eval`).
//!
//! Every distinct keypoint frame of the log (a frame equal to the one before it is a repeat
//! of the ingress's re-publishing, not a new frame) goes through the station's
//! [`Retargeter`], configured and calibrated as the station would be, with the log's time
//! between frames as the time step; the commands are scored by [`retarget::quality`] against
//! the human keypoints with the project's own FK of the model. The station's gate and 25 Hz
//! rate control are left out on purpose: every glove frame is scored, and the figures compare
//! with other retargeters fed the same frames. Only the wall time per frame is measured here.

use std::time::Instant;

use retarget::quality::Reachability;
use retarget::{CalibrationTransform, HandModel, QualityRecorder, QualityReport, Retargeter};
use serde::Serialize;

use crate::station_driver::setup::{describe, load_profile};
pub use error::EvalError;
use live_path::{LivePathReport, live_path};
use variants::TimedFrame;
mod error;
pub mod eval_set;
pub mod external;
pub mod live_path;
pub mod outlier_study;
pub mod profile_scales;
pub mod reach;
pub mod summary;
pub mod synthetic_users;
pub mod tracking;
pub mod variants;

use crate::mcap_log::{LoggedMessage, TrialReader};
use crate::resim::{keypoints, layout_for};
use crate::samples::Samples;
use station::StationConfig;

/// What `pomdar eval --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct EvalOutput {
    /// The recording.
    pub input: String,
    /// Keypoint messages read.
    pub messages: usize,
    /// Frames whose keypoints changed (the ones measured, unless rejected).
    pub distinct_frames: usize,
    /// Distinct frames the retargeter refused as malformed (not measured).
    pub rejected_frames: usize,
    /// The keypoint layout used.
    pub layout: String,
    /// The embodiment retargeted to.
    pub embodiment: String,
    /// The calibration profile applied, if any.
    pub profile: Option<String>,
    /// The metrics (definitions in `retarget::quality`).
    #[serde(flatten)]
    pub quality: QualityReport,
    /// Wall time of one frame's retargeting, microseconds: p50.
    pub time_per_frame_us_p50: Option<f64>,
    /// Wall time of one frame's retargeting, microseconds: p99.
    pub time_per_frame_us_p99: Option<f64>,
    /// The live path: the station's command in force at each distinct frame.
    pub live_path: LivePathReport,
    /// With `--reach`: per digit, the own scale and the reachability bound.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reach: Option<Reachability>,
}

/// The distinct keypoint frames of `reader` on the configured keypoint topic, by log time
/// (a frame equal to the one before it is a re-publishing, not a new frame), and the number
/// of keypoint messages read.
pub fn distinct_frames(
    reader: &TrialReader,
    config: &StationConfig,
) -> Result<(Vec<TimedFrame>, usize), EvalError> {
    let input = &config.input;
    let mut messages: Vec<&LoggedMessage> = reader
        .messages()
        .filter(|m| m.topic == input.keypoints_topic)
        .collect();
    messages.sort_by_key(|m| m.log_time_ns); // stable: file order within equal times
    let mut frames: Vec<TimedFrame> = Vec::new();
    for message in &messages {
        let points = keypoints(message, input.keypoints_format)
            .map_err(|source| EvalError::Keypoints {
                log_time_ns: message.log_time_ns,
                source,
            })?
            .points();
        let previous = frames.last().map(|last| last.points.as_slice());
        if !station::repeats(previous, &points) {
            frames.push(TimedFrame {
                t_ns: message.log_time_ns,
                points,
            });
        }
    }
    if frames.is_empty() {
        return Err(EvalError::NoKeypoints {
            path: reader.path().to_path_buf(),
            topic: input.keypoints_topic.clone(),
        });
    }
    Ok((frames, messages.len()))
}

/// How [`evaluate`] runs: what it adds to the report.
#[derive(Debug, Clone, Copy, Default)]
pub struct EvalOptions {
    /// Also report the reachability bound, on grids of at most this many configurations per
    /// digit ([`retarget::quality::Reachability`]).
    pub reach_max_configurations: Option<usize>,
}

/// The quality of the station's retargeting configured by `config` on `reader`'s keypoints.
pub fn evaluate(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
    options: EvalOptions,
) -> Result<EvalOutput, EvalError> {
    let (frames, message_count) = distinct_frames(reader, config)?;
    let mut retarget_config = config.retarget.clone();
    retarget_config.layout = layout_for(config, frames.first().map(|f| f.points.len()));
    let layout = retarget_config.layout;
    let profile = match &config.calibration_profile {
        Some(path) => Some((path, load_profile(path, &model, layout)?)),
        None => None,
    };
    if let Some((_, profile)) = &profile {
        eprintln!("{}", describe(profile));
    }
    let embodiment = retarget_config.embodiment.clone();
    let transform = profile.as_ref().map(|(_, p)| p.parameters);
    let mut retargeter = build_retargeter(&model, retarget_config, transform)?;
    let run = retarget_frames(&frames, &mut retargeter, 1.0 / config.control.rate_hz);
    let reach = match options.reach_max_configurations {
        Some(max) => Some(
            run.recorder
                .reachability(max)
                .map_err(|source| EvalError::Reachability { source })?,
        ),
        None => None,
    };
    let live_path = live_path(reader, config, retargeter.model().clone())?;
    Ok(EvalOutput {
        live_path,
        input: reader.path().display().to_string(),
        messages: message_count,
        distinct_frames: frames.len(),
        rejected_frames: run.rejected,
        layout: layout.name().to_string(),
        embodiment,
        profile: profile.map(|(path, _)| path.display().to_string()),
        quality: run.recorder.report(),
        time_per_frame_us_p50: run.time_us.percentile(0.5),
        time_per_frame_us_p99: run.time_us.percentile(0.99),
        reach,
    })
}

/// The station's retargeter for `model` and `retarget_config`, with the calibration
/// `transform` when given (else the identity).
pub fn build_retargeter(
    model: &HandModel,
    retarget_config: retarget::RetargetConfig,
    transform: Option<CalibrationTransform>,
) -> Result<Retargeter, EvalError> {
    use station::retargeter_setup::RetargeterSetupError;
    station::retargeter_setup::build_retargeter(model.clone(), retarget_config, transform).map_err(
        |e| match e {
            RetargeterSetupError::Model(source) => EvalError::Retargeter { source },
            RetargeterSetupError::Calibration(source) => EvalError::Calibration { source },
        },
    )
}

/// The frames retargeted one after the other and recorded for the metrics.
pub struct RetargetedFrames {
    /// Every accepted frame with its command.
    pub recorder: QualityRecorder,
    /// Wall time of each accepted frame's retargeting, microseconds.
    pub time_us: Samples,
    /// Frames the retargeter or the recorder refused as malformed.
    pub rejected: usize,
}

/// Retarget `frames` in order with `retargeter`, the log's time between frames as the time
/// step (`first_dt_s` for the first), and record them.
pub fn retarget_frames(
    frames: &[TimedFrame],
    retargeter: &mut Retargeter,
    first_dt_s: f64,
) -> RetargetedFrames {
    let layout = retargeter.config().layout;
    let mut run = RetargetedFrames {
        recorder: QualityRecorder::new(retargeter.model().clone(), layout),
        time_us: Samples::default(),
        rejected: 0,
    };
    let mut previous_ns = None;
    let origin_ns = frames.first().map_or(0, |f| f.t_ns);
    let t_s = |t_ns: i64| (t_ns - origin_ns) as f64 * 1e-9;
    for TimedFrame { t_ns, points } in frames {
        let dt_s = previous_ns.map_or(first_dt_s, |p: i64| (t_ns - p) as f64 * 1e-9);
        let started = Instant::now();
        let solved = retargeter.retarget(points, dt_s);
        let elapsed_us = started.elapsed().as_secs_f64() * 1e6;
        match solved {
            Ok(solution)
                if run
                    .recorder
                    .push_at(t_s(*t_ns), points, &solution.q)
                    .is_ok() =>
            {
                run.time_us.push(elapsed_us);
                previous_ns = Some(*t_ns);
            }
            _ => run.rejected += 1,
        }
    }
    run
}

fn opt(value: Option<f64>, precision: usize) -> String {
    value.map_or("-".into(), |v| format!("{v:.precision$}"))
}

/// The report as a terminal table.
pub fn table(o: &EvalOutput) -> String {
    let q = &o.quality;
    let mut out = format!(
        "retargeting quality of {}\n  {} frames measured ({} distinct of {} messages, {} rejected), \
         layout {}, embodiment {}, profile {}\n  global scale s* = {:.3} (robot ≈ s*·human)\n\n",
        o.input,
        q.frames,
        o.distinct_frames,
        o.messages,
        o.rejected_frames,
        o.layout,
        o.embodiment,
        o.profile.as_deref().unwrap_or("none"),
        q.tip_scale
    );
    out += &quality_lines(q);
    out += &format!(
        "\n  time per frame: p50 {} µs, p99 {} µs\n",
        opt(o.time_per_frame_us_p50, 1),
        opt(o.time_per_frame_us_p99, 1)
    );
    out += &live_path_lines(o);
    match &o.reach {
        Some(reach) => out + &reach::reach_lines(reach),
        None => out,
    }
}

/// The metrics as table lines: overall and per digit, the pinch gap and limit violations,
/// then the metrics without the global scale.
pub fn quality_lines(q: &QualityReport) -> String {
    let mut out = format!(
        "  {:<8} {:>13} {:>12} {:>8} {:>8} {:>11} {:>13}\n",
        "", "tip mean mm", "tip p95 mm", "pinches", "closed", "jerk rad", "max step rad"
    );
    let closed = |v: Option<f64>| v.map_or("-".into(), |v| format!("{v:.0} %"));
    out += &format!(
        "  {:<8} {:>13.1} {:>12.1} {:>8} {:>8} {:>11.4} {:>13.3}\n",
        "overall",
        q.tip_error_mean_mm,
        q.tip_error_p95_mm,
        q.pinch_frames,
        closed(q.pinches_closed_pct),
        q.jerk_rad,
        q.max_step_rad
    );
    for d in &q.per_digit {
        out += &format!(
            "  {:<8} {:>13} {:>12} {:>8} {:>8} {:>11} {:>13}\n",
            d.digit,
            opt(d.tip_error_mean_mm, 1),
            opt(d.tip_error_p95_mm, 1),
            d.pinch_frames,
            closed(d.pinches_closed_pct),
            opt(d.jerk_rad, 4),
            opt(d.max_step_rad, 3)
        );
    }
    out += &format!(
        "\n  pinch gap (robot thumb to pinched fingertip) mean {} mm; limit violations: {} frames\n",
        opt(q.pinch_gap_mean_mm, 1),
        q.limit_violation_frames,
    );
    out += &pinch_pair_lines(q);
    out + &scale_free_lines(q)
}

/// The pinches per finger pair under both definitions: any frame under 2 cm, and sustained
/// (at least 2 frames and 40 ms); the robot's distance over the sustained frames beside the
/// human's.
fn pinch_pair_lines(q: &QualityReport) -> String {
    let share = |closed: usize, frames: usize| {
        if frames == 0 {
            "-".to_string()
        } else {
            format!("{:.0} %", 100.0 * closed as f64 / frames as f64)
        }
    };
    let mut out = format!(
        "\n  pinches per pair: any frame under 2 cm, and sustained ({} frames and {:.0} ms or more)\n  {:<14} {:>7} {:>7} {:>10} {:>7} {:>15} {:>13} {:>14}\n",
        retarget::quality::SUSTAINED_PINCH_MIN_FRAMES,
        retarget::quality::SUSTAINED_PINCH_MIN_S * 1e3,
        "",
        "frames",
        "closed",
        "sustained",
        "closed",
        "robot mean mm",
        "robot p95 mm",
        "human mean mm"
    );
    for p in &q.pinch_pairs {
        out += &format!(
            "  {:<14} {:>7} {:>7} {:>10} {:>7} {:>15} {:>13} {:>14}\n",
            format!("thumb–{}", p.finger),
            p.frames,
            share(p.closed_frames, p.frames),
            p.sustained_frames,
            share(p.sustained_closed_frames, p.sustained_frames),
            opt(p.robot_gap_mean_mm, 1),
            opt(p.robot_gap_p95_mm, 1),
            opt(p.human_gap_mean_mm, 1),
        );
    }
    out
}

/// The metrics that do not reward a smaller hand: per digit, the tip error after the digit's
/// own scale and the flexion correlation; the lag.
fn scale_free_lines(q: &QualityReport) -> String {
    let mut out = format!(
        "\n  without the global scale: tip error after each digit's own scale mean {} mm, flexion \
         correlation mean {}, lag {} frames ({} s)\n  {:<8} {:>10} {:>14} {:>12} {:>14}\n",
        opt(q.tip_error_own_scale_mean_mm, 1),
        opt(q.flexion_correlation_mean, 3),
        q.flexion_lag_frames.map_or("-".into(), |k| k.to_string()),
        opt(q.flexion_lag_s, 3),
        "",
        "own scale",
        "own-scale mm",
        "flexion r",
        "pinch closed"
    );
    for d in q.per_digit.iter().filter(|d| d.tip_own_scale.is_some()) {
        out += &format!(
            "  {:<8} {:>10} {:>14} {:>12} {:>14}\n",
            d.digit,
            opt(d.tip_own_scale, 3),
            opt(d.tip_error_own_scale_mean_mm, 1),
            opt(d.flexion_correlation, 3),
            format!("{}/{}", d.pinch_closed_frames, d.pinch_frames)
        );
    }
    out
}

/// The live path against the retargeter alone.
fn live_path_lines(o: &EvalOutput) -> String {
    let (alone, live) = (&o.quality, &o.live_path.quality);
    format!(
        "\n  live path (the station re-simulated, command in force at each distinct frame):\n  \
         tip mean {:.1} mm ({:+.2} mm), jerk {:.4} rad ({:+.1} %), max step {:.3} rad, pinches closed {} \
         (sustained {}), \
         {} frames before engage, {} not measured; station step p50 {} µs, p99 {} µs\n",
        live.tip_error_mean_mm,
        live.tip_error_mean_mm - alone.tip_error_mean_mm,
        live.jerk_rad,
        100.0 * (live.jerk_rad / alone.jerk_rad - 1.0),
        live.max_step_rad,
        live.pinches_closed_pct
            .map_or("-".into(), |v| format!("{v:.0} %")),
        live.sustained_pinches_closed_pct
            .map_or("-".into(), |v| format!("{v:.0} %")),
        o.live_path.frames_without_command,
        o.live_path.frames_not_measured,
        opt(o.live_path.step_us_p50, 1),
        opt(o.live_path.step_us_p99, 1),
    )
}
