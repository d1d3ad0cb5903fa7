//! `pomdar calibrate --from SESSION.mcap`: a recorded session to a profile. Each pose's frames
//! are checked and averaged ([`calibration::capture_pose`]; a refused capture stops here with
//! its message, which says what to do), the transform is fitted with a progress bar, a table
//! of the per-pose errors before and after is printed, and the profile is written atomically.
//! Nothing is written on any failure, nor after the caller's cancel (Ctrl-C) during the fit.

use std::path::{Path, PathBuf};

use calibration::{
    CalibrationModel, CalibrationProfile, CalibrationSettings, CapturedPose, FitInputs,
    FitProgress, PoseSet, ProfileHeader, calibrate, capture_pose, poses_that_do_not_fit,
};
use retarget::{EmbodimentCatalog, HandModel};

use crate::atomic_file::write_atomically;
use crate::calibrate::CalibrateError;
use crate::calibrate::pose_session::FitDone;
use crate::calibrate::progress_bar::ProgressBar;
use crate::calibrate::session_frames::read_session;
use crate::mcap_log::TrialReader;
use crate::utc_date::{iso8601_utc, now_unix_s};
use station::StationConfig;

/// What a fit needs.
#[derive(Debug, Clone)]
pub struct FitOptions {
    /// The session log.
    pub session: PathBuf,
    /// The user's name (written into the profile).
    pub user: String,
    /// The glove (free text).
    pub glove: String,
    /// Where the profile goes.
    pub out: PathBuf,
    /// The station's configuration (retargeting, layout) the profile is for.
    pub station: StationConfig,
    /// Bounds, budget, capture thresholds.
    pub settings: CalibrationSettings,
    /// The profile's `source` (default: the session file's path).
    pub source: Option<String>,
    /// Show the progress bar and the table.
    pub verbose: bool,
}

/// A fit's result.
#[derive(Debug, Clone)]
pub struct FitOutcome {
    /// The profile written.
    pub profile: CalibrationProfile,
    /// The per-pose errors before and after, as a table's lines.
    pub table: Vec<String>,
}

/// Read the session, fit, report, write the profile; returns the profile written. With
/// `verbose`, a progress bar on stderr and the table on stdout. `cancelled` is asked before
/// every evaluation of the fit and before the profile is written (see [`fit_session_with`]).
pub fn fit_session(
    options: &FitOptions,
    cancelled: &dyn Fn() -> bool,
) -> Result<CalibrationProfile, CalibrateError> {
    let mut bar = options.verbose.then(ProgressBar::new);
    let outcome = fit_session_with(
        options,
        &mut |p| {
            if let Some(bar) = bar.as_mut() {
                bar.update(p);
            }
        },
        cancelled,
    );
    if let Some(bar) = bar.as_mut() {
        bar.finish();
    }
    let outcome = outcome?;
    if options.verbose {
        for line in &outcome.table {
            println!("{line}");
        }
    }
    Ok(outcome.profile)
}

/// Read the session, fit with `progress` after each evaluation, write the profile (nothing
/// is printed).
///
/// `cancelled` is asked before every evaluation and once more just before the profile is
/// written: once it says true the fit ends with [`CalibrateError::FitInterrupted`] and no
/// profile is written (an existing one is left as it is). The atomic write after that last
/// check is the fit's end: a cancel arriving during it finds the profile complete.
pub fn fit_session_with(
    options: &FitOptions,
    progress: &mut dyn FnMut(FitProgress),
    cancelled: &dyn Fn() -> bool,
) -> Result<FitOutcome, CalibrateError> {
    let model = HandModel::orca_v1_right();
    let layout = options.station.retarget.layout;
    let captures = session_captures(options, &model)?;
    let pose_set = PoseSet::orca_v1();
    let catalog = EmbodimentCatalog::builtin();
    let inputs = FitInputs {
        model: &model,
        config: &options.station.retarget,
        catalog: &catalog,
        poses: &pose_set,
        settings: &options.settings,
    };
    let file = || options.session.clone();
    let fitted =
        calibrate(inputs, &captures, &mut |p| progress(p), cancelled).map_err(|source| {
            if source.is_interrupted() {
                CalibrateError::FitInterrupted { file: file() }
            } else {
                CalibrateError::Fit {
                    file: file(),
                    source,
                }
            }
        })?;
    let header = ProfileHeader {
        user: options.user.clone(),
        date: iso8601_utc(now_unix_s()),
        glove: options.glove.clone(),
        source: options
            .source
            .clone()
            .unwrap_or_else(|| options.session.display().to_string()),
    };
    let profile = CalibrationProfile::new(header, &model, layout, &fitted);
    profile
        .validate()
        .map_err(|source| CalibrateError::InvalidProfile { source })?;
    let text = profile
        .to_toml_string()
        .map_err(|source| CalibrateError::ProfileToml { source })?;
    if cancelled() {
        return Err(CalibrateError::FitInterrupted { file: file() });
    }
    write_atomically(&options.out, &text)?;
    let table = table_lines(&profile, &captures);
    Ok(FitOutcome { profile, table })
}

/// The session's seven captures: its layout and model checked against the station's, each
/// pose's frames checked and averaged.
fn session_captures(
    options: &FitOptions,
    model: &HandModel,
) -> Result<Vec<CapturedPose>, CalibrateError> {
    let layout = options.station.retarget.layout;
    let reader = TrialReader::open(&options.session)?;
    let file = || options.session.clone();
    let (info, poses) = read_session(&reader)?;
    if info.layout != layout {
        return Err(CalibrateError::LayoutMismatch {
            file: file(),
            recorded: info.layout.name(),
            station: layout.name(),
        });
    }
    if info.model != model.name() {
        return Err(CalibrateError::ModelMismatch {
            file: file(),
            recorded: info.model,
            station: model.name().to_string(),
        });
    }
    poses
        .iter()
        .map(|pose| {
            capture_pose(
                &pose.pose,
                layout,
                pose.frames.iter().map(Vec::as_slice),
                &options.settings.capture,
            )
            .map_err(|source| CalibrateError::CaptureRefused {
                file: file(),
                source,
            })
        })
        .collect()
}

/// The per-pose errors before and after the fit, and the objective.
fn table_lines(profile: &CalibrationProfile, captures: &[CapturedPose]) -> Vec<String> {
    let mm = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.1}"));
    let mut lines = vec![
        format!(
            "{:<14} {:>7} {:>13} {:>13} {:>14} {:>14}",
            "pose", "frames", "joint RMS", "joint RMS", "pinch gap err", "pinch gap err"
        ),
        format!(
            "{:<14} {:>7} {:>13} {:>13} {:>14} {:>14}",
            "", "", "before (rad)", "after (rad)", "before (mm)", "after (mm)"
        ),
    ];
    for (p, c) in profile.poses.iter().zip(captures) {
        lines.push(format!(
            "{:<14} {:>7} {:>13.3} {:>13.3} {:>14} {:>14}",
            p.name,
            c.frames_used,
            p.joint_rms_before_rad,
            p.joint_rms_after_rad,
            mm(p.pinch_gap_before_mm),
            mm(p.pinch_gap_after_mm)
        ));
    }
    lines.push(format!(
        "objective: {:.3} rad before, {:.3} rad after ({} evaluations)",
        profile.objective.before_rad, profile.objective.after_rad, profile.objective.evaluations
    ));
    let t = &profile.parameters;
    lines.push(match (profile.calibration_model, t.has_digit_scales()) {
        (CalibrationModel::Global, _) => format!(
            "model: global (scale {:.3}, roll/pitch/yaw {:.1}/{:.1}/{:.1}°)",
            t.scale,
            t.roll_rad.to_degrees(),
            t.pitch_rad.to_degrees(),
            t.yaw_rad.to_degrees()
        ),
        (CalibrationModel::PerDigit, true) => format!(
            "model: per digit (scale {:.3}; digit lengths thumb {:.2}, index {:.2}, middle {:.2}, ring {:.2}, little {:.2})",
            t.scale,
            t.digit_scale[0],
            t.digit_scale[1],
            t.digit_scale[2],
            t.digit_scale[3],
            t.digit_scale[4]
        ),
        (CalibrationModel::PerDigit, false) => {
            "model: per digit, but no digit factor lowered the objective: the global fit is kept"
                .to_string()
        }
    });
    lines
}

/// What the session hears of a fit that wrote its profile: where it went, how it changed
/// from the `previous` fit of the session (after a pose was captured again), and the poses it
/// could not match (the settings' `fit_check`), worst first.
pub fn fit_done(
    outcome: &FitOutcome,
    previous: Option<&FitOutcome>,
    options: &FitOptions,
) -> FitDone {
    let profile = &outcome.profile;
    let mut lines = vec![format!(
        "profile written: {} (user {})",
        options.out.display(),
        profile.user
    )];
    if let Some(before) = previous.map(|p| &p.profile) {
        lines.push(format!(
            "the fit changed: objective {:.3} → {:.3} rad, scale {:.3} → {:.3}, roll/pitch/yaw {:.1}/{:.1}/{:.1}° → {:.1}/{:.1}/{:.1}°",
            before.objective.after_rad,
            profile.objective.after_rad,
            before.parameters.scale,
            profile.parameters.scale,
            before.parameters.roll_rad.to_degrees(),
            before.parameters.pitch_rad.to_degrees(),
            before.parameters.yaw_rad.to_degrees(),
            profile.parameters.roll_rad.to_degrees(),
            profile.parameters.pitch_rad.to_degrees(),
            profile.parameters.yaw_rad.to_degrees(),
        ));
    }
    let misfits = poses_that_do_not_fit(
        &profile.poses,
        &PoseSet::orca_v1(),
        &options.settings.fit_check,
    )
    .into_iter()
    .map(|m| (m.index, m.sentence()))
    .collect();
    FitDone { lines, misfits }
}

/// `profiles/<user>.toml`, refusing user names that are not a plain file name.
pub fn default_profile_path(user: &str) -> Result<PathBuf, CalibrateError> {
    let plain = !user.is_empty()
        && !user.starts_with('.')
        && user
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if !plain {
        return Err(CalibrateError::UserNotAFileName {
            user: user.to_string(),
        });
    }
    Ok(Path::new("profiles").join(format!("{user}.toml")))
}
