//! A trajectory's CSV files (`simulate --out` and `--forces`): one row per
//! sample, written with the cells of the CSV layer ([`fc_csv`], whose
//! reader and cell writer are re-exported here).

use std::io::{self, Write};

use chain_ode::{Model, Trajectory};

pub use fc_csv::{field, records, ReadError, Reader, Record, MAX_CELLS};

/// The header of a trajectory CSV for `links` rods:
/// `t,tip_x,tip_y,tip_vx,tip_vy,energy,dissipated,phi_1,...,phi_n`.
pub fn trajectory_header(links: usize) -> String {
    let mut h = String::from("t,tip_x,tip_y,tip_vx,tip_vy,energy,dissipated");
    for i in 1..=links {
        h.push_str(&format!(",phi_{i}"));
    }
    h
}

/// The columns a trajectory CSV adds after `phi_n` for a scene with a
/// floor: the floor's total force on the chain `floor_x,floor_y` (scene
/// axes, force units, `floor_y > 0` pushing up: what a scale under the
/// chain reads) and `landed_weight`, the weight of what rests on it
/// ([`Trajectory::floor_landed_weight`]).
pub const FLOOR_COLUMNS: [&str; 3] = ["floor_x", "floor_y", "landed_weight"];

/// The header of a trajectory CSV for `links` rods on a floor: the
/// columns of [`trajectory_header`], then [`FLOOR_COLUMNS`].
pub fn trajectory_header_with_floor(links: usize) -> String {
    let mut h = trajectory_header(links);
    for c in FLOOR_COLUMNS {
        h.push(',');
        h.push_str(c);
    }
    h
}

/// Writes the header and one row per sample of `traj`. Numbers are written
/// with `{}`, which round-trips every `f64`. Tip position, tip velocity and
/// energy are computed exactly from each sample's state, for either model
/// (the trajectory's accessors); `phi_i` are the rods' angles. A scene
/// with a floor adds [`FLOOR_COLUMNS`] (a scene without one writes the
/// columns it always did).
pub fn write_trajectory<M: Model, W: Write + ?Sized>(
    w: &mut W,
    traj: &Trajectory<M>,
) -> io::Result<()> {
    let floor = !traj.is_empty() && traj.floor_forces(0).is_some();
    let header = if floor {
        trajectory_header_with_floor(traj.links())
    } else {
        trajectory_header(traj.links())
    };
    writeln!(w, "{header}")?;
    let mut line = String::new();
    for (k, s) in traj.samples().enumerate() {
        let p = traj.tip(k);
        let v = traj.tip_velocity(k);
        let e = traj.energy(k);
        line.clear();
        line.push_str(&format!(
            "{},{},{},{},{},{},{}",
            s.t, p[0], p[1], v[0], v[1], e, s.dissipated
        ));
        for a in s.angles {
            line.push(',');
            line.push_str(&a.to_string());
        }
        if floor {
            let f = traj.floor_force(k).unwrap_or([0.0, 0.0]);
            let landed = traj.floor_landed_weight(k).unwrap_or(0.0);
            line.push_str(&format!(",{},{},{landed}", f[0], f[1]));
        }
        writeln!(w, "{line}")?;
    }
    Ok(())
}

/// The header of a joint-force CSV for `links` rods:
/// `t,tension_0,shear_0,...,tension_n,shear_n` (joint 0 is the pivot,
/// joint n the free tip).
pub fn forces_header(links: usize) -> String {
    let mut h = String::from("t");
    for k in 0..=links {
        h.push_str(&format!(",tension_{k},shear_{k}"));
    }
    h
}

/// The header of a joint-force CSV for `links` rods on a floor: the
/// columns of [`forces_header`], then the floor's force at each joint,
/// `floor_x_0,floor_y_0,...,floor_x_n,floor_y_n` (scene axes, force units,
/// `floor_y > 0` pushing up), then its total `floor_x,floor_y` (what a
/// scale under the chain reads).
pub fn forces_header_with_floor(links: usize) -> String {
    let mut h = forces_header(links);
    for k in 0..=links {
        h.push_str(&format!(",floor_x_{k},floor_y_{k}"));
    }
    h.push_str(",floor_x,floor_y");
    h
}

/// Writes the header and one row per sample of `traj`: its time and the
/// joint forces ([`Trajectory::joint_forces`]: the rigid chain's from its
/// banded DAE, the elastic chain's from its springs), and for a scene with
/// a floor the floor's force per joint and in total
/// ([`forces_header_with_floor`]; [`Trajectory::floor_joint_forces`]).
pub fn write_forces<M: Model, W: Write + ?Sized>(
    w: &mut W,
    traj: &Trajectory<M>,
) -> io::Result<()> {
    let floor = !traj.is_empty() && traj.floor_forces(0).is_some();
    let header = if floor {
        forces_header_with_floor(traj.links())
    } else {
        forces_header(traj.links())
    };
    writeln!(w, "{header}")?;
    let mut line = String::new();
    for k in 0..traj.len() {
        line.clear();
        line.push_str(&traj.times[k].to_string());
        for [tension, shear] in traj.joint_forces(k) {
            line.push_str(&format!(",{tension},{shear}"));
        }
        if let Some(joints) = floor.then(|| traj.floor_joint_forces(k)).flatten() {
            let mut total = [0.0, 0.0];
            for [fx, fy] in joints {
                line.push_str(&format!(",{fx},{fy}"));
                total = [total[0] + fx, total[1] + fy];
            }
            line.push_str(&format!(",{},{}", total[0], total[1]));
        }
        writeln!(w, "{line}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_has_one_angle_column_per_rod() {
        let h = trajectory_header(3);
        assert_eq!(
            h,
            "t,tip_x,tip_y,tip_vx,tip_vy,energy,dissipated,phi_1,phi_2,phi_3"
        );
        assert_eq!(
            trajectory_header_with_floor(2),
            "t,tip_x,tip_y,tip_vx,tip_vy,energy,dissipated,phi_1,phi_2,floor_x,floor_y,landed_weight"
        );
    }
}
