//! Catalog, baseline and rules files: validation errors name the file, the entry or key and
//! the allowed values; the baseline computed from human trials refuses other embodiments by
//! name and round-trips through its TOML file.

use crate::common;

use common::*;
use scoring::{BaselineTable, Ending, ScoringRules, TaskCatalog, TrialRecord, compute_baseline};
use serde_json::json;

fn catalog_error(text: &str) -> String {
    TaskCatalog::from_toml_str(text, "lab_tasks.toml")
        .unwrap_err()
        .to_string()
}

const HEADER: &str = "[catalog]\nname = \"lab\"\nprovenance = \"our lab\"\n";

fn one_task(correctness: &str, extra: &str) -> String {
    format!(
        "{HEADER}\n[[task]]\nid = \"V1\"\nname = \"Wheel\"\nconfiguration = \"vertical\"\narm = \"vertical_axis\"\ncorrectness = {correctness}\nprovenance = \"p\"\n{extra}"
    )
}

#[test]
fn catalog_errors_name_the_file_the_task_and_the_allowed_values() {
    let cases = [
        (
            one_task("{ kind = \"notches\", count = 0 }", ""),
            "lab_tasks.toml: task V1: correctness.count = 0: a whole number ≥ 1",
        ),
        (
            one_task("{ kind = \"rotation\", full_deg = -360.0 }", ""),
            "lab_tasks.toml: task V1: correctness.full_deg = -360: degrees, finite and > 0",
        ),
        (
            one_task("{ kind = \"distance\", full_mm = 0.0 }", ""),
            "lab_tasks.toml: task V1: correctness.full_mm = 0: millimetres, finite and > 0",
        ),
        (
            one_task(
                "{ kind = \"notches\", count = 6 }",
                "[[task]]\nid = \"V1\"\nname = \"Again\"\nconfiguration = \"vertical\"\narm = \"fixed\"\ncorrectness = { kind = \"grasp\" }\nprovenance = \"p\"\n",
            ),
            "lab_tasks.toml: task[1].id = \"V1\": a task ID used once",
        ),
        (
            one_task("{ kind = \"notches\", count = 6 }", "")
                .replace("provenance = \"p\"", "provenance = \"\""),
            "lab_tasks.toml: task V1: provenance = \"\": a note saying where the entry comes from",
        ),
        (
            one_task("{ kind = \"notches\", count = 6 }", "")
                .replace("id = \"V1\"", "id = \"V 1\""),
            "lab_tasks.toml: task[0].id = \"V 1\": a non-empty ID of letters, digits, '_' or '-'",
        ),
        (
            "task = []\n".to_string() + HEADER,
            "lab_tasks.toml: task = []: at least one [[task]]",
        ),
    ];
    for (text, expected) in cases {
        let message = catalog_error(&text);
        assert!(
            message.starts_with(expected),
            "got {message:?}\nexpected {expected:?}"
        );
    }
}

#[test]
fn catalog_syntax_errors_name_the_file_and_the_key() {
    // An unknown key, an unknown kind, an unknown configuration.
    let message = catalog_error(&one_task(
        "{ kind = \"notches\", count = 6 }",
        "colour = \"red\"\n",
    ));
    assert!(
        message.starts_with("lab_tasks.toml: ") && message.contains("colour"),
        "{message}"
    );
    let message = catalog_error(&one_task("{ kind = \"spin\", count = 6 }", ""));
    assert!(
        message.contains("spin") && message.contains("notches"),
        "{message}"
    );
    let message = catalog_error(
        &one_task("{ kind = \"notches\", count = 6 }", "").replace("\"vertical\"", "\"diagonal\""),
    );
    assert!(
        message.contains("diagonal") && message.contains("continuous"),
        "{message}"
    );
    let message = catalog_error(&one_task("{ kind = \"grasp\", levels = 3 }", ""));
    assert!(message.contains("levels"), "{message}");
}

#[test]
fn baseline_errors_name_the_file_and_the_task() {
    let catalog = TaskCatalog::builtin();
    let head = "[baseline]\nexample = false\nsource = \"lab\"\n";
    let cases = [
        (
            format!("{head}[[task]]\nid = \"Z1\"\nmean_s = 3.0\nn = 2\n"),
            "base.toml: task[0].id = \"Z1\": a task of the catalog (V1, V2",
        ),
        (
            format!("{head}[[task]]\nid = \"V1\"\nmean_s = 0.0\nn = 2\n"),
            "base.toml: task V1: mean_s = 0: seconds, finite and > 0",
        ),
        (
            format!("{head}[[task]]\nid = \"V1\"\nmean_s = 3.0\nn = 0\n"),
            "base.toml: task V1: n = 0: the number of trials averaged, ≥ 1",
        ),
        (
            format!("{head}[[task]]\nid = \"V1\"\nmean_s = 3.0\nn = 2\nstd_s = -1.0\n"),
            "base.toml: task V1: std_s = -1: seconds, finite and ≥ 0",
        ),
        (
            format!(
                "{head}[[task]]\nid = \"V1\"\nmean_s = 3.0\nn = 2\n[[task]]\nid = \"V1\"\nmean_s = 3.0\nn = 2\n"
            ),
            "base.toml: task V1 = listed twice: one entry per task",
        ),
        (
            "[baseline]\nexample = false\nsource = \" \"\n".to_string(),
            "base.toml: baseline.source = \"\": a note saying where the times come from",
        ),
    ];
    for (text, expected) in cases {
        let message = BaselineTable::from_toml_str(&text, "base.toml", &catalog)
            .unwrap_err()
            .to_string();
        assert!(
            message.starts_with(expected),
            "got {message:?}\nexpected {expected:?}"
        );
    }
    // The header must say whether it is an example.
    let message =
        BaselineTable::from_toml_str("[baseline]\nsource = \"x\"\n", "base.toml", &catalog)
            .unwrap_err()
            .to_string();
    assert!(
        message.starts_with("base.toml: ") && message.contains("example"),
        "{message}"
    );
}

fn human(file: &str, task: &str, stop_s: f64) -> TrialRecord {
    let log = stopped_trial(file, task, "human", &[1.0], stop_s);
    let mut log = log;
    log.metadata.insert("embodiment".into(), "human".into());
    TrialRecord::from_log(&log, &TaskCatalog::builtin()).unwrap()
}

#[test]
fn the_baseline_is_the_mean_time_of_recorded_human_trials() {
    let catalog = TaskCatalog::builtin();
    let mut practice = human("p.mcap", "V1", 50.0);
    practice.practice = true;
    let aborted = {
        let log = trial(
            "ab.mcap",
            "V1",
            "human",
            false,
            &[(0.0, start()), (70.0, json!({"event": "abort"}))],
        );
        TrialRecord::from_log(&log, &catalog).unwrap()
    };
    assert_eq!(aborted.ending, Ending::Aborted);
    let robot = {
        let log = stopped_trial("robot.mcap", "V1", "orca_full", &[], 5.0);
        TrialRecord::from_log(&log, &catalog).unwrap()
    };
    let trials = vec![
        human("a.mcap", "V1", 10.0),
        human("b.mcap", "V1", 12.0),
        human("c.mcap", "V1", 14.0),
        human("d.mcap", "G3", 7.5),
        practice,
        aborted,
        robot,
    ];
    let result = compute_baseline(&trials, &catalog, &ScoringRules::default(), "test");
    assert_eq!(result.refused.len(), 1);
    assert_eq!(result.refused[0].file, "robot.mcap");
    assert!(
        result.refused[0]
            .reason
            .contains("\"orca_full\", not \"human\"")
    );
    let left: Vec<(&str, &str)> = result
        .left_out
        .iter()
        .map(|l| (l.file.as_str(), l.reason.as_str()))
        .collect();
    assert_eq!(left, [("p.mcap", "practice trial"), ("ab.mcap", "aborted")]);
    let v1 = result.table.get("V1").unwrap();
    assert_eq!((v1.mean_s, v1.n, v1.std_s), (12.0, 3, Some(2.0)));
    let g3 = result.table.get("G3").unwrap();
    assert_eq!((g3.mean_s, g3.n, g3.std_s), (7.5, 1, None));
    assert!(!result.table.header.example);

    // The TOML file reads back as the same table.
    let text = result.table.to_toml();
    let back = BaselineTable::from_toml_str(&text, "computed.toml", &catalog).unwrap();
    assert_eq!(back.tasks, result.table.tasks);
    assert_eq!(back.header, result.table.header);
    assert!(text.starts_with("# POMDAR human baseline"), "{text}");

    // A time limit leaves slow trials out.
    let rules = ScoringRules {
        timeout_s: Some(13.0),
        ..ScoringRules::default()
    };
    let result = compute_baseline(&trials, &catalog, &rules, "test");
    assert_eq!(result.table.get("V1").unwrap().n, 2);
    assert!(
        result
            .left_out
            .iter()
            .any(|l| l.file == "c.mcap" && l.reason.starts_with("timed out"))
    );
}
