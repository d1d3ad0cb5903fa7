//! Scoring rules: the weights of the score, timeouts, and what an unfinished trial counts as.
//!
//! The paper publishes the weights (0.8 correctness, 0.2 speed) but not its timeouts or how it
//! counted aborted or timed-out trials, so those are configuration with a documented default
//! (`launch_configs/scoring/default_rules.toml` spells the defaults out).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::catalog::TaskCatalog;
use crate::error::ScoringError;

/// What an aborted or timed-out trial counts as. The paper does not say (unverified).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum UnfinishedRule {
    /// The correctness reached counts, the speed term is 0:
    /// `score = w_c · correctness`. The default.
    #[default]
    Partial,
    /// The trial scores 0 (it still counts in the mean).
    Zero,
    /// The trial is left out of every mean (listed as excluded).
    Exclude,
}

impl UnfinishedRule {
    /// The name used in the rules file.
    pub fn name(self) -> &'static str {
        match self {
            UnfinishedRule::Partial => "partial",
            UnfinishedRule::Zero => "zero",
            UnfinishedRule::Exclude => "exclude",
        }
    }
}

/// The scoring rules. `Default` is the paper's weights with this station's documented choices
/// where the paper is silent; a rules file may leave out any key (its default applies).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ScoringRules {
    /// Weight of correctness in the score (paper: 0.8).
    pub correctness_weight: f64,
    /// Weight of speed in the score (paper: 0.2).
    pub speed_weight: f64,
    /// Time limit for every task, seconds; a trial longer than this is timed out. `None`: no
    /// limit (the paper publishes none). Default `None`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub timeout_s: Option<f64>,
    /// Per-task time limits, seconds, overriding `timeout_s` (`V1 = 90.0`).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub task_timeout_s: BTreeMap<String, f64>,
    /// What an aborted or timed-out trial counts as. Default [`UnfinishedRule::Partial`].
    pub unfinished: UnfinishedRule,
    /// When true, a stopped trial earns the speed term only if its correctness is 1 (so
    /// stopping early is not rewarded); when false (default), `speed = baseline / time` for
    /// every finished trial, as the paper's formula reads.
    pub speed_needs_full_correctness: bool,
}

impl Default for ScoringRules {
    fn default() -> Self {
        ScoringRules {
            correctness_weight: 0.8,
            speed_weight: 0.2,
            timeout_s: None,
            task_timeout_s: BTreeMap::new(),
            unfinished: UnfinishedRule::Partial,
            speed_needs_full_correctness: false,
        }
    }
}

/// Origin string of the default rules in reports.
pub const DEFAULT_RULES_ORIGIN: &str = "default rules";

impl ScoringRules {
    /// Parses and validates rules; `origin` names the file in errors. Task IDs in
    /// `task_timeout_s` must exist in `catalog`.
    pub fn from_toml_str(
        text: &str,
        origin: &str,
        catalog: &TaskCatalog,
    ) -> Result<ScoringRules, ScoringError> {
        let rules: ScoringRules =
            toml::from_str(text).map_err(|e| ScoringError::syntax(origin, &e))?;
        rules.validate(origin, catalog)?;
        Ok(rules)
    }

    /// Checks ranges: weights finite, ≥ 0 and summing to 1; timeouts finite and > 0; per-task
    /// timeouts only for tasks of `catalog`.
    pub fn validate(&self, origin: &str, catalog: &TaskCatalog) -> Result<(), ScoringError> {
        for (key, w) in [
            ("correctness_weight", self.correctness_weight),
            ("speed_weight", self.speed_weight),
        ] {
            if !(w.is_finite() && w >= 0.0) {
                return Err(ScoringError::invalid(
                    origin,
                    key,
                    w,
                    "a finite weight ≥ 0 (paper: correctness 0.8, speed 0.2)",
                ));
            }
        }
        let sum = self.correctness_weight + self.speed_weight;
        if (sum - 1.0).abs() > 1e-9 {
            return Err(ScoringError::invalid(
                origin,
                "correctness_weight + speed_weight",
                sum,
                "weights summing to 1 (paper: 0.8 + 0.2)",
            ));
        }
        let check_timeout = |key: String, t: f64| {
            if t.is_finite() && t > 0.0 {
                Ok(())
            } else {
                Err(ScoringError::invalid(
                    origin,
                    key,
                    t,
                    "seconds, finite and > 0 (omit the key for no limit)",
                ))
            }
        };
        if let Some(t) = self.timeout_s {
            check_timeout("timeout_s".into(), t)?;
        }
        for (task, &t) in &self.task_timeout_s {
            if catalog.get(task).is_none() {
                return Err(ScoringError::invalid(
                    origin,
                    format!("task_timeout_s.{task}"),
                    t,
                    format!("a task of the catalog ({})", catalog.ids()),
                ));
            }
            check_timeout(format!("task_timeout_s.{task}"), t)?;
        }
        Ok(())
    }

    /// The time limit for `task`, seconds, if any.
    pub fn timeout_for(&self, task: &str) -> Option<f64> {
        self.task_timeout_s.get(task).copied().or(self.timeout_s)
    }

    /// Whether these are the paper's weights.
    pub fn has_paper_weights(&self) -> bool {
        (self.correctness_weight - 0.8).abs() < 1e-12 && (self.speed_weight - 0.2).abs() < 1e-12
    }

    /// One line for reports.
    pub fn describe(&self) -> String {
        let timeouts = match (self.timeout_s, self.task_timeout_s.is_empty()) {
            (None, true) => "no time limit".to_string(),
            (Some(t), true) => format!("time limit {t} s"),
            (None, false) => format!("time limits for {}", self.timeout_list()),
            (Some(t), false) => format!("time limit {t} s ({})", self.timeout_list()),
        };
        format!(
            "score = {} · correctness + {} · speed; {timeouts}; aborted or timed-out trials: {}{}",
            self.correctness_weight,
            self.speed_weight,
            match self.unfinished {
                UnfinishedRule::Partial => "correctness reached, speed term 0",
                UnfinishedRule::Zero => "score 0",
                UnfinishedRule::Exclude => "left out of the means",
            },
            if self.speed_needs_full_correctness {
                "; speed term only for trials with correctness 1"
            } else {
                ""
            }
        )
    }

    fn timeout_list(&self) -> String {
        self.task_timeout_s
            .iter()
            .map(|(task, t)| format!("{task} {t} s"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_papers_weights() {
        let rules = ScoringRules::default();
        assert!(rules.has_paper_weights());
        assert_eq!(rules.unfinished, UnfinishedRule::Partial);
        let parsed = ScoringRules::from_toml_str(
            "correctness_weight = 0.8\nspeed_weight = 0.2\n",
            "t",
            &TaskCatalog::builtin(),
        )
        .unwrap_or_default();
        assert_eq!(parsed, rules);
    }

    #[test]
    fn bad_values_name_the_key_and_the_allowed_range() {
        let catalog = TaskCatalog::builtin();
        let err = ScoringRules::from_toml_str(
            "correctness_weight = 0.7\nspeed_weight = 0.2\n",
            "rules.toml",
            &catalog,
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
        assert!(
            err.starts_with("rules.toml: correctness_weight + speed_weight"),
            "{err}"
        );
        let err = ScoringRules::from_toml_str(
            "correctness_weight = 0.8\nspeed_weight = 0.2\n[task_timeout_s]\nX9 = 10.0\n",
            "rules.toml",
            &catalog,
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
        assert!(
            err.contains("task_timeout_s.X9") && err.contains("V1"),
            "{err}"
        );
        let err = ScoringRules::from_toml_str(
            "correctness_weight = 0.8\nspeed_weight = 0.2\nunfinished = \"maybe\"\n",
            "rules.toml",
            &catalog,
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
        assert!(
            err.contains("rules.toml") && err.contains("partial"),
            "{err}"
        );
    }
}
