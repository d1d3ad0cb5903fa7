//! The `source` note of a baseline table `pomdar baseline` writes: the operator's `--source`,
//! then how many recorded human trials were averaged and their users.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use scoring::{HUMAN_EMBODIMENT, TrialRecord};

/// The table's source note: `--source`, then the count of trials averaged and the users of
/// the recorded human trials.
pub fn source_note(source: Option<&str>, records: &[TrialRecord], used: usize) -> String {
    let users: BTreeSet<&str> = records
        .iter()
        .filter(|r| r.embodiment == HUMAN_EMBODIMENT && !r.practice)
        .filter_map(|r| r.user.as_deref())
        .collect();
    let mut note = source.map_or(String::new(), |s| format!("{s}; "));
    let _ = write!(
        note,
        "pomdar baseline over {used} recorded human trials (users: {})",
        if users.is_empty() {
            "not recorded".to_string()
        } else {
            users.into_iter().collect::<Vec<_>>().join(", ")
        }
    );
    note
}
