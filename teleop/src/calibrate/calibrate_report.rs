//! What `pomdar calibrate` prints after a session: the session's captures and the fit's
//! table, and for a simulated user the recovered transform against the true one and the
//! profile's `source` line.

use std::path::Path;

use calibration::{CalibrationProfile, SyntheticUser};
use retarget::human_hand::HandVariation;

use super::CalibrateError;
use super::calibrate_request::CalibrateRequest;
use super::fit_session::FitOptions;
use super::session_node::SessionReport;
use super::simulated_user::{SIMULATED_NOISE_M, true_transform};

/// The profile's `source` for a simulated user's session.
pub(super) fn simulated_source(
    args: &CalibrateRequest,
    user: &SyntheticUser,
    session_out: &Path,
) -> String {
    let [r, p, y] = args.glove_rpy.unwrap_or([0.0; 3]);
    format!(
        "simulated user (hand scale {}{}, glove rpy {r},{p},{y} deg, noise {} m, seed {}), session {}",
        user.hand_scale,
        proportions(user),
        SIMULATED_NOISE_M,
        user.seed,
        session_out.display()
    )
}

/// `, proportions thumb+12-index-4-middle+0-palm+3` for a hand unlike the average, else empty.
pub(super) fn proportions(user: &SyntheticUser) -> String {
    if user.variation == HandVariation::NONE {
        String::new()
    } else {
        format!(", proportions {}", user.variation.label())
    }
}

/// What the session recorded and the fit's table.
pub(super) fn print_session_report(report: &SessionReport, out: &Path) {
    let retried: Vec<String> = calibration::POSE_NAMES
        .iter()
        .zip(&report.captures_per_pose)
        .filter(|(_, n)| **n > 1)
        .map(|(p, n)| format!("{p} ×{n}"))
        .collect();
    eprintln!(
        "session recorded: {} ({} keypoint frames; accepted capture frames per pose {:?}; {})",
        report.path.display(),
        report.frames,
        report.frames_per_pose,
        if retried.is_empty() {
            "no pose captured again".to_string()
        } else {
            format!("captured again: {}", retried.join(", "))
        }
    );
    if report.poses_not_sent > 0 {
        eprintln!(
            "warning: {} sends of a pose to the hand could not be published",
            report.poses_not_sent
        );
    }
    for line in &report.fit.table {
        println!("{line}");
    }
    println!("wrote {} (user {})", out.display(), report.fit.profile.user);
}

/// `--simulate`: the recovered transform against the simulated user's true one.
pub(super) fn print_recovery(
    user: &SyntheticUser,
    fit: &FitOptions,
    profile: &CalibrationProfile,
) -> Result<(), CalibrateError> {
    let truth = true_transform(user, &fit.station, &fit.settings)?;
    let got = profile.parameters;
    println!(
        "recovered vs true (the user's hand size and glove misalignment on top of the average hand's calibration):"
    );
    println!("  {:<10} {:>10} {:>10}", "", "recovered", "true");
    println!(
        "  {:<10} {:>10.4} {:>10.4}",
        "scale", got.scale, truth.scale
    );
    for (name, a, b) in [
        ("roll", got.roll_rad, truth.roll_rad),
        ("pitch", got.pitch_rad, truth.pitch_rad),
        ("yaw", got.yaw_rad, truth.yaw_rad),
    ] {
        println!(
            "  {:<10} {:>9.2}° {:>9.2}°",
            name,
            a.to_degrees(),
            b.to_degrees()
        );
    }
    let scale_error = got.scale / truth.scale - 1.0;
    let rotation_error = (got.rotation().inverse() * truth.rotation())
        .angle()
        .to_degrees();
    println!(
        "  scale error {:+.1} %, rotation error {rotation_error:.2}° (the acceptance test asks 3 % and 3° for 90 % of users)",
        100.0 * scale_error
    );
    if user.variation != HandVariation::NONE {
        println!(
            "  the hand's proportions differ from the average hand's ({}): no global transform is exact for it, so \"true\" is its size and misalignment only",
            user.variation.label()
        );
    }
    Ok(())
}
