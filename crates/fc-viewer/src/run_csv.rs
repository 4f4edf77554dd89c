//! A run read back from `simulate --out`'s CSV, for `view --from`.
//!
//! The file is `t,tip_x,tip_y,tip_vx,tip_vy,energy,dissipated,phi_1..phi_n`
//! ([`fc_scene::csv::trajectory_header`]), optionally followed by the joint
//! forces `tension_0..tension_n` and then `shear_0..shear_n` (issue
//! "elastic links"). It holds neither the pivot `P0` nor the rod length
//! `l`: both are recovered from the rows, since every row states
//! `tip = P0 + l (sum cos phi_i, sum sin phi_i)`; the least-squares `P0`,
//! `l` over all rows must reproduce every kept row's tip to 1e-6 L, or the
//! file is refused. A chain whose angles never change (one row, or a chain
//! at rest) cannot give `l` and is refused too. Nor does the file say the
//! method, the status or the step count: the page says so, and its
//! maximum tip speed is the largest over the rows.

use std::fs::File;
use std::io::{BufReader, Read as _};
use std::path::Path;

use serde_json::json;

use crate::{check_links, keeps, stride_for, JointForces, ViewRun, MAX_VIEW_LINKS};
use fc_scene::csv::FLOOR_COLUMNS;
use fc_scene::error::echo_path;
use fc_scene::Error;

/// The largest CSV read (bytes): `simulate` keeps its samples within 1 GiB
/// of memory, and their text is about as long.
pub const MAX_RUN_CSV_BYTES: u64 = 2 << 30;

/// The leading columns, in order.
const LEADING: [&str; 7] = [
    "t",
    "tip_x",
    "tip_y",
    "tip_vx",
    "tip_vy",
    "energy",
    "dissipated",
];

/// The columns of one file: n, and which force arrays follow the angles.
struct Columns {
    links: usize,
    tension: bool,
    shear: bool,
}

impl Columns {
    fn count(&self) -> usize {
        LEADING.len()
            + self.links
            + (usize::from(self.tension) + usize::from(self.shear)) * (self.links + 1)
    }
}

/// One parsed row.
struct Row {
    cells: Vec<f64>,
}

impl Row {
    fn t(&self) -> f64 {
        self.cells[0]
    }
    fn tip(&self) -> [f64; 2] {
        [self.cells[1], self.cells[2]]
    }
    fn angles(&self, links: usize) -> &[f64] {
        &self.cells[7..7 + links]
    }
    /// `(sum cos phi_i, sum sin phi_i)`: the tip is `P0 + l` times this.
    fn reach(&self, links: usize) -> [f64; 2] {
        self.angles(links)
            .iter()
            .fold([0.0, 0.0], |[c, s], a| [c + a.cos(), s + a.sin()])
    }
}

/// Reads the run in `path`, thinned to `budget` bytes, labelled by the
/// file's stem. Every error names `--from`.
pub fn read_run_csv(path: &Path, budget: usize) -> Result<ViewRun, Error> {
    let bad = |line: usize, what: String| {
        Error::field(
            "--from",
            format!("'{}' line {line}: {what}", echo_path(path)),
        )
    };
    // Pass 1: the number of rows and the means of the tip and the reach.
    let mut rows = 0usize;
    let mut sums = [0.0f64; 4];
    let columns = for_each_row(path, &mut |_, row, links| {
        let [c, s] = row.reach(links);
        let [x, y] = row.tip();
        for (sum, v) in sums.iter_mut().zip([x, y, c, s]) {
            *sum += v;
        }
        rows += 1;
        Ok(())
    })?;
    let links = columns.links;
    if rows < 2 {
        return Err(bad(
            rows + 2,
            format!("needs at least 2 rows of samples (got {rows})"),
        ));
    }
    let means = sums.map(|s| s / rows as f64);
    let forces = usize::from(columns.tension) + usize::from(columns.shear);
    crate::check_fits("--from", links, forces, false, budget)?;
    let stride = stride_for(rows, links, forces, budget);

    // Pass 2: the centred sums of the least squares, and the kept rows.
    let mut run = ViewRun {
        label: path
            .file_stem()
            .map_or_else(|| "run".into(), |s| s.to_string_lossy().into_owned()),
        summary: serde_json::Value::Null,
        status: "not recorded".into(),
        t_failed: None,
        links,
        rod: 0.0,
        anchor: [0.0, 0.0],
        samples: rows,
        stride,
        t: Vec::new(),
        speed: Vec::new(),
        energy: Vec::new(),
        dissipated: Vec::new(),
        phi: Vec::new(),
        forces: (forces > 0).then(|| JointForces {
            tension: columns.tension.then(Vec::new),
            shear: columns.shear.then(Vec::new),
        }),
        // The CSV's rows are placed from one recovered pivot: fixed.
        pivot: None,
        // A CSV does not hold the rods' lengths: equal rods.
        profile: None,
        source: Some(
            path.file_name()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
        ),
        // A CSV does not hold the floor.
        floor: None,
    };
    let (mut num, mut den) = (0.0f64, 0.0f64);
    let mut k = 0usize;
    let mut tips = Vec::new();
    let mut first_energy = None;
    let mut last: Option<(f64, [f64; 2], f64, f64)> = None;
    let mut fastest = (f64::NEG_INFINITY, 0.0);
    for_each_row(path, &mut |line, row, _| {
        if k >= rows {
            return Err(bad(line, "the file grew while it was read".into()));
        }
        let [c, s] = row.reach(links);
        let [x, y] = row.tip();
        let (dc, ds) = (c - means[2], s - means[3]);
        num += (x - means[0]) * dc + (y - means[1]) * ds;
        den += dc * dc + ds * ds;
        let cells = &row.cells;
        let speed = cells[3].hypot(cells[4]);
        if speed > fastest.0 {
            fastest = (speed, row.t());
        }
        first_energy.get_or_insert(cells[5]);
        last = Some((row.t(), [x, y], cells[5], cells[6]));
        if keeps(k, rows, stride) {
            run.t.push(row.t());
            run.speed.push(speed);
            run.energy.push(cells[5]);
            run.dissipated.push(cells[6]);
            run.phi.extend_from_slice(row.angles(links));
            let mut at = 7 + links;
            if let Some(f) = run.forces.as_mut() {
                for values in [&mut f.tension, &mut f.shear].into_iter().flatten() {
                    values.extend_from_slice(&cells[at..at + links + 1]);
                    at += links + 1;
                }
            }
            tips.push((line, [x, y], [c, s]));
        }
        k += 1;
        Ok(())
    })?;
    let (Some((t_last, tip_end, energy_end, dissipated)), Some(energy_start)) =
        (last, first_energy)
    else {
        return Err(bad(1, "the file changed while it was read".into()));
    };
    if k != rows {
        return Err(bad(k + 1, "the file changed while it was read".into()));
    }
    // The angles must move for the tip to tell the rod length.
    if den <= 1e-20 * rows as f64 * (links * links) as f64 {
        return Err(bad(
            2,
            "the angles never change, so the rod length cannot be recovered from tip_x, tip_y"
                .into(),
        ));
    }
    let rod = num / den;
    let length = rod * links as f64;
    if !(rod.is_finite() && rod > 0.0) {
        return Err(bad(
            2,
            format!(
                "tip_x, tip_y and the angles give no positive rod length (got {})",
                fc_scene::error::number(rod)
            ),
        ));
    }
    let anchor = [means[0] - rod * means[2], means[1] - rod * means[3]];
    for (line, tip, [c, s]) in tips {
        let off = (tip[0] - anchor[0] - rod * c).hypot(tip[1] - anchor[1] - rod * s);
        if off.is_nan() || off > 1e-6 * length {
            return Err(bad(
                line,
                format!(
                    "tip_x, tip_y do not match the angles: off by {off:.3e}, more than 1e-6 of \
                     the chain's length {length:.6} that the rows give"
                ),
            ));
        }
    }
    run.rod = rod;
    run.anchor = anchor;
    run.summary = json!({
        "name": run.label,
        "links": links,
        "t_reached": t_last,
        "energy_start": energy_start,
        "energy_end": energy_end,
        "dissipated": dissipated,
        "tip_end": tip_end,
        "tip_speed_max": fastest.0,
        "t_tip_speed_max": fastest.1,
    });
    Ok(run)
}

/// Opens `path` (a regular file of at most [`MAX_RUN_CSV_BYTES`]), checks
/// its header, and calls `each(line, row, links)` on every row in order
/// (finite numbers, the right count, `t` strictly increasing). The file is
/// read as RFC 4180 CSV by the project's one reader ([`fc_scene::csv::Reader`]).
fn for_each_row(
    path: &Path,
    each: &mut dyn FnMut(usize, &Row, usize) -> Result<(), Error>,
) -> Result<Columns, Error> {
    use fc_scene::csv::{ReadError, Reader, Record};
    let read = |e| Error::read("--from", path, e);
    let bad = |line: usize, what: String| {
        Error::field(
            "--from",
            format!("'{}' line {line}: {what}", echo_path(path)),
        )
    };
    let meta = std::fs::metadata(path).map_err(read)?;
    if !meta.is_file() {
        return Err(read(std::io::Error::other(
            "it is not a regular file (a directory, device, FIFO or socket)",
        )));
    }
    if meta.len() > MAX_RUN_CSV_BYTES {
        return Err(read(std::io::Error::other(format!(
            "larger than {MAX_RUN_CSV_BYTES} bytes (2 GiB)"
        ))));
    }
    let file = File::open(path).map_err(read)?;
    // The widest header of a chain the viewer draws, and one more column.
    let widest = LEADING.len() + MAX_VIEW_LINKS + 2 * (MAX_VIEW_LINKS + 1) + 1;
    let mut reader =
        Reader::new(BufReader::new(file.take(MAX_RUN_CSV_BYTES + 1))).max_cells(widest);
    let csv_error = |e: ReadError| match e {
        ReadError::Io(e) => read(e),
        ReadError::Syntax { line, what } => bad(line, what),
    };
    let mut record = Record::default();
    if !reader.read(&mut record).map_err(csv_error)? {
        return Err(bad(
            1,
            "the file is empty: expected simulate --out's CSV".into(),
        ));
    }
    let names: Vec<&str> = record.iter().collect();
    let columns = parse_header(&names).map_err(|what| bad(record.line(), what))?;
    check_links("--from", columns.links)?;
    let count = columns.count();
    // One cell more than the header's, so that a row's numbers are judged
    // before its count (as far as the header's columns go).
    let mut reader = reader.max_cells(count + 1);
    let mut row = Row {
        cells: Vec::with_capacity(count),
    };
    let mut previous = f64::NEG_INFINITY;
    loop {
        match reader.read(&mut record) {
            Ok(true) => {}
            Ok(false) => break,
            Err(ReadError::Syntax { line, what }) if what.starts_with("more than") => {
                return Err(bad(
                    line,
                    format!("expected {count} cells as in the header (got more)"),
                ))
            }
            Err(e) => return Err(csv_error(e)),
        }
        let line_no = record.line();
        row.cells.clear();
        for cell in record.iter().take(count) {
            match cell.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => row.cells.push(v),
                _ => {
                    return Err(bad(
                        line_no,
                        format!(
                            "column {} is not a finite number (got '{}')",
                            row.cells.len() + 1,
                            fc_scene::error::echo(cell)
                        ),
                    ))
                }
            }
        }
        if record.len() != count {
            return Err(bad(
                line_no,
                format!(
                    "expected {count} cells as in the header (got {})",
                    record.len()
                ),
            ));
        }
        if row.t() <= previous {
            return Err(bad(
                line_no,
                format!(
                    "t must increase from row to row (got {} after {})",
                    fc_scene::error::number(row.t()),
                    fc_scene::error::number(previous)
                ),
            ));
        }
        previous = row.t();
        each(line_no, &row, columns.links)?;
    }
    Ok(columns)
}

/// The columns a header names, or what is wrong with it.
fn parse_header(names: &[&str]) -> Result<Columns, String> {
    let expected = "t,tip_x,tip_y,tip_vx,tip_vy,energy,dissipated,phi_1..phi_n \
                    [,tension_0..tension_n][,shear_0..shear_n] (simulate --out's CSV)";
    if names.len() < LEADING.len() + 1 || names[..LEADING.len()] != LEADING {
        return Err(format!("the header must be {expected}"));
    }
    let rest = &names[LEADING.len()..];
    let links = rest
        .iter()
        .enumerate()
        .take_while(|(i, name)| **name == format!("phi_{}", i + 1))
        .count();
    if links == 0 {
        return Err(format!("the header must be {expected}"));
    }
    let mut at = links;
    if rest.get(at).copied() == Some(FLOOR_COLUMNS[0]) {
        return Err(format!(
            "columns {} are a floor's, and a CSV holds neither the floor's line nor the penalty \
             floor's stretched rods (nor the constraint floor's pile, whose pivot end moves \
             freely): view the scene itself (falling-chain view SCENE.toml draws the chain and \
             its floor)",
            FLOOR_COLUMNS.join(", ")
        ));
    }
    let mut take = |prefix: &str| -> Result<bool, String> {
        if rest.get(at).copied() != Some(format!("{prefix}_0").as_str()) {
            return Ok(false);
        }
        for j in 0..=links {
            let want = format!("{prefix}_{j}");
            if rest.get(at + j).copied() != Some(want.as_str()) {
                return Err(format!(
                    "column {} must be {want} (the {prefix} at joints 0..={links}): the header \
                     must be {expected}",
                    LEADING.len() + at + j + 1
                ));
            }
        }
        at += links + 1;
        Ok(true)
    };
    let tension = take("tension")?;
    let shear = take("shear")?;
    if let Some(extra) = rest.get(at) {
        return Err(format!(
            "unexpected column '{}': the header must be {expected}",
            fc_scene::error::echo(extra)
        ));
    }
    Ok(Columns {
        links,
        tension,
        shear,
    })
}
