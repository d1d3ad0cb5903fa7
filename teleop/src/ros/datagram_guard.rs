//! A kernel-side guard on the station's RTPS sockets against crafted DATA_FRAG submessages.
//!
//! RustDDS 0.15 reassembles a DATA_FRAG into a buffer of the sample size the sender declares
//! (up to 4 GiB, zero-filled at once, so resident at once), for any writer GUID, matched or
//! not, addressed to any of its readers (docs/SECURITY.md, "Crafted RTPS datagrams"): one
//! datagram can take gigabytes. The station cannot change RustDDS, and RustDDS offers no
//! setting for it, so the station attaches a classic BPF socket filter to the UDP sockets of
//! its own DDS participant (found through `/proc/self/fd`; `pidfd_getfd` on its own process
//! hands out a duplicate that shares the socket). The kernel runs the filter on every
//! datagram before RustDDS reads it:
//!
//! - it walks the RTPS submessages as RustDDS parses them (each header's `octetsToNextHeader`
//!   in the byte order its E flag says; 0 means "to the end of the message" except for PAD and
//!   INFO_TS, where it means an empty body);
//! - a datagram with a DATA_FRAG whose `sampleSize` is [`MAX_FRAGMENTED_SAMPLE_BYTES`] or
//!   more is dropped whole;
//! - a datagram with more than [`MAX_WALKED_SUBMESSAGES`] submessages (the filter cannot
//!   loop, so its walk is unrolled and bounded) is cut after that many whole submessages: what
//!   is cut is never seen, so no DATA_FRAG can hide behind padding; a reliable writer resends
//!   what was cut.
//!
//! The station's own samples and the discovery data it receives are a few KiB at most, far
//! below the limit.

use std::io;

use socket2::{SockFilter, SockRef};

/// A DATA_FRAG declaring a sample of this many bytes or more is dropped (a power of two).
pub const MAX_FRAGMENTED_SAMPLE_BYTES: u32 = 1 << 14;

/// The filter walks this many submessages of a datagram; the rest is cut off.
pub const MAX_WALKED_SUBMESSAGES: usize = 120;

// Classic BPF opcodes (linux/filter.h, linux/bpf_common.h).
const LD_LEN: u16 = 0x80; // A = datagram length
const LDX_IMM: u16 = 0x01; // X = k
const LD_IMM: u16 = 0x00; // A = k
const LD_W_IND: u16 = 0x40; // A = u32 (big-endian) at X + k
const LD_H_IND: u16 = 0x48; // A = u16 (big-endian) at X + k
const LD_B_IND: u16 = 0x50; // A = u8 at X + k
const LD_MEM: u16 = 0x60; // A = M[k]
const ST: u16 = 0x02; // M[k] = A
const ADD_K: u16 = 0x04;
const ADD_X: u16 = 0x0c;
const MUL_K: u16 = 0x24;
const RSH_K: u16 = 0x74;
const AND_K: u16 = 0x54;
const JA: u16 = 0x05;
const JEQ_K: u16 = 0x15;
const JGT_X: u16 = 0x2d;
const JSET_K: u16 = 0x45;
const TAX: u16 = 0x07;
const TXA: u16 = 0x87;
const RET_K: u16 = 0x06;
const RET_A: u16 = 0x16;

/// A UDP socket filter sees the datagram from its UDP header (8 bytes) on.
const UDP_HEADER: u32 = 8;
/// RTPS message header: "RTPS", version, vendor id, GUID prefix.
const RTPS_HEADER: u32 = 20;
const PAD: u32 = 0x01;
const INFO_TS: u32 = 0x09;
const DATA_FRAG: u32 = 0x16;
/// `sampleSize` in a DATA_FRAG, from its submessage header: header 4, extraFlags 2,
/// octetsToInlineQos 2, readerId 4, writerId 4, writerSN 8, fragmentStartingNum 4,
/// fragmentsInSubmessage 2, fragmentSize 2.
const SAMPLE_SIZE_OFFSET: u32 = 32;
const KEEP_ALL: u32 = u32::MAX;
const DROP: u32 = 0;

fn op(code: u16, jt: u8, jf: u8, k: u32) -> SockFilter {
    SockFilter::new(code, jt, jf, k)
}

/// One unrolled step of the walk: X is the offset of a submessage header.
fn walk_step(program: &mut Vec<SockFilter>) {
    // The bits of a `sampleSize` at or above the limit, as loaded in either byte order.
    let too_big_be = !(MAX_FRAGMENTED_SAMPLE_BYTES - 1);
    let too_big_le = too_big_be.swap_bytes();
    program.extend([
        op(LD_LEN, 0, 0, 0),
        op(JGT_X, 1, 0, 0),        // more bytes: go on
        op(RET_K, 0, 0, KEEP_ALL), // end of the message
        // M[0] = octetsToNextHeader, in the byte order of the E flag (flags bit 0).
        op(LD_B_IND, 0, 0, 1),
        op(JSET_K, 0, 5, 1),
        op(LD_H_IND, 0, 0, 2), // little-endian: swap the two bytes
        op(MUL_K, 0, 0, 0x0001_0001),
        op(RSH_K, 0, 0, 8),
        op(AND_K, 0, 0, 0xffff),
        op(JA, 0, 0, 1),
        op(LD_H_IND, 0, 0, 2), // big-endian
        op(ST, 0, 0, 0),
        // A DATA_FRAG declaring too large a sample drops the datagram.
        op(LD_B_IND, 0, 0, 0),
        op(JEQ_K, 0, 9, DATA_FRAG),
        op(LD_B_IND, 0, 0, 1),
        op(JSET_K, 0, 3, 1),
        op(LD_W_IND, 0, 0, SAMPLE_SIZE_OFFSET),
        op(AND_K, 0, 0, too_big_le),
        op(JA, 0, 0, 2),
        op(LD_W_IND, 0, 0, SAMPLE_SIZE_OFFSET),
        op(AND_K, 0, 0, too_big_be),
        op(JEQ_K, 1, 0, 0),
        op(RET_K, 0, 0, DROP),
        // Next header: X += 4 + length; a length of 0 ends the message unless PAD or INFO_TS.
        op(LD_MEM, 0, 0, 0),
        op(JEQ_K, 0, 5, 0),
        op(LD_B_IND, 0, 0, 0),
        op(JEQ_K, 2, 0, PAD),
        op(JEQ_K, 1, 0, INFO_TS),
        op(RET_K, 0, 0, KEEP_ALL),
        op(LD_IMM, 0, 0, 0),
        op(ADD_X, 0, 0, 0),
        op(ADD_K, 0, 0, 4),
        op(TAX, 0, 0, 0),
    ]);
}

/// The socket filter program (at most 4096 instructions, the kernel's limit).
pub fn filter_program() -> Vec<SockFilter> {
    let mut program = vec![op(LDX_IMM, 0, 0, UDP_HEADER + RTPS_HEADER)];
    for _ in 0..MAX_WALKED_SUBMESSAGES {
        walk_step(&mut program);
    }
    // Walked as far as the filter goes: keep the whole submessages walked, cut the rest.
    program.extend([op(TXA, 0, 0, 0), op(RET_A, 0, 0, 0)]);
    program
}

/// Attach the filter to `socket`.
pub fn attach(socket: SockRef<'_>) -> io::Result<()> {
    socket.attach_filter(&filter_program())
}

/// The unicast discovery port of participant `participant_id` on `domain` (RTPS 9.6.1.1
/// defaults, as RustDDS binds it: a participant that cannot bind it takes the next id).
pub fn unicast_discovery_port(domain: u16, participant_id: u16) -> u16 {
    let port = 7400 + 250 * u32::from(domain) + 10 + 2 * u32::from(participant_id);
    u16::try_from(port).unwrap_or(u16::MAX)
}

#[cfg(test)]
mod tests {
    use std::net::UdpSocket;
    use std::time::Duration;

    use super::*;

    fn header() -> Vec<u8> {
        let mut m = b"RTPS\x02\x03\x01\x0f".to_vec();
        m.extend([7u8; 12]);
        m
    }

    /// A submessage: id, flags (E = little-endian), body.
    fn sub(m: &mut Vec<u8>, id: u8, little_endian: bool, body: &[u8]) {
        let len = body.len() as u16;
        m.push(id);
        m.push(u8::from(little_endian));
        m.extend(if little_endian {
            len.to_le_bytes()
        } else {
            len.to_be_bytes()
        });
        m.extend(body);
    }

    fn data_frag(m: &mut Vec<u8>, little_endian: bool, sample_size: u32) {
        let u32b = |v: u32| {
            if little_endian {
                v.to_le_bytes()
            } else {
                v.to_be_bytes()
            }
        };
        let u16b = |v: u16| {
            if little_endian {
                v.to_le_bytes()
            } else {
                v.to_be_bytes()
            }
        };
        let mut body = vec![0, 0];
        body.extend(u16b(28));
        body.extend([0, 0, 0, 0x04, 0, 0, 1, 0x03]); // readerId, writerId
        body.extend(u32b(0)); // writerSN high
        body.extend(u32b(1)); // writerSN low
        body.extend(u32b(1)); // fragmentStartingNum
        body.extend(u16b(1)); // fragmentsInSubmessage
        body.extend(u16b(16)); // fragmentSize
        body.extend(u32b(sample_size));
        body.extend([0u8; 16]);
        sub(m, 0x16, little_endian, &body);
    }

    /// What a guarded socket receives of `datagram` (None: dropped).
    fn through_filter(datagram: &[u8]) -> Option<Vec<u8>> {
        let rx = UdpSocket::bind("127.0.0.1:0").unwrap();
        attach(SockRef::from(&rx)).unwrap();
        rx.set_read_timeout(Some(Duration::from_millis(300)))
            .unwrap();
        let tx = UdpSocket::bind("127.0.0.1:0").unwrap();
        tx.send_to(datagram, rx.local_addr().unwrap()).unwrap();
        // A marker after it shows a dropped datagram was not merely late.
        tx.send_to(b"marker", rx.local_addr().unwrap()).unwrap();
        let mut buf = vec![0u8; 70_000];
        let n = rx.recv(&mut buf).unwrap();
        if &buf[..n] == b"marker" {
            return None;
        }
        Some(buf[..n].to_vec())
    }

    #[test]
    fn the_program_fits_the_kernel_limit() {
        assert!(filter_program().len() <= 4096);
    }

    #[test]
    fn ordinary_messages_pass_whole() {
        let mut m = header();
        sub(&mut m, 0x09, true, &[1, 2, 3, 4, 5, 6, 7, 8]); // INFO_TS
        sub(&mut m, 0x15, true, &[0u8; 40]); // DATA
        data_frag(&mut m, true, MAX_FRAGMENTED_SAMPLE_BYTES - 1);
        data_frag(&mut m, false, 300);
        sub(&mut m, 0x07, false, &[0u8; 28]); // HEARTBEAT
        assert_eq!(through_filter(&m).as_deref(), Some(&m[..]));
        assert_eq!(
            through_filter(b"not rtps").as_deref(),
            Some(&b"not rtps"[..])
        );
    }

    #[test]
    fn a_data_frag_declaring_a_large_sample_is_dropped_in_either_byte_order() {
        for little_endian in [true, false] {
            for size in [MAX_FRAGMENTED_SAMPLE_BYTES, 1 << 20, u32::MAX] {
                let mut m = header();
                sub(&mut m, 0x09, true, &[0u8; 8]);
                sub(&mut m, 0x01, !little_endian, &[]); // an empty PAD
                data_frag(&mut m, little_endian, size);
                assert_eq!(through_filter(&m), None, "{size} {little_endian}");
            }
        }
    }

    #[test]
    fn past_the_walked_submessages_the_datagram_is_cut() {
        let mut m = header();
        for _ in 0..MAX_WALKED_SUBMESSAGES {
            sub(&mut m, 0x01, true, &[0u8; 4]); // PAD
        }
        let walked = m.len();
        data_frag(&mut m, true, u32::MAX);
        assert_eq!(through_filter(&m).as_deref(), Some(&m[..walked]));
    }
}
