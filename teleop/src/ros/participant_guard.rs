//! The datagram guard ([`datagram_guard`](super::datagram_guard)) on every socket of every DDS
//! participant the process opens, or start-up fails.
//!
//! A command that runs the station or talks to the robot (`station`, `trial`, `study`,
//! `relay`, `calibrate`, `hand-check`, `sim`) calls [`require`] first; with
//! `--no-datagram-guard` it calls [`decline`] instead, which says once on stderr that the
//! process runs unguarded. When required, each participant is guarded as it is built: the
//! UDP sockets that appeared while it was built (its listeners on the discovery and user
//! ports, multicast and unicast, and its senders) get the filter, and if one cannot, or the
//! participant's unicast discovery socket is not among them, building it fails with an error
//! naming the socket. Other commands (the mock robot, the ingresses, the probe) and the
//! library's default leave participants unguarded.
//!
//! Sockets are told apart by their inode, not their descriptor number: a descriptor closed
//! and reused by another thread while the participant was built is still a new socket.
//!
//! A socket is given the filter once. Participants built at the same time each see the
//! other's new sockets, and the participants of one domain share its multicast ports; the
//! kernel charges a replacing filter to the socket's option memory before it frees the old
//! one, and the two (about 30 KiB of instructions each) with the socket's multicast
//! memberships can pass `net.core.optmem_max`: the attach fails with ENOMEM. So the scans run
//! one at a time, and a socket already guarded counts as guarded.

use std::collections::BTreeSet;
use std::io;
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::{Mutex, PoisonError};

use serde_json::{Value, json};
use socket2::{SockRef, Type};

use super::datagram_guard::attach;

/// Test-only: `POMDAR_TEST_DATAGRAM_GUARD_FAIL=1` makes every attach fail, so a test can show
/// that a guard that cannot attach stops start-up. Read by [`guard_new_sockets`] only.
pub const GUARD_FAIL_ENV: &str = "POMDAR_TEST_DATAGRAM_GUARD_FAIL";

const OFF: u8 = 0;
const REQUIRED: u8 = 1;
const DECLINED: u8 = 2;

static MODE: AtomicU8 = AtomicU8::new(OFF);
/// The inodes of every socket guarded so far; held for the whole of a scan, so scans run one
/// at a time.
static GUARDED: Mutex<BTreeSet<u64>> = Mutex::new(BTreeSet::new());

/// Guard every DDS participant this process builds from now on; a participant that cannot be
/// guarded is not built.
pub fn require() {
    MODE.store(REQUIRED, Ordering::SeqCst);
}

/// `--no-datagram-guard`: build participants unguarded, and say so once on stderr.
pub fn decline() {
    if MODE.swap(DECLINED, Ordering::SeqCst) != DECLINED {
        eprintln!(
            "warning: --no-datagram-guard: this process's DDS sockets are not guarded; one crafted DATA_FRAG datagram can take gigabytes of its memory (docs/SECURITY.md)"
        );
    }
}

/// Whether participants must be guarded.
pub fn required() -> bool {
    MODE.load(Ordering::SeqCst) == REQUIRED
}

/// The guard's state for a status document: `required`, `declined` or `off`, and how many
/// sockets this process has guarded since it started.
pub fn status() -> Value {
    let mode = match MODE.load(Ordering::SeqCst) {
        REQUIRED => "required",
        DECLINED => "declined",
        _ => "off",
    };
    let sockets = GUARDED.lock().unwrap_or_else(PoisonError::into_inner).len();
    json!({ "mode": mode, "sockets": sockets })
}

/// The inodes of this process's sockets (from `/proc/self/fd`).
pub fn socket_inodes() -> io::Result<BTreeSet<u64>> {
    let mut inodes = BTreeSet::new();
    for entry in std::fs::read_dir("/proc/self/fd")? {
        // A descriptor closed since the directory was read has no link any more.
        if let Some(inode) = std::fs::read_link(entry?.path())
            .ok()
            .and_then(|target| socket_inode(&target.to_string_lossy()))
        {
            inodes.insert(inode);
        }
    }
    Ok(inodes)
}

/// The inode of a `/proc/self/fd` link target `socket:[INODE]`.
fn socket_inode(target: &str) -> Option<u64> {
    target
        .strip_prefix("socket:[")?
        .strip_suffix(']')?
        .parse()
        .ok()
}

/// Attaches the filter to every datagram socket of this process not in `before` (the
/// participant just built) and not guarded yet; its unicast discovery socket, on
/// `discovery_port`, must be among them. Returns how many it guarded now; an error names the
/// socket that could not be.
pub fn guard_new_sockets(before: &BTreeSet<u64>, discovery_port: u16) -> Result<usize, String> {
    let fail = std::env::var(GUARD_FAIL_ENV).is_ok_and(|v| v.trim() == "1");
    let pid = rustix::process::Pid::from_raw(std::process::id() as i32)
        .ok_or_else(|| "no process id".to_string())?;
    let me = rustix::process::pidfd_open(pid, rustix::process::PidfdFlags::empty())
        .map_err(|e| format!("cannot open this process's pidfd: {e}"))?;
    let entries = std::fs::read_dir("/proc/self/fd")
        .map_err(|e| format!("cannot list /proc/self/fd: {e}"))?;
    let mut already = GUARDED.lock().unwrap_or_else(PoisonError::into_inner);
    let (mut ports, mut guarded) = (BTreeSet::new(), BTreeSet::new());
    for entry in entries.flatten() {
        let Some(inode) = std::fs::read_link(entry.path())
            .ok()
            .and_then(|target| socket_inode(&target.to_string_lossy()))
        else {
            continue;
        };
        let fd = entry.file_name().to_string_lossy().parse::<i32>();
        let (false, Ok(fd)) = (before.contains(&inode), fd) else {
            continue;
        };
        // Closed since the directory was read: not the participant's (it holds its own).
        let Ok(socket) =
            rustix::process::pidfd_getfd(&me, fd, rustix::process::PidfdGetfdFlags::empty())
        else {
            continue;
        };
        let socket = SockRef::from(&socket);
        if !socket.r#type().is_ok_and(|t| t == Type::DGRAM) {
            continue;
        }
        let port = socket
            .local_addr()
            .ok()
            .and_then(|a| a.as_socket())
            .map_or(0, |a| a.port());
        ports.insert(port);
        if already.contains(&inode) {
            continue;
        }
        let attached = match fail {
            true => Err(io::Error::other(format!("{GUARD_FAIL_ENV} is set"))),
            false => attach(socket),
        };
        attached.map_err(|e| attach_failure(port, &e))?;
        guarded.insert(inode);
    }
    if !ports.contains(&discovery_port) {
        return Err(format!(
            "the participant's unicast discovery socket (UDP port {discovery_port}) was not found among its new sockets (guarded: ports {ports:?})"
        ));
    }
    let count = guarded.len();
    already.append(&mut guarded);
    Ok(count)
}

/// Why the socket on `port` could not be guarded, with the way out of a known cause.
fn attach_failure(port: u16, error: &io::Error) -> String {
    let hint = match error.raw_os_error() {
        // ENOMEM: the filter is charged to the socket's option memory.
        Some(12) => {
            "; the filter needs more socket option memory than net.core.optmem_max allows (raise it: sysctl -w net.core.optmem_max=131072)"
        }
        _ => "",
    };
    format!("the UDP socket on port {port}: {error}{hint}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_attach_out_of_option_memory_names_the_sysctl() {
        let text = attach_failure(8150, &io::Error::from_raw_os_error(12));
        assert!(text.starts_with("the UDP socket on port 8150: "), "{text}");
        assert!(text.contains("net.core.optmem_max"), "{text}");
        let other = attach_failure(7410, &io::Error::other("refused"));
        assert_eq!(other, "the UDP socket on port 7410: refused");
    }

    #[test]
    fn socket_inodes_are_read_from_the_link_target() {
        assert_eq!(socket_inode("socket:[123456]"), Some(123_456));
        assert_eq!(socket_inode("pipe:[123456]"), None);
        assert_eq!(socket_inode("/dev/null"), None);
        assert_eq!(socket_inode("socket:[x]"), None);
    }

    #[test]
    fn a_new_udp_socket_is_guarded_and_a_missing_discovery_socket_is_named() {
        let before = socket_inodes().unwrap();
        let socket = std::net::UdpSocket::bind("127.0.0.1:0").unwrap();
        let port = socket.local_addr().unwrap().port();
        // At least this one (another test's socket made meanwhile is guarded too).
        assert!(guard_new_sockets(&before, port).is_ok_and(|n| n >= 1));
        // Nothing new since: the expected discovery socket is missing, and said so.
        let now = socket_inodes().unwrap();
        let err = guard_new_sockets(&now, 7410).unwrap_err();
        assert!(err.contains("UDP port 7410"), "{err}");
    }
}
