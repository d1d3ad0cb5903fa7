//! (being written; the reading type the engine needs first)

/// One reading of a task's progress source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reading {
    /// A slide (m) or hinge (rad) joint's position.
    Joint(f64),
    /// A free-jointed object's position and speed.
    Body {
        /// World position, m.
        position_m: [f64; 3],
        /// Linear speed, m/s.
        speed_m_s: f64,
    },
}
