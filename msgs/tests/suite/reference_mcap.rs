//! Real data: the lab's 30 s Rokoko recording (`../shared/reference`), converted to MCAP by an
//! independent tool, decodes with these types, and its schemas agree field by field with ours.
//! Skips (with a message) where the reference directory is absent.

use std::collections::BTreeMap;
use std::path::PathBuf;

use msgs::{Float32MultiArray, MsgDefinition, PoseStamped, RosMessage, from_cdr, to_cdr};

fn reference_file() -> Option<PathBuf> {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/reference"
    ));
    if !dir.is_dir() {
        println!(
            "SKIPPED: reference data directory {} is absent",
            dir.display()
        );
        return None;
    }
    Some(dir.join("rokoko_orca_2024-11-20.mcap"))
}

/// A `ros2msg` schema as `pkg/Type` → its field lines `(pkg/Type or primitive, name)`, with
/// comments, blank lines and default values dropped and relative type names resolved. Two
/// schemas that describe the same CDR layout compare equal whatever their order or spelling.
fn normalise(root: &str, schema: &str) -> BTreeMap<String, Vec<(String, String)>> {
    let mut out = BTreeMap::new();
    let mut current = root.replace("/msg/", "/");
    let mut fields = Vec::new();
    for line in schema.lines() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.starts_with("====") {
            continue;
        }
        if let Some(name) = line.strip_prefix("MSG: ") {
            out.insert(current, std::mem::take(&mut fields));
            current = name.replace("/msg/", "/");
            continue;
        }
        let mut words = line.split_whitespace();
        let (Some(ty), Some(name)) = (words.next(), words.next()) else {
            continue;
        };
        let (base, array) = ty.split_at(ty.find('[').unwrap_or(ty.len()));
        let package = current.split('/').next().unwrap_or("");
        let base = match base.chars().next() {
            Some(c) if c.is_ascii_uppercase() => format!("{package}/{base}"),
            _ => base.to_string(),
        };
        fields.push((format!("{base}{array}"), name.to_string()));
    }
    out.insert(current, fields);
    out
}

fn check_schema(def: MsgDefinition, schema: &mcap::Schema<'_>) {
    println!(
        "schema {:?} encoding {:?}:\n{}",
        schema.name,
        schema.encoding,
        String::from_utf8_lossy(&schema.data)
    );
    assert_eq!(schema.name, def.ros_type_name());
    assert_eq!(schema.encoding, "ros2msg");
    let theirs = std::str::from_utf8(&schema.data).unwrap();
    let name = def.ros_type_name();
    assert_eq!(
        normalise(&name, theirs),
        normalise(&name, &def.schema_text())
    );
}

#[test]
fn rokoko_recording_decodes() {
    let Some(path) = reference_file() else {
        return;
    };
    let bytes = std::fs::read(&path).unwrap();

    let header = mcap::read::LinearReader::new(&bytes)
        .unwrap()
        .find_map(|r| match r.unwrap() {
            mcap::records::Record::Header(h) => Some(h),
            _ => None,
        })
        .unwrap();
    println!("profile {:?}, library {:?}", header.profile, header.library);

    let (mut mano, mut wrist, mut other) = (0usize, 0usize, 0usize);
    let mut frames = BTreeMap::new();
    let mut strides = BTreeMap::new();
    let mut checked_schema = BTreeMap::new();
    for message in mcap::MessageStream::new(&bytes).unwrap() {
        let message = message.unwrap();
        let channel = &message.channel;
        assert_eq!(channel.message_encoding, "cdr", "{}", channel.topic);
        let schema = channel.schema.as_ref().unwrap();
        match channel.topic.as_str() {
            "/ingress/mano" => {
                let msg: Float32MultiArray = from_cdr(&message.data)
                    .unwrap_or_else(|e| panic!("mano message {}: {e}", message.sequence));
                // Sizes only: the lab writes numpy-style strides (22×3 has strides 3 and 1),
                // not the ROS convention (66 and 3) that `from_points` writes.
                let dims: Vec<_> = msg
                    .layout
                    .dim
                    .iter()
                    .map(|d| (d.label.as_str(), d.size))
                    .collect();
                assert_eq!(dims[..], [("dim_0", 22), ("dim_1", 3)], "{:?}", msg.layout);
                assert_eq!(msg.points().unwrap().len(), 22);
                // An independent CDR writer (rosbags) produced the same bytes we would.
                assert_eq!(to_cdr(&msg).unwrap(), message.data.as_ref());
                *strides
                    .entry(msg.layout.dim.iter().map(|d| d.stride).collect::<Vec<_>>())
                    .or_insert(0usize) += 1;
                checked_schema
                    .entry(channel.topic.clone())
                    .or_insert_with(|| {
                        check_schema(Float32MultiArray::DEFINITION, schema);
                    });
                mano += 1;
            }
            "/ingress/wrist" => {
                let msg: PoseStamped = from_cdr(&message.data)
                    .unwrap_or_else(|e| panic!("wrist message {}: {e}", message.sequence));
                assert_eq!(to_cdr(&msg).unwrap(), message.data.as_ref());
                *frames.entry(msg.header.frame_id).or_insert(0usize) += 1;
                checked_schema
                    .entry(channel.topic.clone())
                    .or_insert_with(|| {
                        check_schema(PoseStamped::DEFINITION, schema);
                    });
                wrist += 1;
            }
            _ => other += 1,
        }
    }
    println!("decoded {mano} /ingress/mano, {wrist} /ingress/wrist, {other} other messages");
    println!("wrist frames: {frames:?}; mano strides: {strides:?}");
    assert!(
        mano > 1000 && wrist > 1000,
        "too few messages: {mano}, {wrist}"
    );
    assert_eq!(checked_schema.len(), 2);
}
