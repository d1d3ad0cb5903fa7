//! How a value on a console reads: the level a health value or a capture's quality is shown
//! with (the shell colours it).

/// How a value on a console reads (a health value, a capture's quality).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Fine.
    Ok,
    /// Look at it.
    Warn,
    /// A trial may not start.
    Bad,
}
