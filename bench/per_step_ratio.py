#!/usr/bin/env python3
"""bdf's wall time per step, one build against another, in the same run.

Runs the `bdf_per_step` example of two builds (OLD and NEW, paths to the
binaries) alternately, one process per run, on the stiffness study's cell
(span d = 3 catenary, damping rate GAMMA, t_end = 1, rtol 1e-6, atol 1e-8,
the block-tridiagonal LU), and prints for each n the median per-step time
of each build, their ratio, and the steps (which must agree: the builds
compute the same steps). Alternating keeps a load that changes during the
run from favouring one build.

Two times per step: `wall`, the run's own wall time (the example's
`per step`), and `cpu`, the process's CPU time (user + system, from the
operating system's accounting of the child) over its steps. On a machine
shared with other jobs the wall time also counts the time the process
waited for a core; the CPU time does not (it includes the set-up before
the run, the same for both builds and a few per cent at n = 200).

    python3 bench/per_step_ratio.py OLD NEW [N1,N2,..] [RUNS] [GAMMA]

Build the old side from a commit into its own directory, e.g.

    git archive COMMIT | tar -x -C /tmp/old
    (cd /tmp/old && CARGO_TARGET_DIR=/tmp/old/target \\
        cargo build --release -p chain-ode --example bdf_per_step)
    cargo build --release -p chain-ode --example bdf_per_step
    python3 bench/per_step_ratio.py /tmp/old/target/release/examples/bdf_per_step \\
        target/release/examples/bdf_per_step 200,800,3200 7
"""

import re
import resource
import statistics
import subprocess
import sys

LINE = re.compile(r"steps (\d+) per step ([0-9.eE+-]+) s")


def per_step(binary, gamma, n):
    """One run of `binary` at `n` rods: (steps, wall seconds per step, CPU
    seconds per step)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(
        [binary, gamma, str(n), "1", "block"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    m = LINE.search(out)
    if m is None:
        sys.exit(f"{binary}: no per-step line in {out!r}")
    steps = int(m.group(1))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return steps, float(m.group(2)), cpu / steps


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    old, new = sys.argv[1], sys.argv[2]
    ns = [int(s) for s in (sys.argv[3] if len(sys.argv) > 3 else "200,800,3200").split(",")]
    runs = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    gamma = sys.argv[5] if len(sys.argv) > 5 else "1e3"
    for n in ns:
        wall = {"old": [], "new": []}
        cpu = {"old": [], "new": []}
        steps = {}
        for _ in range(runs):
            for side, binary in (("old", old), ("new", new)):
                s, w, c = per_step(binary, gamma, n)
                steps.setdefault(side, s)
                wall[side].append(w)
                cpu[side].append(c)
        med = {k: {s: statistics.median(v[s]) for s in v} for k, v in (("wall", wall), ("cpu", cpu))}
        print(
            f"n {n}: steps {steps['old']} / {steps['new']} (median of {runs}) | "
            + " | ".join(
                f"{k} per step old {m['old'] * 1e3:.3f} ms, new {m['new'] * 1e3:.3f} ms, "
                f"old/new {m['old'] / m['new']:.2f}"
                for k, m in med.items()
            ),
            flush=True,
        )


if __name__ == "__main__":
    main()
