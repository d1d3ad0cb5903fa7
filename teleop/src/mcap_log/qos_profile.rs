//! `offered_qos_profiles`: the QoS of a topic's publishers, as rosbag2 stores it in MCAP channel
//! metadata so that `ros2 bag play` can offer the same QoS again.
//!
//! The value is a YAML list, one entry per publisher, in the block style yaml-cpp writes:
//!
//! ```text
//! - history: 1
//!   depth: 10
//!   reliability: 1
//!   durability: 2
//!   deadline:
//!     sec: 9223372036
//!     nsec: 854775807
//!   lifespan:
//!     sec: 9223372036
//!     nsec: 854775807
//!   liveliness: 1
//!   liveliness_lease_duration:
//!     sec: 9223372036
//!     nsec: 854775807
//!   avoid_ros_namespace_conventions: false
//! ```
//!
//! Enums are written as the integers of `rmw/types.h`, which both Humble and Jazzy read (Jazzy
//! itself writes names such as `keep_last`, which Humble cannot read). Durations are
//! `{sec, nsec}`; "infinite" is `RMW_DURATION_INFINITE` = 9223372036 s 854775807 ns.
//! [`qos_profiles_from_yaml`] reads both spellings and any key order, so it also reads files
//! written by Jazzy and by `rosbags`.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::LogError;

macro_rules! rmw_enum {
    ($(#[$doc:meta])* $name:ident { $($(#[$vdoc:meta])* $variant:ident = $code:literal, $text:literal;)+ }) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $($(#[$vdoc])* $variant,)+
        }

        impl $name {
            /// The integer value of the rmw enum (what this module writes).
            pub const fn code(self) -> u8 {
                match self {
                    $($name::$variant => $code,)+
                }
            }

            /// Parses the integer or the rmw name (`keep_last`, `best_effort`, ...).
            fn parse(text: &str) -> Option<Self> {
                match text {
                    $(_ if text == stringify!($code) || text.eq_ignore_ascii_case($text) => Some($name::$variant),)+
                    _ => None,
                }
            }
        }
    };
}

rmw_enum! {
    /// `rmw_qos_history_policy_t`.
    QosHistory {
        /// The middleware's default.
        SystemDefault = 0, "system_default";
        /// Keep the last `depth` samples.
        KeepLast = 1, "keep_last";
        /// Keep all samples.
        KeepAll = 2, "keep_all";
        /// Not known (what discovery reports for remote publishers).
        Unknown = 3, "unknown";
    }
}

rmw_enum! {
    /// `rmw_qos_reliability_policy_t`.
    QosReliability {
        /// The middleware's default.
        SystemDefault = 0, "system_default";
        /// Resent until acknowledged.
        Reliable = 1, "reliable";
        /// Sent once.
        BestEffort = 2, "best_effort";
        /// Not known.
        Unknown = 3, "unknown";
        /// Match the majority of endpoints (Iron and later only).
        BestAvailable = 4, "best_available";
    }
}

rmw_enum! {
    /// `rmw_qos_durability_policy_t`.
    QosDurability {
        /// The middleware's default.
        SystemDefault = 0, "system_default";
        /// Late joiners get the last `depth` samples.
        TransientLocal = 1, "transient_local";
        /// Late joiners get only new samples.
        Volatile = 2, "volatile";
        /// Not known.
        Unknown = 3, "unknown";
        /// Match the majority of endpoints (Iron and later only).
        BestAvailable = 4, "best_available";
    }
}

rmw_enum! {
    /// `rmw_qos_liveliness_policy_t`.
    QosLiveliness {
        /// The middleware's default.
        SystemDefault = 0, "system_default";
        /// Asserted by the middleware.
        Automatic = 1, "automatic";
        /// Deprecated in ROS 2; kept so old files parse.
        ManualByNode = 2, "manual_by_node";
        /// Asserted by the publisher.
        ManualByTopic = 3, "manual_by_topic";
        /// Not known.
        Unknown = 4, "unknown";
        /// Match the majority of endpoints (Iron and later only).
        BestAvailable = 5, "best_available";
    }
}

/// An `rmw_time_t`: seconds and nanoseconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RosDuration {
    /// Whole seconds.
    pub sec: u64,
    /// Nanoseconds.
    pub nsec: u64,
}

impl RosDuration {
    /// `RMW_DURATION_INFINITE` (what Humble and Jazzy write for "no deadline/lifespan/lease").
    pub const INFINITE: RosDuration = RosDuration {
        sec: 9_223_372_036,
        nsec: 854_775_807,
    };
    /// `RMW_DURATION_UNSPECIFIED`: the middleware's default.
    pub const UNSPECIFIED: RosDuration = RosDuration { sec: 0, nsec: 0 };
}

/// One publisher's offered QoS profile, as rosbag2 records it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct OfferedQos {
    /// History kind.
    pub history: QosHistory,
    /// History depth (meaningful for keep-last).
    pub depth: u32,
    /// Reliability.
    pub reliability: QosReliability,
    /// Durability.
    pub durability: QosDurability,
    /// Deadline.
    pub deadline: RosDuration,
    /// Lifespan.
    pub lifespan: RosDuration,
    /// Liveliness kind.
    pub liveliness: QosLiveliness,
    /// Liveliness lease duration.
    pub liveliness_lease_duration: RosDuration,
    /// Whether the topic name bypasses the ROS naming conventions.
    pub avoid_ros_namespace_conventions: bool,
}

impl OfferedQos {
    /// Reliable, keep last `depth`, volatile, no deadline/lifespan, automatic liveliness: the
    /// rclcpp publisher default with another depth.
    pub const fn reliable(depth: u32) -> OfferedQos {
        OfferedQos {
            history: QosHistory::KeepLast,
            depth,
            reliability: QosReliability::Reliable,
            durability: QosDurability::Volatile,
            deadline: RosDuration::INFINITE,
            lifespan: RosDuration::INFINITE,
            liveliness: QosLiveliness::Automatic,
            liveliness_lease_duration: RosDuration::INFINITE,
            avoid_ros_namespace_conventions: false,
        }
    }

    /// Like [`OfferedQos::reliable`] but best effort (sensor streams).
    pub const fn best_effort(depth: u32) -> OfferedQos {
        let mut qos = OfferedQos::reliable(depth);
        qos.reliability = QosReliability::BestEffort;
        qos
    }
}

impl Default for OfferedQos {
    /// The rclcpp publisher default: reliable, keep last 10, volatile.
    fn default() -> Self {
        OfferedQos::reliable(10)
    }
}

impl From<crate::ros::QosConfig> for OfferedQos {
    /// The profile the station's own publishers offer for a topic configured with `config`.
    fn from(config: crate::ros::QosConfig) -> Self {
        match config.reliability {
            crate::ros::Reliability::Reliable => OfferedQos::reliable(config.depth),
            crate::ros::Reliability::BestEffort => OfferedQos::best_effort(config.depth),
        }
    }
}

/// The `offered_qos_profiles` YAML for `profiles` (see the module docs); `[]` for none.
pub fn qos_profiles_to_yaml(profiles: &[OfferedQos]) -> String {
    if profiles.is_empty() {
        return "[]".to_string();
    }
    let mut out = String::new();
    for p in profiles {
        if !out.is_empty() {
            out.push('\n');
        }
        let duration = |out: &mut String, key: &str, d: RosDuration| {
            // Writing to a String cannot fail.
            let _ = write!(out, "\n  {key}:\n    sec: {}\n    nsec: {}", d.sec, d.nsec);
        };
        let _ = write!(
            out,
            "- history: {}\n  depth: {}\n  reliability: {}\n  durability: {}",
            p.history.code(),
            p.depth,
            p.reliability.code(),
            p.durability.code()
        );
        duration(&mut out, "deadline", p.deadline);
        duration(&mut out, "lifespan", p.lifespan);
        let _ = write!(out, "\n  liveliness: {}", p.liveliness.code());
        duration(
            &mut out,
            "liveliness_lease_duration",
            p.liveliness_lease_duration,
        );
        let _ = write!(
            out,
            "\n  avoid_ros_namespace_conventions: {}",
            p.avoid_ros_namespace_conventions
        );
    }
    out
}

/// A value in one list entry: a scalar, or a map of scalars (a duration).
enum Value {
    Scalar(String, usize),
    Map(BTreeMap<String, String>, usize),
}

/// Parses an `offered_qos_profiles` value written by rosbag2 (Foxy to Jazzy), `rosbags` or
/// [`qos_profiles_to_yaml`]: block-style list, integer or named enums, keys in any order.
/// Unknown keys are ignored; a missing one is an error. An empty string or `[]` is no profile.
pub fn qos_profiles_from_yaml(yaml: &str) -> Result<Vec<OfferedQos>, LogError> {
    let err = |line: usize, reason: String| LogError::QosYaml { line, reason };
    let trimmed = yaml.trim();
    if trimmed.is_empty() || trimmed == "[]" {
        return Ok(Vec::new());
    }
    let mut items: Vec<BTreeMap<String, Value>> = Vec::new();
    let mut item_indent: Option<usize> = None;
    let mut open_map: Option<String> = None;
    for (index, raw) in yaml.lines().enumerate() {
        let line_no = index + 1;
        let text = raw.trim_end();
        if text.trim().is_empty() || text.trim_start().starts_with('#') {
            continue;
        }
        let mut indent = text.len() - text.trim_start().len();
        let mut rest = text.trim_start();
        if let Some(after) = rest.strip_prefix('-') {
            if !(after.is_empty() || after.starts_with(' ')) {
                return Err(err(line_no, format!("unexpected {rest:?}")));
            }
            let key_part = after.trim_start();
            indent += 1 + (after.len() - key_part.len());
            rest = key_part;
            items.push(BTreeMap::new());
            open_map = None;
            item_indent = Some(indent);
            if rest.is_empty() {
                continue;
            }
        }
        let (Some(base), Some(item)) = (item_indent, items.last_mut()) else {
            return Err(err(
                line_no,
                "expected a list entry starting with '- '".into(),
            ));
        };
        let Some((key, value)) = rest.split_once(':') else {
            return Err(err(
                line_no,
                format!("expected 'key: value', found {rest:?}"),
            ));
        };
        let (key, value) = (key.trim().to_string(), value.trim().to_string());
        if indent == base {
            if value.is_empty() {
                item.insert(key.clone(), Value::Map(BTreeMap::new(), line_no));
                open_map = Some(key);
            } else {
                item.insert(key, Value::Scalar(value, line_no));
                open_map = None;
            }
        } else if indent > base {
            match open_map.as_ref().and_then(|k| item.get_mut(k)) {
                Some(Value::Map(map, _)) => {
                    map.insert(key, value);
                }
                _ => {
                    return Err(err(
                        line_no,
                        format!("unexpected indentation before {key:?}"),
                    ));
                }
            }
        } else {
            return Err(err(
                line_no,
                format!("unexpected indentation before {key:?}"),
            ));
        }
    }
    items.iter().map(profile_from_entry).collect()
}

fn profile_from_entry(entry: &BTreeMap<String, Value>) -> Result<OfferedQos, LogError> {
    let first_line = entry
        .values()
        .map(|v| match v {
            Value::Scalar(_, l) | Value::Map(_, l) => *l,
        })
        .min()
        .unwrap_or(1);
    let err = |line: usize, reason: String| LogError::QosYaml { line, reason };
    // A scalar field, parsed by `parse`.
    fn field<T>(
        entry: &BTreeMap<String, Value>,
        first_line: usize,
        key: &str,
        parse: impl Fn(&str) -> Option<T>,
    ) -> Result<T, LogError> {
        let err = |line: usize, reason: String| LogError::QosYaml { line, reason };
        match entry.get(key) {
            Some(Value::Scalar(text, line)) => {
                parse(text).ok_or_else(|| err(*line, format!("{key}: unknown value {text:?}")))
            }
            Some(Value::Map(_, line)) => Err(err(*line, format!("{key} must be a single value"))),
            None => Err(err(first_line, format!("entry has no {key}"))),
        }
    }
    let duration = |key: &str| -> Result<RosDuration, LogError> {
        let (map, line) = match entry.get(key) {
            Some(Value::Map(m, l)) => (m, *l),
            Some(Value::Scalar(_, l)) => {
                return Err(err(*l, format!("{key} must have sec and nsec")));
            }
            None => return Err(err(first_line, format!("entry has no {key}"))),
        };
        let part = |name: &str| {
            map.get(name)
                .and_then(|v| v.parse::<u64>().ok())
                .ok_or_else(|| err(line, format!("{key}.{name} missing or not an integer")))
        };
        Ok(RosDuration {
            sec: part("sec")?,
            nsec: part("nsec")?,
        })
    };
    Ok(OfferedQos {
        history: field(entry, first_line, "history", QosHistory::parse)?,
        depth: field(entry, first_line, "depth", |t| t.parse::<u32>().ok())?,
        reliability: field(entry, first_line, "reliability", QosReliability::parse)?,
        durability: field(entry, first_line, "durability", QosDurability::parse)?,
        deadline: duration("deadline")?,
        lifespan: duration("lifespan")?,
        liveliness: field(entry, first_line, "liveliness", QosLiveliness::parse)?,
        liveliness_lease_duration: duration("liveliness_lease_duration")?,
        avoid_ros_namespace_conventions: field(
            entry,
            first_line,
            "avoid_ros_namespace_conventions",
            |t| match t {
                "true" | "True" => Some(true),
                "false" | "False" => Some(false),
                _ => None,
            },
        )?,
    })
}
