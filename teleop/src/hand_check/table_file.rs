//! The verified table, written into a copy of the station configuration it came from: the
//! `[policy_output]` section (with its `[[policy_output.joints]]`) replaced, everything else
//! kept as written (comments included), and the text checked to load back as the
//! configuration with exactly the checked table — else nothing is written.

use std::path::Path;

use station::StationConfig;
use station::policy_output::PolicyOutputConfig;

use crate::hand_check::HandCheckError;

/// `config_text` (read from `config_path`) with its `[policy_output]` section replaced by
/// `table` (appended when it has none), under `header` (comment lines); the result loads back
/// as the same configuration with `table`.
pub fn table_text(
    config_path: &Path,
    config_text: &str,
    table: &PolicyOutputConfig,
    header: &str,
) -> Result<String, HandCheckError> {
    #[derive(serde::Serialize)]
    struct Wrapper<'a> {
        policy_output: &'a PolicyOutputConfig,
    }
    let serialized = toml::to_string(&Wrapper {
        policy_output: table,
    })
    .map_err(|e| HandCheckError::ConfigText {
        path: config_path.to_path_buf(),
        reason: e.to_string(),
    })?;
    let lines: Vec<&str> = config_text.lines().collect();
    let (before, kept_comments, after) = match section(&lines) {
        Some((start, end)) => {
            let comments: Vec<&str> = lines[start + 1..end]
                .iter()
                .copied()
                .take_while(|l| l.trim_start().starts_with('#'))
                .collect();
            (&lines[..start], comments, &lines[end..])
        }
        None => (&lines[..], Vec::new(), &lines[lines.len()..]),
    };
    let mut text = String::new();
    for line in header.lines() {
        text.push_str(&format!("# {line}\n"));
    }
    for line in before {
        text.push_str(&format!("{line}\n"));
    }
    let mut table_lines = serialized.trim_end().lines();
    if let Some(first) = table_lines.next() {
        text.push_str(&format!("{first}\n"));
    }
    for line in kept_comments {
        text.push_str(&format!("{line}\n"));
    }
    for line in table_lines {
        text.push_str(&format!("{line}\n"));
    }
    if !after.is_empty() {
        text.push('\n');
    }
    for line in after {
        text.push_str(&format!("{line}\n"));
    }
    check_roundtrip(config_path, config_text, &text, table)?;
    Ok(text)
}

/// The lines of the `[policy_output]` section: from its header to the next other table's
/// header, less the comments and blank lines just above that header (they belong to it).
fn section(lines: &[&str]) -> Option<(usize, usize)> {
    let is_header = |l: &str| l.trim_start().starts_with('[');
    let ours = |l: &str| {
        let l = l.trim_start();
        l.starts_with("[policy_output]")
            || l.starts_with("[policy_output.")
            || l.starts_with("[[policy_output.")
    };
    let start = lines
        .iter()
        .position(|l| l.trim_start().starts_with("[policy_output]"))?;
    let mut end = lines[start + 1..]
        .iter()
        .position(|l| is_header(l) && !ours(l))
        .map_or(lines.len(), |i| start + 1 + i);
    if end < lines.len() {
        while end > start + 1 && {
            let l = lines[end - 1].trim_start();
            l.is_empty() || l.starts_with('#')
        } {
            end -= 1;
        }
    }
    Some((start, end))
}

/// The new text loads as the old configuration with `table`.
fn check_roundtrip(
    config_path: &Path,
    old: &str,
    new: &str,
    table: &PolicyOutputConfig,
) -> Result<(), HandCheckError> {
    let roundtrip = |reason: String| HandCheckError::Roundtrip {
        path: config_path.to_path_buf(),
        reason,
    };
    let mut expected =
        StationConfig::from_toml_str(old).map_err(|e| roundtrip(format!("the original: {e}")))?;
    expected.policy_output = table.clone();
    let written = StationConfig::from_toml_str(new).map_err(|e| roundtrip(e.to_string()))?;
    if written != expected {
        return Err(roundtrip(
            "it differs from the configuration with the checked table".into(),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const ETH_LAB: &str = include_str!("../../../launch_configs/station/eth_lab.toml");

    #[test]
    fn the_table_is_replaced_and_everything_else_kept() {
        let config = StationConfig::from_toml_str(ETH_LAB).unwrap();
        let mut table = config.policy_output.clone();
        for row in &mut table.joints {
            row.verified = true;
        }
        table.joints[5].sign = 1;
        table.verified_by = "ana".into();
        table.verified_at = "2026-11-26T10:00:00Z".into();
        let path = Path::new("eth_lab.toml");
        let text = table_text(path, ETH_LAB, &table, "checked by ana").unwrap();
        assert!(text.starts_with("# checked by ana\n"), "{text}");
        assert!(
            text.contains("# The lab's station computes a hand command"),
            "comments kept"
        );
        let back = StationConfig::from_toml_str(&text).unwrap();
        assert_eq!(back.policy_output, table);
        assert_eq!(back.control, config.control);
        assert!(back.policy_output.verification().is_verified());
        assert!(text.contains("[retarget]\nlayout = \"lab22\""), "{text}");
        // No section: appended.
        let text = table_text(path, "[control]\nrate_hz = 30.0\n", &table, "").unwrap();
        assert_eq!(
            StationConfig::from_toml_str(&text).unwrap().control.rate_hz,
            30.0
        );
        // A table given as dotted keys elsewhere is not silently doubled.
        let e = table_text(path, "policy_output.topic = \"/x\"\n", &table, "").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("eth_lab.toml: the table written would not load back"),
            "{e}"
        );
    }
}
