//! Schema texts: names, the rosbag2 layout, and consistency of each `.msg` text with the
//! dependencies declared next to it.

use crate::*;

const PRIMITIVES: [&str; 15] = [
    "bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32",
    "uint32", "int64", "uint64", "string", "wstring",
];

fn all_definitions() -> [MsgDefinition; 13] {
    [
        Time::DEFINITION,
        Header::DEFINITION,
        StringMsg::DEFINITION,
        MultiArrayDimension::DEFINITION,
        MultiArrayLayout::DEFINITION,
        Float32MultiArray::DEFINITION,
        Float64MultiArray::DEFINITION,
        Point::DEFINITION,
        Quaternion::DEFINITION,
        Pose::DEFINITION,
        PoseStamped::DEFINITION,
        PoseArray::DEFINITION,
        JointState::DEFINITION,
    ]
}

/// `pkg/Type` of every message type a `.msg` text's fields use.
fn field_types(def: &MsgDefinition) -> Vec<String> {
    let mut types: Vec<String> = def
        .text
        .lines()
        .filter_map(|line| line.split_whitespace().next())
        .map(|t| t.split('[').next().unwrap_or(t))
        .filter(|t| !PRIMITIVES.contains(t))
        .map(|t| match t.contains('/') {
            true => t.to_string(),
            false => format!("{}/{t}", def.package),
        })
        .collect();
    types.sort();
    types.dedup();
    types
}

fn transitive(def: &MsgDefinition, into: &mut Vec<String>) {
    for dep in def.dependencies {
        if !into.contains(&dep.resource_name()) {
            into.push(dep.resource_name());
            transitive(dep, into);
        }
    }
}

#[test]
fn names() {
    assert_eq!(JointState::ros_type_name(), "sensor_msgs/msg/JointState");
    assert_eq!(
        JointState::dds_type_name(),
        "sensor_msgs::msg::dds_::JointState_"
    );
    assert_eq!(StringMsg::ros_type_name(), "std_msgs/msg/String");
    assert_eq!(
        Time::dds_type_name(),
        "builtin_interfaces::msg::dds_::Time_"
    );
    assert_eq!(
        Float32MultiArray::ros_type_name(),
        "std_msgs/msg/Float32MultiArray"
    );
}

#[test]
fn declared_dependencies_match_the_field_types() {
    for def in all_definitions() {
        let mut declared: Vec<String> =
            def.dependencies.iter().map(|d| d.resource_name()).collect();
        declared.sort();
        assert_eq!(declared, field_types(&def), "{}", def.ros_type_name());
        assert!(
            def.text.ends_with('\n') && !def.text.contains("\n\n"),
            "{}",
            def.ros_type_name()
        );
    }
}

#[test]
fn every_dependency_appears_once_after_a_separator() {
    for def in all_definitions() {
        let schema = def.schema_text();
        let lines: Vec<&str> = schema.lines().collect();
        let mut listed = Vec::new();
        for (i, line) in lines.iter().enumerate() {
            if line.starts_with('=') {
                assert_eq!(*line, "=".repeat(80), "{schema}");
                let msg = lines.get(i + 1).and_then(|l| l.strip_prefix("MSG: "));
                let msg = msg.unwrap_or_else(|| panic!("separator without MSG line:\n{schema}"));
                assert!(!msg.contains("/msg/"), "{msg}");
                listed.push(msg.to_string());
            } else if line.starts_with("MSG:") {
                assert_eq!(lines[i - 1], "=".repeat(80), "{schema}");
            }
        }
        let mut expected = Vec::new();
        transitive(&def, &mut expected);
        let mut unique = listed.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), listed.len(), "repeated dependency:\n{schema}");
        expected.sort();
        assert_eq!(unique, expected, "{}", def.ros_type_name());
        assert!(schema.starts_with(def.text));
    }
}

#[test]
fn pose_stamped_schema_is_exactly_what_rosbag2_writes() {
    let sep = "=".repeat(80);
    let expected = format!(
        "std_msgs/Header header\nPose pose\n\
         \n{sep}\nMSG: geometry_msgs/Pose\nPoint position\nQuaternion orientation\n\
         \n{sep}\nMSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n\
         \n{sep}\nMSG: geometry_msgs/Quaternion\nfloat64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n\
         \n{sep}\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n\
         \n{sep}\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n"
    );
    assert_eq!(PoseStamped::schema_text(), expected);
}

#[test]
fn leaf_types_have_no_separator() {
    assert_eq!(Time::schema_text(), "int32 sec\nuint32 nanosec\n");
    assert_eq!(StringMsg::schema_text(), "string data\n");
    let joint_state = JointState::schema_text();
    assert_eq!(joint_state.matches("MSG: ").count(), 2);
    assert!(joint_state.contains("\nMSG: std_msgs/Header\n"));
    assert!(joint_state.contains("\nMSG: builtin_interfaces/Time\n"));
}
