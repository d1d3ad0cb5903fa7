//! Parsing one Rokoko Studio "custom streaming" JSON v3 packet into the lab's keypoints.
//!
//! A packet is one UTF-8 JSON document (docs/LAB_CONVENTIONS.md §2):
//!
//! ```text
//! { "version": "3,0", "fps": 100,
//!   "scene": { "timestamp": 12.34,
//!              "actors": [ { "name": "Actor1",
//!                            "body": { "rightHand": { "position": {"x","y","z"},
//!                                                     "rotation": {"x","y","z","w"} },
//!                                      "rightIndexTip": { ... }, ... },
//!                            ... } ],
//!              ... } }
//! ```
//!
//! Keys this parser does not use (face, dimensions, props, characters, other bones) are
//! ignored. The hand's 22 points, in the lab's order, are the bones `<side>LowerArm`,
//! `<side>Hand`, then for Thumb, Index, Middle, Ring, Little: `Proximal`, `Medial`,
//! `Distal`, `Tip` (`<side>` is `right` or `left`); the 21-point layout drops the forearm.
//! Positions are converted to ROS's frame ([`super::rokoko_frame`]) and scaled to metres.
//! Pure: bytes in, a frame or the reason it was refused out.

use nalgebra::{Isometry3, Point3, Translation3};
use retarget::KeypointLayout;
use serde::Deserialize;

use crate::ingress::ingress_config::Hand;
use crate::ingress::rokoko_frame::{position_to_ros, rotation_to_ros};

/// The finger bone names, per digit, in the lab's order.
const DIGITS: [&str; 5] = ["Thumb", "Index", "Middle", "Ring", "Little"];
/// The segment names of a digit, proximal to tip.
const SEGMENTS: [&str; 4] = ["Proximal", "Medial", "Distal", "Tip"];

/// Why a packet was refused; one counter per kind on the status topic.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PacketError {
    /// Larger than the configured maximum.
    #[error("packet of {bytes} bytes exceeds the {max} byte limit")]
    Oversized {
        /// Received size (at least `max + 1`).
        bytes: usize,
        /// The limit.
        max: usize,
    },
    /// The JSON ends early (a datagram cut short).
    #[error("truncated JSON: {detail}")]
    Truncated {
        /// The parser's message.
        detail: String,
    },
    /// Not JSON, or JSON of another shape.
    #[error("malformed packet: {detail}")]
    Malformed {
        /// What was wrong.
        detail: String,
    },
    /// A format version other than 3.
    #[error("unsupported format version {version:?} (this ingress reads JSON v3)")]
    Version {
        /// The version the packet declared.
        version: String,
    },
    /// No finite `scene.timestamp`: the packet cannot be ordered, so it is refused rather
    /// than let past the duplicate, out-of-order and restart checks.
    #[error("no finite scene.timestamp (every packet is ordered by it, so one without is refused)")]
    NoTimestamp,
    /// No actor (or none with the configured name).
    #[error("no actor {wanted} in the packet (actors: {present})")]
    NoActor {
        /// The actor looked for.
        wanted: String,
        /// The actors present.
        present: String,
    },
    /// A bone the layout needs is missing or not finite.
    #[error("bone '{bone}' {problem}")]
    Bone {
        /// The bone's name.
        bone: String,
        /// Missing, non-finite position, bad rotation.
        problem: String,
    },
}

impl PacketError {
    /// The counter this error is counted under.
    pub fn kind(&self) -> &'static str {
        match self {
            PacketError::Oversized { .. } => "oversized",
            PacketError::Truncated { .. } => "truncated",
            PacketError::Malformed { .. } => "malformed",
            PacketError::Version { .. } => "version",
            PacketError::NoTimestamp => "no_timestamp",
            PacketError::NoActor { .. } => "no_actor",
            PacketError::Bone { .. } => "missing_bone",
        }
    }
}

/// What the parser picks out of a packet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Selection<'a> {
    /// The actor's name; `None`: the first actor.
    pub actor: Option<&'a str>,
    /// Which hand.
    pub hand: Hand,
    /// The keypoint layout to produce (lab22 or lab21).
    pub layout: KeypointLayout,
    /// Packets longer than this are refused, bytes.
    pub max_packet_bytes: usize,
    /// Multiplier from the stream's position unit to metres.
    pub position_scale_to_m: f64,
}

/// One packet's hand, in ROS's frame, metres.
#[derive(Debug, Clone, PartialEq)]
pub struct RokokoFrame {
    /// The studio's `scene.timestamp`, seconds (finite: a packet without one is refused).
    pub timestamp_s: f64,
    /// The layout's keypoints.
    pub keypoints: Vec<Point3<f64>>,
    /// The hand bone's pose.
    pub wrist: Isometry3<f64>,
}

#[derive(Deserialize)]
struct Packet {
    version: Option<serde_json::Value>,
    scene: Scene,
}

#[derive(Deserialize)]
struct Scene {
    timestamp: Option<f64>,
    #[serde(default)]
    actors: Vec<Actor>,
}

#[derive(Deserialize)]
struct Actor {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    body: std::collections::HashMap<String, Bone>,
}

#[derive(Deserialize)]
struct Bone {
    position: Option<Xyz>,
    rotation: Option<Xyzw>,
}

#[derive(Deserialize)]
struct Xyz {
    x: f64,
    y: f64,
    z: f64,
}

#[derive(Deserialize)]
struct Xyzw {
    x: f64,
    y: f64,
    z: f64,
    w: f64,
}

/// The bone names of `layout` for `hand`, in keypoint order.
pub fn bone_names(hand: Hand, layout: KeypointLayout) -> Vec<String> {
    let side = hand.bone_prefix();
    let mut names = Vec::with_capacity(22);
    if layout.forearm().is_some() {
        names.push(format!("{side}LowerArm"));
    }
    names.push(format!("{side}Hand"));
    for digit in DIGITS {
        for segment in SEGMENTS {
            names.push(format!("{side}{digit}{segment}"));
        }
    }
    names
}

/// Parse one packet.
pub fn parse_packet(bytes: &[u8], selection: &Selection<'_>) -> Result<RokokoFrame, PacketError> {
    if bytes.len() > selection.max_packet_bytes {
        return Err(PacketError::Oversized {
            bytes: bytes.len(),
            max: selection.max_packet_bytes,
        });
    }
    let packet: Packet = serde_json::from_slice(bytes).map_err(|e| {
        if e.is_eof() {
            PacketError::Truncated {
                detail: e.to_string(),
            }
        } else {
            PacketError::Malformed {
                detail: e.to_string(),
            }
        }
    })?;
    check_version(packet.version.as_ref())?;
    let timestamp_s = packet
        .scene
        .timestamp
        .filter(|t| t.is_finite())
        .ok_or(PacketError::NoTimestamp)?;
    let actor = pick_actor(&packet.scene.actors, selection.actor)?;
    let names = bone_names(selection.hand, selection.layout);
    let scale = selection.position_scale_to_m;
    let mut keypoints = Vec::with_capacity(names.len());
    for name in &names {
        let bone = actor.body.get(name).ok_or_else(|| PacketError::Bone {
            bone: name.clone(),
            problem: "is missing".into(),
        })?;
        let p = bone.position.as_ref().ok_or_else(|| PacketError::Bone {
            bone: name.clone(),
            problem: "has no position".into(),
        })?;
        let point = position_to_ros(p.x * scale, p.y * scale, p.z * scale);
        if !point.coords.iter().all(|c| c.is_finite()) {
            return Err(PacketError::Bone {
                bone: name.clone(),
                problem: "has a non-finite position".into(),
            });
        }
        keypoints.push(point);
    }
    let hand_name = format!("{}Hand", selection.hand.bone_prefix());
    let rotation = actor
        .body
        .get(&hand_name)
        .and_then(|b| b.rotation.as_ref())
        .and_then(|r| rotation_to_ros(r.x, r.y, r.z, r.w))
        .ok_or_else(|| PacketError::Bone {
            bone: hand_name.clone(),
            problem: "has no valid rotation (missing, non-finite or not a unit quaternion)".into(),
        })?;
    let wrist_index = selection.layout.wrist();
    let wrist = Isometry3::from_parts(Translation3::from(keypoints[wrist_index].coords), rotation);
    Ok(RokokoFrame {
        timestamp_s,
        keypoints,
        wrist,
    })
}

fn check_version(version: Option<&serde_json::Value>) -> Result<(), PacketError> {
    let text = match version {
        None => return Ok(()),
        Some(serde_json::Value::String(s)) => s.clone(),
        Some(other) => other.to_string(),
    };
    // Rokoko writes "3,0" (a decimal comma); accept "3", "3.0", "3,1"...
    let major = text.split([',', '.']).next().unwrap_or("").trim();
    if major == "3" {
        Ok(())
    } else {
        Err(PacketError::Version { version: text })
    }
}

fn pick_actor<'a>(actors: &'a [Actor], wanted: Option<&str>) -> Result<&'a Actor, PacketError> {
    let found = match wanted {
        Some(name) => actors.iter().find(|a| a.name.as_deref() == Some(name)),
        None => actors.first(),
    };
    found.ok_or_else(|| PacketError::NoActor {
        wanted: wanted.map_or_else(|| "(any)".to_string(), |n| format!("'{n}'")),
        present: if actors.is_empty() {
            "none".into()
        } else {
            actors
                .iter()
                .map(|a| a.name.as_deref().unwrap_or("(unnamed)"))
                .collect::<Vec<_>>()
                .join(", ")
        },
    })
}

#[cfg(test)]
#[path = "rokoko_packet_tests.rs"]
mod tests;
