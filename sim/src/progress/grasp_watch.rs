//! Grasp: lifted (0.5), at rest in the target (1), out of the target again (0.5).

use super::{GraspMapping, ProgressEvent};

/// The grasp level reached.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Level {
    /// Not lifted yet (0).
    Resting,
    /// Lifted at least once, not relocated now (0.5).
    Lifted,
    /// At rest inside the target (1).
    Relocated,
}

/// Watches a free object's height, speed and place.
#[derive(Debug, Clone)]
pub(super) struct GraspWatch {
    grasp: GraspMapping,
    /// The object's height in the first reading, m.
    rest_z_m: f64,
    level: Level,
    /// Since when (s) the object has been slower than the rest speed, if it is.
    slow_since_s: Option<f64>,
    /// Whether the current slow spell already counted as a rest.
    rest_counted: bool,
    /// Whether the object was lifted since it last came to rest.
    lifted_since_rest: bool,
}

impl GraspWatch {
    /// A watch for an object resting at height `rest_z_m` (its body origin, m).
    pub(super) fn new(grasp: GraspMapping, rest_z_m: f64) -> GraspWatch {
        GraspWatch {
            grasp,
            rest_z_m,
            level: Level::Resting,
            slow_since_s: None,
            rest_counted: false,
            lifted_since_rest: false,
        }
    }

    /// The level changes (and drops) the reading at `t_s` causes.
    pub(super) fn update(
        &mut self,
        position_m: [f64; 3],
        speed_m_s: f64,
        t_s: f64,
    ) -> Vec<ProgressEvent> {
        let mut events = Vec::new();
        let high = position_m[2] >= self.rest_z_m + self.grasp.lift_m;
        if high {
            self.lifted_since_rest = true;
            if self.level == Level::Resting {
                self.level = Level::Lifted;
                events.push(ProgressEvent::Progress(0.5));
            }
        }
        let inside = self.grasp.in_target(position_m);
        if self.level == Level::Relocated && !inside {
            self.level = Level::Lifted;
            events.push(ProgressEvent::Progress(0.5));
        }
        if self.came_to_rest(speed_m_s, t_s) {
            events.extend(self.settle(inside, high));
        }
        events
    }

    /// Whether the object has just been slow for `rest_time_s` (once per slow spell).
    fn came_to_rest(&mut self, speed_m_s: f64, t_s: f64) -> bool {
        if speed_m_s >= self.grasp.rest_speed_m_s {
            self.slow_since_s = None;
            self.rest_counted = false;
            return false;
        }
        let since = *self.slow_since_s.get_or_insert(t_s);
        if self.rest_counted || t_s - since < self.grasp.rest_time_s {
            return false;
        }
        self.rest_counted = true;
        true
    }

    /// The object came to rest, `inside` the target or not, `high` (held still at lift
    /// height: not a drop) or not. A target box should therefore reach only a little above
    /// the surface an object rests on, or an object held still inside it counts as placed.
    fn settle(&mut self, inside: bool, high: bool) -> Option<ProgressEvent> {
        match (self.level, inside) {
            (Level::Lifted, true) => {
                self.level = Level::Relocated;
                self.lifted_since_rest = false;
                Some(ProgressEvent::Progress(1.0))
            }
            (Level::Lifted, false) if !high && self.lifted_since_rest => {
                self.lifted_since_rest = false;
                Some(ProgressEvent::Drop)
            }
            _ => None,
        }
    }
}
