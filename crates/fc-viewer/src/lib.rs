//! The self-contained HTML viewer of `falling-chain view`: one page with the
//! runs' data and every script inline (no network, no server), which plays,
//! scrubs and steps through up to [`MAX_RUNS`] runs overlaid, and a run read
//! back from `simulate --out`'s CSV for it ([`run_csv`]). It builds on
//! fc-scene (a run's summary); the CLI's `view`, Python's `view` and the
//! paper's viewer figures (through fc-paper-figures) call it.
//!
//! The page's data model, one object per run in `#fc-data` (JSON):
//! `label`; `summary` (the `simulate --json` object, or for a run read from
//! a CSV the fields that file gives); `status` and `t_failed`; `links` (n),
//! `rod` (l = L/n) and `anchor` (P0), in the scene's length unit; `samples`
//! (before thinning) and `stride` (every `stride`-th sample is kept, and the
//! last); per kept sample `t`, `speed` (tip speed), `energy` (E) and
//! `dissipated` (W); `phi`, the n absolute rod angles of every kept sample
//! in a row (rad from the horizontal, 6 decimals), from which the page
//! builds the joints `P0 + l sum (cos, sin)`; and `forces`, `null` or
//! `{ "tension": [...], "shear": [...] }` (either may be absent), n + 1 joint
//! values per kept sample in a row (issue "elastic links"), drawn as
//! colour along the chain. `pivot`, `null` for a fixed pivot, else `x, y`
//! of `P0` per kept sample in a row (a moving or released pivot, the
//! `pivot.*` keys), from which the page builds that frame's joints instead
//! of `anchor`. `rod_lengths` and `density`, both `null` for equal rods,
//! else (a per-rod profile: `chain.taper`, `chain.rod_masses`,
//! `chain.rod_lengths`) n values once per run: each rod's length in the
//! scene's length unit (7 significant digits), which replaces `rod` in the
//! joints `P0 + sum l_i (cos, sin)`, and its mass per length over the
//! chain's mean `M / L` (3 digits), which sets the rod's line width (in
//! proportion to its square root: the diameter of a rod of one material).
//! `source` names the CSV a run was read from.

use std::fmt::Write as _;

use chain_ode::Trajectory;
use serde_json::{json, Value};

use fc_scene::{Error, RunSummary};

pub mod run_csv;

/// The most runs one page overlays (one colour each).
pub const MAX_RUNS: usize = 8;

/// The data a page holds, over all its runs, in bytes: each of `k` runs is
/// thinned to `DATA_BUDGET_BYTES / k`. A 50-rod, 8 s run at the default
/// output step (801 samples) takes about 0.5 MB, well inside one run's
/// share, so the page of one such run stays under 2 MB unthinned.
pub const DATA_BUDGET_BYTES: usize = 1_800_000;

/// The most rods a page draws: two frames of each of 8 runs must fit the
/// budget ([`DATA_BUDGET_BYTES`]).
pub const MAX_VIEW_LINKS: usize = 10_000;

/// The most rods of a profiled chain (unequal rods) a page draws: its
/// per-rod lengths and densities ([`PROFILE_BYTES`] a rod, once per run)
/// and two frames of each of 8 runs must fit the budget.
pub const MAX_VIEW_PROFILED_LINKS: usize = 5_000;

/// Bytes of one rod's length and density in the data (`1.234567e-1,` and
/// `1.23e-1,`, with room for a sign or a wider exponent).
pub const PROFILE_BYTES: usize = 24;

/// Bytes of one angle in the data (`-1.570796,`).
const ANGLE_BYTES: usize = 10;
/// Bytes of one force value (`-1.2345e-3,`).
const FORCE_BYTES: usize = 11;
/// Bytes of the per-sample scalars (t, speed, energy, dissipated).
const SCALAR_BYTES: usize = 4 * 24;

/// Each rod's length and mass per length of a profiled chain (unequal
/// rods), from the pivot to the tip.
#[derive(Clone, Debug, PartialEq)]
pub struct RodProfile {
    /// `l_i` in the scene's length unit (summing to `L`).
    pub lengths: Vec<f64>,
    /// `(m_i / l_i) / (M / L)`: the rod's mass per length over the chain's
    /// mean (dimensionless; all 1 for equal rods).
    pub density: Vec<f64>,
}

impl RodProfile {
    /// The profile of `chain`; `None` for equal rods (the page then uses
    /// one rod length, `L / n`).
    pub fn of(chain: &chain_ode::Chain) -> Option<Self> {
        let rods = chain.rods()?;
        let l = chain.rod_length();
        Some(Self {
            lengths: rods.length.iter().map(|lam| lam * l).collect(),
            density: rods
                .mass
                .iter()
                .zip(&rods.length)
                .map(|(mu, lam)| mu / lam)
                .collect(),
        })
    }
}

/// The bytes of a run's data that do not depend on its samples: the
/// per-rod profile of `links` rods, if it has one. A run's samples are
/// thinned to its share of the budget less these.
pub fn fixed_bytes(links: usize, profiled: bool) -> usize {
    if profiled {
        links * PROFILE_BYTES
    } else {
        0
    }
}

/// Joint forces of one run: n + 1 values per kept sample, in a row.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointForces {
    /// Tension at each joint (force unit of the scene), if the run has it.
    pub tension: Option<Vec<f64>>,
    /// Shear at each joint, if the run has it.
    pub shear: Option<Vec<f64>>,
}

/// One run as the page holds it (see the module's data model).
#[derive(Clone, Debug, PartialEq)]
pub struct ViewRun {
    pub label: String,
    pub summary: Value,
    pub status: String,
    pub t_failed: Option<f64>,
    pub links: usize,
    pub rod: f64,
    pub anchor: [f64; 2],
    pub samples: usize,
    pub stride: usize,
    pub t: Vec<f64>,
    pub speed: Vec<f64>,
    pub energy: Vec<f64>,
    pub dissipated: Vec<f64>,
    pub phi: Vec<f64>,
    pub forces: Option<JointForces>,
    /// The pivot `P0` of every kept sample, `x, y` each, for a moving or
    /// released pivot (`pivot.*` keys); `None`: fixed at `anchor`.
    pub pivot: Option<Vec<f64>>,
    /// The rods' lengths and densities of a profiled chain; `None`: `links`
    /// equal rods of length `rod` and equal density.
    pub profile: Option<RodProfile>,
    /// The file a run was read from (`--from`), shown on the page.
    pub source: Option<String>,
    /// The floor `[height at x = 0, angle]` (scene coordinates, rad) of a
    /// run with a `[floor]`, drawn as a line; `None`: no floor (and no
    /// `floor` in the page's JSON).
    pub floor: Option<[f64; 2]>,
}

/// The bytes of one kept frame of `links` rods with forces of
/// `force_arrays` kinds, as the thinning counts them.
pub fn frame_bytes(links: usize, force_arrays: usize) -> usize {
    links * ANGLE_BYTES + force_arrays * (links + 1) * FORCE_BYTES + SCALAR_BYTES
}

/// Checks, before any run, that the fewest frames a run keeps (its first
/// and its last) of `links` rods, with forces of `force_arrays` kinds and
/// (`profiled`) the rods' lengths and densities, fit `share` bytes (its
/// share of [`DATA_BUDGET_BYTES`]); the error names `field` and the most
/// rods that fit.
pub fn check_fits(
    field: &str,
    links: usize,
    force_arrays: usize,
    profiled: bool,
    share: usize,
) -> Result<(), Error> {
    let need = fixed_bytes(links, profiled).saturating_add(2 * frame_bytes(links, force_arrays));
    if need <= share {
        return Ok(());
    }
    // need(n) = n per_rod + fixed: the most rods within the share.
    let fixed = 2 * (force_arrays * FORCE_BYTES + SCALAR_BYTES);
    let per_rod =
        2 * (ANGLE_BYTES + force_arrays * FORCE_BYTES) + if profiled { PROFILE_BYTES } else { 0 };
    let most = share.saturating_sub(fixed) / per_rod;
    Err(Error::field(
        field,
        format!(
            "a run of {links} rods{} needs at least {need} bytes of data (its first and last \
             frame), more than its share of the page's {DATA_BUDGET_BYTES} bytes ({share}): at \
             most {most} rods at this many runs (or fewer runs)",
            if force_arrays > 0 {
                " with joint forces"
            } else {
                ""
            }
        ),
    ))
}

/// The stride that keeps `samples` frames of `links` rods (with forces of
/// `force_arrays` kinds) within `budget` bytes: every `stride`-th sample
/// and the last are kept. At least 1.
pub fn stride_for(samples: usize, links: usize, force_arrays: usize, budget: usize) -> usize {
    let frame = frame_bytes(links, force_arrays);
    let kept = (budget / frame.max(1)).max(2);
    if samples <= kept {
        1
    } else {
        // Samples 0, s, 2s, ... below the last, then the last.
        (samples - 1).div_ceil(kept - 1)
    }
}

/// Whether sample `k` of `samples` is kept at `stride`.
pub fn keeps(k: usize, samples: usize, stride: usize) -> bool {
    k.is_multiple_of(stride) || k + 1 == samples
}

/// Checks the number of runs of one page: 1..=[`MAX_RUNS`]; the error
/// names `field`.
pub fn check_run_count(field: &str, runs: usize) -> Result<(), Error> {
    if (1..=MAX_RUNS).contains(&runs) {
        Ok(())
    } else {
        Err(Error::field(
            field,
            format!("a page shows 1 to {MAX_RUNS} runs (got {runs})"),
        ))
    }
}

/// Checks the page's file name: it ends in `.html` exactly (the contract's
/// `FILE.html`: not `.htm`, not `.HTML`); the error names `field`.
pub fn check_page_path(field: &str, path: &std::path::Path) -> Result<(), Error> {
    if path.extension().is_some_and(|e| e == "html") {
        Ok(())
    } else {
        Err(Error::field(
            field,
            format!(
                "must end in .html (got '{}')",
                fc_scene::error::echo_path(path)
            ),
        ))
    }
}

/// Checks that a page can draw `links` rods (at most [`MAX_VIEW_LINKS`]);
/// the error names `field`.
pub fn check_links(field: &str, links: usize) -> Result<(), Error> {
    if links <= MAX_VIEW_LINKS {
        Ok(())
    } else {
        Err(Error::field(
            field,
            format!("the viewer draws at most {MAX_VIEW_LINKS} rods (got {links})"),
        ))
    }
}

/// Checks that a page can draw `chain`: at most [`MAX_VIEW_LINKS`] rods,
/// or [`MAX_VIEW_PROFILED_LINKS`] for unequal rods (whose lengths and
/// densities the page holds too); the error names `field`.
pub fn check_chain(field: &str, chain: &chain_ode::Chain) -> Result<(), Error> {
    let links = chain.links();
    check_links(field, links)?;
    if chain.rods().is_some() && links > MAX_VIEW_PROFILED_LINKS {
        return Err(Error::field(
            field,
            format!(
                "the viewer draws at most {MAX_VIEW_PROFILED_LINKS} rods of unequal mass or \
                 length (got {links})"
            ),
        ));
    }
    Ok(())
}

impl ViewRun {
    /// A finished (or failed) run, thinned to `budget` bytes, with its
    /// `simulate --json` summary.
    ///
    /// With `forces`, the run's joint forces (tension and shear at the n + 1
    /// joints, `Trajectory::joint_forces`) go with it, and the page colours
    /// the chain by them. Speed and energy come from the trajectory's
    /// accessors, right for rigid and elastic links alike.
    pub fn from_trajectory(
        label: &str,
        traj: &Trajectory,
        summary: &RunSummary,
        budget: usize,
        forces: bool,
    ) -> Self {
        let links = traj.chain().links();
        let samples = traj.len();
        let profile = RodProfile::of(traj.chain());
        let budget = budget.saturating_sub(fixed_bytes(links, profile.is_some()));
        let stride = stride_for(samples, links, if forces { 2 } else { 0 }, budget);
        let kept = samples.div_ceil(stride) + 1;
        let mut run = Self {
            label: label.to_string(),
            summary: serde_json::to_value(summary).unwrap_or(Value::Null),
            status: summary.status.clone(),
            t_failed: summary.t_failed,
            links,
            rod: traj.chain().length() / links as f64,
            anchor: traj.anchor,
            samples,
            stride,
            t: Vec::with_capacity(kept),
            speed: Vec::with_capacity(kept),
            energy: Vec::with_capacity(kept),
            dissipated: Vec::with_capacity(kept),
            phi: Vec::with_capacity(kept * links),
            forces: None,
            pivot: (!traj.chain().pivot().is_fixed()).then(|| Vec::with_capacity(2 * kept)),
            profile,
            source: None,
            floor: {
                use chain_ode::Model as _;
                traj.model.view().floor_line().map(|(h, a)| [h, a])
            },
        };
        let (mut tension, mut shear) = (Vec::new(), Vec::new());
        for (k, s) in traj.samples().enumerate() {
            if !keeps(k, samples, stride) {
                continue;
            }
            let v = traj.tip_velocity(k);
            run.t.push(s.t);
            run.speed.push(v[0].hypot(v[1]));
            run.energy.push(traj.energy(k));
            run.dissipated.push(s.dissipated);
            run.phi.extend_from_slice(s.angles);
            if let Some(p) = run.pivot.as_mut() {
                p.extend(traj.pivot_at(k)[0]);
            }
            if forces {
                for f in traj.joint_forces(k) {
                    tension.push(f[0]);
                    shear.push(f[1]);
                }
            }
        }
        if forces {
            run.forces = Some(JointForces {
                tension: Some(tension),
                shear: Some(shear),
            });
        }
        run
    }

    /// The number of samples kept.
    pub fn kept(&self) -> usize {
        self.t.len()
    }

    /// Keeps every other kept sample and the last (the stride doubles:
    /// still every `stride`-th sample and the last); `false`, and nothing
    /// changed, when two or fewer are kept.
    pub fn thin_by_two(&mut self) -> bool {
        let kept = self.kept();
        if kept <= 2 {
            return false;
        }
        let keep = |i: usize| i.is_multiple_of(2) || i + 1 == kept;
        let thin = |values: &mut Vec<f64>, per: usize| {
            let mut i = 0;
            values.retain(|_| {
                let k = keep(i / per);
                i += 1;
                k
            });
        };
        let links = self.links;
        for v in [
            &mut self.t,
            &mut self.speed,
            &mut self.energy,
            &mut self.dissipated,
        ] {
            thin(v, 1);
        }
        thin(&mut self.phi, links.max(1));
        if let Some(p) = self.pivot.as_mut() {
            thin(p, 2);
        }
        if let Some(f) = self.forces.as_mut() {
            for v in [&mut f.tension, &mut f.shear].into_iter().flatten() {
                thin(v, links + 1);
            }
        }
        self.stride = self.stride.saturating_mul(2);
        true
    }

    /// The run as the page's JSON object (numbers written by hand: angles
    /// to 6 decimals, forces to 5 digits, the rest round-tripping).
    fn write_json(&self, out: &mut String) {
        let head = json!({
            "label": self.label,
            "summary": self.summary,
            "status": self.status,
            "t_failed": self.t_failed,
            "links": self.links,
            "rod": self.rod,
            "anchor": self.anchor,
            "samples": self.samples,
            "stride": self.stride,
            "source": self.source,
        });
        let mut head = head;
        if let Some(f) = self.floor {
            head["floor"] = json!(f);
        }
        let head = head.to_string();
        // The object without its closing brace, then the arrays.
        out.push_str(&head[..head.len() - 1]);
        for (name, values) in [
            ("t", &self.t),
            ("speed", &self.speed),
            ("energy", &self.energy),
            ("dissipated", &self.dissipated),
        ] {
            write_array(out, name, values, |out, v| {
                let _ = write!(out, "{}", finite(v));
            });
        }
        write_array(out, "phi", &self.phi, |out, v| {
            let _ = write!(out, "{:.6}", finite(v));
        });
        match &self.profile {
            None => out.push_str(",\"rod_lengths\":null,\"density\":null"),
            Some(p) => {
                write_array(out, "rod_lengths", &p.lengths, |out, v| {
                    let _ = write!(out, "{:.6e}", finite(v));
                });
                write_array(out, "density", &p.density, |out, v| {
                    let _ = write!(out, "{:.2e}", finite(v));
                });
            }
        }
        match &self.pivot {
            None => out.push_str(",\"pivot\":null"),
            Some(p) => write_array(out, "pivot", p, |out, v| {
                let _ = write!(out, "{}", finite(v));
            }),
        }
        out.push_str(",\"forces\":");
        match &self.forces {
            None => out.push_str("null"),
            Some(f) => {
                out.push('{');
                let mut first = true;
                for (name, values) in [("tension", &f.tension), ("shear", &f.shear)] {
                    if let Some(values) = values {
                        if !first {
                            out.push(',');
                        }
                        first = false;
                        write_array(&mut *out, name, values, |out, v| {
                            let _ = write!(out, "{:.4e}", finite(v));
                        });
                    }
                }
                out.push('}');
            }
        }
        out.push('}');
    }
}

/// A JSON number for `v` (the data hold only finite values; a stray
/// non-finite one becomes 0 rather than invalid JSON).
fn finite(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

/// Appends `,"name":[v,v,...]` (without the leading comma when `out` ends
/// in `{` or `,`).
fn write_array(out: &mut String, name: &str, values: &[f64], each: impl Fn(&mut String, f64)) {
    if !(out.ends_with('{') || out.ends_with(',')) {
        out.push(',');
    }
    let _ = write!(out, "\"{name}\":[");
    for (k, &v) in values.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        each(out, v);
    }
    out.push(']');
}

/// The page's data (`#fc-data`, JSON) of `runs`, as the page holds it,
/// with the time it opens at (`at`: `view --at`; a `#t=` in its URL wins).
fn data_of(runs: &[ViewRun], at: Option<f64>) -> String {
    let mut data = String::from("{\"version\":1,");
    if let Some(t) = at.filter(|t| t.is_finite()) {
        let _ = write!(data, "\"at\":{t},");
    }
    data.push_str("\"runs\":[");
    for (k, run) in runs.iter().enumerate() {
        if k > 0 {
            data.push(',');
        }
        run.write_json(&mut data);
    }
    data.push_str("]}");
    // `<` appears only inside JSON strings, where \u003c is the same text:
    // no label can end the script element.
    data.replace('<', "\\u003c")
}

/// The page around `data`.
fn page_of(title: &str, data: &str) -> String {
    TEMPLATE
        .replace("{{CSS}}", CSS)
        .replace("{{SCRIPT}}", SCRIPT)
        .replace("{{TITLE}}", &html_escape(title))
        .replace("{{DATA}}", data)
}

/// The HTML page of `runs`, titled `title`: the data, the style and the
/// script inline.
pub fn page(title: &str, runs: &[ViewRun]) -> String {
    page_of(title, &data_of(runs, None))
}

/// Checks `view --at T` against `runs`: a time in `[0, t]`, `t` the last
/// time of the longest run (the page opens at the sample nearest `T`).
pub fn check_at(field: &str, at: f64, last: f64) -> Result<(), Error> {
    if at.is_finite() && (0.0..=last).contains(&at) {
        return Ok(());
    }
    Err(Error::field(
        field,
        format!(
            "must be a time in [0, {}] (the runs' last time; got {})",
            fc_scene::error::number(last),
            fc_scene::error::number(at)
        ),
    ))
}

/// The page of `runs` with at most [`DATA_BUDGET_BYTES`] of data, as the
/// page's cap promises: while the data (as written) exceed it, every run
/// keeps every other of its kept samples (and the last; at most 64
/// halvings); if the runs' first and last frames alone exceed it, the page
/// is refused, naming `field`.
pub fn fitted_page(field: &str, title: &str, runs: &mut [ViewRun]) -> Result<String, Error> {
    fitted_page_at(field, title, runs, None)
}

/// [`fitted_page`], opening at the time `at` (`view --at`) when given.
pub fn fitted_page_at(
    field: &str,
    title: &str,
    runs: &mut [ViewRun],
    at: Option<f64>,
) -> Result<String, Error> {
    for _ in 0..64 {
        let data = data_of(runs, at);
        if data.len() <= DATA_BUDGET_BYTES {
            return Ok(page_of(title, &data));
        }
        let mut thinned = false;
        for run in runs.iter_mut() {
            thinned |= run.thin_by_two();
        }
        if !thinned {
            return Err(Error::field(
                field,
                format!(
                    "the page's data would be {} bytes with only each run's first and last \
                     frame, more than its {DATA_BUDGET_BYTES}: fewer runs or fewer rods",
                    data.len()
                ),
            ));
        }
    }
    Err(Error::field(
        field,
        format!("the page's data do not fit its {DATA_BUDGET_BYTES} bytes"),
    ))
}

/// `text` with `&`, `<`, `>` and `"` escaped for HTML.
pub fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The page wrapped in an `<iframe srcdoc>`, for a notebook's output
/// (Jupyter shows HTML but may not run its scripts inline).
pub fn iframe(page: &str) -> String {
    format!(
        "<iframe srcdoc=\"{}\" style=\"width: 100%; height: 900px; border: 0\" \
         sandbox=\"allow-scripts\"></iframe>",
        html_escape(page)
    )
}

const TEMPLATE: &str = include_str!("../viewer/page.html");
const CSS: &str = include_str!("../viewer/viewer.css");
const SCRIPT: &str = include_str!("../viewer/viewer.js");

#[cfg(test)]
mod tests {
    use super::*;

    fn toy(forces: Option<JointForces>) -> ViewRun {
        ViewRun {
            label: "a </script> b".into(),
            summary: json!({ "status": "ok" }),
            status: "ok".into(),
            t_failed: None,
            links: 2,
            rod: 0.5,
            anchor: [0.0, 0.0],
            samples: 2,
            stride: 1,
            t: vec![0.0, 0.1],
            speed: vec![0.0, 1.0],
            energy: vec![-1.0, -1.0],
            dissipated: vec![0.0, 0.0],
            phi: vec![0.0, -1.0, -0.5, -1.5],
            forces,
            pivot: None,
            profile: None,
            source: None,
            floor: None,
        }
    }

    fn data_of(page: &str) -> Value {
        let start = page.find("type=\"application/json\">").unwrap() + 24;
        let end = start + page[start..].find("</script>").unwrap();
        serde_json::from_str(&page[start..end]).unwrap()
    }

    #[test]
    fn the_data_is_json_and_no_label_ends_the_script() {
        let forces = JointForces {
            tension: Some(vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
            shear: None,
        };
        let page = page("t", &[toy(None), toy(Some(forces))]);
        let data = data_of(&page);
        let runs = data["runs"].as_array().unwrap();
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0]["label"], "a </script> b");
        assert_eq!(runs[0]["forces"], Value::Null);
        assert_eq!(runs[1]["forces"]["tension"].as_array().unwrap().len(), 6);
        assert_eq!(runs[1]["phi"][1].as_f64(), Some(-1.0));
    }

    /// A profiled run's lengths and densities take at most
    /// [`PROFILE_BYTES`] a rod, and two frames of the most profiled rods a
    /// page draws fit each of 8 runs' share with them.
    #[test]
    fn a_profile_fits_its_bytes_and_the_most_profiled_rods_fit_the_budget() {
        let n = 1000;
        // Long mantissas and two-digit negative exponents: the widest values.
        let profile = RodProfile {
            lengths: (0..n)
                .map(|i| 1.234_567_89e-11 * (1.0 + i as f64 * 1e-3))
                .collect(),
            density: (0..n)
                .map(|i| 9.876_54e-12 * (1.0 + i as f64 * 1e-3))
                .collect(),
        };
        let bare = page("t", &[toy(None)]).len();
        let mut run = toy(None);
        run.profile = Some(profile.clone());
        let with = page("t", &[run]);
        // Less the two nulls the bare page holds.
        let extra = with.len() + ",\"rod_lengths\":null,\"density\":null".len() - bare;
        assert!(extra <= fixed_bytes(n, true), "{extra} bytes");
        let back = &data_of(&with)["runs"][0];
        for (k, v) in back["rod_lengths"].as_array().unwrap().iter().enumerate() {
            let v = v.as_f64().unwrap();
            assert!((v / profile.lengths[k] - 1.0).abs() < 5e-7, "{k}: {v}");
        }
        let frame = MAX_VIEW_PROFILED_LINKS * ANGLE_BYTES + SCALAR_BYTES;
        assert!(
            fixed_bytes(MAX_VIEW_PROFILED_LINKS, true) + 2 * frame <= DATA_BUDGET_BYTES / MAX_RUNS
        );
        assert_eq!(fixed_bytes(n, false), 0);
    }

    #[test]
    fn halving_keeps_the_stride_the_first_and_the_last_sample() {
        // 11 samples at stride 2 keep 0, 2, .., 10; halved: 0, 4, 8, 10.
        let mut run = toy(Some(JointForces {
            tension: Some((0..6 * 3).map(f64::from).collect()),
            shear: None,
        }));
        run.samples = 11;
        run.stride = 2;
        run.t = vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0];
        run.speed.clone_from(&run.t);
        run.energy.clone_from(&run.t);
        run.dissipated.clone_from(&run.t);
        run.phi = (0..12).map(f64::from).collect();
        run.pivot = Some((0..12).map(f64::from).collect());
        assert!(run.thin_by_two());
        assert_eq!(run.stride, 4);
        let kept: Vec<f64> = (0..11)
            .filter(|&k| keeps(k, 11, 4))
            .map(|k| k as f64)
            .collect();
        assert_eq!(run.t, kept);
        assert_eq!(run.phi, [0.0, 1.0, 4.0, 5.0, 8.0, 9.0, 10.0, 11.0]);
        assert_eq!(run.pivot.as_deref(), Some(&run.phi[..]));
        let tension = run.forces.as_ref().and_then(|f| f.tension.clone()).unwrap();
        assert_eq!(
            tension,
            [0.0, 1.0, 2.0, 6.0, 7.0, 8.0, 12.0, 13.0, 14.0, 15.0, 16.0, 17.0]
        );
        while run.thin_by_two() {}
        assert_eq!(run.t, [0.0, 10.0]);
        assert!(!run.thin_by_two());
    }

    /// Where the thinning's estimate falls short (angles of many turns
    /// take more than their bytes), the page is halved until its data fit
    /// the cap, and refused when two frames alone exceed it.
    #[test]
    fn the_page_is_thinned_to_its_cap_or_refused() {
        let (links, samples) = (1000, 400);
        let mut run = toy(None);
        run.links = links;
        run.samples = samples;
        run.stride = 1;
        run.t = (0..samples).map(|k| k as f64).collect();
        run.speed.clone_from(&run.t);
        run.energy.clone_from(&run.t);
        run.dissipated.clone_from(&run.t);
        // -12345.678901, 14 bytes an angle: 14 MB at stride 1.
        run.phi = vec![-12_345.678_901; samples * links];
        let mut runs = [run.clone()];
        let page = fitted_page("--out", "t", &mut runs).unwrap();
        let data = super::data_of(&runs, None);
        assert!(data.len() <= DATA_BUDGET_BYTES, "{}", data.len());
        assert!(page.contains(&data));
        assert!(runs[0].stride > 1 && runs[0].kept() > 2);
        let kept: Vec<f64> = (0..samples)
            .filter(|&k| keeps(k, samples, runs[0].stride))
            .map(|k| k as f64)
            .collect();
        assert_eq!(runs[0].t, kept);
        // Two frames of 10^5 such angles are 2.8 MB: refused.
        run.links = 100_000;
        run.samples = 2;
        run.t.truncate(2);
        run.speed.truncate(2);
        run.energy.truncate(2);
        run.dissipated.truncate(2);
        run.phi = vec![-12_345.678_901; 2 * 100_000];
        let e = fitted_page("--out", "t", &mut [run])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--out: the page's data would be"), "{e}");
    }

    /// The fewest frames of the most rods the page draws fit a run's share
    /// of 8 without forces; with forces the bound is smaller, and named.
    #[test]
    fn the_fewest_frames_fit_or_are_refused() {
        let share = DATA_BUDGET_BYTES / MAX_RUNS;
        assert!(check_fits("chain.links", MAX_VIEW_LINKS, 0, false, share).is_ok());
        assert!(check_fits("chain.links", MAX_VIEW_PROFILED_LINKS, 0, true, share).is_ok());
        let e = check_fits("--forces", 5000, 2, false, share)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("--forces: a run of 5000 rods with joint forces"),
            "{e}"
        );
        let most: usize = e
            .split("at most ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap();
        assert!(check_fits("--forces", most, 2, false, share).is_ok());
        assert!(check_fits("--forces", most + 1, 2, false, share).is_err());
    }

    #[test]
    fn thinning_keeps_the_budget_the_first_and_the_last_sample() {
        for (samples, links) in [(801, 50), (801, 400), (100_001, 50), (3, 10_000)] {
            let budget = DATA_BUDGET_BYTES / 8;
            let stride = stride_for(samples, links, 0, budget);
            let kept = (0..samples).filter(|&k| keeps(k, samples, stride)).count();
            assert!(keeps(0, samples, stride) && keeps(samples - 1, samples, stride));
            let bytes = kept * (links * ANGLE_BYTES + SCALAR_BYTES);
            assert!(
                bytes <= budget || kept == 2.min(samples),
                "{samples} {links}"
            );
            // The next smaller stride would not fit.
            if stride > 1 {
                let k2 = (0..samples)
                    .filter(|&k| keeps(k, samples, stride - 1))
                    .count();
                assert!(k2 * (links * ANGLE_BYTES + SCALAR_BYTES) > budget);
            }
        }
        assert_eq!(stride_for(801, 50, 0, DATA_BUDGET_BYTES), 1);
    }
}
