//! A lab of hosts on one machine: each host a Linux network namespace with one Ethernet
//! interface (`eth0`, a veth pair) cabled to a switch (a bridge in a namespace of its own),
//! all on one private subnet. Nothing is created in the machine's own namespace: the veth
//! pairs are created directly inside the namespaces, and the addresses exist only there.
//!
//! Dropping the lab ends every process still running inside its namespaces (SIGKILL) and
//! deletes the namespaces, which removes their interfaces: a failing or panicking test
//! leaves nothing behind. Needs root (or CAP_NET_ADMIN + CAP_SYS_ADMIN) and iproute2's `ip`.

use std::net::Ipv4Addr;
use std::process::{Command, Stdio};

/// One host of the lab.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LabHost {
    /// The host's name in the lab (`A`).
    pub name: String,
    /// Its network namespace.
    pub namespace: String,
    /// Its address on the lab subnet.
    pub address: Ipv4Addr,
    /// The switch's end of its cable (an interface in the switch namespace).
    switch_port: String,
}

/// Hosts on a switch, in network namespaces; removed on drop.
#[derive(Debug)]
pub struct NetnsLab {
    switch: String,
    hosts: Vec<LabHost>,
    created: Vec<String>,
}

/// Run `ip ARGS`; the error says which command failed and why.
pub fn ip(args: &[&str]) -> Result<(), String> {
    let output = Command::new("ip")
        .args(args)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("cannot run `ip` (iproute2): {e}"))?;
    if output.status.success() {
        Ok(())
    } else {
        Err(format!(
            "`ip {}` failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&output.stderr).trim()
        ))
    }
}

impl NetnsLab {
    /// Create hosts `(name, address)` on a /24 behind one switch. `tag` makes the namespace
    /// and interface names unique on the machine (use the process id); at most 8 characters.
    pub fn create(tag: &str, hosts: &[(&str, Ipv4Addr)]) -> Result<NetnsLab, String> {
        let switch = format!("pomdar-{tag}-switch");
        let mut lab = NetnsLab {
            switch: switch.clone(),
            hosts: Vec::new(),
            created: Vec::new(),
        };
        lab.add_namespace(&switch)?;
        ip(&["-n", &switch, "link", "add", "br0", "type", "bridge"])?;
        // Without a multicast querier a snooping bridge may stop forwarding SPDP after the
        // membership timeout; a plain switch floods multicast, as this one does.
        ip(&[
            "-n",
            &switch,
            "link",
            "set",
            "br0",
            "type",
            "bridge",
            "mcast_snooping",
            "0",
        ])?;
        ip(&["-n", &switch, "link", "set", "br0", "up"])?;
        for (index, (name, address)) in hosts.iter().enumerate() {
            let namespace = format!("pomdar-{tag}-{}", name.to_lowercase());
            // Interface names are at most 15 bytes.
            let switch_port = format!("p{tag}{index}");
            lab.add_namespace(&namespace)?;
            ip(&["-n", &namespace, "link", "set", "lo", "up"])?;
            ip(&[
                "-n",
                &namespace,
                "link",
                "add",
                "eth0",
                "type",
                "veth",
                "peer",
                "name",
                &switch_port,
                "netns",
                &switch,
            ])?;
            ip(&[
                "-n",
                &namespace,
                "address",
                "add",
                &format!("{address}/24"),
                "dev",
                "eth0",
            ])?;
            ip(&["-n", &namespace, "link", "set", "eth0", "up"])?;
            ip(&["-n", &switch, "link", "set", &switch_port, "master", "br0"])?;
            ip(&["-n", &switch, "link", "set", &switch_port, "up"])?;
            lab.hosts.push(LabHost {
                name: name.to_string(),
                namespace,
                address: *address,
                switch_port,
            });
        }
        Ok(lab)
    }

    fn add_namespace(&mut self, name: &str) -> Result<(), String> {
        ip(&["netns", "add", name])?;
        self.created.push(name.to_string());
        Ok(())
    }

    /// The host named `name`.
    pub fn host(&self, name: &str) -> Result<&LabHost, String> {
        self.hosts
            .iter()
            .find(|h| h.name == name)
            .ok_or_else(|| format!("the lab has no host {name}"))
    }

    /// A command that runs `program` inside host `name`'s namespace.
    pub fn command(&self, name: &str, program: &str) -> Result<Command, String> {
        let host = self.host(name)?;
        let mut command = Command::new("ip");
        command.args(["netns", "exec", &host.namespace, program]);
        Ok(command)
    }

    /// Pull host `name`'s cable: its switch port goes down (the host sees no carrier).
    pub fn cut(&self, name: &str) -> Result<(), String> {
        let host = self.host(name)?;
        ip(&["-n", &self.switch, "link", "set", &host.switch_port, "down"])
    }

    /// Plug host `name`'s cable back in.
    pub fn restore(&self, name: &str) -> Result<(), String> {
        let host = self.host(name)?;
        ip(&["-n", &self.switch, "link", "set", &host.switch_port, "up"])
    }
}

/// The process ids running inside network namespace `namespace`.
fn pids_in(namespace: &str) -> Vec<u32> {
    Command::new("ip")
        .args(["netns", "pids", namespace])
        .output()
        .map(|o| {
            String::from_utf8_lossy(&o.stdout)
                .split_whitespace()
                .filter_map(|p| p.parse().ok())
                .collect()
        })
        .unwrap_or_default()
}

impl Drop for NetnsLab {
    fn drop(&mut self) {
        for namespace in self.created.iter().rev() {
            for pid in pids_in(namespace) {
                // The shell's builtin `kill`: no procps needed.
                Command::new("sh")
                    .args(["-c", &format!("kill -KILL {pid}")])
                    .status()
                    .ok();
            }
            if let Err(e) = ip(&["netns", "delete", namespace]) {
                eprintln!("warning: {e}");
            }
        }
    }
}

/// Whether this machine lets the test create network namespaces: `Err` says why not.
pub fn namespaces_available(tag: &str) -> Result<(), String> {
    let name = format!("pomdar-{tag}-check");
    ip(&["netns", "add", &name])?;
    ip(&["netns", "delete", &name])
}
