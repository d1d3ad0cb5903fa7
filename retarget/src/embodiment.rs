//! Embodiments: which joints of a hand the retargeter may move (the rest are locked at zero).
//!
//! The POMDAR embodiments of the ORCA hand ship as data in `models/embodiments.toml`; a lab can
//! load its own catalog with [`EmbodimentCatalog::from_toml_str`].

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::hand_model::HandModel;

/// The built-in embodiment catalog (ORCA: `orca_full`, `orca_5`, `orca_3`, `orca_2`).
pub const EMBODIMENTS_TOML: &str = include_str!("../models/embodiments.toml");

/// One embodiment.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Embodiment {
    /// Name used on the command line (`orca_full`).
    pub name: String,
    /// Declared number of unlocked joints (checked against `unlocked`).
    pub dof: usize,
    /// One line for the operator.
    pub description: String,
    /// Joint names the retargeter may move.
    pub unlocked: Vec<String>,
    /// Where the definition comes from, and what about it is unverified.
    pub provenance: String,
}

impl Embodiment {
    /// Per degree of freedom of `model`: whether it is unlocked. Errors name any joint the
    /// model does not have.
    pub fn unlocked_mask(&self, model: &HandModel) -> Result<Vec<bool>, Error> {
        let mut mask = vec![false; model.dof()];
        for joint in &self.unlocked {
            let index = model.dof_index(joint).ok_or_else(|| Error::BadEmbodiment {
                embodiment: self.name.clone(),
                problem: format!(
                    "unlocked joint '{joint}' is not a degree of freedom of model '{}'",
                    model.name()
                ),
            })?;
            mask[index] = true;
        }
        Ok(mask)
    }
}

/// A validated list of embodiments.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EmbodimentCatalog {
    /// The embodiments, in file order.
    #[serde(rename = "embodiment")]
    pub embodiments: Vec<Embodiment>,
}

impl EmbodimentCatalog {
    /// The built-in ORCA catalog.
    pub fn builtin() -> EmbodimentCatalog {
        #[allow(clippy::expect_used)] // the embedded file is validated by a unit test
        EmbodimentCatalog::from_toml_str(EMBODIMENTS_TOML).expect("built-in catalog is valid")
    }

    /// Parse and validate a catalog: unique names, no repeated joints, `dof` matching.
    pub fn from_toml_str(text: &str) -> Result<EmbodimentCatalog, Error> {
        let catalog: EmbodimentCatalog = toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        for (i, e) in catalog.embodiments.iter().enumerate() {
            let bad = |problem: String| Error::BadEmbodiment {
                embodiment: e.name.clone(),
                problem,
            };
            if catalog.embodiments[..i].iter().any(|o| o.name == e.name) {
                return Err(bad("defined twice".into()));
            }
            if e.unlocked.is_empty() {
                return Err(bad("unlocks no joint".into()));
            }
            for (k, joint) in e.unlocked.iter().enumerate() {
                if e.unlocked[..k].contains(joint) {
                    return Err(bad(format!("joint '{joint}' is listed twice")));
                }
            }
            if e.unlocked.len() != e.dof {
                return Err(bad(format!(
                    "dof = {} but {} joints are unlocked",
                    e.dof,
                    e.unlocked.len()
                )));
            }
        }
        Ok(catalog)
    }

    /// The embodiment called `name`.
    pub fn get(&self, name: &str) -> Option<&Embodiment> {
        self.embodiments.iter().find(|e| e.name == name)
    }

    /// Names of all embodiments.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.embodiments.iter().map(|e| e.name.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_catalog_matches_the_paper_dof_counts_and_the_orca_model() {
        let catalog = EmbodimentCatalog::from_toml_str(EMBODIMENTS_TOML).unwrap();
        let model = HandModel::orca_v1_right();
        let expected = [
            ("orca_full", 16),
            ("orca_5", 11),
            ("orca_3", 7),
            ("orca_2", 5),
        ];
        for (name, dof) in expected {
            let e = catalog.get(name).unwrap();
            let mask = e.unlocked_mask(&model).unwrap();
            assert_eq!(mask.iter().filter(|&&m| m).count(), dof, "{name}");
            assert!(
                !mask[model.dof_index("wrist").unwrap()],
                "{name}: wrist is not a finger DoF"
            );
        }
        assert_eq!(catalog.names().count(), expected.len());
    }

    #[test]
    fn reduced_embodiments_lock_every_finger_abduction() {
        let catalog = EmbodimentCatalog::builtin();
        for name in ["orca_5", "orca_3", "orca_2"] {
            let e = catalog.get(name).unwrap();
            assert!(e.unlocked.iter().all(|j| !j.ends_with("_abd")), "{name}");
        }
    }

    #[test]
    fn bad_catalogs_are_rejected_by_name() {
        let wrong_count = EMBODIMENTS_TOML.replacen("dof = 16", "dof = 15", 1);
        let err = EmbodimentCatalog::from_toml_str(&wrong_count)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("orca_full") && err.contains("dof = 15"),
            "{err}"
        );

        let unknown = EMBODIMENTS_TOML.replacen(
            "\"thumb_dip\",\n    \"index_mcp\"",
            "\"thumb_tip\",\n    \"index_mcp\"",
            1,
        );
        let catalog = EmbodimentCatalog::from_toml_str(&unknown).unwrap();
        let model = HandModel::orca_v1_right();
        let err = catalog
            .embodiments
            .iter()
            .find_map(|e| e.unlocked_mask(&model).err())
            .unwrap()
            .to_string();
        assert!(err.contains("thumb_tip"), "{err}");
    }
}
