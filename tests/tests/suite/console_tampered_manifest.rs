//! `pomdar trial` refuses to resume a session whose manifest (`session.json`) names a trial
//! log outside the session directory: a clear error naming the manifest, the field and the
//! names allowed; the manifest is checked before any trial file is opened, and nothing in or
//! around the session directory is renamed or written (a crash's `.part` log beside it is
//! left as it was too).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use pomdar_tests::pomdar_binary::run_pomdar;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::test_domain;
use serde_json::json;

/// Every file under `dir` with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                todo.push(path);
            } else {
                files.insert(path.clone(), std::fs::read(&path).unwrap());
            }
        }
    }
    files
}

fn tampered_manifest(file: &str) -> String {
    json!({
        "format": "pomdar-session/1", "task": "V1", "embodiment": "orca_full",
        "user": "sim", "operator": "ci", "practice_planned": 0, "trials_planned": 1,
        "calibration_profile": null, "config_digest": "", "baseline": null,
        "created_utc": "20261126T000000Z", "updated_utc": "20261126T000000Z", "runs": 1,
        "trials": [{"file": file, "practice": false, "index": 1, "status": "scored",
                    "correctness": 1.0}],
        "notes": []
    })
    .to_string()
}

#[test]
fn a_manifest_naming_a_file_outside_the_session_is_refused_and_nothing_is_touched() {
    let root = scratch_dir("tampered-manifest");
    let sessions = root.join("sessions");
    let dir = sessions.join("sim").join("orca_full").join("V1");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = "../../../../victim.mcap";
    std::fs::write(dir.join("session.json"), tampered_manifest(bad)).unwrap();
    // What a resumed session would otherwise rename (the trial "set aside") or recover.
    std::fs::write(root.join("victim.mcap"), b"not the console's").unwrap();
    std::fs::write(dir.join("V1-t01.mcap.part"), b"a crash's partial log").unwrap();
    let script = root.join("quit.script");
    std::fs::write(&script, "quit\n").unwrap();
    let before = snapshot(&root);

    let domain = test_domain().to_string();
    let output = run_pomdar(&[
        "trial",
        "--task",
        "V1",
        "--user",
        "sim",
        "--operator",
        "ci",
        "--trials",
        "1",
        "--practice",
        "0",
        "--simulate",
        "--domain-id",
        &domain,
        "--script",
        script.to_str().unwrap(),
        "--out",
        sessions.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    let manifest = dir.join("session.json");
    assert!(
        stderr.contains(&format!(
            "{}: trials[0].file = \"{bad}\" is refused: a path, not a file name",
            manifest.display()
        )),
        "{stderr}"
    );
    assert!(
        stderr.contains("allowed: V1-pNN.mcap or V1-tNN.mcap"),
        "{stderr}"
    );
    assert_eq!(snapshot(&root), before, "nothing was renamed or written");
    std::fs::remove_dir_all(&root).ok();
}
