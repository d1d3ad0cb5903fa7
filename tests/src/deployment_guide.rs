//! The command blocks of `docs/DEPLOYMENT.md` that a test runs: fenced `sh` blocks whose
//! first line is `# on host X ...`. Their lines are the operator's commands, taken as they
//! are written; a line of another shape fails the test, so the guide cannot drift into
//! commands the test does not run.

use std::path::Path;

/// One step of a host block.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum GuideStep {
    /// `export NAME=VALUE`: set in the environment of the host's later steps.
    Export {
        /// Variable name.
        name: String,
        /// Its value, as written.
        value: String,
    },
    /// A line ending in ` &`: a node that keeps running (the line without the `&`).
    Background(String),
    /// Any other command line: runs to completion.
    Run(String),
}

/// A block of commands for one host, in the guide's order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HostBlock {
    /// The host's name (`A` in `# on host A (...)`).
    pub host: String,
    /// The block's first line.
    pub title: String,
    /// Its commands.
    pub steps: Vec<GuideStep>,
}

/// Commands a host block may contain (the first word of a line).
const PROGRAMS: [&str; 2] = ["pomdar", "mkdir"];

fn step(line: &str) -> Result<GuideStep, String> {
    if let Some(assignment) = line.strip_prefix("export ") {
        let (name, value) = assignment
            .split_once('=')
            .ok_or_else(|| format!("`{line}`: expected `export NAME=VALUE`"))?;
        return Ok(GuideStep::Export {
            name: name.trim().to_string(),
            value: value.trim().to_string(),
        });
    }
    let program = line.split_whitespace().next().unwrap_or_default();
    if !PROGRAMS.contains(&program) {
        return Err(format!(
            "`{line}`: the test runs only {PROGRAMS:?} and `export` lines in host blocks"
        ));
    }
    Ok(match line.strip_suffix(" &") {
        Some(command) => GuideStep::Background(command.trim_end().to_string()),
        None => GuideStep::Run(line.to_string()),
    })
}

/// The host blocks of a Markdown text, in order.
pub fn host_blocks(markdown: &str) -> Result<Vec<HostBlock>, String> {
    let mut blocks = Vec::new();
    let mut lines = markdown.lines();
    while let Some(line) = lines.next() {
        if line.trim() != "```sh" {
            continue;
        }
        let body: Vec<&str> = lines.by_ref().take_while(|l| l.trim() != "```").collect();
        let Some(title) = body.first().map(|l| l.trim()) else {
            continue;
        };
        let Some(rest) = title.strip_prefix("# on host ") else {
            continue;
        };
        let host: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        if host.is_empty() {
            return Err(format!("`{title}`: no host name after `# on host`"));
        }
        let steps = body[1..]
            .iter()
            .map(|l| l.trim())
            .filter(|l| !l.is_empty() && !l.starts_with('#'))
            .map(step)
            .collect::<Result<Vec<_>, _>>()?;
        blocks.push(HostBlock {
            host,
            title: title.to_string(),
            steps,
        });
    }
    Ok(blocks)
}

/// The host blocks of the guide file at `path`.
pub fn read_host_blocks(path: &Path) -> Result<Vec<HostBlock>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    host_blocks(&text).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn host_blocks_are_parsed_and_other_blocks_ignored() {
        let text = "intro\n```sh\n# on host C (robot): x\nexport ROS_DOMAIN_ID=42\n\npomdar mock-hand --interface 10.0.0.3 &\n```\n```sh\npomdar demo\n```\n```sh\n# on host C: check\npomdar probe --topics /a\n```\n";
        let blocks = host_blocks(text).unwrap();
        assert_eq!(blocks.len(), 2);
        assert_eq!(blocks[0].host, "C");
        assert_eq!(
            blocks[0].steps,
            vec![
                GuideStep::Export {
                    name: "ROS_DOMAIN_ID".into(),
                    value: "42".into()
                },
                GuideStep::Background("pomdar mock-hand --interface 10.0.0.3".into()),
            ]
        );
        assert_eq!(
            blocks[1].steps,
            vec![GuideStep::Run("pomdar probe --topics /a".into())]
        );
    }

    #[test]
    fn an_unknown_command_in_a_host_block_is_refused() {
        let err = host_blocks("```sh\n# on host A\nsudo ip link set eth0 up\n```\n").unwrap_err();
        assert!(err.contains("sudo ip link"), "{err}");
    }
}
