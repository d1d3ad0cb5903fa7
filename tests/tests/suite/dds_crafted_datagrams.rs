//! Crafted RTPS datagrams at the DDS ports of every `pomdar` command that opens a participant
//! on the lab network must not exhaust its memory (docs/SECURITY.md, "Crafted RTPS
//! datagrams"): `pomdar station`, a simulated operator console (`pomdar trial --simulate`), a
//! simulated human study (`pomdar study --simulate`) and `pomdar relay`.
//!
//! RustDDS 0.15 allocates and zero-fills a reassembly buffer of the sample size a DATA_FRAG
//! declares (up to 4 GiB), from any sender, for any of its readers. The commands guard their
//! RTPS sockets with a socket filter (teleop/src/ros/datagram_guard.rs). Each test runs its
//! command as the operator does (its own process, loopback only, a domain of its own), learns
//! its readers' entity ids and ports from discovery (every participant of the process), then
//! sends DATA_FRAG submessages written here from the RTPS specification (RTPS 2.5, 9.4:
//! message header, INFO_TS, DATA_FRAG): huge declared sample sizes, from a GUID prefix never
//! announced, many writer ids and sequence numbers, to the SPDP, SEDP and user readers and to
//! ENTITYID_UNKNOWN, at every port (unicast and multicast, discovery and user). After each case
//! it reads the process's memory from /proc and prints it. Its resident memory must stay
//! within [`RSS_BOUND_KIB`] of its idle figure, it must say its sockets are guarded and still
//! publish its status, and Ctrl-C must still end it as it ends an idle run.

use std::net::{Ipv4Addr, SocketAddr, UdpSocket};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::StringMsg;
use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::{loopback, test_domain};
use ros2_client::dds::rustdds::{GUID, RTPSEntity as _};
use teleop::ros::datagram_guard::MAX_FRAGMENTED_SAMPLE_BYTES;
use teleop::ros::{NetworkContext as _, QosConfig, RosNode};

/// How far the station's resident memory may grow over its idle figure, in KiB.
const RSS_BOUND_KIB: u64 = 64 * 1024;
/// The station's address space limit (`ulimit -v`), in KiB: idle it maps about 0.3 GiB.
const ADDRESS_SPACE_CAP_KIB: u64 = 2 * 1024 * 1024;
/// Multicast group of RTPS discovery and user traffic.
const MULTICAST: Ipv4Addr = Ipv4Addr::new(239, 255, 0, 1);

/// The process under test, killed and reaped when dropped: a failing test leaves none running.
struct Station(Child);

/// A command under test: its arguments (loopback and the domain are added), the topics of
/// readers it must have before the test begins (some reader's topic contains each), where it
/// publishes its status, and its exit code on Ctrl-C while idle.
struct Subject {
    name: &'static str,
    args: Vec<String>,
    ready_topics: Vec<String>,
    status_topic: String,
    ctrl_c_code: i32,
}

impl Subject {
    fn station() -> Subject {
        let config = pomdar_tests::workspace_root().join("launch_configs/station/eth_lab.toml");
        Subject {
            name: "station",
            args: vec!["station".into(), "--config".into(), path(&config)],
            ready_topics: vec!["/ingress/mano".into(), "/ingress/wrist".into()],
            status_topic: station::StationConfig::default().output.status_topic,
            ctrl_c_code: 0,
        }
    }

    /// A console session's arguments, its logs under `dir`.
    fn console(name: &'static str, head: &[&str], dir: &Path) -> Subject {
        let tail = ["--plain", "--simulate", "--practice", "0", "--out"];
        let mut args: Vec<String> = head.iter().chain(&tail).map(|s| s.to_string()).collect();
        args.push(path(&dir.join("sessions")));
        let config = station::StationConfig::default();
        Subject {
            name,
            args,
            ready_topics: vec![config.input.keypoints_topic],
            status_topic: config.output.status_topic,
            // An interrupted session.
            ctrl_c_code: 130,
        }
    }

    fn relay() -> Subject {
        let config =
            pomdar_tests::workspace_root().join("launch_configs/station/deploy_station.toml");
        let link = teleop::station_driver::setup::read_station_config(&config)
            .unwrap()
            .robot_link;
        Subject {
            name: "relay",
            args: vec!["relay".into(), "--config".into(), path(&config)],
            ready_topics: vec![link.relay_prefix.clone()],
            status_topic: link.relay_status_topic(),
            ctrl_c_code: 0,
        }
    }
}

fn path(p: &Path) -> String {
    p.display().to_string()
}

impl Drop for Station {
    fn drop(&mut self) {
        self.0.kill().ok();
        self.0.wait().ok();
    }
}

/// `subject` on loopback `domain`, its stderr in `dir`, its stdin open (a console waits on it),
/// its address space capped at [`ADDRESS_SPACE_CAP_KIB`]: should the guard fail, a 4 GiB
/// allocation fails and the process ends (and the test with it) instead of the machine
/// running out of memory.
fn start(subject: &Subject, dir: &Path, domain: u16) -> Station {
    let stderr = std::fs::File::create(dir.join("stderr")).unwrap();
    let cap = format!("ulimit -v {ADDRESS_SPACE_CAP_KIB} && exec \"$0\" \"$@\"");
    Station(
        Command::new("sh")
            .args(["-c", &cap])
            .arg(pomdar_binary().unwrap())
            .args(&subject.args)
            .args(["--interface", "127.0.0.1", "--domain-id"])
            .arg(domain.to_string())
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(stderr)
            .spawn()
            .unwrap(),
    )
}

/// The station's memory, in KiB, from /proc/PID/status.
#[derive(Debug, Clone, Copy)]
struct Memory {
    rss: u64,
    size: u64,
    peak: u64,
}

fn memory(pid: u32) -> Option<Memory> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let field = |name: &str| {
        status
            .lines()
            .find_map(|l| l.strip_prefix(name))
            .and_then(|rest| rest.split_whitespace().next())
            .and_then(|kib| kib.parse::<u64>().ok())
    };
    Some(Memory {
        rss: field("VmRSS:")?,
        size: field("VmSize:")?,
        peak: field("VmPeak:")?,
    })
}

/// The station's memory once its resident size stops changing (it reads queued datagrams,
/// zero-fills buffers): the same twice 500 ms apart, or after 15 s.
fn settled_memory(pid: u32) -> Option<Memory> {
    let started = Instant::now();
    let mut last = memory(pid)?;
    loop {
        std::thread::sleep(Duration::from_millis(500));
        let now = memory(pid)?;
        if now.rss == last.rss || started.elapsed() > Duration::from_secs(15) {
            return Some(now);
        }
        last = now;
    }
}

/// What discovery tells about the process under test: its participants' GUID prefixes, their
/// readers' entity ids (topic, id) and their unicast ports (discovery, user).
struct Target {
    prefixes: Vec<[u8; 12]>,
    user_readers: Vec<(String, [u8; 4])>,
    unicast_ports: Vec<u16>,
    domain: u16,
}

type Reader = ros2_client::dds::rustdds::discovery::DiscoveredReaderData;

/// Learn the process's readers from SEDP with a participant of this process (returned: the
/// process's SEDP readers have matched its SEDP writers while it lives), once a reader of each
/// of `subject.ready_topics` and every participant's readers are there (the same for 1 s).
fn learn(subject: &Subject, domain: u16) -> (Target, ros2_client::Context) {
    let context = loopback(domain).context().unwrap();
    let participant = context.domain_participant();
    let own_prefix = participant.guid().to_bytes()[..12].to_vec();
    let started = Instant::now();
    let mut seen = (0, Instant::now());
    loop {
        let readers: Vec<Reader> = participant
            .discovered_readers()
            .into_iter()
            .filter(|r| r.reader_proxy.remote_reader_guid.to_bytes()[..12] != own_prefix[..])
            .collect();
        let ready = subject.ready_topics.iter().all(|topic| {
            (readers.iter()).any(|r| {
                r.subscription_topic_data
                    .topic_name
                    .contains(topic.as_str())
            })
        });
        if readers.len() != seen.0 {
            seen = (readers.len(), Instant::now());
        }
        if ready && seen.1.elapsed() > Duration::from_secs(1) {
            return (target_of(&readers, domain), context);
        }
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "{}: readers of {:?} were not discovered",
            subject.name,
            subject.ready_topics
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn target_of(readers: &[Reader], domain: u16) -> Target {
    let guid = |r: &Reader| -> GUID { r.reader_proxy.remote_reader_guid };
    let prefix_of = |r: &Reader| -> [u8; 12] { guid(r).to_bytes()[..12].try_into().unwrap() };
    let mut prefixes: Vec<[u8; 12]> = readers.iter().map(prefix_of).collect();
    prefixes.sort_unstable();
    prefixes.dedup();
    let mut unicast_ports = Vec::new();
    for prefix in &prefixes {
        let user_port = readers
            .iter()
            .filter(|r| prefix_of(r) == *prefix)
            .flat_map(|r| r.reader_proxy.unicast_locator_list.iter())
            .filter(|l| l.is_udp())
            .map(|l| SocketAddr::from(*l).port())
            .find(|port| *port != 0);
        // Without a locator in SEDP, the participant's default: the first participant's port.
        let user_port = user_port.unwrap_or(7411 + 250 * domain);
        unicast_ports.extend([user_port - 1, user_port]);
    }
    unicast_ports.sort_unstable();
    unicast_ports.dedup();
    let user_readers = readers
        .iter()
        .map(|r| {
            let id: [u8; 4] = guid(r).to_bytes()[12..].try_into().unwrap();
            (r.subscription_topic_data.topic_name.clone(), id)
        })
        .collect();
    Target {
        prefixes,
        user_readers,
        unicast_ports,
        domain,
    }
}

/// Every UDP destination of the process: each participant's unicast discovery and user ports,
/// multicast discovery and user.
fn destinations(target: &Target) -> Vec<SocketAddr> {
    let base = 7400 + 250 * target.domain;
    let unicast = (target.unicast_ports.iter()).map(|port| (Ipv4Addr::LOCALHOST, *port));
    let multicast = [(MULTICAST, base), (MULTICAST, base + 1)];
    unicast.chain(multicast).map(SocketAddr::from).collect()
}

/// One DATA_FRAG, as the spec lays it out (little-endian: E flag set).
struct Frag {
    reader: [u8; 4],
    writer: [u8; 4],
    sn: u32,
    fragment_start: u32,
    fragment_size: u16,
    sample_size: u32,
}

/// An RTPS message: header (protocol "RTPS", version 2.5, vendor id, `prefix`), INFO_TS, and
/// the DATA_FRAG carrying one fragment of zeros.
fn datagram(prefix: &[u8; 12], frag: &Frag) -> Vec<u8> {
    let mut m = b"RTPS".to_vec();
    m.extend([2, 5]); // protocol version
    m.extend([0x01, 0x7f]); // vendor id: none assigned
    m.extend(prefix);
    // INFO_TS (0x09), E flag, 8 octets: seconds, fraction.
    m.extend([0x09, 0x01, 8, 0]);
    m.extend(1_700_000_000u32.to_le_bytes());
    m.extend(0u32.to_le_bytes());
    let payload = vec![0u8; usize::from(frag.fragment_size)];
    // DATA_FRAG (0x16), E flag; octetsToNextHeader = 32 fixed octets + payload.
    m.extend([0x16, 0x01]);
    m.extend(u16::try_from(32 + payload.len()).unwrap().to_le_bytes());
    m.extend(0u16.to_le_bytes()); // extraFlags
    m.extend(28u16.to_le_bytes()); // octetsToInlineQos: from here to the payload
    m.extend(frag.reader);
    m.extend(frag.writer);
    m.extend(0i32.to_le_bytes()); // writerSN high
    m.extend(frag.sn.to_le_bytes()); // writerSN low
    m.extend(frag.fragment_start.to_le_bytes());
    m.extend(1u16.to_le_bytes()); // fragmentsInSubmessage
    m.extend(frag.fragment_size.to_le_bytes());
    m.extend(frag.sample_size.to_le_bytes());
    m.extend(payload);
    m
}

/// One attack: which readers (and the writer ids sent as), which declared sample size.
struct Case {
    name: &'static str,
    readers: Vec<[u8; 4]>,
    /// Writer entity ids to send as; `None`: a different user writer id per datagram.
    writers: Option<Vec<[u8; 4]>>,
    sample_size: u32,
    datagrams: u32,
}

const SPDP_READER: [u8; 4] = [0x00, 0x01, 0x00, 0xc7];
const SPDP_WRITER: [u8; 4] = [0x00, 0x01, 0x00, 0xc2];
const SEDP_READERS: [[u8; 4]; 4] = [
    [0x00, 0x00, 0x02, 0xc7], // topics
    [0x00, 0x00, 0x03, 0xc7], // publications
    [0x00, 0x00, 0x04, 0xc7], // subscriptions
    [0x00, 0x02, 0x00, 0xc7], // participant messages
];
const SEDP_WRITERS: [[u8; 4]; 4] = [
    [0x00, 0x00, 0x02, 0xc2],
    [0x00, 0x00, 0x03, 0xc2],
    [0x00, 0x00, 0x04, 0xc2],
    [0x00, 0x02, 0x00, 0xc2],
];
const UNKNOWN_READER: [u8; 4] = [0, 0, 0, 0];

/// The cases, 10^4 datagrams in all: every reader kind, sample sizes from the guard's limit up
/// to 4 GiB, and one just under the limit (what the guard lets through).
fn cases(target: &Target) -> Vec<Case> {
    let user: Vec<[u8; 4]> = target.user_readers.iter().map(|(_, id)| *id).collect();
    let mut user_and_sedp = user.clone();
    user_and_sedp.extend(SEDP_READERS);
    let case = |name, readers, writers, sample_size, datagrams| Case {
        name,
        readers,
        writers,
        sample_size,
        datagrams,
    };
    vec![
        case(
            "ENTITYID_UNKNOWN, built-in writer ids, 4 GiB",
            vec![UNKNOWN_READER],
            Some([SPDP_WRITER].into_iter().chain(SEDP_WRITERS).collect()),
            u32::MAX,
            1000,
        ),
        case(
            "SPDP reader, 4 GiB",
            vec![SPDP_READER],
            Some(vec![SPDP_WRITER]),
            u32::MAX,
            1000,
        ),
        case(
            "SEDP readers, 4 GiB",
            SEDP_READERS.to_vec(),
            Some(SEDP_WRITERS.to_vec()),
            u32::MAX,
            2000,
        ),
        case(
            "user readers, many writers, 4 GiB",
            user.clone(),
            None,
            u32::MAX,
            3000,
        ),
        case(
            "user and SEDP readers, 256 MiB",
            user_and_sedp.clone(),
            None,
            256 << 20,
            1000,
        ),
        case(
            "user and SEDP readers, the limit (16 KiB)",
            user_and_sedp.clone(),
            None,
            MAX_FRAGMENTED_SAMPLE_BYTES,
            1000,
        ),
        case(
            "user and SEDP readers, under the limit (16 KiB - 1)",
            user_and_sedp,
            None,
            MAX_FRAGMENTED_SAMPLE_BYTES - 1,
            1000,
        ),
    ]
}

/// Send `case`'s datagrams round-robin over `destinations` from an unannounced GUID prefix.
fn send(case: &Case, prefix: &[u8; 12], destinations: &[SocketAddr]) {
    // Bound to loopback, multicast goes out on the loopback interface.
    let socket = UdpSocket::bind((Ipv4Addr::LOCALHOST, 0)).unwrap();
    socket.set_multicast_loop_v4(true).unwrap();
    let fragment_size = 64u16;
    let fragments = u64::from(case.sample_size).div_ceil(u64::from(fragment_size));
    for i in 0..case.datagrams {
        let n = i as usize;
        let writer = match &case.writers {
            Some(writers) => writers[n % writers.len()],
            // A user writer with key (kind 0x02), a new entity key each time.
            None => {
                let key = (i + 1).to_be_bytes();
                [key[1], key[2], key[3], 0x02]
            }
        };
        let frag = Frag {
            reader: case.readers[n % case.readers.len()],
            writer,
            sn: 1 + i / 7,
            fragment_start: u32::try_from(1 + (u64::from(i) * 7919) % fragments).unwrap(),
            fragment_size,
            sample_size: case.sample_size,
        };
        let bytes = datagram(prefix, &frag);
        // A full socket buffer at the station drops datagrams: that is its business.
        socket
            .send_to(&bytes, destinations[n % destinations.len()])
            .ok();
        if i % 100 == 99 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// A GUID prefix no participant announced: this process's id and the clock's nanoseconds.
fn unannounced_prefix() -> [u8; 12] {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos();
    let mut prefix = [0u8; 12];
    prefix[..4].copy_from_slice(&std::process::id().to_be_bytes());
    prefix[4..].copy_from_slice(&(nanos as u64).to_be_bytes());
    prefix[0] = 0xfe;
    prefix
}

/// The process's status document on `topic`, heard by a fresh node within 20 s.
fn status_on(topic: &str, domain: u16) -> Option<serde_json::Value> {
    let runtime = tokio::runtime::Runtime::new().unwrap();
    runtime.block_on(async {
        let mut node = RosNode::join(&loopback(domain), "/", "crafted_datagrams_check").unwrap();
        // Best effort reads a reliable writer's status as well as a best-effort one's.
        let status = node
            .subscription::<StringMsg>(topic, QosConfig::best_effort(10))
            .unwrap();
        let mut stream = Box::pin(status.async_stream());
        let heard = tokio::time::timeout(Duration::from_secs(20), async {
            while let Some(item) = stream.next().await {
                if let Ok((message, _)) = item {
                    return serde_json::from_str::<serde_json::Value>(&message.data).ok();
                }
            }
            None
        })
        .await;
        heard.ok().flatten()
    })
}

/// SIGINT, and the process's exit code (None: it did not exit within 15 s).
fn interrupt(station: &mut Station) -> Option<i32> {
    let pid = station.0.id().to_string();
    Command::new("kill").args(["-INT", &pid]).status().unwrap();
    let started = Instant::now();
    while started.elapsed() < Duration::from_secs(15) {
        if let Some(status) = station.0.try_wait().unwrap() {
            return status.code();
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    None
}

/// The station's memory after one case.
struct Row {
    name: &'static str,
    datagrams: u32,
    memory: Option<Memory>,
    running: bool,
}

fn print_row(row: &Row, idle: Memory) {
    match row.memory {
        Some(m) => println!(
            "{:<52} {:>5} datagrams: VmRSS {:>7} KiB ({:+} KiB), VmSize {:>8} KiB, VmPeak {:>8} KiB, {}",
            row.name,
            row.datagrams,
            m.rss,
            m.rss as i64 - idle.rss as i64,
            m.size,
            m.peak,
            if row.running { "running" } else { "exited" }
        ),
        None => println!(
            "{:<52} {:>5} datagrams: the station is gone",
            row.name, row.datagrams
        ),
    }
}

#[test]
fn crafted_data_frags_do_not_exhaust_the_station_memory() {
    crafted_data_frags_against(&Subject::station());
}

#[test]
fn crafted_data_frags_do_not_exhaust_a_simulated_trial_console() {
    let dir = scratch_dir("crafted-datagrams-trial");
    let head = ["trial", "--task", "V1", "--user", "u", "--operator", "ci"];
    crafted_data_frags_against(&Subject::console("trial --simulate", &head, &dir));
}

#[test]
fn crafted_data_frags_do_not_exhaust_a_simulated_study_console() {
    let dir = scratch_dir("crafted-datagrams-study");
    let head = [
        "study",
        "--participant",
        "p",
        "--operator",
        "ci",
        "--tasks",
        "V1",
    ];
    crafted_data_frags_against(&Subject::console("study --simulate", &head, &dir));
}

#[test]
fn crafted_data_frags_do_not_exhaust_the_relay() {
    crafted_data_frags_against(&Subject::relay());
}

fn crafted_data_frags_against(subject: &Subject) {
    let _alone = pomdar_tests::load_turns::flooding();
    let dir = scratch_dir(&format!(
        "crafted-datagrams-{}",
        subject.name.replace(' ', "_")
    ));
    let domain = test_domain();
    // This process's own participants (discovery here, the status check after) are guarded
    // too: the multicast datagrams reach them as well.
    teleop::ros::participant_guard::require();
    let mut station = start(subject, &dir, domain);
    let pid = station.0.id();
    let (target, learner) = learn(subject, domain);
    let name = subject.name;
    for (topic, id) in &target.user_readers {
        println!("{name} reader {topic}: entity id {id:02x?}");
    }
    println!("{name} GUID prefixes {:02x?}", target.prefixes);
    // It says its sockets are guarded: at least each participant's unicast discovery and user
    // ones.
    let status = status_on(&subject.status_topic, domain);
    let guard = status.expect("its status")["datagram_guard"].clone();
    println!("{name} datagram guard: {guard}");
    assert_eq!(guard["mode"], "required", "{guard}");
    let least = 2 * target.prefixes.len() as u64;
    assert!(
        guard["sockets"].as_u64().is_some_and(|n| n >= least),
        "{guard}: fewer than {least}"
    );
    let destinations = destinations(&target);
    println!("destinations: {destinations:?}");
    std::thread::sleep(Duration::from_secs(1));
    let idle = memory(pid).expect("the station runs");
    println!(
        "idle: VmRSS {} KiB, VmSize {} KiB, VmPeak {} KiB",
        idle.rss, idle.size, idle.peak
    );
    let prefix = unannounced_prefix();
    let mut run = |case: &Case, destinations: &[SocketAddr]| {
        send(case, &prefix, destinations);
        let row = Row {
            name: case.name,
            datagrams: case.datagrams,
            memory: settled_memory(pid),
            running: station.0.try_wait().unwrap().is_none(),
        };
        print_row(&row, idle);
        row
    };
    let mut cases = cases(&target).into_iter();
    // ENTITYID_UNKNOWN goes to the readers that matched a writer of that entity id: the
    // station's SEDP readers matched the learner's SEDP writers, so it stays for this case,
    // sent by unicast only (no crafted datagram reaches this process).
    let unicast = &destinations[..target.unicast_ports.len()];
    let mut rows = vec![run(&cases.next().unwrap(), unicast)];
    drop(learner);
    std::thread::sleep(Duration::from_secs(1));
    rows.extend(cases.map(|case| run(&case, &destinations)));
    let stderr = || std::fs::read_to_string(dir.join("stderr")).unwrap_or_default();
    for row in &rows {
        let grown = row
            .memory
            .map_or(u64::MAX, |m| m.rss.saturating_sub(idle.rss));
        assert!(
            row.running && grown < RSS_BOUND_KIB,
            "after \"{}\" the {name} grew by {grown} KiB (bound {RSS_BOUND_KIB}) or is gone; its stderr:\n{}",
            row.name,
            stderr()
        );
    }
    assert!(
        status_on(&subject.status_topic, domain).is_some(),
        "the {name} no longer publishes its status; its stderr:\n{}",
        stderr()
    );
    assert_eq!(
        interrupt(&mut station),
        Some(subject.ctrl_c_code),
        "Ctrl-C ends the {name} as it ends an idle run; its stderr:\n{}",
        stderr()
    );
    println!("--- {name} stderr\n{}", stderr());
}
