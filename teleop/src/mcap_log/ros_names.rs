//! Topic and type names: what the writer accepts and how the reader compares types.

use msgs::MsgDefinition;

/// Why `topic` is not a fully qualified ROS 2 topic name, or `None` if it is one.
///
/// Checked: starts with `/`, has no empty segment, does not end with `/`, and uses only ASCII
/// letters, digits, `_` and `/` (the ROS 2 rules, without the tilde and substitution forms,
/// which never appear in a recorded name).
pub(crate) fn topic_problem(topic: &str) -> Option<&'static str> {
    if !topic.starts_with('/') {
        return Some("must start with '/'");
    }
    if topic.len() > 1 && topic.ends_with('/') {
        return Some("must not end with '/'");
    }
    if topic.contains("//") {
        return Some("must not contain an empty segment");
    }
    if !topic
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '/')
    {
        return Some("may contain only ASCII letters, digits, '_' and '/'");
    }
    None
}

/// Whether `type_name` is `pkg/msg/Type` (three non-empty parts, no whitespace).
pub(crate) fn is_type_name(type_name: &str) -> bool {
    let parts: Vec<&str> = type_name.split('/').collect();
    parts.len() == 3
        && parts
            .iter()
            .all(|p| !p.is_empty() && !p.chars().any(char::is_whitespace))
}

/// `pkg/msg/Type` or `pkg/Type` → `(pkg, Type)`, so both spellings compare equal.
fn package_and_name(type_name: &str) -> Option<(&str, &str)> {
    let (package, rest) = type_name.split_once('/')?;
    let name = rest.strip_prefix("msg/").unwrap_or(rest);
    Some((package, name))
}

/// Whether a recorded type name names `definition` (`pkg/msg/Type`, or the older `pkg/Type`).
pub(crate) fn names_definition(type_name: &str, definition: &MsgDefinition) -> bool {
    package_and_name(type_name) == Some((definition.package, definition.name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn topics() {
        assert_eq!(topic_problem("/ingress/mano"), None);
        assert_eq!(topic_problem("/"), None);
        assert!(topic_problem("ingress/mano").is_some());
        assert!(topic_problem("/ingress/").is_some());
        assert!(topic_problem("/a//b").is_some());
        assert!(topic_problem("/a b").is_some());
        assert!(topic_problem("").is_some());
    }

    #[test]
    fn type_names() {
        assert!(is_type_name("sensor_msgs/msg/JointState"));
        assert!(!is_type_name("sensor_msgs/JointState"));
        assert!(!is_type_name("sensor_msgs//JointState"));
        let def = <msgs::JointState as msgs::RosMessage>::DEFINITION;
        assert!(names_definition("sensor_msgs/msg/JointState", &def));
        assert!(names_definition("sensor_msgs/JointState", &def));
        assert!(!names_definition("sensor_msgs/msg/Joy", &def));
        assert!(!names_definition("std_msgs/msg/JointState", &def));
    }
}
