"""Which method for which question: the README's table, measured.

For each question, one scene and one quantity with its accuracy target;
each method climbs a ladder (rtol 1e-3, 1e-4, ..., 1e-12; RK4 a ladder of
steps) until its error against a reference is within the target, and the
cell is that run's cost: the median wall time of three repeats
(`wall_seconds`, the solve alone) and its accepted steps, or why it never
got there. The reference is DOP853 at a tight tolerance, checked by a
second method; both and their agreement are printed.

    pip install ./crates/falling-chain-py      # the module, once
    python bench/which_method.py [QUESTION ...] [--methods m1,m2] > table.md

Questions (docs/speed.md, "Which method for which question"):

* motion: the U of Fig. 7b (`scenes/span-d3.toml`, n = 50) to t = 4.157,
  the tip's end (over L) and its largest speed (relative), to 1e-6;
* forces: the same U as a stiff rope (EA = 1e7, 5% axial damping, issue
  49's steel rope ten times softer) to t = 3.2, the support's peak force
  at the snap (the summary's `pivot_force_max`, tracked at every step; a
  run with `forces_resolved = false` has not answered), relative, to 1e-3;
* undamped: the horizontal chain of Fig. 3 (n = 25, r = 0) to t = 100,
  the energy balance error over the energy scale, to 1e-6;
* stiff: the stiff rope (`scenes/stiff-rope.toml`, n = 100, r = 1,
  gamma = 1389) to t = 4, the tip as for motion, to 1e-6;
* contact: the U onto a floor (`scenes/span-d3-floor.toml`) to t = 1.8,
  0.35 after its first contact (before the landings make single runs
  irreproducible), the tip's end over L, to 1e-4.

Every number is printed with the command that makes it; the run takes
about 10 minutes on two cores.
"""

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

import falling_chain as fc

ROOT = Path(__file__).resolve().parents[1]
RTOLS = [10.0**-k for k in range(3, 13)]
RK4_DTS = [1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5]
METHODS = ["rk4", "dopri5", "dop853", "bdf", "bdf-dense", "gen-alpha", "auto"]
# The longest a ladder may spend on one method (seconds of wall time).
LADDER_BUDGET = 120.0


def scene(name, **keys):
    s = fc.Scene.load(str(ROOT / "scenes" / f"{name}.toml"))
    return s.set(keys) if keys else s


def tip_error(run, ref, length):
    a, b = run.summary, ref.summary
    end = math.hypot(a["tip_end"][0] - b["tip_end"][0], a["tip_end"][1] - b["tip_end"][1]) / length
    vmax = abs(a["tip_speed_max"] / b["tip_speed_max"] - 1)
    return max(end, vmax)


def peak_pivot_error(run, ref):
    """The run's largest support force (tracked at every step, the summary's
    `pivot_force_max`) against the reference's; a run that says it did not
    resolve its forces (`forces_resolved = false`) has not answered."""
    if run.summary.get("forces_resolved") is False:
        return math.inf
    return abs(run.summary["pivot_force_max"] / ref.summary["pivot_force_max"] - 1)


QUESTIONS = {
    "motion": dict(
        scene=lambda: scene("span-d3"),
        flags={},
        error=lambda run, ref: tip_error(run, ref, 6.0),
        target=1e-6,
        what="max(|tip end - ref| / L, |v_max / ref - 1|)",
    ),
    "forces": dict(
        scene=lambda: scene("span-d3", **{"chain.axial_stiffness": 1e7, "chain.axial_damping": 49.0,
                                           "run.t_end": 3.2}),
        flags={},
        error=peak_pivot_error,
        target=1e-3,
        # Issue 49's converged value was DOPRI5 at rtol 1e-9.
        reference=("dop853", 1e-10, "dopri5", 1e-9),
        what="|pivot_force_max / ref - 1| (the peak tracked at every step), forces_resolved",
    ),
    "undamped": dict(
        scene=lambda: scene("horizontal-undamped", **{"run.t_end": 100.0, "run.output_dt": 1.0}),
        flags={},
        error=lambda run, ref: run.summary["energy_balance_error"] / run.summary["energy_scale"],
        target=1e-6,
        what="max |E + W - E(0)| / (M g L) over every step",
    ),
    "stiff": dict(
        scene=lambda: scene("stiff-rope"),
        flags={},
        error=lambda run, ref: tip_error(run, ref, 6.0),
        target=1e-6,
        what="max(|tip end - ref| / L, |v_max / ref - 1|)",
    ),
    "contact": dict(
        scene=lambda: scene("span-d3-floor", **{"run.t_end": 1.8}),
        flags={},
        error=lambda run, ref: math.hypot(*(np.array(run.summary["tip_end"]) - ref.summary["tip_end"])) / 6.0,
        target=1e-4,
        what="|tip end - ref| / L",
    ),
}


def simulate(s, method, knob, flags):
    kw = dict(flags)
    if method == "rk4":
        kw["dt"] = knob
    else:
        kw["rtol"] = knob
        kw["atol"] = knob / 100
    return fc.simulate(s, method=method, **kw)


def reference(q):
    s = q["scene"]()
    m1, r1, m2, r2 = q.get("reference", ("dop853", 1e-12, "dopri5", 1e-11))
    ref = simulate(s, m1, r1, q["flags"])
    check = simulate(s, m2, r2, q["flags"])
    agree = q["error"](check, ref)
    print(f"  reference {m1} rtol {r1:g}: {ref.summary['status']}, {ref.summary['steps']} steps, "
          f"{ref.summary['wall_seconds']:.2f} s; {m2} rtol {r2:g} agrees to {agree:.1e}", file=sys.stderr)
    return s, ref, agree


def cell(q, s, ref, method):
    knobs = RK4_DTS if method == "rk4" else RTOLS
    spent = 0.0
    tried = []
    for knob in knobs:
        try:
            run = simulate(s, method, knob, q["flags"])
        except ValueError as e:
            return f"refused: {str(e).split(':')[0]}", None
        spent += run.summary["wall_seconds"]
        if run.status != "ok":
            tried.append(f"{knob:g}: {run.status}")
            if spent > LADDER_BUDGET:
                break
            continue
        err = q["error"](run, ref)
        tried.append(f"{knob:g}: {err:.1e}")
        if err <= q["target"]:
            walls = [run.summary["wall_seconds"]] + [
                simulate(s, method, knob, q["flags"]).summary["wall_seconds"] for _ in range(2)]
            return (f"{fmt_time(statistics.median(walls))} ({'dt' if method == 'rk4' else 'rtol'} "
                    f"{knob:g}, {run.summary['steps']} steps)"), tried
        if spent > LADDER_BUDGET:
            break
    last = tried[-1] if tried else "nothing ran"
    if spent > LADDER_BUDGET and knob != knobs[-1]:
        return f"not reached in its {LADDER_BUDGET:.0f} s ladder ({last})", tried
    return f"not reached ({last})", tried


def fmt_time(seconds):
    if seconds < 1.0:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds:.3g} s"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("questions", nargs="*", default=list(QUESTIONS))
    ap.add_argument("--methods", default=",".join(METHODS))
    args = ap.parse_args()
    methods = args.methods.split(",")
    rows = {m: {} for m in methods}
    for name in args.questions:
        q = QUESTIONS[name]
        print(f"{name}: error {q['what']} <= {q['target']:g}", file=sys.stderr)
        start = time.time()
        s, ref, agree = reference(q)
        for m in methods:
            text, tried = cell(q, s, ref, m)
            rows[m][name] = text
            print(f"  {m}: {text}; ladder {tried}", file=sys.stderr)
        print(f"  ({time.time() - start:.0f} s)", file=sys.stderr)
    print("| method | " + " | ".join(args.questions) + " |")
    print("|---|" + "---|" * len(args.questions))
    for m in methods:
        print(f"| `{m}` | " + " | ".join(rows[m][q] for q in args.questions) + " |")


if __name__ == "__main__":
    main()
