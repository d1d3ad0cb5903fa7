//! The configuration of a scoring run, read from files: task catalog (`--catalog`, default
//! the built-in one), rules (`--rules`, default the paper's weights), baseline
//! (`--baseline`), and the embodiments' degrees of freedom (the built-in embodiment catalog).

use std::collections::BTreeMap;
use std::path::Path;

use scoring::{
    BaselineTable, DEFAULT_RULES_ORIGIN, FileProblem, ReportInputs, ScoreReport, ScoringError,
    ScoringRules, TaskCatalog, TrialScore, score_trial,
};

use super::load_trial::load_trial_log;
use super::{ScoreFileError, TrialFileError};

/// The scoring files a command takes (`pomdar score`, `pomdar trial`).
#[derive(Debug, Clone, clap::Args)]
pub struct ScoringFileArgs {
    /// Human baseline table (TOML, from `pomdar baseline`). Without it, or for tasks it does
    /// not list, trials show correctness only (with a warning), never an invented time.
    #[arg(long, value_name = "FILE")]
    pub baseline: Option<std::path::PathBuf>,
    /// Task catalog (TOML; default: the built-in 18 POMDAR tasks, also shipped as
    /// launch_configs/tasks/pomdar_tasks.toml).
    #[arg(long, value_name = "FILE")]
    pub catalog: Option<std::path::PathBuf>,
    /// Scoring rules (TOML; default: launch_configs/scoring/default_rules.toml's values:
    /// weights 0.8/0.2, no time limit, unfinished trials keep their correctness with speed 0).
    #[arg(long, value_name = "FILE")]
    pub rules: Option<std::path::PathBuf>,
}

impl ScoringFileArgs {
    /// Loads the files given (see [`ScoringInputs::load`]).
    pub fn load(&self) -> Result<ScoringInputs, ScoreFileError> {
        ScoringInputs::load(
            self.catalog.as_deref(),
            self.rules.as_deref(),
            self.baseline.as_deref(),
        )
    }
}

/// The catalog, rules and baseline of a run.
#[derive(Debug, Clone)]
pub struct ScoringInputs {
    /// Task catalog.
    pub catalog: TaskCatalog,
    /// Rules.
    pub rules: ScoringRules,
    /// Where the rules came from.
    pub rules_origin: String,
    /// Baseline, if given.
    pub baseline: Option<BaselineTable>,
    /// Degrees of freedom per embodiment.
    pub dof: BTreeMap<String, u32>,
}

fn read(path: &Path, what: &'static str) -> Result<String, ScoreFileError> {
    std::fs::read_to_string(path).map_err(|source| ScoreFileError::Read {
        what,
        path: path.to_path_buf(),
        source,
    })
}

impl ScoringInputs {
    /// Reads a trial log and scores it; the error is the reason alone (the report shows the
    /// file beside it).
    pub fn score_file(&self, path: &Path) -> Result<TrialScore, TrialFileError> {
        let log = load_trial_log(path)?;
        Ok(score_trial(
            &log,
            &self.catalog,
            self.baseline.as_ref(),
            &self.rules,
        )?)
    }

    /// The report of these scores with these files' problems.
    pub fn report(
        &self,
        scores: Vec<TrialScore>,
        rejected: Vec<FileProblem>,
        skipped: Vec<FileProblem>,
    ) -> ScoreReport {
        ScoreReport::build(ReportInputs {
            catalog: &self.catalog,
            baseline: self.baseline.as_ref(),
            rules: &self.rules,
            rules_origin: &self.rules_origin,
            dof: &self.dof,
            scores,
            rejected,
            skipped,
        })
    }

    /// Loads and validates the files given (errors name the file, the key and the allowed
    /// values).
    pub fn load(
        catalog: Option<&Path>,
        rules: Option<&Path>,
        baseline: Option<&Path>,
    ) -> Result<ScoringInputs, ScoreFileError> {
        let catalog = match catalog {
            Some(path) => TaskCatalog::from_toml_str(
                &read(path, "task catalog")?,
                &path.display().to_string(),
            )?,
            None => TaskCatalog::builtin(),
        };
        let (rules, rules_origin) = match rules {
            Some(path) => {
                let origin = path.display().to_string();
                let rules =
                    ScoringRules::from_toml_str(&read(path, "scoring rules")?, &origin, &catalog)?;
                (rules, origin)
            }
            None => (ScoringRules::default(), DEFAULT_RULES_ORIGIN.to_string()),
        };
        let baseline = baseline
            .map(|path| {
                BaselineTable::from_toml_str(
                    &read(path, "baseline")?,
                    &path.display().to_string(),
                    &catalog,
                )
                .map_err(ScoreFileError::from)
            })
            .transpose()?;
        let dof = retarget::EmbodimentCatalog::builtin()
            .embodiments
            .iter()
            .map(|e| (e.name.clone(), u32::try_from(e.dof).unwrap_or(u32::MAX)))
            .collect();
        Ok(ScoringInputs {
            catalog,
            rules,
            rules_origin,
            baseline,
            dof,
        })
    }
}

/// The reason of a scoring error, without the file name the report shows beside it.
pub(crate) fn reason(error: ScoringError) -> String {
    TrialFileError::from(error).to_string()
}
