//! Correctness in [0, 1] from a trial's progress and drop events, per the task's kind.
//!
//! | kind | progress `value` | correctness |
//! |---|---|---|
//! | notches, curves (`count` N) | whole numbers (negative undoes a mistaken mark) | `min(Σ value, N) / N` |
//! | rotation (`full_deg` D) | degrees turned (negative: turned back) | `clamp(Σ value / D, 0, 1)` |
//! | distance (`full_mm` L) | millimetres slid (negative: slid back) | `clamp(Σ value / L, 0, 1)` |
//! | grasp | the level reached: 0, 0.5 or 1 | the last level given |
//!
//! Grasp: 0 not lifted, 0.5 lifted then dropped, 1 relocated (the paper's levels). A `drop`
//! event sets the level to 0.5 (an object can only be dropped once lifted), unless a later
//! level event says otherwise (re-grasped and relocated: 1). Drops in other tasks do not change
//! correctness; they are counted in the trial's notes.
//!
//! The running total of notches or curves may never go below 0 (an undo of a mark that was
//! never given is an error). Events after `cutoff_ns` (the time limit of a timed-out trial)
//! are checked but not counted.

use crate::catalog::CorrectnessKind;
use crate::trial_log::Mark;

/// The allowed grasp levels.
pub const GRASP_LEVELS: [f64; 3] = [0.0, 0.5, 1.0];

/// A trial's correctness.
#[derive(Debug, Clone, PartialEq)]
pub struct Correctness {
    /// Correctness in [0, 1].
    pub value: f64,
    /// The raw progress counted: notches, curves, degrees, millimetres or the grasp level.
    pub progress: f64,
    /// Remarks for the report (capped totals, drops, ignored late events).
    pub notes: Vec<String>,
}

/// Correctness of `marks` (log time ns, mark) for a task of `kind`; events after `cutoff_ns`
/// are not counted. `Err` says which value is invalid for the kind.
pub fn correctness(
    kind: &CorrectnessKind,
    marks: &[(i64, Mark)],
    cutoff_ns: Option<i64>,
) -> Result<Correctness, String> {
    let counted = |t: i64| cutoff_ns.is_none_or(|c| t <= c);
    let mut notes = Vec::new();
    let late = marks.iter().filter(|(t, _)| !counted(*t)).count();
    if late > 0 {
        notes.push(format!(
            "{late} progress/drop event(s) after the time limit not counted"
        ));
    }
    let unit = kind.progress_unit();
    let by_kind = match *kind {
        CorrectnessKind::Notches { count } | CorrectnessKind::Curves { count } => {
            whole_count_correctness(count, unit, marks, counted)?
        }
        CorrectnessKind::Rotation { full_deg: full }
        | CorrectnessKind::Distance { full_mm: full } => {
            continuous_correctness(full, unit, marks, counted)
        }
        CorrectnessKind::Grasp {} => grasp_correctness(marks, counted)?,
    };
    notes.extend(by_kind.notes);
    let drops = marks.iter().filter(|(_, m)| *m == Mark::Drop).count();
    if drops > 0 {
        notes.push(format!("{drops} drop(s)"));
    }
    Ok(Correctness { notes, ..by_kind })
}

/// Notches or curves: whole numbers of `unit` summed (never below 0), capped at `count`.
fn whole_count_correctness(
    count: u32,
    unit: &str,
    marks: &[(i64, Mark)],
    counted: impl Fn(i64) -> bool,
) -> Result<Correctness, String> {
    let mut total = 0.0_f64;
    for (i, (t, mark)) in marks.iter().enumerate() {
        let Mark::Progress(v) = *mark else { continue };
        if v.fract() != 0.0 {
            return Err(format!(
                "progress value {v} is not a whole number of {unit} (mark {})",
                i + 1
            ));
        }
        if !counted(*t) {
            continue;
        }
        total += v;
        if total < 0.0 {
            return Err(format!(
                "progress total goes below 0 {unit} at mark {} (value {v})",
                i + 1
            ));
        }
    }
    let full = f64::from(count);
    let mut notes = Vec::new();
    if total > full {
        notes.push(format!(
            "progress total {total} {unit} exceeds the task's {count}: counted as {count}"
        ));
    }
    Ok(Correctness {
        value: total.min(full) / full,
        progress: total,
        notes,
    })
}

/// Rotation or distance: the net progress in `unit` over `full`, clamped to [0, 1].
fn continuous_correctness(
    full: f64,
    unit: &str,
    marks: &[(i64, Mark)],
    counted: impl Fn(i64) -> bool,
) -> Correctness {
    // A sum of no values is −0.0 in Rust; `+ 0.0` makes it 0 (no "-0.000" in a report).
    let total: f64 = marks
        .iter()
        .filter(|(t, _)| counted(*t))
        .filter_map(|(_, m)| match m {
            Mark::Progress(v) => Some(*v),
            Mark::Drop => None,
        })
        .sum::<f64>()
        + 0.0;
    let mut notes = Vec::new();
    if total > full {
        notes.push(format!(
            "progress total {total} {unit} exceeds the full {full} {unit}: correctness capped at 1"
        ));
    } else if total < 0.0 {
        notes.push(format!(
            "net progress {total} {unit} is negative: correctness 0"
        ));
    }
    Correctness {
        value: (total / full).clamp(0.0, 1.0),
        progress: total,
        notes,
    }
}

/// Grasp: the last counted level, a drop meaning 0.5; every level is checked.
fn grasp_correctness(
    marks: &[(i64, Mark)],
    counted: impl Fn(i64) -> bool,
) -> Result<Correctness, String> {
    let mut level = 0.0;
    for (i, (t, mark)) in marks.iter().enumerate() {
        let next = match *mark {
            Mark::Progress(v) if GRASP_LEVELS.contains(&v) => v,
            Mark::Progress(v) => {
                return Err(format!(
                    "grasp level {v} (mark {}) is not one of 0, 0.5, 1",
                    i + 1
                ));
            }
            Mark::Drop => 0.5,
        };
        if counted(*t) {
            level = next;
        }
    }
    Ok(Correctness {
        value: level,
        progress: level,
        notes: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn progress(values: &[f64]) -> Vec<(i64, Mark)> {
        values
            .iter()
            .enumerate()
            .map(|(i, v)| (i as i64, Mark::Progress(*v)))
            .collect()
    }

    #[test]
    fn notches_are_counted_and_capped() {
        let kind = CorrectnessKind::Notches { count: 6 };
        let c = correctness(&kind, &progress(&[1.0, 1.0, 1.0, -1.0, 1.0]), None);
        assert_eq!(c.map(|c| c.value), Ok(0.5));
        let c = correctness(&kind, &progress(&[4.0, 4.0]), None);
        assert_eq!(c.as_ref().map(|c| c.value), Ok(1.0));
        assert!(c.is_ok_and(|c| c.notes[0].contains("counted as 6")));
        assert!(correctness(&kind, &progress(&[0.5]), None).is_err());
        assert!(correctness(&kind, &progress(&[-1.0]), None).is_err());
    }

    #[test]
    fn no_progress_on_a_continuous_task_is_zero_not_negative_zero() {
        let kind = CorrectnessKind::Rotation { full_deg: 360.0 };
        let c = correctness(&kind, &[], None).unwrap();
        assert!(c.value == 0.0 && c.value.is_sign_positive(), "{}", c.value);
        assert_eq!(format!("{:.3} {}", c.value, c.progress), "0.000 0");
    }

    #[test]
    fn a_cutoff_leaves_late_progress_out() {
        let kind = CorrectnessKind::Curves { count: 4 };
        let c = correctness(&kind, &progress(&[1.0, 1.0, 1.0, 1.0]), Some(1));
        assert_eq!(c.map(|c| c.value), Ok(0.5));
    }

    #[test]
    fn grasp_takes_the_last_level_and_a_drop_means_half() {
        let marks = vec![
            (0, Mark::Progress(0.5)),
            (1, Mark::Drop),
            (2, Mark::Progress(1.0)),
        ];
        let c = correctness(&CorrectnessKind::Grasp {}, &marks, None);
        assert_eq!(c.map(|c| c.value), Ok(1.0));
        let c = correctness(&CorrectnessKind::Grasp {}, &marks[..2], None);
        assert_eq!(c.map(|c| c.value), Ok(0.5));
        let bad = correctness(&CorrectnessKind::Grasp {}, &progress(&[0.7]), None);
        assert!(bad.is_err_and(|e| e.contains("0.7")));
    }
}
