//! A task's start moved from a seed: the free object of a grasp task, or the whole mechanism
//! of the others, shifted on the table and turned about the vertical, so that a scripted
//! or programmed strategy is shown to hold for a start it was not tuned on.
//!
//! Free objects are moved themselves (MuJoCo allows a free joint only in a body of the world,
//! so they cannot be wrapped); a mechanism is wrapped in a placement body that turns it about
//! its own centre, [`MECHANISM_CENTRE_XY`], where the scaffolds stand. Progress read from a
//! slide's or a hinge's position is unchanged by the move; a grasp target stays where it is.

use retarget::human_hand::SplitMix64;

use super::mjcf::{nums, yaw};

/// The largest shift along x and along y, m.
pub const START_OFFSET_MAX_M: f64 = 0.005;
/// The largest turn about the vertical, rad (3°).
pub const START_YAW_MAX_RAD: f64 = 3.0 * std::f64::consts::PI / 180.0;
/// Where the mechanisms stand on the table (world x, y), m: the centre they are turned about.
pub const MECHANISM_CENTRE_XY: [f64; 2] = [0.5, 0.0];
/// The key of the perturbation's random stream (independent of a glove's noise of the same
/// seed).
const STREAM_KEY: u64 = 0x5354_4152_5450_4F53;

/// How a task's start is moved: a shift on the table and a turn about the vertical.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StartPerturbation {
    /// The shift along world x and y, m.
    pub offset_m: [f64; 2],
    /// The turn about the vertical, rad.
    pub yaw_rad: f64,
}

impl StartPerturbation {
    /// No move: the scene as drawn.
    pub const NONE: StartPerturbation = StartPerturbation {
        offset_m: [0.0, 0.0],
        yaw_rad: 0.0,
    };

    /// A move drawn uniformly within ±[`START_OFFSET_MAX_M`] along x and y and
    /// ±[`START_YAW_MAX_RAD`] about the vertical; the same seed gives the same move.
    pub fn from_seed(seed: u64) -> StartPerturbation {
        let mut rng = SplitMix64::keyed(seed, STREAM_KEY);
        let mut symmetric = |max: f64| (2.0 * rng.next_f64() - 1.0) * max;
        StartPerturbation {
            offset_m: [symmetric(START_OFFSET_MAX_M), symmetric(START_OFFSET_MAX_M)],
            yaw_rad: symmetric(START_YAW_MAX_RAD),
        }
    }

    /// Whether this moves anything.
    pub fn is_none(&self) -> bool {
        *self == StartPerturbation::NONE
    }

    /// A free object's body attributes: its start `xyz` shifted, turned about its origin.
    pub(super) fn free_body_attributes(&self, xyz: [f64; 3]) -> String {
        let [dx, dy] = self.offset_m;
        let pos = nums(&[xyz[0] + dx, xyz[1] + dy, xyz[2]]);
        if self.yaw_rad == 0.0 {
            format!("pos=\"{pos}\"")
        } else {
            format!("pos=\"{pos}\" quat=\"{}\"", yaw(self.yaw_rad))
        }
    }

    /// A mechanism's bodies inside a placement body that shifts them and turns them about
    /// [`MECHANISM_CENTRE_XY`]; unchanged when nothing moves.
    pub(super) fn place_mechanism(&self, bodies: &str) -> String {
        if self.is_none() {
            return bodies.to_string();
        }
        let [cx, cy] = MECHANISM_CENTRE_XY;
        let [dx, dy] = self.offset_m;
        format!(
            "    <body name=\"pomdar_task_placement\" pos=\"{}\" quat=\"{}\">\n      <body name=\"pomdar_task_origin\" pos=\"{}\">\n{}      </body>\n    </body>\n",
            nums(&[cx + dx, cy + dy, 0.0]),
            yaw(self.yaw_rad),
            nums(&[-cx, -cy, 0.0]),
            super::mjcf::indent(bodies, 4) + "\n",
        )
    }
}

#[cfg(test)]
mod tests {
    use scoring::TaskCatalog;

    use super::super::tests::tiny_hand;
    use super::super::{SceneOptions, task_scene};
    use super::*;

    fn floats(node: roxmltree::Node<'_, '_>, name: &str) -> Vec<f64> {
        node.attribute(name)
            .unwrap_or_else(|| panic!("no {name}"))
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect()
    }

    fn scene_xml(id: &str, start: StartPerturbation) -> String {
        let task = TaskCatalog::builtin().get(id).unwrap().clone();
        let options = SceneOptions {
            start,
            ..SceneOptions::default()
        };
        task_scene(&task, &tiny_hand(), &options).unwrap().xml
    }

    fn body<'a>(doc: &'a roxmltree::Document, name: &str) -> Option<roxmltree::Node<'a, 'a>> {
        doc.descendants()
            .find(|n| n.tag_name().name() == "body" && n.attribute("name") == Some(name))
    }

    #[test]
    fn seeds_draw_moves_within_the_bounds_reproducibly() {
        let moves: Vec<_> = (0..200).map(StartPerturbation::from_seed).collect();
        assert_eq!(moves[7], StartPerturbation::from_seed(7));
        for m in &moves {
            assert!(m.offset_m.iter().all(|v| v.abs() <= START_OFFSET_MAX_M));
            assert!(m.yaw_rad.abs() <= START_YAW_MAX_RAD);
        }
        // Spread over the whole range, both signs, not one corner.
        let extreme = |f: &dyn Fn(&StartPerturbation) -> f64, max: f64| {
            let (lo, hi) = moves
                .iter()
                .map(f)
                .fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(v), h.max(v)));
            lo < -0.8 * max && hi > 0.8 * max
        };
        assert!(extreme(&|m| m.offset_m[0], START_OFFSET_MAX_M));
        assert!(extreme(&|m| m.offset_m[1], START_OFFSET_MAX_M));
        assert!(extreme(&|m| m.yaw_rad, START_YAW_MAX_RAD));
    }

    #[test]
    fn a_free_object_is_moved_and_a_mechanism_turned_about_its_centre() {
        let start = StartPerturbation {
            offset_m: [0.004, -0.003],
            yaw_rad: 0.05,
        };
        let xml = scene_xml("G4", start);
        let doc = roxmltree::Document::parse(&xml).unwrap();
        let object = body(&doc, "object").unwrap();
        assert_eq!(floats(object, "pos"), vec![0.504, -0.203, 0.115]);
        let q = floats(object, "quat");
        assert!((q[0] - 0.025_f64.cos()).abs() < 1e-6 && (q[3] - 0.025_f64.sin()).abs() < 1e-6);
        assert!(body(&doc, "pomdar_task_placement").is_none());

        let xml = scene_xml("V1", start);
        let doc = roxmltree::Document::parse(&xml).unwrap();
        let placement = body(&doc, "pomdar_task_placement").unwrap();
        assert_eq!(floats(placement, "pos"), vec![0.504, -0.003, 0.0]);
        let origin = body(&doc, "pomdar_task_origin").unwrap();
        assert_eq!(floats(origin, "pos"), vec![-0.5, 0.0, 0.0]);
        assert!(body(&doc, "tower").is_some_and(|t| t.ancestors().any(|a| a == origin)));
        // Unmoved, the scenes are as drawn.
        assert_eq!(
            scene_xml("V1", StartPerturbation::NONE),
            scene_xml("V1", StartPerturbation::default())
        );
        assert!(!scene_xml("V1", StartPerturbation::NONE).contains("pomdar_task_placement"));
    }

    #[test]
    fn a_move_out_of_range_is_refused() {
        let task = TaskCatalog::builtin().get("G4").unwrap().clone();
        let options = SceneOptions {
            start: StartPerturbation {
                offset_m: [0.006, 0.0],
                yaw_rad: 0.0,
            },
            ..SceneOptions::default()
        };
        let message = task_scene(&task, &tiny_hand(), &options)
            .unwrap_err()
            .to_string();
        assert!(message.contains("at most 5 mm"), "{message}");
    }
}
