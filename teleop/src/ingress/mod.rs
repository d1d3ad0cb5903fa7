//! Glove ingress: Rokoko Studio Live's UDP stream to the lab's ROS 2 keypoint topics
//! (`pomdar ingress rokoko`).
//!
//! | file | what |
//! |---|---|
//! | `rokoko_frame.rs` | Studio's left-handed Y-up frame to ROS's (the maths, tested) |
//! | `rokoko_packet.rs` | one JSON v3 packet to keypoints and a wrist pose, or why not |
//! | `rokoko_packet_builder.rs` | packets in Studio's format, for tests, benchmarks, stand-ins |
//! | `ingress_counters.rs` | ordering by studio timestamp, drop counts, the status report |
//! | `ingress_config.rs` | the settings (`launch_configs/ingress/rokoko.toml`) |
//! | `rokoko_node.rs` | the UDP socket and the ROS publishers |
//! | `error.rs` | the one error type ([`IngressError`]) |

mod error;
pub mod ingress_config;
pub mod ingress_counters;
pub mod rokoko_frame;
pub mod rokoko_node;
pub mod rokoko_packet;
pub mod rokoko_packet_builder;

pub use error::IngressError;
