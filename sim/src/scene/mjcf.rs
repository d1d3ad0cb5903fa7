//! Small helpers for writing MJCF text: numbers, vectors, poses.

use nalgebra::{Isometry3, UnitQuaternion};

/// `x` with at most 6 decimals (micrometres, microradians), trailing zeros dropped.
pub(super) fn num(x: f64) -> String {
    let text = format!("{x:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    match text {
        "-0" | "" => "0".to_string(),
        t => t.to_string(),
    }
}

/// Numbers separated by spaces (`pos`, `size`, `fromto`).
pub(super) fn nums(values: &[f64]) -> String {
    values.iter().map(|v| num(*v)).collect::<Vec<_>>().join(" ")
}

/// `text` with every non-empty line indented by `spaces` more, without a trailing newline.
pub(super) fn indent(text: &str, spaces: usize) -> String {
    let pad = " ".repeat(spaces);
    text.trim_end()
        .lines()
        .map(|line| {
            if line.trim().is_empty() {
                String::new()
            } else {
                format!("{pad}{line}")
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// `quat="w x y z"` of a rotation.
pub(super) fn quat(rotation: &UnitQuaternion<f64>) -> String {
    let q = rotation.quaternion();
    nums(&[q.w, q.i, q.j, q.k])
}

/// `pos="…" quat="…"` attributes of a pose.
pub(super) fn pose_attributes(pose: &Isometry3<f64>) -> String {
    let t = pose.translation.vector;
    format!(
        "pos=\"{}\" quat=\"{}\"",
        nums(&[t.x, t.y, t.z]),
        quat(&pose.rotation)
    )
}

/// `quat="…"` of a turn of `angle_rad` about the vertical axis.
pub(super) fn yaw(angle_rad: f64) -> String {
    quat(&UnitQuaternion::from_axis_angle(
        &nalgebra::Vector3::z_axis(),
        angle_rad,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_exact_to_a_micrometre() {
        assert_eq!(num(0.1 + 0.2), "0.3");
        assert_eq!(num(-0.0000001), "0");
        assert_eq!(num(62.831853), "62.831853");
        assert_eq!(num(2.0), "2");
        assert_eq!(nums(&[0.5, -0.25, 0.0]), "0.5 -0.25 0");
        assert_eq!(yaw(0.0), "1 0 0 0");
    }

    #[test]
    fn indenting_keeps_lines_and_drops_the_trailing_newline() {
        assert_eq!(
            indent("<a>\n  <b/>\n\n</a>\n", 2),
            "  <a>\n    <b/>\n\n  </a>"
        );
    }
}
