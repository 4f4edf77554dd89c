//! The memory a run needs, estimated from its model, method and size
//! before anything is allocated, against the memory the machine can give
//! (issue 47 A2): a run that cannot fit is refused with one line instead
//! of aborting on an allocation mid-run.
//!
//! The estimate is `BASE_BYTES + bytes_per_rod(model, method) n` plus the
//! run's recorded samples; the bytes a rod were measured as the slope of
//! the maximum resident set between `n = 5e4` and `n = 2e5`
//! (`/usr/bin/time -v falling-chain simulate ... --set chain.links=N
//! --t-end 1e-4`, docs/speed.md, "Memory at large n") and are held here
//! with a margin of a quarter, rounded up. The machine's memory is
//! `MemAvailable` of `/proc/meminfo`, and no more than what the process's
//! address-space limit (`RLIMIT_AS`, `prlimit --as`) leaves; the
//! environment variable [`MEMORY_ENV`] replaces both (tests, and a user who
//! knows better). Where neither can be read (not Linux) no run is refused
//! on memory: the bound is then the machine's own.

use fc_methods::{InvalidParameter, Method};

/// The environment variable that sets the memory available to a run
/// (bytes, a number such as `4e9`), instead of reading the machine's.
pub const MEMORY_ENV: &str = "FC_MEMORY_AVAILABLE";

/// What any run holds whatever its size (bytes): the program, its
/// threads' stacks and the allocator's first arenas (the largest maximum
/// resident set of a run at `n = 50` was 12 MB; a thread's stack reserves
/// 8 MiB of address space).
pub const BASE_BYTES: u64 = 64 << 20;

/// The margin the measured bytes a rod are held with.
pub const MEMORY_MARGIN: f64 = 1.25;

/// The measured bytes a rod of a run of `method` on `model` (`rigid`,
/// `elastic`, `contact`, `report`: [`crate::Model::name`]), the margin not
/// included: the slope of the maximum resident set between two sizes,
/// `n = 2e4` and `5e4` on rigid links (`scenes/span-d3.toml`), `5e3` and
/// `2e4` on elastic ones (`span-d3.toml --set chain.axial_stiffness=1e6`,
/// and `span-d3-floor.toml`'s penalty floor, the larger of the two) and on
/// the constraint floor (`span-d3.toml --set floor.height=-2.5`); the
/// report's model (at most 200 rods) is costed as the rigid chain. `auto`
/// may run its explicit method and then BDF or gen-alpha: the largest.
pub fn measured_bytes_per_rod(model: &str, method: Method) -> u64 {
    let elastic = model == "elastic";
    match method {
        Method::Rk4 if elastic => 763,
        Method::Rk4 => 467,
        Method::Dopri5 if elastic => 1207,
        Method::Dopri5 => 589,
        Method::Dop853 if elastic => 1391,
        Method::Dop853 => 667,
        Method::Bdf | Method::BdfDense if elastic => 7952,
        Method::Bdf | Method::BdfDense => 6931,
        Method::GenAlpha if elastic => 6889,
        Method::GenAlpha => 6009,
        Method::MoreauJean => 3254,
        Method::Auto => [
            Method::Dop853,
            Method::Bdf,
            Method::GenAlpha,
            Method::MoreauJean,
        ]
        .iter()
        .map(|&m| measured_bytes_per_rod(model, m))
        .max()
        .unwrap_or(0),
    }
}

/// The estimated memory of one run (bytes): [`BASE_BYTES`], the measured
/// bytes a rod of `links` rods with [`MEMORY_MARGIN`], and `samples_bytes`
/// of recorded samples; `bdf-dense` adds its dense Jacobian and LU
/// (`(2 n + 1)^2` numbers each, eight such matrices in diffsol's BDF).
pub fn estimate(model: &str, method: Method, links: usize, samples_bytes: u64) -> u64 {
    let n = links as f64;
    let per_rod = measured_bytes_per_rod(model, method) as f64 * MEMORY_MARGIN;
    let dense = if method == Method::BdfDense {
        let dim = 6.0 * n + 1.0;
        8.0 * 8.0 * dim * dim
    } else {
        0.0
    };
    let bytes = BASE_BYTES as f64 + per_rod * n + dense + samples_bytes as f64;
    if bytes >= u64::MAX as f64 {
        u64::MAX
    } else {
        bytes.ceil() as u64
    }
}

/// The memory a run may take, and where that number came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Available {
    /// Bytes.
    pub bytes: u64,
    /// `MemAvailable`, `RLIMIT_AS` or [`MEMORY_ENV`].
    pub source: &'static str,
}

/// The memory this process can still take: [`MEMORY_ENV`] if it is set to
/// a number >= 0, else `MemAvailable` (`/proc/meminfo`), lowered to what
/// the address-space limit leaves (its soft limit in `/proc/self/limits`
/// less `VmSize` in `/proc/self/status`); `None` where neither can be
/// read.
pub fn available() -> Option<Available> {
    if let Ok(text) = std::env::var(MEMORY_ENV) {
        if let Ok(v) = text.trim().parse::<f64>() {
            if v.is_finite() && v >= 0.0 {
                return Some(Available {
                    bytes: v.min(u64::MAX as f64) as u64,
                    source: MEMORY_ENV,
                });
            }
        }
    }
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok();
    let free = meminfo
        .as_deref()
        .and_then(|t| kib_field(t, "MemAvailable:"));
    let limit = address_space_left();
    match (free, limit) {
        (Some(f), Some(l)) if l < f => Some(Available {
            bytes: l,
            source: "the address-space limit RLIMIT_AS",
        }),
        (Some(f), _) => Some(Available {
            bytes: f,
            source: "MemAvailable",
        }),
        (None, Some(l)) => Some(Available {
            bytes: l,
            source: "the address-space limit RLIMIT_AS",
        }),
        (None, None) => None,
    }
}

/// `FIELD  N kB` of a `/proc` file, in bytes.
fn kib_field(text: &str, field: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(field))?;
    let kib: u64 = line[field.len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    kib.checked_mul(1024)
}

/// The soft address-space limit less the address space in use; `None`
/// when it is unlimited or cannot be read.
fn address_space_left() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    let soft: u64 = line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let used = kib_field(&status, "VmSize:")?;
    Some(soft.saturating_sub(used))
}

/// Refuses `concurrent` runs of `method` on `model` with `links` rods (and
/// `samples_bytes` of samples each) whose estimate ([`estimate`]) exceeds
/// the available memory ([`available`]); the error names `chain.links`,
/// the method, the estimate and the memory available.
pub fn check(
    model: &str,
    method: Method,
    links: usize,
    samples_bytes: u64,
    concurrent: usize,
) -> Result<(), InvalidParameter> {
    let Some(avail) = available() else {
        return Ok(());
    };
    let one = estimate(model, method, links, samples_bytes);
    let runs = concurrent.max(1) as u64;
    let total = one.saturating_mul(runs);
    if total <= avail.bytes {
        return Ok(());
    }
    let per_rod = measured_bytes_per_rod(model, method) as f64 * MEMORY_MARGIN;
    let room = avail
        .bytes
        .saturating_sub(runs.saturating_mul(BASE_BYTES + samples_bytes)) as f64;
    let fits = if per_rod > 0.0 {
        (room / (runs as f64 * per_rod)).floor() as u64
    } else {
        0
    };
    let times = if runs > 1 {
        format!(" x {runs} runs at once")
    } else {
        String::new()
    };
    Err(InvalidParameter {
        field: "chain.links",
        accepted: format!(
            "at most {fits} for {method} on the {model} chain on this machine: the run needs \
             about {} ({} bytes a rod{times}) and {} is available ({})",
            gigabytes(total),
            per_rod.ceil(),
            gigabytes(avail.bytes),
            if avail.source == MEMORY_ENV {
                MEMORY_ENV.to_string()
            } else {
                format!("{}; {MEMORY_ENV} sets it", avail.source)
            },
        )
        .into(),
        got: links.to_string(),
    })
}

/// `bytes` as `1.23 GB`, or `45.6 MB` below a gigabyte.
fn gigabytes(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= 1e9 {
        format!("{:.2} GB", b / 1e9)
    } else {
        format!("{:.1} MB", b / 1e6)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimate_grows_with_n_and_with_the_samples() {
        for m in Method::ALL {
            let small = estimate("rigid", m, 10, 0);
            let large = estimate("rigid", m, 1_000_000, 0);
            assert!(small >= BASE_BYTES && large > small, "{m}");
            assert_eq!(estimate("rigid", m, 10, 1000), small + 1000);
        }
        assert!(
            estimate("elastic", Method::Bdf, 1000, 0) > estimate("rigid", Method::Bdf, 1000, 0)
        );
    }

    #[test]
    fn proc_fields_are_read_in_bytes() {
        let t = "MemTotal:       24000000 kB\nMemAvailable:   2000 kB\n";
        assert_eq!(kib_field(t, "MemAvailable:"), Some(2_048_000));
        assert_eq!(kib_field(t, "VmSize:"), None);
    }
}
