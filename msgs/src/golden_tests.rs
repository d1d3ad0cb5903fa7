//! Byte-exact encodings worked out by hand from the CDR rules (see the crate docs): offsets in
//! the comments count from the first byte after the encapsulation header.

use crate::*;

fn check<T: RosMessage + PartialEq + std::fmt::Debug>(value: &T, expected: &[u8]) {
    let bytes = to_cdr(value).unwrap();
    assert_eq!(bytes, expected, "encoding of {value:?}");
    assert_eq!(&from_cdr::<T>(expected).unwrap(), value);
}

#[test]
fn string_msg() {
    let hi = StringMsg { data: "hi".into() };
    #[rustfmt::skip]
    let expected = [
        0x00, 0x01, 0x00, 0x00,
        0x03, 0x00, 0x00, 0x00, // length 3 counts the NUL
        b'h', b'i', 0x00,
    ];
    check(&hi, &expected);
    // An empty string still has its NUL.
    check(&StringMsg::default(), &[0, 1, 0, 0, 1, 0, 0, 0, 0]);
}

#[test]
fn float32_multi_array_with_one_dim_and_two_floats() {
    let msg = Float32MultiArray {
        layout: MultiArrayLayout {
            dim: vec![MultiArrayDimension {
                label: "dim_0".into(),
                size: 2,
                stride: 2,
            }],
            data_offset: 0,
        },
        data: vec![1.0, 2.0],
    };
    #[rustfmt::skip]
    let expected = [
        0x00, 0x01, 0x00, 0x00,
        0x01, 0x00, 0x00, 0x00,                   //  0: dim count 1
        0x06, 0x00, 0x00, 0x00,                   //  4: label length 6
        b'd', b'i', b'm', b'_', b'0', 0x00,       //  8: "dim_0\0"
        0x00, 0x00,                               // 14: pad to 16
        0x02, 0x00, 0x00, 0x00,                   // 16: size 2
        0x02, 0x00, 0x00, 0x00,                   // 20: stride 2
        0x00, 0x00, 0x00, 0x00,                   // 24: data_offset 0
        0x02, 0x00, 0x00, 0x00,                   // 28: data count 2
        0x00, 0x00, 0x80, 0x3f,                   // 32: 1.0f32
        0x00, 0x00, 0x00, 0x40,                   // 36: 2.0f32
    ];
    check(&msg, &expected);
}

#[test]
fn joint_state_with_one_joint() {
    let msg = JointState {
        header: Header {
            stamp: Time { sec: 1, nanosec: 2 },
            frame_id: "base".into(),
        },
        name: vec!["j1".into()],
        position: vec![0.5],
        velocity: vec![],
        effort: vec![],
    };
    #[rustfmt::skip]
    let expected = [
        0x00, 0x01, 0x00, 0x00,
        0x01, 0x00, 0x00, 0x00,                   //  0: sec 1
        0x02, 0x00, 0x00, 0x00,                   //  4: nanosec 2
        0x05, 0x00, 0x00, 0x00,                   //  8: frame_id length 5
        b'b', b'a', b's', b'e', 0x00,             // 12: "base\0"
        0x00, 0x00, 0x00,                         // 17: pad to 20
        0x01, 0x00, 0x00, 0x00,                   // 20: name count 1
        0x03, 0x00, 0x00, 0x00,                   // 24: length 3
        b'j', b'1', 0x00,                         // 28: "j1\0"
        0x00,                                     // 31: pad to 32
        0x01, 0x00, 0x00, 0x00,                   // 32: position count 1
        0x00, 0x00, 0x00, 0x00,                   // 36: pad to 40 (f64 aligns to 8)
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xe0, 0x3f, // 40: 0.5
        0x00, 0x00, 0x00, 0x00,                   // 48: velocity count 0
        0x00, 0x00, 0x00, 0x00,                   // 52: effort count 0
    ];
    check(&msg, &expected);
}

#[test]
fn pose_stamped_aligns_f64_after_the_frame_id() {
    let msg = PoseStamped {
        header: Header {
            stamp: Time {
                sec: 10,
                nanosec: 500,
            },
            frame_id: "coil".into(),
        },
        pose: Pose {
            position: Point {
                x: 1.0,
                y: 2.0,
                z: 3.0,
            },
            orientation: Quaternion::identity(),
        },
    };
    // Counting alignment from the start of the payload instead would pad 3 bytes, not 7.
    #[rustfmt::skip]
    let expected = [
        0x00, 0x01, 0x00, 0x00,
        0x0a, 0x00, 0x00, 0x00,                   //  0: sec 10
        0xf4, 0x01, 0x00, 0x00,                   //  4: nanosec 500
        0x05, 0x00, 0x00, 0x00,                   //  8: frame_id length 5
        b'c', b'o', b'i', b'l', 0x00,             // 12: "coil\0"
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 17: pad to 24
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f, // 24: x 1.0
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40, // 32: y 2.0
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x40, // 40: z 3.0
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 48: qx 0
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 56: qy 0
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 64: qz 0
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f, // 72: qw 1.0
    ];
    check(&msg, &expected);

    // The same message big-endian: header 00 00, every number byte-reversed.
    let mut be = vec![0x00, 0x00, 0x00, 0x00];
    for field in [&expected[4..8], &expected[8..12], &expected[12..16]] {
        be.extend(field.iter().rev());
    }
    be.extend_from_slice(&expected[16..28]); // string bytes and padding
    for f in expected[28..].chunks_exact(8) {
        be.extend(f.iter().rev());
    }
    assert_eq!(from_cdr::<PoseStamped>(&be).unwrap(), msg);
}
