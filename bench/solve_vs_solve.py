#!/usr/bin/env python3
"""Solve against solve at matched tip error: scipy's solve_ivp (DOP853, the
numpy model of bench/scipy_dop853.py) against falling-chain's own
`wall_seconds`, on span-d3 (n = 50, t_end = 8).

    python3 bench/solve_vs_solve.py [--scipy-rtol 1e-6,1e-8,1e-10]
        [--ours-rtol 1e-5,...,1e-12] [--method dop853] [--repeats 5]

For each scipy tolerance it prints scipy's tip error at t = 8 and its median
solve_ivp time, then the time our method needs for the same error: our
median `wall_seconds` interpolated linearly in log(error)-log(time) between
the two of our runs that bracket that error (never extrapolated; "-" when
none do). Both sides use atol = rtol / 100. The reference tip is the CLI's
DOPRI5 at rtol 1e-13, atol 1e-15. Nothing here is part of the build or the
tests.
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scipy_dop853 as sp  # noqa: E402  (the same model and initial state)


def cli_json(cli, method, rtol, atol):
    cmd = [cli, "simulate", sp.SCENE, "--set", f"chain.links={sp.N}",
           "--set", f"run.t_end={sp.T_END:g}", "--method", method,
           "--rtol", repr(rtol), "--atol", repr(atol), "--json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def interpolate(points, err):
    """Our wall time at `err` from (error, wall) points, log-log, bracketed."""
    pts = sorted(points)
    for (e0, w0), (e1, w1) in zip(pts, pts[1:]):
        if e0 <= err <= e1 and e0 > 0 and e1 > e0:
            s = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(w0) + s * (math.log(w1) - math.log(w0)))
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scipy-rtol", default="1e-6,1e-8,1e-10")
    ap.add_argument("--ours-rtol", default="1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12")
    ap.add_argument("--method", default="dop853")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--cli", default=sp.CLI)
    args = ap.parse_args()
    if args.repeats < 1:
        sys.exit("--repeats must be >= 1")

    ref = np.array(cli_json(args.cli, "dopri5", 1e-13, 1e-15)["tip_end"])
    # Round robin over the tolerances, so that a busy spell of the machine
    # spreads over all of them instead of landing on one.
    rtols = [float(s) for s in args.ours_rtol.split(",")]
    runs = {r: [] for r in rtols}
    for _ in range(args.repeats):
        for r in rtols:
            runs[r].append(cli_json(args.cli, args.method, r, r / 100))
    ours = []
    for r in rtols:
        err = float(np.hypot(*(np.array(runs[r][0]["tip_end"]) - ref)))
        wall = statistics.median(x["wall_seconds"] for x in runs[r])
        ours.append((err, wall))
        print(f"ours {args.method:7} rtol {r:7.0e}: tip error {err:.2e}, "
              f"{runs[r][0]['rhs_evals']:6d} RHS, wall_seconds {wall * 1e3:8.3f} ms "
              f"(median of {args.repeats})", flush=True)

    phi0, _ = sp.initial_angles_from_cli(args.cli)
    y0 = np.concatenate((phi0, np.zeros(sp.N)))
    rhs, _, tip = sp.make_model()
    print(f"{'scipy rtol':>10} {'tip error':>10} {'nfev':>7} {'solve_ivp ms':>13} "
          f"{'ours ms':>9} {'ratio':>7}")
    for r in [float(s) for s in args.scipy_rtol.split(",")]:
        sol, wall = sp.run(rhs, y0, r, args.repeats)
        err = float(np.hypot(*(tip(sol.y[:, -1]) - ref)))
        mine = interpolate(ours, err)
        ratio = "-" if mine is None else f"{wall / mine:7.1f}"
        mine_txt = "-" if mine is None else f"{mine * 1e3:9.3f}"
        print(f"{r:>10.0e} {err:>10.2e} {sol.nfev:>7d} {wall * 1e3:>13.1f} {mine_txt:>9} "
              f"{ratio:>7}",
              flush=True)


if __name__ == "__main__":
    main()
