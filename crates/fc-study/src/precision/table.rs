//! The study's table ([`COLUMNS`], [`csv_text`]) and its fastest point
//! per error level ([`fastest`]).

use super::*;
use chain_ode::Method;

use crate::measure::{Measure, Measures};

use fc_batch::shard::Provenance;
use fc_csv::format::{exp, num, text};
use fc_csv::Column::{self, Float, Int, Text};

/// The columns of the table ([`csv_text`]), before the CLI's extra ones,
/// each with its type (the CSV layer's [`Column`]).
pub const COLUMNS: [(&str, Column); 20] = [
    ("scene", Text),
    ("t_eval", Float),
    ("method", Text),
    ("param_name", Text),
    ("param", Float),
    ("status", Text),
    ("t_reached", Float),
    ("steps", Int),
    ("rejected_steps", Int),
    ("rhs_evals", Int),
    ("jacobian_evals", Int),
    ("lu_factorizations", Int),
    ("rhs_equiv", Int),
    ("switched", Int),
    ("err_tip", Float),
    ("err_vmax", Float),
    ("tip_ref_x", Float),
    ("tip_ref_y", Float),
    ("vmax_ref", Float),
    ("note", Text),
];

/// The columns the CLI's table adds before the provenance's
/// ([`fc_batch::shard::COLUMNS`]): the median wall time and the run number
/// (empty for the reference and its checks).
pub const CLI_COLUMNS: [(&str, Column); 2] = [("wall_seconds", Float), ("run", Int)];

/// The table: a header line ([`COLUMNS`]) and a row per point, every
/// number in the formats of [`fc_csv::format`]. With `provenance` (the
/// CLI's), each row also has its median wall time, its run number and the
/// provenance columns: `wall_seconds,run,runs,scene_hash`.
pub fn csv_text(
    scene: &str,
    t_eval: f64,
    reference: &Reference,
    rows: &[Point],
    provenance: Option<&Provenance>,
) -> String {
    let mut csv = fc_csv::header(&COLUMNS);
    if provenance.is_some() {
        csv.push(',');
        csv.push_str(&fc_csv::header(&CLI_COLUMNS));
        csv.push_str(&Provenance::header_suffix());
    }
    // `--measure` other than the tip: each measure's error and reference
    // value, last (the tip's table is unchanged without it). The tip's own
    // error is the larger of `err_tip` and `err_vmax`, already columns: a
    // second `err_tip` would make two columns of one name.
    let measures = rows.first().map_or(Measures::TIP, |r| r.measures);
    let extra: Vec<Measure> = measures
        .list()
        .into_iter()
        .filter(|&m| m != Measure::Tip)
        .collect();
    for m in &extra {
        csv.push_str(&format!(",err_{},{}_ref", m.name(), m.name()));
    }
    csv.push('\n');
    for pt in rows {
        let s = &pt.stats;
        let cells = [
            fc_csv::field(scene).into_owned(),
            num(t_eval),
            pt.method.clone(),
            pt.param_name.to_string(),
            exp(pt.param),
            pt.status.clone(),
            num(pt.t_reached),
            s.steps.to_string(),
            s.rejected_steps.to_string(),
            s.rhs_evals.to_string(),
            s.jacobian_evals.to_string(),
            s.lu_factorizations.to_string(),
            pt.rhs_equiv().to_string(),
            u8::from(pt.switched).to_string(),
            exp(pt.err_tip),
            exp(pt.err_vmax),
            num(reference.tip[0]),
            num(reference.tip[1]),
            num(reference.vmax),
            text(&pt.note),
        ];
        csv.push_str(&cells.join(","));
        if let Some(prov) = provenance {
            let wall = if pt.walls.is_empty() {
                String::new()
            } else {
                exp(crate::median(&pt.walls))
            };
            let run = pt.run.map_or_else(String::new, |r| r.to_string());
            csv.push_str(&format!(",{wall},{run}{}", prov.cells()));
        }
        for &m in &extra {
            csv.push(',');
            csv.push_str(&exp(pt.err_of(m)));
            csv.push(',');
            csv.push_str(&num(reference.values.get(m)));
        }
        csv.push('\n');
    }
    csv
}

/// The fastest method at each error level: for each level `1e-k`, the
/// completed point of a method (not the reference or its checks) whose
/// error is at most it at the least cost (`cost` of the point: wall time
/// or work), as `(level, point)`.
pub fn fastest<'a>(
    rows: &'a [Point],
    levels: &[f64],
    cost: impl Fn(&Point) -> f64,
) -> Vec<(f64, Option<&'a Point>)> {
    levels
        .iter()
        .map(|&level| {
            let best = rows
                .iter()
                .filter(|pt| {
                    pt.run.is_some() || Method::ALL.iter().any(|m| m.as_str() == pt.method)
                })
                .filter(|pt| pt.ok() && pt.err() <= level && cost(pt).is_finite())
                .min_by(|a, b| cost(a).total_cmp(&cost(b)));
            (level, best)
        })
        .collect()
}
