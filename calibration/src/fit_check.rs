//! Which poses the fit could not match. After the fit, a pose whose joints the retargeter still
//! puts far from the pose's, or (a pinch pose) whose robot thumb still stops far from the
//! finger, was most likely held wrongly: the user stayed in the previous pose, or the thumb
//! never reached the finger. Such a pose is named in words, worst first, with an offer to
//! capture it alone again ([`PoseMisfit::sentence`]).
//!
//! The limits ([`FitCheck`], the settings' `fit_check` table) sit above what well-held poses
//! of synthetic users leave after the fit, uniform and non-uniform hands alike, and below
//! what a pose held as the previous one leaves (`cargo bench -p calibration --bench
//! calibration -- fit_check` measures both on users the limits were not chosen on).

use crate::poses::PoseSet;
use crate::profile::PoseReport;
use crate::settings::FitCheck;

/// A pose the fit could not match.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseMisfit {
    /// Index of the pose, in capture order.
    pub index: usize,
    /// Its name.
    pub pose: String,
    /// For a pinch pose, the finger the thumb should touch.
    pub pinch_finger: Option<retarget::Finger>,
    /// Its RMS joint error after the fit, radians.
    pub joint_rms_rad: f64,
    /// A pinch pose's gap error after the fit, mm.
    pub pinch_gap_mm: Option<f64>,
    /// How far over the check it is: the larger of error / limit over its two measures (> 1).
    pub excess: f64,
    /// The check it failed.
    pub check: FitCheck,
}

impl PoseMisfit {
    /// What the console says: "pinch_ring: the thumb stays 54 mm off the ring finger after the
    /// fit (40 mm allowed) — redo the pose?".
    pub fn sentence(&self) -> String {
        let gap_over = self
            .pinch_gap_mm
            .filter(|gap| *gap > self.check.pinch_gap_mm);
        let what = match (gap_over, self.pinch_finger) {
            (Some(gap), Some(finger)) => format!(
                "the thumb stays {gap:.0} mm off the {finger} finger after the fit ({:.0} mm allowed)",
                self.check.pinch_gap_mm
            ),
            _ => format!(
                "its joints stay {:.2} rad from the pose after the fit ({:.2} rad allowed)",
                self.joint_rms_rad, self.check.joint_rms_rad
            ),
        };
        format!("{}: {what} — redo the pose?", self.pose)
    }
}

/// The poses of `reports` (a profile's, in capture order) that fail `check`, worst first.
pub fn poses_that_do_not_fit(
    reports: &[PoseReport],
    poses: &PoseSet,
    check: &FitCheck,
) -> Vec<PoseMisfit> {
    let mut misfits: Vec<PoseMisfit> = reports
        .iter()
        .enumerate()
        .filter_map(|(index, report)| {
            let joints = report.joint_rms_after_rad / check.joint_rms_rad;
            let gap = report
                .pinch_gap_after_mm
                .map_or(0.0, |g| g / check.pinch_gap_mm);
            let excess = joints.max(gap);
            (excess > 1.0).then(|| PoseMisfit {
                index,
                pose: report.name.clone(),
                pinch_finger: poses
                    .poses
                    .iter()
                    .find(|p| p.name == report.name)
                    .and_then(|p| p.pinch),
                joint_rms_rad: report.joint_rms_after_rad,
                pinch_gap_mm: report.pinch_gap_after_mm,
                excess,
                check: *check,
            })
        })
        .collect();
    misfits.sort_by(|a, b| b.excess.total_cmp(&a.excess));
    misfits
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(name: &str, rms: f64, gap: Option<f64>) -> PoseReport {
        PoseReport {
            name: name.into(),
            joint_rms_before_rad: 0.3,
            joint_rms_after_rad: rms,
            pinch_gap_before_mm: gap.map(|g| g + 5.0),
            pinch_gap_after_mm: gap,
        }
    }

    #[test]
    fn poses_over_either_limit_are_named_worst_first_in_words() {
        let poses = PoseSet::orca_v1();
        let reports = vec![
            report("pinch_index", 0.05, Some(2.0)),
            report("pinch_middle", 0.05, Some(3.0)),
            report("pinch_ring", 0.12, Some(54.0)),
            report("pinch_little", 0.05, Some(2.0)),
            report("open", 0.05, None),
            report("open_spread", 0.05, None),
            report("closed", 0.51, None),
        ];
        let misfits = poses_that_do_not_fit(&reports, &poses, &FitCheck::default());
        let names: Vec<&str> = misfits.iter().map(|m| m.pose.as_str()).collect();
        assert_eq!(names, ["pinch_ring", "closed"]);
        assert_eq!(misfits[0].index, 2);
        assert_eq!(
            misfits[0].sentence(),
            "pinch_ring: the thumb stays 54 mm off the ring finger after the fit (40 mm allowed) — redo the pose?"
        );
        assert_eq!(
            misfits[1].sentence(),
            "closed: its joints stay 0.51 rad from the pose after the fit (0.38 rad allowed) — redo the pose?"
        );
    }

    #[test]
    fn a_session_within_the_limits_names_nothing() {
        let poses = PoseSet::orca_v1();
        let reports: Vec<PoseReport> = poses
            .poses
            .iter()
            .map(|p| report(&p.name, 0.37, p.pinch.map(|_| 39.0)))
            .collect();
        assert!(poses_that_do_not_fit(&reports, &poses, &FitCheck::default()).is_empty());
    }
}
