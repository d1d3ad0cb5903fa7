//! An evaluation set's summary: one row per recording, for the retargeter alone and for the
//! live path (the station's command in force at each distinct frame, which is what the robot
//! gets), and the worst value of each column over the set.

use std::fmt::Write as _;
use std::path::Path;

use retarget::QualityReport;
use serde::Serialize;

use super::EvalOutput;

/// One recording's headline figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SummaryRow {
    /// The recording's file name.
    pub recording: String,
    /// The keypoint layout it was read in.
    pub layout: String,
    /// Frames measured by the retargeter alone.
    pub frames: usize,
    /// The retargeter alone.
    pub alone: Headline,
    /// The live path.
    pub live: Headline,
}

/// The figures the set's targets are stated in.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Headline {
    /// Fingertip error after the global scale s*, mean, millimetres.
    pub tip_error_mean_mm: f64,
    /// Mean absolute third difference per joint and frame, radians.
    pub jerk_rad: f64,
    /// Largest per-frame joint step, radians.
    pub max_step_rad: f64,
    /// Frames where the human pinches.
    pub pinch_frames: usize,
    /// Share of them the robot closes, percent.
    pub pinches_closed_pct: Option<f64>,
    /// Frames of sustained human pinches (at least 2 frames and 40 ms; a tracker's one-frame
    /// outlier is not one).
    pub sustained_pinch_frames: usize,
    /// Share of them the robot closes, percent.
    pub sustained_pinches_closed_pct: Option<f64>,
    /// The same for the thumb–index pinches alone, percent.
    pub index_pinches_closed_pct: Option<f64>,
    /// Frames outside the joint limits or not finite.
    pub limit_violation_frames: usize,
    /// Fingertip error after each digit's own scale, mean, millimetres.
    pub tip_error_own_scale_mean_mm: Option<f64>,
    /// Mean over the digits of the human–robot flexion correlation.
    pub flexion_correlation_mean: Option<f64>,
    /// The robot's lag behind the human, seconds (frames when no times).
    pub lag_s: Option<f64>,
}

impl Headline {
    fn of(q: &QualityReport) -> Headline {
        Headline {
            tip_error_mean_mm: q.tip_error_mean_mm,
            jerk_rad: q.jerk_rad,
            max_step_rad: q.max_step_rad,
            pinch_frames: q.pinch_frames,
            pinches_closed_pct: q.pinches_closed_pct,
            sustained_pinch_frames: q.sustained_pinch_frames,
            sustained_pinches_closed_pct: q.sustained_pinches_closed_pct,
            index_pinches_closed_pct: index_closed_pct(q),
            limit_violation_frames: q.limit_violation_frames,
            tip_error_own_scale_mean_mm: q.tip_error_own_scale_mean_mm,
            flexion_correlation_mean: q.flexion_correlation_mean,
            lag_s: q.flexion_lag_s,
        }
    }
}

/// The share of the sustained thumb–index pinch frames the robot closes, percent.
fn index_closed_pct(q: &QualityReport) -> Option<f64> {
    let index = q.pinch_pairs.iter().find(|p| p.finger == "index")?;
    (index.sustained_frames > 0)
        .then(|| 100.0 * index.sustained_closed_frames as f64 / index.sustained_frames as f64)
}

/// What `pomdar eval --json` prints for several recordings.
#[derive(Debug, Clone, Serialize)]
pub struct SetOutput {
    /// Every recording's full report.
    pub recordings: Vec<EvalOutput>,
    /// One row per recording.
    pub summary: Vec<SummaryRow>,
}

impl SetOutput {
    /// The set of `recordings`' reports with their summary.
    pub fn of(recordings: Vec<EvalOutput>) -> SetOutput {
        let summary = recordings
            .iter()
            .map(|o| SummaryRow {
                recording: Path::new(&o.input)
                    .file_name()
                    .map_or_else(|| o.input.clone(), |n| n.to_string_lossy().into()),
                layout: o.layout.clone(),
                frames: o.quality.frames,
                alone: Headline::of(&o.quality),
                live: Headline::of(&o.live_path.quality),
            })
            .collect();
        SetOutput {
            recordings,
            summary,
        }
    }
}

fn opt(value: Option<f64>, precision: usize) -> String {
    value.map_or("-".into(), |v| format!("{v:.precision$}"))
}

fn pct(value: Option<f64>) -> String {
    value.map_or("-".into(), |v| format!("{v:.0} %"))
}

fn row(out: &mut String, width: usize, name: &str, frames: &str, h: &Headline) {
    let _ = writeln!(
        out,
        "  {name:<width$} {frames:>6} {:>9.1} {:>9.4} {:>9.3} {:>7} {:>7} {:>7} {:>7} {:>7} {:>6} {:>9} {:>7} {:>7}",
        h.tip_error_mean_mm,
        h.jerk_rad,
        h.max_step_rad,
        h.pinch_frames,
        pct(h.pinches_closed_pct),
        h.sustained_pinch_frames,
        pct(h.sustained_pinches_closed_pct),
        pct(h.index_pinches_closed_pct),
        h.limit_violation_frames,
        opt(h.tip_error_own_scale_mean_mm, 1),
        opt(h.flexion_correlation_mean, 3),
        h.lag_s.map_or("-".into(), |s| format!("{:.0}", s * 1e3)),
    );
}

/// The set's summary as a terminal table: the live path per recording (what the robot gets),
/// then the retargeter alone, each with the worst value of every column.
pub fn summary_table(set: &SetOutput) -> String {
    let mut out = format!("evaluation set: {} recordings\n", set.summary.len());
    let width = set
        .summary
        .iter()
        .map(|r| r.recording.chars().count())
        .max()
        .unwrap_or(0)
        .max(28);
    for (title, pick) in [
        (
            "live path (the station's command in force at each distinct frame)",
            (|r: &SummaryRow| &r.live) as fn(&SummaryRow) -> &Headline,
        ),
        ("retargeter alone", |r: &SummaryRow| &r.alone),
    ] {
        let _ = writeln!(
            out,
            "\n  {title}\n  {:<width$} {:>6} {:>9} {:>9} {:>9} {:>7} {:>7} {:>7} {:>7} {:>7} {:>6} {:>9} {:>7} {:>7}",
            "recording",
            "frames",
            "tip mm",
            "jerk rad",
            "step rad",
            "pinch",
            "closed",
            "held",
            "closed",
            "index",
            "limits",
            "own mm",
            "flex r",
            "lag ms"
        );
        for r in &set.summary {
            row(
                &mut out,
                width,
                &r.recording,
                &r.frames.to_string(),
                pick(r),
            );
        }
        let total = worst(set.summary.iter().map(pick));
        row(&mut out, width, "worst (pinch, limits: total)", "", &total);
    }
    out
}

/// The worst of every column: largest error, jerk, step and violations, smallest closure.
fn worst<'a>(rows: impl Iterator<Item = &'a Headline>) -> Headline {
    let mut w = Headline {
        tip_error_mean_mm: 0.0,
        jerk_rad: 0.0,
        max_step_rad: 0.0,
        pinch_frames: 0,
        pinches_closed_pct: None,
        sustained_pinch_frames: 0,
        sustained_pinches_closed_pct: None,
        index_pinches_closed_pct: None,
        limit_violation_frames: 0,
        tip_error_own_scale_mean_mm: None,
        flexion_correlation_mean: None,
        lag_s: None,
    };
    for h in rows {
        w.tip_error_mean_mm = w.tip_error_mean_mm.max(h.tip_error_mean_mm);
        w.jerk_rad = w.jerk_rad.max(h.jerk_rad);
        w.max_step_rad = w.max_step_rad.max(h.max_step_rad);
        w.pinch_frames += h.pinch_frames;
        w.sustained_pinch_frames += h.sustained_pinch_frames;
        w.limit_violation_frames += h.limit_violation_frames;
        w.pinches_closed_pct = worse(w.pinches_closed_pct, h.pinches_closed_pct, f64::min);
        w.sustained_pinches_closed_pct = worse(
            w.sustained_pinches_closed_pct,
            h.sustained_pinches_closed_pct,
            f64::min,
        );
        w.index_pinches_closed_pct = worse(
            w.index_pinches_closed_pct,
            h.index_pinches_closed_pct,
            f64::min,
        );
        w.tip_error_own_scale_mean_mm = worse(
            w.tip_error_own_scale_mean_mm,
            h.tip_error_own_scale_mean_mm,
            f64::max,
        );
        w.flexion_correlation_mean = worse(
            w.flexion_correlation_mean,
            h.flexion_correlation_mean,
            f64::min,
        );
        w.lag_s = worse(
            w.lag_s,
            h.lag_s,
            |a, b| if b.abs() > a.abs() { b } else { a },
        );
    }
    w
}

/// The worse of two optional figures by `pick`; a missing one does not count.
fn worse(a: Option<f64>, b: Option<f64>, pick: fn(f64, f64) -> f64) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(pick(a, b)),
        (a, b) => a.or(b),
    }
}
