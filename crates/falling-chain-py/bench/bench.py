"""The two speed targets of the Python module, measured (medians).

1. `simulate` from Python on span d = 3, n = 50, t_end = 8, DOPRI5 at 1e-8
   takes at most 1.1x the Rust run's own `wall_seconds`, plus 1 ms.
2. The Fig. 9 sweep (120 spans from 0.3 to 5.97, DOPRI5 at 1e-8, atol
   1e-10) from Python takes at most 1.2x `falling-chain sweep` on the same
   values (the CLI's process time).

Usage, from the repository's root, with the module installed:

    python crates/falling-chain-py/bench/bench.py [--repeats N] [--cli PATH]

Runs are interleaved (Python, CLI, Python, ...) so that a machine busy with
other work slows both alike; the numbers are still only as quiet as it is.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import falling_chain as fc

ROOT = Path(__file__).resolve().parents[3]
SCENE = ROOT / "scenes" / "span-d3.toml"
PRECISE = dict(method="dopri5", rtol=1e-8, atol=1e-10)
SPANS = "0.3:5.97:120"


def simulate_target(cli, repeats):
    scene = fc.Scene.load(SCENE)
    flags = dict(method="dopri5", rtol=1e-8, t_end=8.0)
    cli_args = [cli, "simulate", SCENE, "--json", "--method", "dopri5", "--rtol=1e-8", "--t-end", "8"]
    fc.simulate(scene, **flags)  # warm up
    py_wall, py_rust, cli_rust = [], [], []
    for _ in range(repeats):
        t = time.perf_counter()
        run = fc.simulate(scene, **flags)
        py_wall.append(time.perf_counter() - t)
        py_rust.append(run.summary["wall_seconds"])
        out = subprocess.run(cli_args, capture_output=True, text=True, check=True)
        cli_rust.append(json.loads(out.stdout)["wall_seconds"])
    m = {k: statistics.median(v) for k, v in
         dict(python=py_wall, same_run=py_rust, cli=cli_rust).items()}
    overhead = statistics.median(w - r for w, r in zip(py_wall, py_rust))
    bound = 1.1 * m["cli"] + 1e-3
    print(f"simulate span-d3, n = 50, t_end = 8, DOPRI5 rtol 1e-8 ({repeats} runs, medians)")
    print(f"  Python simulate() wall         {1e3 * m['python']:8.3f} ms")
    print(f"  its own run's wall_seconds     {1e3 * m['same_run']:8.3f} ms "
          f"(overhead of the binding {1e3 * overhead:.3f} ms)")
    print(f"  CLI run's wall_seconds         {1e3 * m['cli']:8.3f} ms")
    print(f"  target 1.1 x CLI + 1 ms        {1e3 * bound:8.3f} ms: "
          f"{'met' if m['python'] <= bound else 'MISSED'} "
          f"(ratio {m['python'] / m['cli']:.3f}; vs its own run "
          f"{m['python'] / m['same_run']:.3f}, bound {1e3 * (1.1 * m['same_run'] + 1e-3):.3f} ms: "
          f"{'met' if m['python'] <= 1.1 * m['same_run'] + 1e-3 else 'MISSED'})")
    return m["python"] <= bound


def sweep_target(cli, repeats):
    scene = fc.Scene.load(SCENE)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "fig09.csv"
        cli_args = [cli, "sweep", SCENE, "--vary", f"start.p1.0={SPANS}", "--quiet", "--out", out,
                    "--set", "run.method=dopri5", "--set", "run.rtol=1e-8", "--set", "run.atol=1e-10"]
        py, proc = [], []
        for _ in range(repeats):
            t = time.perf_counter()
            cols = fc.sweep(scene, {"start.p1.0": SPANS}, **PRECISE)
            py.append(time.perf_counter() - t)
            t = time.perf_counter()
            subprocess.run(cli_args, check=True, capture_output=True)
            proc.append(time.perf_counter() - t)
    assert len(cols["run"]) == 120
    m_py, m_cli = statistics.median(py), statistics.median(proc)
    print(f"Fig. 9 sweep, 120 spans {SPANS}, DOPRI5 rtol 1e-8 ({repeats} sweeps each, medians, "
          f"{os.cpu_count()} threads)")
    print(f"  Python sweep()                 {m_py:8.3f} s")
    print(f"  falling-chain sweep (process)  {m_cli:8.3f} s")
    print(f"  ratio {m_py / m_cli:.3f} (target <= 1.2): {'met' if m_py <= 1.2 * m_cli else 'MISSED'}")
    return m_py <= 1.2 * m_cli


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=21, help="runs of simulate (sweeps: a quarter)")
    parser.add_argument("--cli", default=os.environ.get(
        "FALLING_CHAIN_CLI", ROOT / "target" / "release" / "falling-chain"))
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    ok = simulate_target(str(args.cli), args.repeats)
    ok &= sweep_target(str(args.cli), max(3, args.repeats // 4))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
