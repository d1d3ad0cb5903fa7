//! The task → station configuration step every path takes before it builds a station: the
//! catalog task's arm constraint (the station's own type), and who engages the arm
//! ([`Engage`]: the operator, or the station itself on its first fresh frame).

use scoring::TaskSpec;
use station::StationConfig;

/// Who engages the station's arm.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engage {
    /// The operator engages (the console's trials): the station waits for the command.
    ByOperator,
    /// The station engages on its first fresh frame (`pomdar station --engage`, the demo, a
    /// glove recording's re-simulation, the lock step).
    OnFirstFrame,
}

/// `config` with `task`'s arm constraint.
pub fn constrain_for_task(config: &mut StationConfig, task: &TaskSpec) {
    config.arm.constraint = task.arm;
}

/// `config` engaging as `engage` says.
pub fn set_engage(config: &mut StationConfig, engage: Engage) {
    config.control.auto_engage = engage == Engage::OnFirstFrame;
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use station::arm::Constraint;

    use super::*;

    #[test]
    fn a_task_gives_the_station_its_constraint() {
        let catalog = scoring::TaskCatalog::builtin();
        let mut config = StationConfig::default();
        constrain_for_task(&mut config, catalog.get("V1").unwrap());
        assert_eq!(config.arm.constraint, Constraint::VerticalAxis);
    }

    #[test]
    fn engage_sets_auto_engage() {
        let mut config = StationConfig::default();
        set_engage(&mut config, Engage::OnFirstFrame);
        assert!(config.control.auto_engage);
        set_engage(&mut config, Engage::ByOperator);
        assert!(!config.control.auto_engage);
    }
}
