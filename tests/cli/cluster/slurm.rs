//! A one-node Slurm cluster of the distribution's daemons, started for a
//! test and stopped by PID when it is dropped, pass or fail.
//!
//! Everything the cluster writes (its configuration, state, spool, logs and
//! pid files) lives in one scratch directory; it listens on two free ports
//! found at start, so it cannot meet another Slurm on the machine. It needs
//! root (the daemons run as root, without cgroups: `proctrack/linuxproc`,
//! `task/none`), `munged`, `slurmctld`, `slurmd` and the client commands.

use std::fs;
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The programs a cluster needs, in the order they are looked for.
pub const PROGRAMS: [&str; 6] = ["munged", "munge", "slurmctld", "slurmd", "sbatch", "sinfo"];

/// The directories searched besides `PATH` (the daemons live in sbin, which
/// a non-login `PATH` may lack).
const SBIN: [&str; 2] = ["/usr/sbin", "/sbin"];

/// `program`'s path, on `PATH` or in sbin.
pub fn find(program: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .chain(SBIN.iter().map(PathBuf::from))
        .map(|d| d.join(program))
        .find(|p| p.is_file())
}

/// Why a cluster cannot start here, or `None` if it can: a missing program,
/// or not root.
pub fn missing() -> Option<String> {
    let absent: Vec<&str> = PROGRAMS.into_iter().filter(|p| find(p).is_none()).collect();
    if !absent.is_empty() {
        return Some(format!(
            "no {} (apt-get install slurmctld slurmd slurm-client munge)",
            absent.join(", ")
        ));
    }
    let uid = Command::new("id").arg("-u").output().ok()?;
    if String::from_utf8_lossy(&uid.stdout).trim() != "0" {
        return Some("the daemons need root".into());
    }
    None
}

/// A running cluster.
pub struct Slurm {
    dir: PathBuf,
    conf: PathBuf,
    /// The daemons this cluster started, to stop: (name, pid file).
    started: Vec<(&'static str, PathBuf)>,
}

/// Runs `cmd` for at most `limit`: `Err` if it could not start or had to be
/// killed, else its output.
pub fn run_within(mut cmd: Command, limit: Duration) -> Result<Output, String> {
    let what = format!("{cmd:?}");
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("{what}: {e}"))?;
    let start = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) if start.elapsed() < limit => std::thread::sleep(Duration::from_millis(20)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!("{what} did not end within {limit:?}"));
            }
        }
    }
    child.wait_with_output().map_err(|e| format!("{what}: {e}"))
}

/// A TCP port nobody listens on now.
fn free_port() -> Result<u16, String> {
    let l = TcpListener::bind("127.0.0.1:0").map_err(|e| format!("no free port: {e}"))?;
    l.local_addr()
        .map(|a| a.port())
        .map_err(|e| format!("no free port: {e}"))
}

/// Whether process `pid` lives (a zombie, which a container's init may
/// never reap, does not).
fn alive(pid: u32) -> bool {
    fs::read_to_string(format!("/proc/{pid}/stat"))
        .ok()
        .and_then(|s| s.rsplit(") ").next().map(|rest| !rest.starts_with('Z')))
        .unwrap_or(false)
}

/// The pid in `file`, if the file holds one and that process lives.
fn live_pid(file: &Path) -> Option<u32> {
    let pid: u32 = fs::read_to_string(file).ok()?.trim().parse().ok()?;
    alive(pid).then_some(pid)
}

fn output_text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Runs `cmd` to completion within `limit` and requires exit 0.
fn must(cmd: Command, limit: Duration) -> Result<Output, String> {
    let what = format!("{cmd:?}");
    let o = run_within(cmd, limit)?;
    if o.status.success() {
        Ok(o)
    } else {
        Err(format!("{what} failed: {}", output_text(&o)))
    }
}

const MUNGE_DIR: &str = "/run/munge";
const MUNGE_PID: &str = "/run/munge/munged.pid";

impl Slurm {
    /// Starts munged (unless one already runs: it is then left alone),
    /// slurmctld and slurmd with a configuration in `dir`, and waits until
    /// the node is idle (at most 30 s).
    pub fn start(dir: &Path) -> Result<Slurm, String> {
        let dir = dir.to_path_buf();
        for sub in ["state", "spool"] {
            fs::create_dir_all(dir.join(sub)).map_err(|e| e.to_string())?;
        }
        let conf = dir.join("slurm.conf");
        let mut cluster = Slurm {
            dir,
            conf,
            started: Vec::new(),
        };
        cluster.write_conf()?;
        cluster.start_munge()?;
        for daemon in ["slurmctld", "slurmd"] {
            let pid_file = cluster.dir.join(format!("{daemon}.pid"));
            let mut cmd = Command::new(find(daemon).ok_or(format!("no {daemon}"))?);
            cmd.arg("-f").arg(&cluster.conf);
            // Without -D each daemonises once its pid file is written.
            must(cmd, Duration::from_secs(20))?;
            cluster.started.push((daemon, pid_file));
        }
        cluster.wait_idle(Duration::from_secs(30))?;
        Ok(cluster)
    }

    fn write_conf(&self) -> Result<(), String> {
        let mut hostname = Command::new("hostname");
        hostname.arg("-s");
        let host = must(hostname, Duration::from_secs(5))?;
        let host = String::from_utf8_lossy(&host.stdout).trim().to_string();
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        let d = self.dir.display();
        let (ctld, slurmd) = (free_port()?, free_port()?);
        let text = format!(
            "ClusterName=falling-chain-test\n\
             SlurmctldHost={host}\n\
             SlurmctldPort={ctld}\n\
             SlurmdPort={slurmd}\n\
             SlurmUser=root\n\
             SlurmdUser=root\n\
             AuthType=auth/munge\n\
             ProctrackType=proctrack/linuxproc\n\
             TaskPlugin=task/none\n\
             JobAcctGatherType=jobacct_gather/none\n\
             MpiDefault=none\n\
             SelectType=select/cons_tres\n\
             SelectTypeParameters=CR_Core\n\
             ReturnToService=2\n\
             StateSaveLocation={d}/state\n\
             SlurmdSpoolDir={d}/spool\n\
             SlurmctldPidFile={d}/slurmctld.pid\n\
             SlurmdPidFile={d}/slurmd.pid\n\
             SlurmctldLogFile={d}/slurmctld.log\n\
             SlurmdLogFile={d}/slurmd.log\n\
             NodeName={host} CPUs={cpus} State=UNKNOWN\n\
             PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP\n"
        );
        fs::write(&self.conf, text).map_err(|e| e.to_string())
    }

    /// munged as the munge user, with its run directory made as the
    /// package expects; an already running munged is used as it is.
    fn start_munge(&mut self) -> Result<(), String> {
        if live_pid(Path::new(MUNGE_PID)).is_some() {
            return Ok(());
        }
        fs::create_dir_all(MUNGE_DIR).map_err(|e| format!("{MUNGE_DIR}: {e}"))?;
        must(
            {
                let mut c = Command::new("chown");
                c.args(["munge:munge", MUNGE_DIR]);
                c
            },
            Duration::from_secs(5),
        )?;
        let munged = find("munged").ok_or("no munged")?;
        let mut cmd = Command::new("runuser");
        cmd.args(["-u", "munge", "--"]).arg(munged);
        must(cmd, Duration::from_secs(10))?;
        self.started.push(("munged", PathBuf::from(MUNGE_PID)));
        Ok(())
    }

    /// A client command (`sbatch`, `sinfo`, ...) that talks to this cluster.
    pub fn client(&self, program: &str) -> Command {
        let mut c = Command::new(find(program).unwrap_or_else(|| PathBuf::from(program)));
        c.env("SLURM_CONF", &self.conf);
        c
    }

    fn wait_idle(&self, limit: Duration) -> Result<(), String> {
        let start = Instant::now();
        let mut last = String::new();
        while start.elapsed() < limit {
            let mut sinfo = self.client("sinfo");
            sinfo.args(["-h", "-o", "%t"]);
            if let Ok(o) = run_within(sinfo, Duration::from_secs(5)) {
                last = output_text(&o).trim().to_string();
                if last == "idle" {
                    return Ok(());
                }
            }
            std::thread::sleep(Duration::from_millis(200));
        }
        Err(format!(
            "the node is not idle after {limit:?} (sinfo: '{last}'); slurmctld.log: {}",
            self.log("slurmctld")
        ))
    }

    /// The tail of a daemon's log, for failure messages.
    pub fn log(&self, daemon: &str) -> String {
        let text = fs::read_to_string(self.dir.join(format!("{daemon}.log"))).unwrap_or_default();
        let lines: Vec<&str> = text.lines().collect();
        lines[lines.len().saturating_sub(15)..].join("\n")
    }
}

impl Drop for Slurm {
    /// SIGTERM to every daemon this cluster started, newest first, and a
    /// wait of up to 10 s each for it to go (SIGKILL after that).
    fn drop(&mut self) {
        for (_, pid_file) in self.started.iter().rev() {
            let Some(pid) = live_pid(pid_file) else {
                continue;
            };
            let _ = Command::new("kill").arg(pid.to_string()).status();
            let start = Instant::now();
            while alive(pid) && start.elapsed() < Duration::from_secs(10) {
                std::thread::sleep(Duration::from_millis(50));
            }
            if alive(pid) {
                let _ = Command::new("kill")
                    .args(["-KILL", &pid.to_string()])
                    .status();
            }
        }
    }
}
