//! Fuzzing of CDR decoding on stable Rust: structure-aware generators for every `msgs` type
//! (NaN, infinities, any Unicode, empty and long sequences), then byte-level mutation of their
//! valid encodings (bit flips, byte writes, truncation, extension, insertion, deletion, copied
//! ranges, the other byte order). Every payload goes through `cdr_oracle::check_payload`: no
//! panic, errors are `Err`, what decodes is consistent.
//!
//! The CI budget is a few thousand cases per property (seconds); `PROPTEST_CASES=N` sets a
//! longer run, and `fuzz/` has the same oracle as a cargo-fuzz target (docs/FUZZING.md).

use crate::cdr_oracle;

use msgs::{
    Float32MultiArray, Float64MultiArray, Header, JointState, MultiArrayDimension,
    MultiArrayLayout, Point, Pose, PoseArray, PoseStamped, Quaternion, StringMsg, Time, to_cdr,
};
use proptest::prelude::*;
use proptest::sample::Index;

/// Cases per property in CI, unless `PROPTEST_CASES` asks for another number.
fn budget(ci_cases: u32) -> ProptestConfig {
    let mut config = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = ci_cases;
    }
    // A failure prints its minimal input; no regression files beside the sources.
    config.failure_persistence = None;
    config
}

fn seqs<T: std::fmt::Debug>(s: impl Strategy<Value = T>) -> impl Strategy<Value = Vec<T>> {
    prop::collection::vec(s, 0..16)
}

fn strings() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(String::new()),
        any::<String>(),
        "[a-z_/]{0,12}",
        "\\PC{0,64}",
    ]
}

prop_compose! {
    fn times()(sec in any::<i32>(), nanosec in any::<u32>()) -> Time { Time { sec, nanosec } }
}
prop_compose! {
    fn headers()(stamp in times(), frame_id in strings()) -> Header { Header { stamp, frame_id } }
}
prop_compose! {
    fn points()(x in any::<f64>(), y in any::<f64>(), z in any::<f64>()) -> Point {
        Point { x, y, z }
    }
}
prop_compose! {
    fn quaternions()(x in any::<f64>(), y in any::<f64>(), z in any::<f64>(), w in any::<f64>())
        -> Quaternion {
        Quaternion { x, y, z, w }
    }
}
prop_compose! {
    fn poses()(position in points(), orientation in quaternions()) -> Pose {
        Pose { position, orientation }
    }
}
prop_compose! {
    fn dims()(label in strings(), size in any::<u32>(), stride in any::<u32>())
        -> MultiArrayDimension {
        MultiArrayDimension { label, size, stride }
    }
}
prop_compose! {
    fn layouts()(dim in seqs(dims()), data_offset in any::<u32>()) -> MultiArrayLayout {
        MultiArrayLayout { dim, data_offset }
    }
}

/// A message of any `msgs` type.
#[derive(Debug, Clone)]
enum AnyMessage {
    Time(Time),
    Header(Header),
    String(StringMsg),
    Dimension(MultiArrayDimension),
    Layout(MultiArrayLayout),
    F32Array(Float32MultiArray),
    F64Array(Float64MultiArray),
    Point(Point),
    Quaternion(Quaternion),
    Pose(Pose),
    PoseStamped(PoseStamped),
    PoseArray(PoseArray),
    JointState(JointState),
}

impl AnyMessage {
    fn encode(&self) -> Vec<u8> {
        match self {
            AnyMessage::Time(m) => to_cdr(m),
            AnyMessage::Header(m) => to_cdr(m),
            AnyMessage::String(m) => to_cdr(m),
            AnyMessage::Dimension(m) => to_cdr(m),
            AnyMessage::Layout(m) => to_cdr(m),
            AnyMessage::F32Array(m) => to_cdr(m),
            AnyMessage::F64Array(m) => to_cdr(m),
            AnyMessage::Point(m) => to_cdr(m),
            AnyMessage::Quaternion(m) => to_cdr(m),
            AnyMessage::Pose(m) => to_cdr(m),
            AnyMessage::PoseStamped(m) => to_cdr(m),
            AnyMessage::PoseArray(m) => to_cdr(m),
            AnyMessage::JointState(m) => to_cdr(m),
        }
        .unwrap()
    }

    /// Its own type decodes its own encoding to the same bytes again.
    fn round_trips(&self) -> bool {
        fn same<M: msgs::RosMessage + std::fmt::Debug>(m: &M) -> bool {
            let bytes = to_cdr(m).unwrap();
            cdr_oracle::check_as::<M>(&bytes).is_some_and(|d| to_cdr(&d).unwrap() == bytes)
        }
        match self {
            AnyMessage::Time(m) => same(m),
            AnyMessage::Header(m) => same(m),
            AnyMessage::String(m) => same(m),
            AnyMessage::Dimension(m) => same(m),
            AnyMessage::Layout(m) => same(m),
            AnyMessage::F32Array(m) => same(m),
            AnyMessage::F64Array(m) => same(m),
            AnyMessage::Point(m) => same(m),
            AnyMessage::Quaternion(m) => same(m),
            AnyMessage::Pose(m) => same(m),
            AnyMessage::PoseStamped(m) => same(m),
            AnyMessage::PoseArray(m) => same(m),
            AnyMessage::JointState(m) => same(m),
        }
    }
}

fn messages() -> impl Strategy<Value = AnyMessage> {
    prop_oneof![
        times().prop_map(AnyMessage::Time),
        headers().prop_map(AnyMessage::Header),
        strings().prop_map(|data| AnyMessage::String(StringMsg { data })),
        dims().prop_map(AnyMessage::Dimension),
        layouts().prop_map(AnyMessage::Layout),
        (layouts(), seqs(any::<f32>()))
            .prop_map(|(layout, data)| AnyMessage::F32Array(Float32MultiArray { layout, data })),
        // Well-formed keypoint matrices too, so `points()` succeeds as often as it fails.
        seqs(any::<[f32; 3]>())
            .prop_map(|rows| AnyMessage::F32Array(Float32MultiArray::from_points(&rows).unwrap())),
        (layouts(), seqs(any::<f64>()))
            .prop_map(|(layout, data)| AnyMessage::F64Array(Float64MultiArray { layout, data })),
        points().prop_map(AnyMessage::Point),
        quaternions().prop_map(AnyMessage::Quaternion),
        poses().prop_map(AnyMessage::Pose),
        (headers(), poses())
            .prop_map(|(header, pose)| AnyMessage::PoseStamped(PoseStamped { header, pose })),
        (headers(), seqs(poses()))
            .prop_map(|(header, poses)| AnyMessage::PoseArray(PoseArray { header, poses })),
        (
            headers(),
            seqs(strings()),
            seqs(any::<f64>()),
            seqs(any::<f64>()),
            seqs(any::<f64>())
        )
            .prop_map(|(header, name, position, velocity, effort)| {
                AnyMessage::JointState(JointState {
                    header,
                    name,
                    position,
                    velocity,
                    effort,
                })
            }),
    ]
}

/// One edit of a payload.
#[derive(Debug, Clone)]
enum Mutation {
    FlipBit(Index, u8),
    SetByte(Index, u8),
    /// A length or count field made huge or zero.
    SetWord(Index, u32),
    Truncate(Index),
    Extend(Vec<u8>),
    Insert(Index, Vec<u8>),
    Remove(Index, usize),
    /// Copy a range over another place (a field from elsewhere in the message).
    CopyRange(Index, Index, usize),
    /// Flip the encapsulation to the other byte order (the body stays as it is).
    SwapEndianness,
}

fn mutations() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<Index>(), 0u8..8).prop_map(|(i, b)| Mutation::FlipBit(i, b)),
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::SetByte(i, b)),
        (
            any::<Index>(),
            prop_oneof![
                Just(0),
                Just(1),
                Just(u32::MAX),
                Just(0x8000_0000),
                any::<u32>()
            ]
        )
            .prop_map(|(i, w)| Mutation::SetWord(i, w)),
        any::<Index>().prop_map(Mutation::Truncate),
        prop::collection::vec(any::<u8>(), 1..16).prop_map(Mutation::Extend),
        (any::<Index>(), prop::collection::vec(any::<u8>(), 1..16))
            .prop_map(|(i, b)| Mutation::Insert(i, b)),
        (any::<Index>(), 1usize..16).prop_map(|(i, n)| Mutation::Remove(i, n)),
        (any::<Index>(), any::<Index>(), 1usize..16)
            .prop_map(|(a, b, n)| Mutation::CopyRange(a, b, n)),
        Just(Mutation::SwapEndianness),
    ]
}

fn apply(bytes: &mut Vec<u8>, mutation: &Mutation) {
    let len = bytes.len();
    match mutation {
        Mutation::FlipBit(at, bit) if len > 0 => bytes[at.index(len)] ^= 1 << bit,
        Mutation::SetByte(at, byte) if len > 0 => bytes[at.index(len)] = *byte,
        Mutation::SetWord(at, word) if len >= 4 => {
            let i = at.index(len - 3);
            bytes[i..i + 4].copy_from_slice(&word.to_le_bytes());
        }
        Mutation::Truncate(at) => bytes.truncate(at.index(len + 1)),
        Mutation::Extend(tail) => bytes.extend_from_slice(tail),
        Mutation::Insert(at, new) => {
            let i = at.index(len + 1);
            bytes.splice(i..i, new.iter().copied());
        }
        Mutation::Remove(at, n) if len > 0 => {
            let i = at.index(len);
            bytes.drain(i..(i + n).min(len));
        }
        Mutation::CopyRange(from, to, n) if len > 0 => {
            let (f, t) = (from.index(len), to.index(len));
            let n = (*n).min(len - f).min(len - t);
            bytes.copy_within(f..f + n, t);
        }
        Mutation::SwapEndianness if len >= 2 => bytes[1] ^= 1,
        _ => {}
    }
}

proptest! {
    #![proptest_config(budget(3000))]

    #[test]
    fn every_type_round_trips(message in messages()) {
        prop_assert!(message.round_trips(), "{:?}", message);
    }

    #[test]
    fn mutated_valid_payloads_decode_consistently_or_fail(
        message in messages(),
        edits in prop::collection::vec(mutations(), 1..6),
    ) {
        let mut bytes = message.encode();
        for edit in &edits {
            apply(&mut bytes, edit);
        }
        cdr_oracle::check_payload(&bytes);
    }

    #[test]
    fn every_truncation_and_extension_of_a_valid_payload_is_checked(message in messages()) {
        let bytes = message.encode();
        for len in 0..bytes.len() {
            cdr_oracle::check_payload(&bytes[..len]);
        }
        for tail in 1..=8 {
            let mut longer = bytes.clone();
            longer.resize(bytes.len() + tail, 0xA5);
            cdr_oracle::check_payload(&longer);
        }
    }

    #[test]
    fn random_payloads_decode_consistently_or_fail(
        header in prop_oneof![Just([0u8, 1, 0, 0]), Just([0u8, 0, 0, 0]), any::<[u8; 4]>()],
        body in prop::collection::vec(any::<u8>(), 0..200),
    ) {
        let mut bytes = header.to_vec();
        bytes.extend(body);
        cdr_oracle::check_payload(&bytes);
    }
}
