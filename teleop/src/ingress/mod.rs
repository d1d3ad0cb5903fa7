//! Hand-tracking ingress: a glove or headset stream to the lab's ROS 2 keypoint topics
//! (`pomdar ingress rokoko`, `pomdar ingress avp`).
//!
//! | file | what |
//! |---|---|
//! | `rokoko_frame.rs` | Studio's left-handed Y-up frame to ROS's (the maths, tested) |
//! | `rokoko_packet.rs` | one JSON v3 packet to keypoints and a wrist pose, or why not |
//! | `rokoko_packet_builder.rs` | packets in Studio's format, for tests, benchmarks, stand-ins |
//! | `ingress_counters.rs` | ordering by studio timestamp, drop counts, the status report |
//! | `log_limit.rs` | at most one log line per kind per 10 s, with the count held back |
//! | `ingress_config.rs` | the Rokoko settings (`launch_configs/ingress/rokoko.toml`) |
//! | `rokoko_node.rs` | the UDP socket and the ROS publishers |
//! | `avp_proto.rs` | the Vision Pro app's gRPC messages (prost derive) and codec |
//! | `avp_frame.rs` | one hand update to keypoints and a wrist pose, ARKit y-up to ROS (the maths, tested) |
//! | `avp_update_builder.rs` | hand updates from ROS-frame keypoints, for tests and benchmarks |
//! | `avp_config.rs` | the AVP settings (`launch_configs/ingress/avp.toml`) |
//! | `avp_node.rs` | the gRPC client (reconnecting) and the ROS publishers |
//! | `error.rs` | the one error type ([`IngressError`]) |

pub mod avp_config;
pub mod avp_frame;
pub mod avp_node;
pub mod avp_proto;
pub mod avp_update_builder;
mod error;
pub mod ingress_config;
pub mod ingress_counters;
pub mod log_limit;
pub mod rokoko_frame;
pub mod rokoko_node;
pub mod rokoko_packet;
pub mod rokoko_packet_builder;

pub use error::IngressError;
