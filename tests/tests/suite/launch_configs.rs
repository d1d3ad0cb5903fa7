//! Every file in `launch_configs/` parses and validates.

use pomdar_tests::{files_with_extension, workspace_root};
use teleop::launch_config::check_file;

#[test]
fn every_launch_config_is_valid() {
    let all = files_with_extension(&workspace_root().join("launch_configs"), "toml").unwrap();
    assert!(!all.is_empty(), "no launch configs found");
    for path in &all {
        if let Err(e) = check_file(path) {
            panic!("{e:#}");
        }
    }
    println!("checked {} launch configs", all.len());
}

#[test]
fn a_broken_launch_config_is_reported_with_file_and_key() {
    let dir = std::env::temp_dir().join(format!("pomdar-launch-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("hands")).unwrap();
    let path = dir.join("hands/broken.toml");
    std::fs::write(&path, "strip_prefix = \"right_\"\nframe = {}\n").unwrap();
    let err = format!("{:#}", check_file(&path).unwrap_err());
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        err.contains("broken.toml") && err.contains("frame"),
        "{err}"
    );
}

#[test]
fn the_shipped_retarget_config_spells_out_the_defaults() {
    let path = workspace_root().join("launch_configs/retarget/orca_full_lab22.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let config = retarget::RetargetConfig::from_toml_str(&text).unwrap();
    assert_eq!(config, retarget::RetargetConfig::default());
}

#[test]
fn the_shipped_calibration_settings_spell_out_the_defaults() {
    let path = workspace_root().join("launch_configs/calibration/default_settings.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let settings = calibration::CalibrationSettings::from_toml_str(&text).unwrap();
    assert_eq!(settings, calibration::CalibrationSettings::default());
}

#[test]
fn the_shipped_task_catalog_is_the_builtin_one() {
    let path = workspace_root().join("launch_configs/tasks/pomdar_tasks.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        text,
        scoring::POMDAR_TASKS_TOML,
        "{} differs from scoring/data/tasks_pomdar.toml",
        path.display()
    );
    let catalog = scoring::TaskCatalog::from_toml_str(&text, "pomdar_tasks.toml").unwrap();
    assert_eq!(catalog.len(), 18);
}

#[test]
fn the_shipped_scoring_rules_spell_out_the_defaults() {
    let path = workspace_root().join("launch_configs/scoring/default_rules.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let rules = scoring::ScoringRules::from_toml_str(
        &text,
        "default_rules.toml",
        &scoring::TaskCatalog::builtin(),
    )
    .unwrap();
    assert_eq!(rules, scoring::ScoringRules::default());
}

#[test]
fn a_broken_baseline_is_reported_with_file_and_task() {
    let dir = std::env::temp_dir().join(format!("pomdar-launch-baseline-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("baselines")).unwrap();
    let path = dir.join("baselines/lab.toml");
    std::fs::write(
        &path,
        "[baseline]\nexample = false\nsource = \"lab\"\n[[task]]\nid = \"V1\"\nmean_s = -2.0\nn = 3\n",
    )
    .unwrap();
    let err = format!("{:#}", check_file(&path).unwrap_err());
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        err.contains("lab.toml") && err.contains("task V1: mean_s"),
        "{err}"
    );
}

/// Every station preset's policy output resolves on the ORCA hand (a table's ranges reachable
/// through its signs and offsets); a shipped table names its consumer and provenance, and no
/// shipped row claims a check on a hand (`pomdar hand-check` writes verified copies).
#[test]
fn every_station_presets_policy_output_resolves_and_no_shipped_table_claims_a_check() {
    let model = retarget::HandModel::orca_v1_right();
    let dir = workspace_root().join("launch_configs/station");
    let mut tables = Vec::new();
    for path in files_with_extension(&dir, "toml").unwrap() {
        let text = std::fs::read_to_string(&path).unwrap();
        let config = station::StationConfig::from_toml_str(&text).unwrap();
        let policy = &config.policy_output;
        if let Err(e) = station::policy_output::PolicyOutput::new(&model, policy) {
            panic!("{}: {e}", path.display());
        }
        if policy.joints.is_empty() {
            continue;
        }
        assert!(
            !policy.consumer.is_empty() && !policy.provenance.is_empty(),
            "{}",
            path.display()
        );
        assert!(
            policy.joints.iter().all(|r| !r.verified) && policy.verified_by.is_empty(),
            "{}: a shipped table claims a check on a hand",
            path.display()
        );
        tables.push(policy.consumer.clone());
    }
    tables.sort();
    assert_eq!(tables, ["eth_hand_control", "orca_core"]);
}

/// DDS stays on the lab network by default where a preset is for the multi-host lab and names
/// its address (docs/SECURITY.md, "Interfaces"): `deploy_station.toml` keeps DDS on the
/// station PC's 10.251.0.2, as docs/DEPLOYMENT.md deploys it. Every other station preset is
/// for any machine (the single-host demos and tests use them) and names no interface, so it
/// never fails on a machine without the lab's address.
#[test]
fn only_the_multi_host_station_preset_restricts_dds_to_its_lab_address() {
    let dir = workspace_root().join("launch_configs/station");
    for path in files_with_extension(&dir, "toml").unwrap() {
        let text = std::fs::read_to_string(&path).unwrap();
        let config = station::StationConfig::from_toml_str(&text).unwrap();
        let interfaces = &config.network.interfaces;
        if path.ends_with("deploy_station.toml") {
            assert_eq!(
                interfaces,
                &[std::net::IpAddr::from([10, 251, 0, 2])],
                "{}",
                path.display()
            );
        } else {
            assert!(interfaces.is_empty(), "{}", path.display());
        }
    }
}
