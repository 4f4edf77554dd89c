#!/usr/bin/env python3
"""scipy's DOP853 on the falling-chain scene span-d3 (n = 50, t_end = 8).

The model is written here in numpy as a scipy user would write it: a dense
mass matrix A_ij = mt_ij cos(phi_i - phi_j) and np.linalg.solve per RHS call.
The initial angles (the exact discrete catenary with the free end at
P1 = (3, 0)) come from the Rust CLI, not from Python.

    python3 bench/scipy_dop853.py [--rtol 1e-6,1e-8] [--repeats 3]
                                  [--reference X,Y] [--init-csv FILE]
                                  [--no-selfcheck]

Only solve_ivp is timed (time.perf_counter); see bench/README.md for timing
the whole process from outside.
"""

import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.integrate import solve_ivp

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Scene "span-d3" as benchmarked (scenes/span-d3.toml, links = 50, t_end = 8).
L = 6.0          # total length
N = 50           # rods
M = 0.2          # mass of one rod
G = 1.0          # gravity, along -y
R = 5e-4         # joint friction between rods
P0 = np.array([0.0, 0.0])
P1 = np.array([3.0, 0.0])
T_END = 8.0
SCENE = os.path.join(ROOT, "scenes", "span-d3.toml")
CLI = os.path.join(ROOT, "target", "release", "falling-chain")


# ---------------------------------------------------------------- initial state

def initial_angles_from_cli(cli, init_csv=None):
    """phi_1..phi_n at t = 0, read from the CLI's CSV (first row).

    With init_csv, read that file (a previous `--out` of the same command)
    instead of running the CLI.
    """
    if init_csv is None:
        fd, path = tempfile.mkstemp(suffix=".csv")
        os.close(fd)
        try:
            cmd = [cli, "simulate", SCENE,
                   "--set", f"chain.links={N}",
                   "--set", f"run.t_end={T_END:g}",
                   "--set", f"run.output_dt={T_END:g}",
                   "--out", path]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            return read_first_row(path)
        finally:
            os.unlink(path)
    return read_first_row(init_csv)


def read_first_row(path):
    with open(path, newline="") as f:
        rows = csv.reader(f)
        header = next(rows)
        first = next(rows)
    cols = {name: k for k, name in enumerate(header)}
    names = [f"phi_{i}" for i in range(1, N + 1)]
    missing = [nm for nm in names if nm not in cols]
    if missing:
        sys.exit(f"{path}: no angle columns {missing[:3]}... (header: {header[:10]}...)")
    if float(first[cols["t"]]) != 0.0:
        sys.exit(f"{path}: first row is not t = 0")
    phi = np.array([float(first[cols[nm]]) for nm in names])
    extra = {k: float(first[cols[k]]) for k in ("tip_x", "tip_y", "energy") if k in cols}
    return phi, extra


# ---------------------------------------------------------------- the model

def make_model(n=N, length=L, m=M, g=G, r=R):
    l = length / n
    i = np.arange(1, n + 1)
    mt = n - np.maximum.outer(i, i) + 0.5          # i != j
    np.fill_diagonal(mt, n - i + 1.0 / 3.0)          # i == j
    q = n - i + 0.5
    gl = g / l
    gamma = r / (m * l * l)

    def rhs(t, y):
        phi = y[:n]
        w = y[n:]
        d = np.subtract.outer(phi, phi)
        a = mt * np.cos(d)
        ms = mt * np.sin(d)
        dw = np.diff(w)                              # w_{i+1} - w_i
        fric = np.zeros(n)
        fric[:-1] += dw
        fric[1:] -= dw
        b = -ms @ (w * w) - gl * q * np.cos(phi) + gamma * fric
        return np.concatenate((w, np.linalg.solve(a, b)))

    def energy(y):
        phi = y[:n]
        w = y[n:]
        a = mt * np.cos(np.subtract.outer(phi, phi))
        return 0.5 * m * l * l * (w @ a @ w) + m * g * l * (q @ np.sin(phi))

    def tip(y):
        phi = y[:n]
        return P0 + l * np.array([np.cos(phi).sum(), np.sin(phi).sum()])

    return rhs, energy, tip


# ---------------------------------------------------------------- runs

def self_check(phi0, extra):
    """Energy conservation with r = 0 over a short DOP853 run; start values vs CLI."""
    y0 = np.concatenate((phi0, np.zeros(N)))
    rhs0, energy0, tip0 = make_model(r=0.0)
    t_chk = 2.0
    sol = solve_ivp(rhs0, (0.0, t_chk), y0, method="DOP853", rtol=1e-10, atol=1e-12,
                    t_eval=np.linspace(0.0, t_chk, 41))
    e = np.array([energy0(sol.y[:, k]) for k in range(sol.y.shape[1])])
    e0 = e[0]
    drift = np.max(np.abs(e - e0)) / abs(e0)
    print(f"self-check (r = 0, DOP853 rtol 1e-10 to t = {t_chk:g}, {sol.nfev} RHS): "
          f"E0 = {e0:.12f}, max |E - E0| / |E0| = {drift:.2e}  "
          f"[{'ok' if drift < 1e-6 else 'FAIL'}]")
    tip_start = tip0(y0)
    if "energy" in extra:
        print(f"  start vs CLI: E0 - E_cli = {e0 - extra['energy']:.2e}, "
              f"|tip0 - tip_cli| = {np.hypot(tip_start[0] - extra['tip_x'], tip_start[1] - extra['tip_y']):.2e}, "
              f"|tip0 - P1| = {np.hypot(*(tip_start - P1)):.2e}")
    return drift


def run(rhs, y0, rtol, repeats):
    walls = []
    sol = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        sol = solve_ivp(rhs, (0.0, T_END), y0, method="DOP853", rtol=rtol, atol=rtol / 100)
        walls.append(time.perf_counter() - t0)
        if not sol.success:
            sys.exit(f"solve_ivp failed at rtol {rtol:g}: {sol.message}")
    return sol, statistics.median(walls)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rtol", default="1e-8",
                    help="relative tolerance(s), comma-separated; atol = rtol/100 (default 1e-8)")
    ap.add_argument("--repeats", type=int, default=3,
                    help="solve_ivp runs per rtol; the median wall time is reported (default 3)")
    ap.add_argument("--reference", default=None,
                    help="reference tip X,Y at t = 8 (the CLI's tip_end); prints |tip - ref|")
    ap.add_argument("--cli", default=CLI, help=f"falling-chain binary (default {CLI})")
    ap.add_argument("--init-csv", default=None,
                    help="read the t = 0 angles from this CSV (a saved --out of the CLI) "
                         "instead of running the CLI")
    ap.add_argument("--no-selfcheck", action="store_true", help="skip the energy self-check")
    args = ap.parse_args()

    rtols = [float(s) for s in args.rtol.split(",") if s.strip()]
    ref = None
    if args.reference:
        ref = np.array([float(s) for s in args.reference.split(",")])
        if ref.shape != (2,):
            sys.exit("--reference wants X,Y")
    if args.repeats < 1:
        sys.exit("--repeats must be >= 1")

    phi0, extra = initial_angles_from_cli(args.cli, args.init_csv)
    y0 = np.concatenate((phi0, np.zeros(N)))
    print(f"span-d3: L = {L:g}, n = {N}, m = {M:g}, g = {G:g}, r = {R:g}, "
          f"P0 = ({P0[0]:g}, {P0[1]:g}), P1 = ({P1[0]:g}, {P1[1]:g}), t_end = {T_END:g}")
    if not args.no_selfcheck:
        self_check(phi0, extra)

    rhs, _, tip = make_model()
    head = f"{'rtol':>8} {'tip_x':>20} {'tip_y':>20} {'nfev':>8} {'median_wall_s':>14}"
    if ref is not None:
        head += f" {'|tip-ref|':>10}"
    print(head)
    for rtol in rtols:
        sol, wall = run(rhs, y0, rtol, args.repeats)
        p = tip(sol.y[:, -1])
        line = f"{rtol:>8.0e} {p[0]:>20.15f} {p[1]:>20.15f} {sol.nfev:>8d} {wall:>14.6f}"
        if ref is not None:
            line += f" {np.hypot(*(p - ref)):>10.2e}"
        print(line, flush=True)


if __name__ == "__main__":
    main()
