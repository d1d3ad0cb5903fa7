//! Running docs/DEPLOYMENT.md's `# on host` blocks on a [`NetnsLab`]'s hosts, as the guide
//! says: `export` lines set the host's environment, lines ending in `&` start long-running
//! nodes, the rest run to completion; each host has its own home directory.

#![allow(clippy::unwrap_used, clippy::expect_used)] // test support: a panic is the failure report

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicU8, Ordering};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use station::StationConfig;

use crate::deployment_guide::{GuideStep, HostBlock, read_host_blocks};
use crate::netns_lab::{NetnsLab, namespaces_available};
use crate::pomdar_binary::pomdar_binary;
use crate::workspace_root;

/// Wall-clock nanoseconds since the epoch.
pub fn wall_ns() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap()
        .as_nanos() as i64
}

/// A node started from a guide line; SIGKILLed if still running when dropped (the lab's drop
/// also kills whatever runs in its namespaces).
pub struct Node {
    /// The host it runs on.
    pub host: String,
    /// The guide's line.
    pub line: String,
    child: Child,
    log: PathBuf,
}

impl Node {
    /// Ctrl-C, as the guide stops nodes; wait for the node to finish.
    pub fn interrupt(&mut self) -> std::process::ExitStatus {
        // The shell's builtin `kill`: no procps needed.
        Command::new("sh")
            .args(["-c", &format!("kill -INT {}", self.child.id())])
            .status()
            .unwrap();
        let started = Instant::now();
        loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                return status;
            }
            assert!(
                started.elapsed() < Duration::from_secs(30),
                "host {}: `{}` did not stop on SIGINT within 30 s; its output: {}",
                self.host,
                self.line,
                self.log.display()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// What it printed so far.
    pub fn output(&self) -> String {
        std::fs::read_to_string(&self.log).unwrap_or_default()
    }
}

impl Drop for Node {
    fn drop(&mut self) {
        if self.child.try_wait().ok().flatten().is_none() {
            self.child.kill().ok();
            self.child.wait().ok();
        }
    }
}

/// Runs the guide's blocks on the lab's hosts.
pub struct Session<'a> {
    /// The hosts.
    pub lab: &'a NetnsLab,
    /// The session's directory: homes, node logs, `bin/pomdar`.
    pub dir: PathBuf,
    /// The directory put first on the hosts' PATH.
    pub bin: PathBuf,
    /// Variables each host's blocks exported.
    pub env: BTreeMap<String, BTreeMap<String, String>>,
    /// The long-running nodes started.
    pub nodes: Vec<Node>,
}

/// The guide's three hosts and their addresses on the lab network.
pub const GUIDE_HOSTS: [(&str, std::net::Ipv4Addr); 3] = [
    ("A", std::net::Ipv4Addr::new(10, 251, 0, 1)),
    ("B", std::net::Ipv4Addr::new(10, 251, 0, 2)),
    ("C", std::net::Ipv4Addr::new(10, 251, 0, 3)),
];

impl<'a> Session<'a> {
    /// A session on `lab` in `dir`, with `bin` first on the hosts' PATH; nothing run yet.
    pub fn new(lab: &'a NetnsLab, dir: PathBuf, bin: PathBuf) -> Session<'a> {
        Session {
            lab,
            dir,
            bin,
            env: BTreeMap::new(),
            nodes: Vec::new(),
        }
    }
}

impl Session<'_> {
    /// A host's home directory.
    pub fn home(&self, host: &str) -> PathBuf {
        self.dir.join(format!("home-{}", host.to_lowercase()))
    }

    /// `line` through `sh` in `host`'s namespace, from the checkout's top directory, with the
    /// host's home, its exported variables and `pomdar` on the PATH.
    pub fn shell(&self, host: &str, line: &str) -> Command {
        let mut command = self.lab.command(host, "sh").unwrap();
        command
            .arg("-c")
            .arg(format!("exec {line}"))
            .current_dir(workspace_root())
            .env_remove("ROS_DOMAIN_ID")
            .env("HOME", self.home(host))
            .env(
                "PATH",
                format!(
                    "{}:{}",
                    self.bin.display(),
                    std::env::var("PATH").unwrap_or_default()
                ),
            )
            .envs(self.env.get(host).into_iter().flatten())
            .stdin(Stdio::null());
        command
    }

    /// Run one block; returns the output of the commands that ran to completion.
    pub fn run(&mut self, block: &HostBlock) -> Vec<String> {
        std::fs::create_dir_all(self.home(&block.host)).unwrap();
        let mut outputs = Vec::new();
        for step in &block.steps {
            match step {
                GuideStep::Export { name, value } => {
                    self.env
                        .entry(block.host.clone())
                        .or_default()
                        .insert(name.clone(), value.clone());
                }
                GuideStep::Background(line) => {
                    let log =
                        self.dir
                            .join(format!("host-{}-{}.log", block.host, self.nodes.len()));
                    let file = std::fs::File::create(&log).unwrap();
                    let child = self
                        .shell(&block.host, line)
                        .stdout(file.try_clone().unwrap())
                        .stderr(file)
                        .spawn()
                        .unwrap();
                    println!("host {}: started `{line}`", block.host);
                    self.nodes.push(Node {
                        host: block.host.clone(),
                        line: line.clone(),
                        child,
                        log,
                    });
                }
                GuideStep::Run(line) => {
                    let output = self.shell(&block.host, line).output().unwrap();
                    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
                    println!(
                        "host {}: `{line}` → {}\n{stdout}{}",
                        block.host,
                        output.status,
                        String::from_utf8_lossy(&output.stderr)
                    );
                    assert!(
                        output.status.success(),
                        "host {}: `{line}` failed ({}); nodes' output in {}",
                        block.host,
                        output.status,
                        self.dir.display()
                    );
                    outputs.push(stdout);
                }
            }
        }
        outputs
    }

    /// What the node started as `program` on `host` printed.
    pub fn output_of(&self, host: &str, program: &str) -> String {
        self.nodes
            .iter()
            .find(|n| n.host == host && n.line.starts_with(program))
            .map(Node::output)
            .unwrap_or_default()
    }

    /// The node started as `program` on `host`.
    pub fn node(&mut self, host: &str, program: &str) -> &mut Node {
        self.nodes
            .iter_mut()
            .find(|n| n.host == host && n.line.starts_with(program))
            .unwrap_or_else(|| panic!("the guide starts no `{program}` on host {host}"))
    }
}

/// A tag for one lab's namespaces, unique on the machine (the process id and a letter per lab
/// of this process, as tests of one binary run side by side), or None (after saying SKIPPED)
/// where network namespaces cannot be created; under CI (`CI` set) that is a failure instead.
pub fn lab_tag_or_skip() -> Option<String> {
    static LABS: AtomicU8 = AtomicU8::new(0);
    let lab = LABS.fetch_add(1, Ordering::Relaxed) % 26;
    let tag = format!("{}{}", std::process::id() % 100_000, char::from(b'a' + lab));
    if let Err(why) = namespaces_available(&tag) {
        assert!(
            !crate::interop::under_ci(),
            "CI must be able to create network namespaces (root and iproute2; .ci/run installs iproute2): {why}"
        );
        eprintln!("SKIPPED: cannot create network namespaces here ({why})");
        return None;
    }
    Some(tag)
}

/// A fresh session directory for `name` and `tag`, with `bin/pomdar` linked to the built
/// binary; returns it and its `bin`.
pub fn session_dir(name: &str, tag: &str) -> (PathBuf, PathBuf) {
    let binary = pomdar_binary().unwrap();
    let dir = std::env::temp_dir().join(format!("pomdar-{name}-{tag}"));
    std::fs::remove_dir_all(&dir).ok();
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::os::unix::fs::symlink(&binary, bin.join("pomdar")).unwrap();
    (dir, bin)
}

/// The guide's host blocks, checked to be robot, station, glove, then the check; and the
/// station configuration its station command names.
pub fn guide_blocks_and_station_config(root: &std::path::Path) -> (Vec<HostBlock>, StationConfig) {
    let blocks = read_host_blocks(&root.join("docs/DEPLOYMENT.md")).unwrap();
    let station_line = blocks
        .iter()
        .flat_map(|b| &b.steps)
        .find_map(|s| match s {
            GuideStep::Background(line) if line.starts_with("pomdar station") => Some(line),
            _ => None,
        })
        .expect("the guide starts no station");
    let config_path = station_line
        .split_whitespace()
        .skip_while(|w| *w != "--config")
        .nth(1)
        .expect("the guide's station command has no --config");
    let config =
        teleop::station_driver::setup::read_station_config(&root.join(config_path)).unwrap();
    let hosts: Vec<&str> = blocks.iter().map(|b| b.host.as_str()).collect();
    assert_eq!(
        hosts,
        ["C", "B", "A", "C"],
        "the guide's host blocks: robot, station, glove, then the check"
    );
    (blocks, config)
}
