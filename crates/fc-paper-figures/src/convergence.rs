//! Convergence in the number of rods, as a table: each level of a ladder
//! (`converge::run_level`, the continuum held fixed) with its deviation from
//! the finest, and the smallest adequate `n` by each criterion.

use fc_csv::format::{num, text};
use fc_scene::scene::Scene;
use fc_study::converge::{run_level, smallest_adequate, Deviation, Level, SCALING};

/// The columns of [`rows`].
pub const COLUMNS: &str = "scene,links,mass,damping,bending_viscosity,damping_rate,status,\
                           tip_speed_max,t_tip_speed_max,tip_end_x,tip_end_y,reference_links,\
                           dev_tip_speed_max,dev_tip_end,dev_tip_path,rhs_evals";

/// A line per level of `ladder` (coarse to fine, the last the reference)
/// of scene `scene`, each ending in a newline.
pub fn rows(scene: &str, ladder: &[Level]) -> String {
    let Some(reference) = ladder.last() else {
        return String::new();
    };
    let mut out = String::new();
    for l in ladder {
        let d = Deviation::between(l, reference);
        let c = &l.chain;
        let cells = [
            scene.to_string(),
            c.links().to_string(),
            num(c.mass()),
            num(c.damping()),
            num(c.damping() * c.rod_length()),
            num(c.damping_rate()),
            l.summary.status.clone(),
            num(l.summary.tip_speed_max),
            num(l.summary.t_tip_speed_max),
            num(l.summary.tip_end[0]),
            num(l.summary.tip_end[1]),
            reference.links().to_string(),
            num(d.tip_speed_max),
            num(d.tip_end),
            num(d.tip_path),
            l.summary.rhs_evals.to_string(),
        ];
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// The smallest adequate `n` of `ladder` at `tol` by three criteria: the
/// maximum tip speed; the tip path; the maximum tip speed and the tip end
/// (`converge`'s).
pub fn adequate(ladder: &[Level], tol: f64) -> [Option<usize>; 3] {
    [
        smallest_adequate(ladder, |d| d.tip_speed_max < tol),
        smallest_adequate(ladder, |d| d.tip_path < tol),
        smallest_adequate(ladder, |d| d.tip_speed_max < tol && d.tip_end < tol),
    ]
}

/// The two tolerances of the paper's summary: 1% and 0.1%.
pub const TOLS: [f64; 2] = [1e-2, 1e-3];

/// The options of [`ladders`].
pub struct LadderOptions<'a> {
    /// The ladder of `n` every scene runs.
    pub ladder: &'a [usize],
    /// The `n` a scene goes on to where the last doubling of the ladder
    /// changed its maximum tip speed by more than `go_on` (relative).
    pub finest: usize,
    pub go_on: f64,
    pub method: &'a str,
    pub rtol: f64,
    /// The two tolerances of the summary (1% and 0.1%).
    pub tols: [f64; 2],
}

/// The convergence in n of each named scene (its `output_dt` the tip
/// path's grid), every level run in parallel on the current rayon pool:
/// the table of [`rows`] ([`COLUMNS`]), a summary line per scene
/// (`scene,reference_links,last_doubling_change,n_vmax_1pct,...`, the
/// smallest adequate n by each criterion at each tolerance, and the
/// continuum held fixed), and a line per run and per scene on progress.
pub fn ladders(
    scenes: &[(&str, Scene)],
    o: &LadderOptions,
) -> Result<(String, String, Vec<String>), String> {
    use rayon::prelude::*;
    let notes = std::sync::Mutex::new(vec![]);
    let run = |s: usize, links: usize| -> Result<(usize, Level), String> {
        let (name, scene) = &scenes[s];
        let level =
            run_level(scene, links, Some(o.method), Some(o.rtol)).map_err(|e| e.to_string())?;
        if !level.summary.is_ok() {
            return Err(format!(
                "{name} at n = {links}: status {} at t = {}",
                level.summary.status, level.summary.t_reached
            ));
        }
        if let Ok(mut n) = notes.lock() {
            n.push(format!(
                "{name} n = {links}: vmax {:.6}, {} RHS",
                level.summary.tip_speed_max, level.summary.rhs_evals
            ));
        }
        Ok((s, level))
    };
    let jobs: Vec<(usize, usize)> = (0..scenes.len())
        .flat_map(|s| o.ladder.iter().rev().map(move |&n| (s, n)))
        .collect();
    let first: Vec<(usize, Level)> = jobs
        .par_iter()
        .map(|&(s, n)| run(s, n))
        .collect::<Result<Vec<_>, String>>()?;
    let mut ladders: Vec<Vec<Level>> = vec![vec![]; scenes.len()];
    for (s, level) in first {
        ladders[s].push(level);
    }
    for l in &mut ladders {
        l.sort_by_key(Level::links);
    }
    let change = |l: &[Level]| match l {
        [.., a, b] => (b.summary.tip_speed_max / a.summary.tip_speed_max - 1.0).abs(),
        _ => f64::NAN,
    };
    let last_doubling: Vec<f64> = ladders.iter().map(|l| change(l)).collect();
    let more: Vec<usize> = (0..scenes.len())
        .filter(|&s| last_doubling[s] > o.go_on)
        .collect();
    let extra: Vec<(usize, Level)> = more
        .par_iter()
        .map(|&s| run(s, o.finest))
        .collect::<Result<Vec<_>, String>>()?;
    let mut final_change = last_doubling.clone();
    for (s, level) in extra {
        ladders[s].push(level);
        final_change[s] = change(&ladders[s]);
    }

    let mut notes = notes.into_inner().unwrap_or_default();
    let mut csv = format!("{COLUMNS}\n");
    let mut summary = String::from(
        "scene,reference_links,last_doubling_change,n_vmax_1pct,n_vmax_0.1pct,n_path_1pct,\
         n_path_0.1pct,n_vmax_and_tip_end_1pct,n_vmax_and_tip_end_0.1pct,total_mass,\
         bending_viscosity,scaling\n",
    );
    let cell = |n: Option<usize>| n.map_or("none".to_string(), |n| n.to_string());
    let [lo, hi] = o.tols;
    for (s, ladder) in ladders.iter().enumerate() {
        let (name, scene) = &scenes[s];
        let Some(reference) = ladder.last() else {
            return Err(format!("{name}: an empty ladder"));
        };
        csv.push_str(&rows(name, ladder));
        let by = |tol: f64, k: usize| cell(adequate(ladder, tol)[k]);
        // The continuum held fixed: the scene's own chain.
        let base = scene.chain().map_err(|e| e.to_string())?;
        let cells = [
            name.to_string(),
            reference.links().to_string(),
            num(final_change[s]),
            by(lo, 0),
            by(hi, 0),
            by(lo, 1),
            by(hi, 1),
            by(lo, 2),
            by(hi, 2),
            num(base.total_mass()),
            num(base.damping() * base.rod_length()),
            text(SCALING),
        ];
        summary.push_str(&cells.join(","));
        summary.push('\n');
        notes.push(format!(
            "{name}: n = {} (1%), {} (0.1%); path: {}, {}",
            by(lo, 0),
            by(hi, 0),
            by(lo, 1),
            by(hi, 1),
        ));
    }
    Ok((csv, summary, notes))
}
