//! The tables of the `viewer-peak` figure (a screenshot of `falling-chain
//! view`'s page at a run's peak tip speed) and the page's run read back
//! from them.
//!
//! [`tables`] gives the trajectory as `simulate --out` writes it and the
//! summary fields the page shows (`key,value`, values as JSON; a point is
//! two rows, `<key>_x` and `<key>_y`, so that no cell holds a comma; no wall
//! time, so the data reproduce to the byte). A JSON string, `"ok"`, is a
//! quoted cell to the CSV reader, which gives its text: read back as that
//! string. [`view_run`] reads them back
//! into the page's [`ViewRun`] (the trajectory as `view --from` reads it)
//! with the time of the peak tip speed.

use std::path::Path;

use chain_ode::Trajectory;
use serde_json::Value;

use fc_csv::table::Table;
use fc_scene::summary::RunSummary;
use fc_viewer::{ViewRun, DATA_BUDGET_BYTES};

/// The summary fields the page's table shows.
pub const SHOWN: [&str; 11] = [
    "status",
    "method",
    "model",
    "links",
    "steps",
    "tip_speed_max",
    "t_tip_speed_max",
    "t_reached",
    "t_failed",
    "tip_end",
    "energy_balance_error",
];

/// The trajectory's CSV (as `simulate --out`) and its shown summary fields
/// (`key,value`).
pub fn tables(name: &str, traj: &Trajectory) -> Result<(String, String), String> {
    let mut csv = Vec::new();
    fc_scene::csv::write_trajectory(&mut csv, traj).map_err(|e| e.to_string())?;
    let csv = String::from_utf8(csv).map_err(|e| e.to_string())?;
    let summary =
        serde_json::to_value(RunSummary::from_trajectory(name, traj)).map_err(|e| e.to_string())?;
    let mut shown = String::from("key,value\n");
    for key in SHOWN {
        match &summary[key] {
            Value::Array(xy) => {
                for (axis, v) in ["x", "y"].iter().zip(xy) {
                    shown.push_str(&format!("{key}_{axis},{v}\n"));
                }
            }
            v => shown.push_str(&format!("{key},{v}\n")),
        }
    }
    Ok((csv, shown))
}

/// The page's run, labelled `label`, from the trajectory file `csv` and
/// the shown summary `summary` (as [`tables`] wrote them), and the time of
/// its peak tip speed.
pub fn view_run(csv: &Path, summary: &Table, label: &str) -> Result<(ViewRun, f64), String> {
    let mut run =
        fc_viewer::run_csv::read_run_csv(csv, DATA_BUDGET_BYTES).map_err(|e| e.to_string())?;
    let mut fields = serde_json::Map::new();
    for (key, value) in summary.strs("key")?.iter().zip(summary.strs("value")?) {
        // A JSON string ("ok") is a quoted CSV cell, read as its text.
        let value: Value =
            serde_json::from_str(value).unwrap_or_else(|_| Value::String(value.to_string()));
        fields.insert((*key).to_string(), value);
    }
    for key in SHOWN {
        if let (Some(x), Some(y)) = (
            fields.remove(&format!("{key}_x")),
            fields.remove(&format!("{key}_y")),
        ) {
            fields.insert(key.to_string(), Value::Array(vec![x, y]));
        }
    }
    let peak = fields["t_tip_speed_max"]
        .as_f64()
        .ok_or("no t_tip_speed_max")?;
    run.label = label.into();
    run.status = fields["status"].as_str().unwrap_or("ok").to_string();
    run.t_failed = fields["t_failed"].as_f64();
    run.summary = Value::Object(fields);
    run.source = None;
    Ok((run, peak))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_reads_back_as_written() {
        let text = "name = \"t\"\n[chain]\nlinks = 10\n[start]\nkind = \"catenary\"\n\
                    p1 = [3, 0]\n[run]\nt_end = 0.5\noutput_dt = 0.05\n";
        let scene = fc_scene::scene::Scene::from_toml_str(text).unwrap();
        let traj = scene.prepare().and_then(|p| p.solve()).unwrap();
        let (csv, shown) = tables("t", &traj).unwrap();
        let dir = std::env::temp_dir().join(format!("viewer-peak-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("run.csv");
        std::fs::write(&path, csv).unwrap();
        let t = Table::parse("shown", &shown).unwrap();
        let back = view_run(&path, &t, "label");
        std::fs::remove_dir_all(&dir).unwrap();
        let (run, peak) = back.unwrap();
        let s = RunSummary::from_trajectory("t", &traj);
        assert_eq!(peak, s.t_tip_speed_max);
        assert_eq!(run.summary["tip_end"][0].as_f64(), Some(s.tip_end[0]));
        assert_eq!(run.label, "label");
    }
}
