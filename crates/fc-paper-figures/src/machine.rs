//! The machine wall times are measured on: `figures/data/machine-timing.csv`
//! (one row: the date, whether a virtual or physical machine, the CPU, its
//! cores, the memory, the load average of the last 15 minutes, the OS and the
//! Rust compiler), which the paper quotes beside every wall time.

use std::fmt::Write as _;
use std::fs;
use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

use fc_csv::format::text;

/// The value of the first line of `text` that starts with `key` (in the
/// `key : value` form of /proc/cpuinfo and /proc/meminfo).
fn field<'a>(text: &'a str, key: &str) -> Option<&'a str> {
    text.lines()
        .find(|l| l.starts_with(key))
        .and_then(|l| l.split_once(':'))
        .map(|(_, v)| v.trim())
}

/// The civil date (UTC) of a Unix day number (H. Hinnant's algorithm).
fn civil(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

/// `machine-timing.csv`: one row describing this machine, now (written at
/// the end of a `--timings` run, so the load average covers its last 15
/// minutes).
pub fn csv() -> String {
    let cpuinfo = fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let meminfo = fs::read_to_string("/proc/meminfo").unwrap_or_default();
    let cpu = field(&cpuinfo, "model name").unwrap_or("unknown");
    // The CPU flag a hypervisor sets for its guests.
    let kind = match field(&cpuinfo, "flags") {
        Some(f) if f.split_whitespace().any(|x| x == "hypervisor") => "virtual machine",
        Some(_) => "physical machine",
        None => "machine",
    };
    // How busy the machine was over the last quarter of an hour.
    let load = fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|l| l.split_whitespace().nth(2).map(str::to_string))
        .unwrap_or_default();
    let memory_gib = field(&meminfo, "MemTotal")
        .and_then(|v| v.trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(String::new(), |kib| format!("{:.0}", kib / 1024.0 / 1024.0));
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let rustc = Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (y, m, d) = civil((secs / 86_400) as i64);
    let mut s = String::from("date,kind,cpu,cores,memory_gib,load_average_15min,os,rustc\n");
    // Writing to a String cannot fail.
    let _ = writeln!(
        s,
        "{y:04}-{m:02}-{d:02},{kind},{},{cores},{memory_gib},{load},{},{}",
        text(cpu),
        std::env::consts::OS,
        text(&rustc)
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates() {
        assert_eq!(civil(0), (1970, 1, 1));
        assert_eq!(civil(19_723), (2024, 1, 1));
        assert_eq!(civil(20_513), (2026, 3, 1));
        assert_eq!(civil(-1), (1969, 12, 31));
    }

    #[test]
    fn the_machine_is_one_row() {
        let t = fc_csv::table::Table::parse("machine", &csv()).unwrap();
        assert_eq!(t.len(), 1);
    }
}

/// The CPU time this process has used so far, user and system, all its
/// threads (s; `/proc/self/stat`'s `utime + stime` in the kernel's fixed
/// 100 ticks a second), or `None` off Linux. A step's difference is its
/// compute whatever the machine's load: a wall time on a shared machine
/// also counts the time other processes held the cores.
pub fn cpu_seconds() -> Option<f64> {
    let stat = fs::read_to_string("/proc/self/stat").ok()?;
    cpu_of_stat(&stat)
}

/// [`cpu_seconds`] from the text of a `/proc/<pid>/stat` (its second field,
/// the command, is in parentheses and may hold spaces: the fields are
/// counted after its closing one).
fn cpu_of_stat(stat: &str) -> Option<f64> {
    let (_, rest) = stat.rsplit_once(')')?;
    // After the command: state (field 3) .. utime (14), stime (15).
    let mut fields = rest.split_whitespace().skip(11);
    let utime: u64 = fields.next()?.parse().ok()?;
    let stime: u64 = fields.next()?.parse().ok()?;
    Some((utime + stime) as f64 / 100.0)
}

#[cfg(test)]
mod cpu_tests {
    use super::*;

    /// The fields are counted after the command's closing parenthesis,
    /// whatever it holds.
    #[test]
    fn the_cpu_time_is_utime_plus_stime() {
        let stat = "4242 (x task) (R) S 1 2 3 4 5 6 7 8 9 10 250 75 12 13 20 0";
        assert_eq!(cpu_of_stat(stat), Some(3.25));
        assert_eq!(cpu_of_stat("4242 (xtask) R 1"), None);
    }

    /// It grows with work done (within 10 s of wall time, however loaded
    /// the machine).
    #[test]
    fn the_cpu_time_grows_with_work() {
        let Some(c0) = cpu_seconds() else { return };
        let t0 = std::time::Instant::now();
        let mut x = 1.0f64;
        while cpu_seconds().unwrap() < c0 + 0.05 && t0.elapsed().as_secs_f64() < 10.0 {
            for _ in 0..100_000 {
                x = (x * 1.000_000_1).sin() + 1.0;
            }
        }
        assert!(x.is_finite());
        assert!(cpu_seconds().unwrap() >= c0 + 0.05, "{c0} after 10 s");
    }
}
