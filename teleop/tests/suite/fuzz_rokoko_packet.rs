//! Fuzzing of the Rokoko Studio packet parser on stable Rust, structure-aware: real packets
//! (one and two actors, both hands, metres and centimetres) are parsed as JSON and mutated —
//! values set to hostile ones (huge, zero, negative, strings, null, arrays, objects), numbers
//! scaled, keys removed or renamed to another bone, actors reordered — then serialised and
//! edited as bytes (changed, cut, extended). Every datagram goes through `rokoko_oracle`: no
//! panic, refusals are `Err` with a counter name, parsed frames are finite and consistent.
//! (The parser's own unit tests also feed it arbitrary and byte-flipped packets.)
//!
//! CI budget: 2,000 packets; `PROPTEST_CASES=N` for longer.

use crate::rokoko_oracle;

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion};
use proptest::prelude::*;
use proptest::sample::Index;
use retarget::KeypointLayout;
use serde_json::{Value, json};
use teleop::ingress::ingress_config::Hand;
use teleop::ingress::rokoko_packet_builder::{HandPose, actor, packet, right_hand_packet};

/// Cases per property in CI, unless `PROPTEST_CASES` asks for another number.
fn budget(ci_cases: u32) -> ProptestConfig {
    let mut config = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = ci_cases;
    }
    config.failure_persistence = None;
    config
}

fn hand(layout: KeypointLayout, scale: f64) -> Vec<Point3<f64>> {
    (0..layout.len())
        .map(|i| {
            Point3::new(
                0.3 + 0.01 * i as f64,
                -0.1 + 0.002 * i as f64,
                1.0 - 0.003 * i as f64,
            ) * scale
        })
        .collect()
}

/// The seed packets.
fn seeds() -> Vec<Value> {
    let wrist = Isometry3::from_parts(
        Translation3::new(0.3, -0.1, 1.0),
        UnitQuaternion::from_euler_angles(0.2, -0.4, 1.1),
    );
    let mut out = Vec::new();
    for layout in [KeypointLayout::Lab22, KeypointLayout::Lab21] {
        let bytes = right_hand_packet(12.5, layout, &hand(layout, 1.0), &wrist);
        out.push(serde_json::from_slice(&bytes).unwrap());
    }
    let points = hand(KeypointLayout::Lab22, 1.0);
    let pose = HandPose {
        layout: KeypointLayout::Lab22,
        keypoints: &points,
        wrist_rotation: wrist.rotation,
    };
    let two = packet(
        3.0,
        vec![
            actor("Actor1", Hand::Right, &pose, 0.01),
            actor("Actor2", Hand::Left, &pose, 1.0),
        ],
    );
    out.push(serde_json::from_slice(&two).unwrap());
    out
}

/// One edit of a packet.
#[derive(Debug, Clone)]
enum JsonEdit {
    Set(Index, Value),
    Scale(Index, f64),
    Remove(Index),
    /// Give a key another key's name from elsewhere in the document.
    Rename(Index, Index),
    /// Reverse an array (actors, colours).
    Reverse(Index),
}

/// A byte-level edit of the serialised packet.
#[derive(Debug, Clone)]
enum ByteEdit {
    Set(Index, u8),
    Truncate(Index),
    Extend(Vec<u8>),
}

fn hostile() -> impl Strategy<Value = Value> {
    prop_oneof![
        Just(json!(0)),
        Just(json!(-1)),
        Just(json!(1e308)),
        Just(json!(-1e308)),
        Just(json!(5e-324)),
        Just(json!(u64::MAX)),
        Just(json!(i64::MIN)),
        Just(json!("3,0")),
        Just(json!("4")),
        Just(json!("")),
        Just(Value::Null),
        Just(json!(true)),
        Just(json!([])),
        Just(json!({})),
        Just(json!([1.0, 2.0, 3.0])),
        Just(json!({"x": 1.0, "y": 2.0, "z": 3.0})),
        Just(json!({"x": 0.0, "y": 0.0, "z": 0.0, "w": 0.0})),
        (-1e3f64..1e3).prop_map(|v| json!(v)),
    ]
}

fn json_edits() -> impl Strategy<Value = JsonEdit> {
    prop_oneof![
        4 => (any::<Index>(), hostile()).prop_map(|(i, v)| JsonEdit::Set(i, v)),
        4 => (
            any::<Index>(),
            prop_oneof![Just(0.0), Just(-1.0), Just(1e300), Just(1e-300), 0.5f64..2.0]
        )
            .prop_map(|(i, f)| JsonEdit::Scale(i, f)),
        2 => any::<Index>().prop_map(JsonEdit::Remove),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| JsonEdit::Rename(a, b)),
        1 => any::<Index>().prop_map(JsonEdit::Reverse),
    ]
}

fn byte_edits() -> impl Strategy<Value = ByteEdit> {
    prop_oneof![
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| ByteEdit::Set(i, b)),
        any::<Index>().prop_map(ByteEdit::Truncate),
        prop::collection::vec(any::<u8>(), 1..16).prop_map(ByteEdit::Extend),
    ]
}

/// JSON pointers to every value, parents first.
fn pointers(value: &Value, prefix: &str, out: &mut Vec<String>) {
    let children: Vec<(String, &Value)> = match value {
        Value::Object(map) => map
            .iter()
            .map(|(k, v)| (k.replace('~', "~0").replace('/', "~1"), v))
            .collect(),
        Value::Array(items) => items
            .iter()
            .enumerate()
            .map(|(i, v)| (i.to_string(), v))
            .collect(),
        _ => Vec::new(),
    };
    for (key, child) in children {
        let pointer = format!("{prefix}/{key}");
        out.push(pointer.clone());
        pointers(child, &pointer, out);
    }
}

fn parent_and_key(pointer: &str) -> (&str, String) {
    let (parent, key) = pointer.rsplit_once('/').unwrap_or(("", pointer));
    (parent, key.replace("~1", "/").replace("~0", "~"))
}

fn edit(root: &mut Value, edit: &JsonEdit) {
    let mut all = Vec::new();
    pointers(root, "", &mut all);
    if all.is_empty() {
        return;
    }
    let pick = |i: &Index| all[i.index(all.len())].clone();
    match edit {
        JsonEdit::Set(i, v) => {
            if let Some(node) = root.pointer_mut(&pick(i)) {
                *node = v.clone();
            }
        }
        JsonEdit::Scale(i, f) => {
            if let Some(node) = root.pointer_mut(&pick(i))
                && let Some(x) = node.as_f64()
            {
                *node = serde_json::Number::from_f64(x * f).map_or(Value::Null, Value::Number);
            }
        }
        JsonEdit::Remove(i) => {
            let pointer = pick(i);
            let (parent, key) = parent_and_key(&pointer);
            match root.pointer_mut(parent) {
                Some(Value::Object(map)) => {
                    map.remove(&key);
                }
                Some(Value::Array(items)) => {
                    if let Ok(n) = key.parse::<usize>()
                        && n < items.len()
                    {
                        items.remove(n);
                    }
                }
                _ => {}
            }
        }
        JsonEdit::Rename(a, b) => {
            let pointer = pick(a);
            let (parent, key) = parent_and_key(&pointer);
            let (_, new_key) = parent_and_key(&pick(b));
            if let Some(Value::Object(map)) = root.pointer_mut(parent)
                && let Some(v) = map.remove(&key)
            {
                map.insert(new_key, v);
            }
        }
        JsonEdit::Reverse(i) => {
            if let Some(Value::Array(items)) = root.pointer_mut(&pick(i)) {
                items.reverse();
            }
        }
    }
}

proptest! {
    #![proptest_config(budget(2000))]

    #[test]
    fn mutated_packets_parse_consistently_or_are_refused(
        seed in 0usize..3,
        json in prop::collection::vec(json_edits(), 0..5),
        bytes in prop::collection::vec(byte_edits(), 0..2),
    ) {
        let mut value = seeds().swap_remove(seed);
        for e in &json {
            edit(&mut value, e);
        }
        let mut text = value.to_string().into_bytes();
        for e in &bytes {
            let len = text.len();
            match e {
                ByteEdit::Set(i, b) if len > 0 => text[i.index(len)] = *b,
                ByteEdit::Truncate(i) => text.truncate(i.index(len + 1)),
                ByteEdit::Extend(tail) => text.extend_from_slice(tail),
                _ => {}
            }
        }
        rokoko_oracle::check_packet(&text);
    }
}

#[test]
fn the_seeds_parse() {
    // lab22 right hand; lab21 right hand; Actor1's right hand in centimetres.
    let selections = rokoko_oracle::selections();
    for (seed, selection) in seeds().into_iter().zip([0, 2, 4]) {
        let bytes = seed.to_string().into_bytes();
        let parsed = teleop::ingress::rokoko_packet::parse_packet(&bytes, &selections[selection]);
        assert!(parsed.is_ok(), "{parsed:?}");
        rokoko_oracle::check_packet(&bytes);
    }
}
