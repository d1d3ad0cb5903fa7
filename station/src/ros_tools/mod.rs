//! What the station offers the lab's ROS tools besides its commands, as pure functions of its
//! model, configuration and status: `/tf` and `/tf_static` from its own kinematics
//! ([`hand_tf`]), markers of the glove keypoints and a drawing of the hand ([`markers`]),
//! `/diagnostics` ([`diagnostics`]), and the `[ros_tools]` configuration with the service names
//! ([`ros_tools_config`]). The application publishes and records them.

pub mod diagnostics;
pub mod hand_tf;
pub mod markers;
pub mod ros_tools_config;

pub use diagnostics::diagnostics;
pub use hand_tf::HandTf;
pub use ros_tools_config::{RosToolsConfig, ServiceAction, ServiceMapping, ServicesConfig};

use retarget::HandModel;

/// The joint names the station publishes for `model`: `prefix` + the model's names when the
/// configuration sets a prefix, else the names the robot's own URDF uses (the model's import
/// prefix added back, so an import file and the station agree by construction).
pub fn published_joint_names(model: &HandModel, prefix: Option<&str>) -> Vec<String> {
    match prefix {
        Some(prefix) => model.dof_names().map(|n| format!("{prefix}{n}")).collect(),
        None => model.ros_dof_names().to_vec(),
    }
}

/// The model's degree of freedom a published joint name stands for: the model's own name, or
/// its URDF name (`right_index_abd`), or `prefix` + the model's name.
pub fn dof_of_published_name(model: &HandModel, name: &str, prefix: Option<&str>) -> Option<usize> {
    model
        .dof_index(name)
        .or_else(|| model.ros_dof_names().iter().position(|n| n == name))
        .or_else(|| {
            prefix
                .and_then(|p| name.strip_prefix(p))
                .and_then(|n| model.dof_index(n))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orca_publishes_the_urdf_names_unless_told_otherwise() {
        let model = HandModel::orca_v1_right();
        let names = published_joint_names(&model, None);
        assert_eq!(names[0], "right_thumb_mcp");
        assert_eq!(names[16], "right_wrist");
        let bare = published_joint_names(&model, Some(""));
        assert_eq!(bare[4], "index_abd");
        for (dof, name) in names.iter().enumerate() {
            assert_eq!(dof_of_published_name(&model, name, None), Some(dof));
            assert_eq!(dof_of_published_name(&model, &bare[dof], None), Some(dof));
        }
        assert_eq!(
            dof_of_published_name(&model, "left_wrist", Some("left_")),
            Some(16)
        );
        assert_eq!(dof_of_published_name(&model, "left_wrist", None), None);
    }
}
