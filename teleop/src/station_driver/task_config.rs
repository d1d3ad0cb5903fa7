//! The task → station configuration step every path takes before it builds a station: the
//! catalog task's arm constraint as the station's [`Constraint`], and who engages the arm
//! ([`Engage`]: the operator, or the station itself on its first fresh frame).

use scoring::{ArmConstraint, TaskSpec};
use station::StationConfig;
use station::arm::Constraint;

/// Who engages the station's arm.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engage {
    /// The operator engages (the console's trials): the station waits for the command.
    ByOperator,
    /// The station engages on its first fresh frame (`pomdar station --engage`, the demo, a
    /// glove recording's re-simulation, the lock step).
    OnFirstFrame,
}

/// The station's arm constraint for a catalog task's.
pub fn station_constraint(arm: ArmConstraint) -> Constraint {
    match arm {
        ArmConstraint::Fixed => Constraint::Fixed,
        ArmConstraint::VerticalAxis => Constraint::VerticalAxis,
        ArmConstraint::HorizontalAxis => Constraint::HorizontalAxis,
        ArmConstraint::Free => Constraint::Free,
    }
}

/// `config` with `task`'s arm constraint.
pub fn constrain_for_task(config: &mut StationConfig, task: &TaskSpec) {
    config.arm.constraint = station_constraint(task.arm);
}

/// `config` engaging as `engage` says.
pub fn set_engage(config: &mut StationConfig, engage: Engage) {
    config.control.auto_engage = engage == Engage::OnFirstFrame;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_catalog_constraint_maps_to_the_station_constraint_of_the_same_name() {
        for (arm, expected) in [
            (ArmConstraint::Fixed, Constraint::Fixed),
            (ArmConstraint::VerticalAxis, Constraint::VerticalAxis),
            (ArmConstraint::HorizontalAxis, Constraint::HorizontalAxis),
            (ArmConstraint::Free, Constraint::Free),
        ] {
            assert_eq!(station_constraint(arm), expected);
        }
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
