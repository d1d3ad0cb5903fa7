//! `pomdar eval --profile-scales`: the retargeter alone (as the first part of `pomdar eval`)
//! under calibration transforms of each given scale and no rotation, in place of a profile.

use retarget::{CalibrationTransform, HandModel};
use serde::Serialize;

use super::{EvalError, build_retargeter, distinct_frames, retarget_frames};
use crate::mcap_log::TrialReader;
use crate::resim::layout_for;
use station::StationConfig;

/// One scale's figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScaleRow {
    /// The calibration transform's scale (roll, pitch and yaw 0).
    pub profile_scale: f64,
    /// The global scale `s*` of the tip error.
    pub tip_scale: f64,
    /// Tip error mean after `s*`, millimetres.
    pub tip_error_mean_mm: f64,
    /// Tip error mean after each digit's own scale, millimetres.
    pub tip_error_own_scale_mean_mm: Option<f64>,
    /// Jerk, radians.
    pub jerk_rad: f64,
    /// Frames measured.
    pub frames: usize,
}

/// The retargeter alone on `reader`'s distinct frames, once per scale in `scales` (the
/// configuration's own profile, if any, is replaced).
pub fn profile_scales(
    reader: &TrialReader,
    config: &StationConfig,
    model: &HandModel,
    scales: &[f64],
) -> Result<Vec<ScaleRow>, EvalError> {
    let (frames, _) = distinct_frames(reader, config)?;
    let mut retarget_config = config.retarget.clone();
    retarget_config.layout = layout_for(config, frames.first().map(|f| f.points.len()));
    scales
        .iter()
        .map(|&scale| {
            let transform = CalibrationTransform {
                scale,
                ..CalibrationTransform::IDENTITY
            };
            let mut retargeter = build_retargeter(model, retarget_config.clone(), Some(transform))?;
            let run = retarget_frames(&frames, &mut retargeter, 1.0 / config.control.rate_hz);
            let q = run.recorder.report();
            Ok(ScaleRow {
                profile_scale: scale,
                tip_scale: q.tip_scale,
                tip_error_mean_mm: q.tip_error_mean_mm,
                tip_error_own_scale_mean_mm: q.tip_error_own_scale_mean_mm,
                jerk_rad: q.jerk_rad,
                frames: q.frames,
            })
        })
        .collect()
}

/// The rows as a terminal table, one column per scale.
pub fn profile_scales_table(input: &str, rows: &[ScaleRow]) -> String {
    let mut out = format!(
        "retargeter alone on {input} under calibration profiles of each scale, no rotation\n"
    );
    let line = |name: &str, cell: &dyn Fn(&ScaleRow) -> String| {
        let cells: Vec<String> = rows.iter().map(|r| format!("{:>8}", cell(r))).collect();
        format!("  {name:<22} {}\n", cells.join(" "))
    };
    out += &line("profile scale", &|r| format!("{:.2}", r.profile_scale));
    out += &line("s*", &|r| format!("{:.3}", r.tip_scale));
    out += &line("tip error mean mm", &|r| {
        format!("{:.1}", r.tip_error_mean_mm)
    });
    out += &line("own-scale tip mean mm", &|r| {
        r.tip_error_own_scale_mean_mm
            .map_or("-".into(), |v| format!("{v:.1}"))
    });
    out += &line("jerk rad", &|r| format!("{:.4}", r.jerk_rad));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_has_a_column_per_scale() {
        let row = |s: f64, tip: f64| ScaleRow {
            profile_scale: s,
            tip_scale: 0.86 * s,
            tip_error_mean_mm: tip,
            tip_error_own_scale_mean_mm: None,
            jerk_rad: 0.0046,
            frames: 727,
        };
        let text = profile_scales_table("rec.mcap", &[row(1.0, 23.5), row(0.6, 20.3)]);
        let tip = text.lines().find(|l| l.contains("tip error mean")).unwrap();
        assert!(tip.contains("23.5") && tip.contains("20.3"), "{text}");
        let scale = text.lines().find(|l| l.contains("profile scale")).unwrap();
        assert!(scale.contains("1.00") && scale.contains("0.60"), "{text}");
    }
}
