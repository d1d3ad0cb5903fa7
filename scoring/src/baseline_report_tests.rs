//! `baseline_report`'s tests: grouping, statistics, the minimum flag and the renderings.

use super::*;
use crate::baseline::compute_baseline;
use crate::rules::ScoringRules;
use crate::trial_log::{Ending, HUMAN_EMBODIMENT, TrialRecord};

const T0_NS: i64 = 1_000_000_000;

fn human(
    file: &str,
    task: &str,
    user: Option<&str>,
    index: Option<&str>,
    time_s: f64,
) -> TrialRecord {
    TrialRecord {
        source: file.into(),
        task: task.into(),
        embodiment: HUMAN_EMBODIMENT.into(),
        practice: false,
        user: user.map(Into::into),
        operator: None,
        trial_index: index.map(Into::into),
        metadata: BTreeMap::new(),
        start_ns: T0_NS,
        end_ns: T0_NS + (time_s * 1e9).round() as i64,
        ending: Ending::Stopped,
        marks: Vec::new(),
        notes: Vec::new(),
    }
}

fn study(trials: &[TrialRecord], min_trials: u32) -> BaselineStudy {
    let catalog = TaskCatalog::builtin();
    let computation = compute_baseline(trials, &catalog, &ScoringRules::default(), "test");
    baseline_study(&computation, &catalog, min_trials)
}

fn task<'a>(study: &'a BaselineStudy, id: &str) -> &'a StudyTask {
    study.tasks.iter().find(|t| t.id == id).unwrap()
}

/// V1: ann #10, #1, #2 and bob #2, #1 out of order, one trial without a user; C1: ann and
/// bob, all named.
fn mixed_trials() -> Vec<TrialRecord> {
    vec![
        human("bob_2.mcap", "V1", Some("bob"), Some("2"), 12.0),
        human("ann_10.mcap", "V1", Some("ann"), Some("10"), 9.0),
        human("anon.mcap", "V1", None, Some("1"), 11.0),
        human("ann_1.mcap", "V1", Some("ann"), Some("1"), 10.0),
        human("c1_bob.mcap", "C1", Some("bob"), None, 20.0),
        human("ann_2.mcap", "V1", Some("ann"), Some("2"), 11.5),
        human("bob_1.mcap", "V1", Some("bob"), Some("1"), 14.0),
        human("c1_ann.mcap", "C1", Some("ann"), Some("1"), 22.0),
    ]
}

/// A participant's label and trials as (index, seconds).
type Grouped<'a> = (&'a str, Vec<(Option<&'a str>, f64)>);

#[test]
fn trials_are_grouped_per_participant_in_trial_index_order() {
    let study = study(&mixed_trials(), 3);
    let v1 = task(&study, "V1");
    let grouped: Vec<Grouped> = v1
        .participants
        .iter()
        .map(|p| {
            let trials = p.trials.iter();
            (
                p.label(),
                trials
                    .map(|t| (t.trial_index.as_deref(), t.time_s))
                    .collect(),
            )
        })
        .collect();
    assert_eq!(
        grouped,
        [
            (
                "ann",
                vec![(Some("1"), 10.0), (Some("2"), 11.5), (Some("10"), 9.0)]
            ),
            ("bob", vec![(Some("1"), 14.0), (Some("2"), 12.0)]),
            (UNNAMED_PARTICIPANT, vec![(Some("1"), 11.0)]),
        ]
    );
    assert_eq!(v1.participants[2].participant, None);
    let s = v1.summary.as_ref().unwrap();
    assert_eq!((s.trials, s.participants, s.unnamed_trials), (6, 2, 1));
    let c1 = task(&study, "C1");
    let s = c1.summary.as_ref().unwrap();
    assert_eq!((s.trials, s.participants, s.unnamed_trials), (2, 2, 0));
    assert_eq!(c1.participants[0].trials[0].source, "c1_ann.mcap");
    // Tasks without trials are listed, in catalog order, without statistics.
    let ids: Vec<&str> = study.tasks.iter().map(|t| t.id.as_str()).collect();
    assert_eq!(
        ids,
        TaskCatalog::builtin().ids().split(", ").collect::<Vec<_>>()
    );
    assert!(task(&study, "H2").summary.is_none() && task(&study, "H2").participants.is_empty());
}

#[test]
fn the_table_counts_participants_only_when_every_trial_names_one() {
    let catalog = TaskCatalog::builtin();
    let computation = compute_baseline(&mixed_trials(), &catalog, &ScoringRules::default(), "test");
    assert_eq!(computation.table.get("V1").unwrap().participants, None);
    assert_eq!(computation.table.get("C1").unwrap().participants, Some(2));
    assert_eq!(computation.used.len(), 8);
    assert_eq!(computation.used[0].participant.as_deref(), Some("bob"));
}

#[test]
fn mean_std_min_and_max_match_hand_computed_values() {
    // 10, 16, 12, 14: mean 13, sample std √((9 + 9 + 1 + 1) / 3) = √(20/3) = 2.58199.
    let trials = [
        human("a.mcap", "G3", Some("ann"), Some("1"), 10.0),
        human("b.mcap", "G3", Some("ann"), Some("2"), 16.0),
        human("c.mcap", "G3", Some("bob"), Some("1"), 12.0),
        human("d.mcap", "G3", Some("bob"), Some("2"), 14.0),
        human("e.mcap", "V2", Some("cat"), Some("1"), 7.25),
    ];
    let study = study(&trials, 4);
    let s = task(&study, "G3").summary.clone().unwrap();
    assert_eq!((s.mean_s, s.std_s), (13.0, Some(2.582)));
    assert_eq!((s.min_s, s.max_s), (10.0, 16.0));
    let single = task(&study, "V2").summary.clone().unwrap();
    assert_eq!((single.mean_s, single.std_s), (7.25, None));
    assert_eq!((single.min_s, single.max_s), (7.25, 7.25));
}

#[test]
fn tasks_below_the_minimum_are_flagged_and_tasks_at_it_are_not() {
    let trials: Vec<TrialRecord> = (1..=4)
        .map(|i| {
            human(
                &format!("{i}.mcap"),
                "V1",
                Some("ann"),
                Some(&i.to_string()),
                10.0,
            )
        })
        .collect();
    let at = study(&trials, 4);
    let s = task(&at, "V1").summary.clone().unwrap();
    assert!(!s.below_minimum);
    assert_eq!(s.flag(4), None);
    assert_eq!(at.below_minimum().count(), 0);
    let above = study(&trials, 5);
    let s = task(&above, "V1").summary.clone().unwrap();
    assert!(s.below_minimum);
    assert_eq!(s.flag(5).as_deref(), Some("FEW: 4 trials < minimum 5"));
    let flagged: Vec<&str> = above.below_minimum().map(|(t, _)| t.id.as_str()).collect();
    assert_eq!(flagged, ["V1"], "tasks without trials are missing, not few");
}

#[test]
fn the_text_lists_the_table_then_the_times_per_participant() {
    let text = render_study_text(&study(&mixed_trials(), 18));
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "task  name              trials   mean s    std s    min s    max s  participants"
    );
    let v1 = lines.iter().find(|l| l.starts_with("V1 ")).unwrap();
    assert_eq!(
        *v1,
        "V1    Wheel                  6   11.250    1.725    9.000   14.000   2 + unnamed  \
         FEW: 6 trials < minimum 18"
    );
    assert!(text.contains("H2    Chopsticks             0   (no usable human trial)"));
    assert!(text.contains("minimum 18 trials per task: 2 of 2 tasks with trials below it"));
    assert!(
        text.contains("\nV1    ann        #1 10.000   #2 11.500   #10 9.000\n"),
        "{text}"
    );
    assert!(
        text.contains("\n      bob        #1 14.000   #2 12.000\n"),
        "{text}"
    );
    assert!(text.contains("\n      (unnamed)  #1 11.000\n"), "{text}");
    assert!(text.contains("\nC1    ann        #1 22.000\n      bob        #? 20.000\n"));
}

#[test]
fn the_markdown_has_the_table_the_times_and_the_warnings() {
    let mut trials = mixed_trials();
    trials[0].user = Some("b|ob".into());
    let mut practice = human("p.mcap", "V1", Some("ann"), None, 30.0);
    practice.practice = true;
    trials.push(practice);
    let text = render_study_markdown(&study(&trials, 2));
    assert!(!text.contains("> **WARNING:**"), "{text}");
    assert!(
        text.contains("| V1 | Wheel | 6 | 3 + unnamed | 11.250 | 1.725 | 9.000 | 14.000 |  |"),
        "{text}"
    );
    assert!(text.contains("| H2 | Chopsticks | 0 | 0 | – | – | – | – | no usable human trial |"));
    assert!(text.contains("| V1 | b\\|ob | 1 | #2 12.000 |"), "{text}");
    assert!(text.contains("| p.mcap | practice trial |"), "{text}");
    let few = render_study_markdown(&study(&mixed_trials(), 7));
    assert!(
        few.contains("> **WARNING:** task V1: 6 trials < minimum 7"),
        "{few}"
    );
    assert!(few.contains("| **FEW: 6 trials < minimum 7** |"), "{few}");
}
