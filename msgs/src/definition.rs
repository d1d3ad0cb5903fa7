//! Type names and `.msg` schema texts: what ROS 2 and MCAP need to know about a message type
//! besides its bytes.

use serde::{Serialize, de::DeserializeOwned};

/// The separator rosbag2 writes before each dependency in a `ros2msg` schema: 80 `=`.
pub const SCHEMA_SEPARATOR: &str =
    "================================================================================";

/// One ROS 2 message type: its name, its own `.msg` text and the types its fields use.
///
/// `text` is the `.msg` file without comments, ending in a newline; field types are written as
/// in the ROS 2 sources (a type from the same package may be named without its package).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MsgDefinition {
    /// ROS package, e.g. `sensor_msgs`.
    pub package: &'static str,
    /// Type name within the package, e.g. `JointState`.
    pub name: &'static str,
    /// The type's own `.msg` text.
    pub text: &'static str,
    /// The message types named by the fields (direct dependencies only, each once).
    pub dependencies: &'static [&'static MsgDefinition],
}

impl MsgDefinition {
    /// ROS 2 type name as used by rosbag2 and MCAP schemas: `pkg/msg/Type`.
    pub fn ros_type_name(&self) -> String {
        format!("{}/msg/{}", self.package, self.name)
    }

    /// DDS type name on the wire: `pkg::msg::dds_::Type_`. Peers match topics by this name.
    pub fn dds_type_name(&self) -> String {
        format!("{}::msg::dds_::{}_", self.package, self.name)
    }

    /// Name in a schema's `MSG:` line and in `.msg` field types: `pkg/Type`.
    pub fn resource_name(&self) -> String {
        format!("{}/{}", self.package, self.name)
    }

    /// The complete `ros2msg` schema, as rosbag2 writes it into MCAP.
    ///
    /// The type's own text comes first. Then, depth first, every transitive dependency appears
    /// once: a newline, a line of 80 `=`, a line `MSG: pkg/Type`, and that type's text
    /// (followed in turn by its own not-yet-written dependencies). Like rosbag2, the direct
    /// dependencies of each type are visited in lexicographic order of `pkg/Type`.
    pub fn schema_text(&self) -> String {
        let mut written = Vec::new();
        let mut out = String::new();
        self.append_schema(&mut written, &mut out);
        out
    }

    fn append_schema(&self, written: &mut Vec<String>, out: &mut String) {
        out.push_str(self.text);
        let mut deps: Vec<&MsgDefinition> = self.dependencies.to_vec();
        deps.sort_by_key(|d| d.resource_name());
        for dep in deps {
            let name = dep.resource_name();
            if written.contains(&name) {
                continue;
            }
            out.push('\n');
            out.push_str(SCHEMA_SEPARATOR);
            out.push_str("\nMSG: ");
            out.push_str(&name);
            out.push('\n');
            written.push(name);
            dep.append_schema(written, out);
        }
    }
}

/// A ROS 2 message type: serde (so ros2-client can publish it and [`crate::to_cdr`] encode it)
/// plus its static description.
pub trait RosMessage: Serialize + DeserializeOwned {
    /// The type's name and `.msg` text.
    const DEFINITION: MsgDefinition;

    /// `pkg/msg/Type`, e.g. `sensor_msgs/msg/JointState`.
    fn ros_type_name() -> String {
        Self::DEFINITION.ros_type_name()
    }

    /// `pkg::msg::dds_::Type_`, e.g. `sensor_msgs::msg::dds_::JointState_`.
    fn dds_type_name() -> String {
        Self::DEFINITION.dds_type_name()
    }

    /// The complete MCAP `ros2msg` schema (see [`MsgDefinition::schema_text`]).
    fn schema_text() -> String {
        Self::DEFINITION.schema_text()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LEAF: MsgDefinition = MsgDefinition {
        package: "a_msgs",
        name: "Leaf",
        text: "float64 x\n",
        dependencies: &[],
    };
    const MID: MsgDefinition = MsgDefinition {
        package: "b_msgs",
        name: "Mid",
        text: "a_msgs/Leaf leaf\n",
        dependencies: &[&LEAF],
    };
    const ROOT: MsgDefinition = MsgDefinition {
        package: "c_msgs",
        name: "Root",
        text: "b_msgs/Mid mid\na_msgs/Leaf leaf\n",
        dependencies: &[&MID, &LEAF],
    };

    #[test]
    fn names() {
        assert_eq!(ROOT.ros_type_name(), "c_msgs/msg/Root");
        assert_eq!(ROOT.dds_type_name(), "c_msgs::msg::dds_::Root_");
        assert_eq!(ROOT.resource_name(), "c_msgs/Root");
        assert_eq!(SCHEMA_SEPARATOR.len(), 80);
        assert!(SCHEMA_SEPARATOR.chars().all(|c| c == '='));
    }

    #[test]
    fn dependencies_are_sorted_depth_first_and_written_once() {
        let sep = SCHEMA_SEPARATOR;
        let expected = format!(
            "b_msgs/Mid mid\na_msgs/Leaf leaf\n\n{sep}\nMSG: a_msgs/Leaf\nfloat64 x\n\
             \n{sep}\nMSG: b_msgs/Mid\na_msgs/Leaf leaf\n"
        );
        assert_eq!(ROOT.schema_text(), expected);
        assert_eq!(LEAF.schema_text(), "float64 x\n");
    }
}
