//! Reading a simulated glove's task script ([`GloveScript`]) from a TOML file, e.g.
//! `launch_configs/sim/grasp_place.toml`; every error names the file.

use std::path::Path;

use retarget::human_hand::GloveScript;

use crate::stand_ins::error::SimError;

/// Read and validate the glove script in `path`. `Err` naming the file (and the keyframe's
/// field for a value out of range) when it cannot be read, does not parse or is not valid.
pub fn load_glove_script(path: &Path) -> Result<GloveScript, SimError> {
    let in_file = |source: retarget::Error| SimError::Glove {
        source: source.in_file(path),
    };
    let text = std::fs::read_to_string(path).map_err(|e| {
        in_file(retarget::Error::Read {
            reason: e.to_string(),
        })
    })?;
    GloveScript::from_toml_str(&text).map_err(in_file)
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use nalgebra::Vector3;
    use retarget::human_hand::{HumanHandPose, HumanHandShape, ResolvedScript, ScriptPose};

    use super::*;

    fn shipped(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../launch_configs/sim")
            .join(name)
    }

    fn load(name: &str) -> (GloveScript, ResolvedScript) {
        let script = load_glove_script(&shipped(name)).unwrap();
        let resolved = script.resolve(&HumanHandShape::average()).unwrap();
        (script, resolved)
    }

    /// The wrist offset where the hand first closes (the first keyframe not open).
    fn grasp_point(script: &GloveScript) -> Vector3<f64> {
        let closed = script
            .keyframes
            .iter()
            .find(|k| k.pose != ScriptPose::Open)
            .unwrap();
        Vector3::from(closed.wrist_m)
    }

    #[test]
    fn grasp_place_approaches_grasps_lifts_carries_lowers_and_releases() {
        let (script, resolved) = load("grasp_place.toml");
        assert!(script.duration_s() <= 15.0, "{}", script.duration_s());
        let grasp = grasp_point(&script);
        // The G4 rod in front of the palm (README "The simulated benchmark").
        assert!(
            (grasp - Vector3::new(0.01, -0.2, -0.06)).norm() < 1e-12,
            "{grasp}"
        );
        let closed: Vec<_> = script
            .keyframes
            .iter()
            .filter(|k| k.pose == ScriptPose::Fist)
            .collect();
        assert!(closed.iter().all(|k| (k.closure - 0.85).abs() < 1e-12));
        let highest_carry = closed
            .iter()
            .map(|k| k.wrist_m[2] - grasp.z)
            .fold(f64::MIN, f64::max);
        assert!((highest_carry - 0.10).abs() < 1e-12, "lifted 10 cm");
        let end = resolved.sample(script.duration_s() + 10.0);
        assert!(
            (end.wrist_m.x - grasp.x - 0.16).abs() < 1e-12,
            "carried 16 cm along +x"
        );
        assert!(end.wrist_m.z > grasp.z, "risen after the release");
        assert_eq!(end.pose, HumanHandPose::open());
        assert_eq!(resolved.sample(0.0).wrist_m, Vector3::zeros());
    }

    #[test]
    fn grasp_miss_follows_the_same_path_fifteen_centimetres_beside_the_object() {
        let (place, _) = load("grasp_place.toml");
        let (miss, _) = load("grasp_miss.toml");
        assert!(miss.duration_s() <= 15.0);
        let beside = grasp_point(&miss) - grasp_point(&place);
        assert!(
            (beside - Vector3::new(0.0, 0.15, 0.0)).norm() < 1e-12,
            "{beside}"
        );
        assert_eq!(miss.keyframes.len(), place.keyframes.len());
        for (m, p) in miss.keyframes.iter().zip(&place.keyframes) {
            assert_eq!((m.t_s, m.pose, m.closure), (p.t_s, p.pose, p.closure));
        }
    }

    #[test]
    fn a_bad_script_file_is_named_with_the_field() {
        let dir = std::env::temp_dir().join(format!("pomdar-glove-script-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("late_start.toml");
        std::fs::write(
            &path,
            "[[keyframes]]\nt_s = 1.0\nwrist_m = [0.0, 0.0, 0.0]\npose = \"open\"\n",
        )
        .unwrap();
        let bad = load_glove_script(&path).unwrap_err().to_string();
        let missing = load_glove_script(&dir.join("absent.toml"))
            .unwrap_err()
            .to_string();
        std::fs::remove_dir_all(&dir).ok();
        assert!(
            bad.contains("late_start.toml") && bad.contains("keyframes[0].t_s"),
            "{bad}"
        );
        assert!(missing.contains("absent.toml"), "{missing}");
    }
}
