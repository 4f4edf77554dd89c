//! Convergence in the number of rods, as a table: each level of a ladder
//! (`converge::run_level`, the continuum held fixed) with its deviation from
//! the finest, and the smallest adequate `n` by each criterion.

use super::format::num;
use crate::converge::{smallest_adequate, Deviation, Level};

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
