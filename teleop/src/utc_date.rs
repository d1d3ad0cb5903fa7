//! ISO 8601 UTC timestamps from Unix time, for profile dates and default file names (no date
//! library needed for one conversion: Howard Hinnant's days-to-civil algorithm).

use std::time::{SystemTime, UNIX_EPOCH};

/// `(year, month, day)` of the proleptic Gregorian calendar for `days` since 1970-01-01.
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let year = yoe + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

fn parts(unix_s: i64) -> (i64, u32, u32, i64, i64, i64) {
    let (y, mo, d) = civil_from_days(unix_s.div_euclid(86_400));
    let secs = unix_s.rem_euclid(86_400);
    (y, mo, d, secs / 3600, secs / 60 % 60, secs % 60)
}

/// `2026-11-21T10:32:05Z` for `unix_s` seconds since the epoch.
pub fn iso8601_utc(unix_s: i64) -> String {
    let (y, mo, d, h, mi, s) = parts(unix_s);
    format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{s:02}Z")
}

/// `20261121T103205Z`: the same instant, safe in a file name.
pub fn compact_utc(unix_s: i64) -> String {
    let (y, mo, d, h, mi, s) = parts(unix_s);
    format!("{y:04}{mo:02}{d:02}T{h:02}{mi:02}{s:02}Z")
}

/// Seconds since the Unix epoch, from the system clock.
pub fn now_unix_s() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_instants() {
        assert_eq!(iso8601_utc(0), "1970-01-01T00:00:00Z");
        assert_eq!(iso8601_utc(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(iso8601_utc(1_732_098_725), "2024-11-20T10:32:05Z");
        assert_eq!(compact_utc(1_732_098_725), "20241120T103205Z");
        assert_eq!(iso8601_utc(-1), "1969-12-31T23:59:59Z");
    }
}
