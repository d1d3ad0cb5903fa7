//! The Apple Vision Pro streaming app's gRPC interface, declared in Rust.
//!
//! The headset app (VisionProTeleop, its Python client `avp_stream`, MIT) serves
//! `handtracking.HandTrackingService` on port 12345 with one server-streaming method:
//!
//! ```text
//! rpc StreamHandUpdates(HandUpdate) returns (stream HandUpdate)
//! message Matrix4x4  { float m00 = 1; m01 = 2; … m33 = 16; }       row-major, m{row}{column}
//! message Skeleton   { repeated Matrix4x4 jointMatrices = 1; }      25 joints, 27 with forearm
//! message Hand       { Matrix4x4 wristMatrix = 1; Skeleton skeleton = 2; }
//! message HandUpdate { Hand left_hand = 1; Hand right_hand = 2; Matrix4x4 Head = 3; }
//! ```
//!
//! The messages below carry the same field numbers and wire types, written with prost's derive,
//! so no `protoc` runs at build time; `tests/interop/avp/handtracking.proto` is the schema the
//! interop suite's fake headset is generated from, and the tests check the two agree byte for
//! byte. The codec ([`HandUpdateCodec`]) decodes each streamed message into a `Result`, so one
//! undecodable message is counted by the node and the stream goes on.
//!
//! The first request: `avp_stream` 2.50 (commit 4c54990 of the app's repository, the version
//! targeted here) sends a `HandUpdate` whose head matrix is a discovery marker: `m00 = 888`,
//! `m01 m02 m03 m10` the client's IPv4 octets, `m30` its library version code (major·10⁴ +
//! minor·10² + patch). Older apps ignore the request's content; newer ones use the marker to
//! learn the client's address and check its version. A streamed update whose head `m00` is 777
//! is the app's reply to a latency benchmark, not hand data.

use std::net::Ipv4Addr;

use prost::Message as _;
use tonic::Status;
use tonic::codec::{Codec, DecodeBuf, Decoder, EncodeBuf, Encoder};
use tonic::codegen::http::uri::PathAndQuery;

/// The streaming method's path.
pub const STREAM_HAND_UPDATES: &str = "/handtracking.HandTrackingService/StreamHandUpdates";

/// The head `m00` marking a client's discovery request.
pub const DISCOVERY_MARKER: f32 = 888.0;

/// The head `m00` marking the app's latency-benchmark replies.
pub const BENCHMARK_MARKER: f32 = 777.0;

/// The `avp_stream` version this client announces: 2.50.0.
pub const CLIENT_VERSION_CODE: f32 = 25_000.0;

/// A 4 × 4 homogeneous transform, row-major (`m03 m13 m23` the translation, metres).
#[derive(Clone, Copy, PartialEq, prost::Message)]
#[allow(missing_docs)]
pub struct Matrix4x4 {
    #[prost(float, tag = "1")]
    pub m00: f32,
    #[prost(float, tag = "2")]
    pub m01: f32,
    #[prost(float, tag = "3")]
    pub m02: f32,
    #[prost(float, tag = "4")]
    pub m03: f32,
    #[prost(float, tag = "5")]
    pub m10: f32,
    #[prost(float, tag = "6")]
    pub m11: f32,
    #[prost(float, tag = "7")]
    pub m12: f32,
    #[prost(float, tag = "8")]
    pub m13: f32,
    #[prost(float, tag = "9")]
    pub m20: f32,
    #[prost(float, tag = "10")]
    pub m21: f32,
    #[prost(float, tag = "11")]
    pub m22: f32,
    #[prost(float, tag = "12")]
    pub m23: f32,
    #[prost(float, tag = "13")]
    pub m30: f32,
    #[prost(float, tag = "14")]
    pub m31: f32,
    #[prost(float, tag = "15")]
    pub m32: f32,
    #[prost(float, tag = "16")]
    pub m33: f32,
}

impl Matrix4x4 {
    /// The matrix from its rows.
    pub fn from_rows(rows: [[f32; 4]; 4]) -> Matrix4x4 {
        let [r0, r1, r2, r3] = rows;
        Matrix4x4 {
            m00: r0[0],
            m01: r0[1],
            m02: r0[2],
            m03: r0[3],
            m10: r1[0],
            m11: r1[1],
            m12: r1[2],
            m13: r1[3],
            m20: r2[0],
            m21: r2[1],
            m22: r2[2],
            m23: r2[3],
            m30: r3[0],
            m31: r3[1],
            m32: r3[2],
            m33: r3[3],
        }
    }

    /// The rows.
    pub fn rows(&self) -> [[f32; 4]; 4] {
        [
            [self.m00, self.m01, self.m02, self.m03],
            [self.m10, self.m11, self.m12, self.m13],
            [self.m20, self.m21, self.m22, self.m23],
            [self.m30, self.m31, self.m32, self.m33],
        ]
    }
}

/// One hand's joints, each relative to the wrist.
#[derive(Clone, PartialEq, prost::Message)]
pub struct Skeleton {
    /// The joint transforms (`jointMatrices`).
    #[prost(message, repeated, tag = "1")]
    pub joint_matrices: Vec<Matrix4x4>,
}

/// One hand.
#[derive(Clone, PartialEq, prost::Message)]
pub struct Hand {
    /// The wrist in the headset's world (`wristMatrix`).
    #[prost(message, optional, tag = "1")]
    pub wrist_matrix: Option<Matrix4x4>,
    /// The joints (`skeleton`).
    #[prost(message, optional, tag = "2")]
    pub skeleton: Option<Skeleton>,
}

/// One update: both hands and the head.
#[derive(Clone, PartialEq, prost::Message)]
pub struct HandUpdate {
    /// The left hand (`left_hand`).
    #[prost(message, optional, tag = "1")]
    pub left_hand: Option<Hand>,
    /// The right hand (`right_hand`).
    #[prost(message, optional, tag = "2")]
    pub right_hand: Option<Hand>,
    /// The head (`Head`), or a marker in a request or a benchmark reply.
    #[prost(message, optional, tag = "3")]
    pub head: Option<Matrix4x4>,
}

impl HandUpdate {
    /// Whether this is the app's latency-benchmark reply rather than hand data.
    pub fn is_benchmark_reply(&self) -> bool {
        self.head.is_some_and(|h| h.m00 == BENCHMARK_MARKER)
    }
}

/// The first request: the discovery marker with this client's address and version.
pub fn discovery_request(client: Ipv4Addr) -> HandUpdate {
    let [a, b, c, d] = client.octets().map(f32::from);
    HandUpdate {
        head: Some(Matrix4x4 {
            m00: DISCOVERY_MARKER,
            m01: a,
            m02: b,
            m03: c,
            m10: d,
            m30: CLIENT_VERSION_CODE,
            ..Matrix4x4::default()
        }),
        ..HandUpdate::default()
    }
}

/// The method path as tonic takes it.
pub fn stream_path() -> PathAndQuery {
    PathAndQuery::from_static(STREAM_HAND_UPDATES)
}

/// A streamed message: an update, or why its bytes are not one.
pub type Decoded = Result<HandUpdate, prost::DecodeError>;

/// Protobuf both ways; a message that does not decode is an item, not the stream's end.
#[derive(Debug, Clone, Copy, Default)]
pub struct HandUpdateCodec;

/// [`HandUpdateCodec`]'s encoding half.
#[derive(Debug, Clone, Copy, Default)]
pub struct HandUpdateEncoder;

/// [`HandUpdateCodec`]'s decoding half.
#[derive(Debug, Clone, Copy, Default)]
pub struct HandUpdateDecoder;

impl Codec for HandUpdateCodec {
    type Encode = HandUpdate;
    type Decode = Decoded;
    type Encoder = HandUpdateEncoder;
    type Decoder = HandUpdateDecoder;

    fn encoder(&mut self) -> HandUpdateEncoder {
        HandUpdateEncoder
    }

    fn decoder(&mut self) -> HandUpdateDecoder {
        HandUpdateDecoder
    }
}

impl Encoder for HandUpdateEncoder {
    type Item = HandUpdate;
    type Error = Status;

    fn encode(&mut self, item: HandUpdate, dst: &mut EncodeBuf<'_>) -> Result<(), Status> {
        item.encode(dst)
            .map_err(|e| Status::internal(format!("cannot encode a HandUpdate: {e}")))
    }
}

impl Decoder for HandUpdateDecoder {
    type Item = Decoded;
    type Error = Status;

    fn decode(&mut self, src: &mut DecodeBuf<'_>) -> Result<Option<Decoded>, Status> {
        Ok(Some(HandUpdate::decode(src)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_numbers_match_the_published_schema() {
        // Hand-encoded: HandUpdate { right_hand (2) { wristMatrix (1) { m03 (4) = 1.0 } } }.
        // m03: key (4 << 3) | 5 (fixed32) = 0x25, then 1.0f32 little-endian.
        let m03 = [0x25, 0x00, 0x00, 0x80, 0x3f];
        let wrist = [&[0x0a, m03.len() as u8][..], &m03].concat();
        let hand = [&[0x12, wrist.len() as u8][..], &wrist].concat();
        let update = HandUpdate::decode(&hand[..]).unwrap();
        let w = update.right_hand.unwrap().wrist_matrix.unwrap();
        assert_eq!(w.m03, 1.0);
        assert_eq!(w.rows()[0], [0.0, 0.0, 0.0, 1.0]);
        // The head is field 3, a skeleton's joints field 1 of field 2.
        let update = HandUpdate {
            head: Some(Matrix4x4 {
                m33: 2.0,
                ..Matrix4x4::default()
            }),
            left_hand: Some(Hand {
                wrist_matrix: None,
                skeleton: Some(Skeleton {
                    joint_matrices: vec![Matrix4x4::default()],
                }),
            }),
            ..HandUpdate::default()
        };
        // m33 is field 16: key (16 << 3) | 5 = 0x85 0x01 (varint).
        let bytes = update.encode_to_vec();
        assert_eq!(
            bytes,
            [
                0x0a, 0x04, 0x12, 0x02, 0x0a, 0x00, // left_hand { skeleton { [ {} ] } }
                0x1a, 0x06, 0x85, 0x01, 0x00, 0x00, 0x00, 0x40, // Head { m33 = 2 }
            ]
        );
    }

    #[test]
    fn the_discovery_request_carries_the_address_and_version() {
        let request = discovery_request(Ipv4Addr::new(192, 168, 1, 42));
        let head = request.head.unwrap();
        assert_eq!(
            [head.m00, head.m01, head.m02, head.m03, head.m10, head.m30],
            [888.0, 192.0, 168.0, 1.0, 42.0, 25_000.0]
        );
        assert!(request.right_hand.is_none());
    }

    #[test]
    fn rows_round_trip() {
        let rows = [
            [1.0, 2.0, 3.0, 4.0],
            [5.0, 6.0, 7.0, 8.0],
            [9.0, 10.0, 11.0, 12.0],
            [13.0, 14.0, 15.0, 16.0],
        ];
        let m = Matrix4x4::from_rows(rows);
        assert_eq!(m.rows(), rows);
        assert_eq!((m.m12, m.m30), (7.0, 13.0));
    }
}
