//! `pomdar model`: a hand model's joints, limits, named frames and embodiments.

use retarget::{EmbodimentCatalog, Finger, HandModel};
use serde_json::json;

use crate::hand_source::{HandSource, HandSourceError};

/// The model could not be loaded or posed, a `--pose` item is not valid, or the report
/// could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ModelReportError {
    /// The model could not be loaded.
    #[error(transparent)]
    Load {
        /// The loader's error (names the file).
        #[from]
        source: HandSourceError,
    },
    /// A `--pose` item without `=`.
    #[error("--pose: expected NAME=RADIANS, got '{item}'")]
    PoseSyntax {
        /// The item as given.
        item: String,
    },
    /// A `--pose` joint the model does not have.
    #[error("--pose: '{name}' is not a joint of {model}; joints: {joints}")]
    UnknownJoint {
        /// The joint name given.
        name: String,
        /// The model's name.
        model: String,
        /// The model's joints, comma-separated.
        joints: String,
    },
    /// A `--pose` value that is not a number.
    #[error("--pose: '{value}' is not a number (radians) for {name}: {source}")]
    NotANumber {
        /// The joint name given.
        name: String,
        /// The value given.
        value: String,
        /// The parse error.
        #[source]
        source: std::num::ParseFloatError,
    },
    /// A `--pose` value outside the joint's limits.
    #[error("--pose: {name} = {value} rad is outside its limits [{lower}, {upper}] rad")]
    OutsideLimits {
        /// The joint name given.
        name: String,
        /// The value, radians.
        value: f64,
        /// Lower limit, radians.
        lower: f64,
        /// Upper limit, radians.
        upper: f64,
    },
    /// Forward kinematics failed at the requested pose.
    #[error(transparent)]
    Pose {
        /// The model's error.
        #[from]
        source: retarget::Error,
    },
    /// The palm frame cannot be built at the requested pose.
    #[error("palm frame at the requested pose: {source}")]
    PalmFrame {
        /// The model's error.
        #[source]
        source: retarget::Error,
    },
    /// The JSON report could not be serialised.
    #[error(transparent)]
    Json {
        /// serde_json's error.
        #[from]
        source: serde_json::Error,
    },
}

/// Load the model, pose it and print the report.
pub fn run(source: &HandSource, pose: &[String], json: bool) -> Result<(), ModelReportError> {
    let model = source.load()?;
    let q = parse_pose(&model, pose)?;
    let state = model.forward_new(&q)?;
    let palm = model
        .palm_frame(&state)
        .map_err(|source| ModelReportError::PalmFrame { source })?;
    let frames = model.frames();
    let named: Vec<(String, [f64; 3])> = Finger::ALL
        .iter()
        .flat_map(|&f| {
            [
                (format!("{f}_base"), frames.base(f)),
                (format!("{f}_tip"), frames.tip(f)),
            ]
        })
        .chain([("wrist".to_string(), frames.wrist)])
        .map(|(name, link)| {
            let p = palm.point_to_palm(&state.position(link)) * 1e3;
            (name, [p.x, p.y, p.z])
        })
        .collect();
    let catalog = EmbodimentCatalog::builtin();
    let embodiments: Vec<_> = catalog
        .embodiments
        .iter()
        .map(|e| (e.name.as_str(), e.dof, e.unlocked_mask(&model).is_ok()))
        .collect();

    if json {
        let doc = json!({
            "model": model.name(),
            "source": source.describe(),
            "dof": model.dof(),
            "links": model.link_count(),
            "joints": model.dofs().iter().zip(&q).map(|(d, v)| json!({
                "name": d.name, "lower_rad": d.limits.lower_rad,
                "upper_rad": d.limits.upper_rad, "q_rad": v,
            })).collect::<Vec<_>>(),
            "frames_in_palm_mm": named.iter().map(|(n, p)| (n.clone(), json!(p)))
                .collect::<serde_json::Map<_, _>>(),
            "embodiments": embodiments.iter().map(|(n, dof, ok)| json!({
                "name": n, "dof": dof, "applies": ok,
            })).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&doc)?);
        return Ok(());
    }

    println!(
        "{} — {} ({} degrees of freedom, {} links)",
        model.name(),
        source.describe(),
        model.dof(),
        model.link_count()
    );
    println!(
        "\n{:<12} {:>10} {:>10} {:>10}   {:>8} {:>8}",
        "joint", "lower rad", "upper rad", "q rad", "lower °", "upper °"
    );
    for (dof, v) in model.dofs().iter().zip(&q) {
        println!(
            "{:<12} {:>10.4} {:>10.4} {:>10.4}   {:>8.1} {:>8.1}",
            dof.name,
            dof.limits.lower_rad,
            dof.limits.upper_rad,
            v,
            dof.limits.lower_rad.to_degrees(),
            dof.limits.upper_rad.to_degrees()
        );
    }
    println!("\nnamed frames in the palm frame (mm; x across the knuckles, y to the fingers):");
    for (name, p) in &named {
        println!("  {name:<13} {:>8.1} {:>8.1} {:>8.1}", p[0], p[1], p[2]);
    }
    println!("\nembodiments (built-in catalog):");
    for (name, dof, ok) in &embodiments {
        let status = if *ok {
            ""
        } else {
            "  (not applicable: joints missing in this model)"
        };
        println!("  {name:<10} {dof:>2} DoF{status}");
    }
    Ok(())
}

fn parse_pose(model: &HandModel, pose: &[String]) -> Result<Vec<f64>, ModelReportError> {
    let mut q = model.zero_pose();
    for item in pose {
        let Some((name, value)) = item.split_once('=') else {
            return Err(ModelReportError::PoseSyntax { item: item.clone() });
        };
        let index = model
            .dof_index(name.trim())
            .ok_or_else(|| ModelReportError::UnknownJoint {
                name: name.trim().to_string(),
                model: model.name().to_string(),
                joints: model.dof_names().collect::<Vec<_>>().join(", "),
            })?;
        let value: f64 = value
            .trim()
            .parse()
            .map_err(|source| ModelReportError::NotANumber {
                name: name.to_string(),
                value: value.to_string(),
                source,
            })?;
        let limits = model.dofs()[index].limits;
        if !limits.contains(value) {
            return Err(ModelReportError::OutsideLimits {
                name: name.to_string(),
                value,
                lower: limits.lower_rad,
                upper: limits.upper_rad,
            });
        }
        q[index] = value;
    }
    Ok(q)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose_error(item: &str) -> String {
        let model = HandModel::orca_v1_right();
        parse_pose(&model, &[item.to_string()])
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn pose_errors_say_what_is_wrong() {
        let model = HandModel::orca_v1_right();
        let joint = model.dof_names().next().unwrap().to_string();
        assert_eq!(
            pose_error("thumb"),
            "--pose: expected NAME=RADIANS, got 'thumb'"
        );
        assert!(
            pose_error("nope=0.1").starts_with("--pose: 'nope' is not a joint of "),
            "{}",
            pose_error("nope=0.1")
        );
        let err = pose_error(&format!("{joint}=x"));
        assert!(
            err.starts_with(&format!(
                "--pose: 'x' is not a number (radians) for {joint}: "
            )),
            "{err}"
        );
        let err = pose_error(&format!("{joint}=99"));
        assert!(
            err.starts_with(&format!("--pose: {joint} = 99 rad is outside its limits [")),
            "{err}"
        );
    }
}
