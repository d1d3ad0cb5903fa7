//! `offered_qos_profiles`: the exact text written, and reading every spelling in use.

#![allow(clippy::unwrap_used)]

use super::LogError;
use super::qos_profile::*;

const RELIABLE_10: &str = "- history: 1
  depth: 10
  reliability: 1
  durability: 2
  deadline:
    sec: 9223372036
    nsec: 854775807
  lifespan:
    sec: 9223372036
    nsec: 854775807
  liveliness: 1
  liveliness_lease_duration:
    sec: 9223372036
    nsec: 854775807
  avoid_ros_namespace_conventions: false";

#[test]
fn writes_the_humble_layout_with_integer_enums() {
    assert_eq!(
        qos_profiles_to_yaml(&[OfferedQos::reliable(10)]),
        RELIABLE_10
    );
    assert_eq!(qos_profiles_to_yaml(&[]), "[]");
    let two = qos_profiles_to_yaml(&[OfferedQos::reliable(10), OfferedQos::best_effort(5)]);
    assert!(two.starts_with(RELIABLE_10), "{two}");
    assert!(
        two.contains("false\n- history: 1\n  depth: 5\n  reliability: 2\n"),
        "{two}"
    );
}

#[test]
fn round_trips() {
    let mut odd = OfferedQos::best_effort(1);
    odd.history = QosHistory::KeepAll;
    odd.durability = QosDurability::TransientLocal;
    odd.deadline = RosDuration {
        sec: 0,
        nsec: 5_000_000,
    };
    odd.liveliness = QosLiveliness::ManualByTopic;
    odd.avoid_ros_namespace_conventions = true;
    let profiles = vec![OfferedQos::default(), odd];
    let yaml = qos_profiles_to_yaml(&profiles);
    assert_eq!(qos_profiles_from_yaml(&yaml).unwrap(), profiles);
    assert!(qos_profiles_from_yaml("").unwrap().is_empty());
    assert!(qos_profiles_from_yaml("[]").unwrap().is_empty());
}

#[test]
fn reads_named_enums_in_any_key_order() {
    // As Jazzy and rosbags write it (the reference recording has this text).
    let yaml = "- avoid_ros_namespace_conventions: false
  deadline:
    nsec: 854775807
    sec: 9223372036
  depth: 0
  durability: volatile
  history: unknown
  lifespan:
    nsec: 854775807
    sec: 9223372036
  liveliness: automatic
  liveliness_lease_duration:
    nsec: 854775807
    sec: 9223372036
  reliability: best_effort
";
    let parsed = qos_profiles_from_yaml(yaml).unwrap();
    assert_eq!(parsed.len(), 1);
    let p = parsed[0];
    assert_eq!(p.history, QosHistory::Unknown);
    assert_eq!(p.depth, 0);
    assert_eq!(p.reliability, QosReliability::BestEffort);
    assert_eq!(p.durability, QosDurability::Volatile);
    assert_eq!(p.deadline, RosDuration::INFINITE);
    assert_eq!(p.liveliness, QosLiveliness::Automatic);
}

#[test]
fn foxy_infinities_are_kept_as_written() {
    let yaml = RELIABLE_10
        .replace("sec: 9223372036", "sec: 2147483647")
        .replace("nsec: 854775807", "nsec: 4294967295");
    let p = qos_profiles_from_yaml(&yaml).unwrap()[0];
    assert_eq!(
        p.lifespan,
        RosDuration {
            sec: 2_147_483_647,
            nsec: 4_294_967_295
        }
    );
}

#[test]
fn bad_text_is_an_error_with_its_line() {
    let line_of = |yaml: &str| match qos_profiles_from_yaml(yaml) {
        Err(LogError::QosYaml { line, reason }) => (line, reason),
        other => panic!("expected a QoS YAML error, got {other:?}"),
    };
    let (line, reason) = line_of(&RELIABLE_10.replace("reliability: 1", "reliability: 9"));
    assert_eq!(line, 3, "{reason}");
    let (_, reason) = line_of(&RELIABLE_10.replace("  depth: 10\n", ""));
    assert!(reason.contains("depth"), "{reason}");
    let (line, _) = line_of("history: 1");
    assert_eq!(line, 1);
    let (_, reason) = line_of(&RELIABLE_10.replace("    nsec: 854775807", "    nsec: x"));
    assert!(reason.contains("nsec"), "{reason}");
}
