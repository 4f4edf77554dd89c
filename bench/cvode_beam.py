#!/usr/bin/env python3
"""SUNDIALS CVODE (BDF, through scikit-sundae) on BEAM, the IVP test set's
stiff beam (crates/chain-ode/src/beam.rs has the equations and the
reference), beside falling-chain's `bdf` and `bdf-dense` on the same problem
(`cargo run --release -p chain-ode --example beam -- METHOD RTOL`).

    pip install numpy scipy scikit-sundae
    python3 bench/cvode_beam.py [--rtol 1e-4,1e-6,1e-8]

The right-hand side is the test set's definition written in numpy (one
tridiagonal solve per call); CVODE builds its dense Jacobian by difference
quotients (the BEAM Jacobian is dense: C^-1 couples every segment), with
rtol = atol as in the test set. It prints CVODE's status, its counters and
its largest error in y1, y40, y41, y80 at t = 5 against the reference.
Nothing here is part of the build or the tests.
"""

import argparse
import time

import numpy as np
from scipy.linalg import solveh_banded
from sksundae.cvode import CVODE

N = 40
T_END = 5.0
# The test set's reference at t = 5 (1-based index, value), as in beam.rs.
REFERENCE = [(1, -5.792366591285007e-3), (40, -1.767201761075488e-1),
             (41, 3.747362681329794e-2), (80, 1.186724615113034)]
C_DIAG = np.full(N, 2.0)
C_DIAG[0], C_DIAG[-1] = 1.0, 3.0


def rhs(t, y, yp):
    z, w = y[:N], y[N:]
    phi = 1.5 * np.sin(t) ** 2 if t <= np.pi else 0.0
    left = np.concatenate(([-z[0]], z[:-1]))      # z_0 = -z_1
    right = np.concatenate((z[1:], [z[-1]]))      # z_{n+1} = z_n
    v = N ** 4 * (left - 2.0 * z + right) + N ** 2 * phi * (np.cos(z) + np.sin(z))
    d = z[:-1] - z[1:]                            # z_l - z_{l+1}
    s, c = np.sin(d), np.cos(d)
    # g = D v + w^2, D_{l,l+1} = -sin(z_l - z_{l+1}), D_{l+1,l} = +sin(...)
    g = w * w
    g[:-1] -= s * v[1:]
    g[1:] += s * v[:-1]
    # C u = g, C symmetric positive definite tridiagonal (upper band form).
    ab = np.zeros((2, N))
    ab[0, 1:] = -c
    ab[1] = C_DIAG
    u = solveh_banded(ab, g)
    acc = C_DIAG * v
    acc[:-1] -= c * v[1:] + s * u[1:]
    acc[1:] += s * u[:-1] - c * v[:-1]
    yp[:N] = w
    yp[N:] = acc


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rtol", default="1e-4,1e-6,1e-8")
    args = ap.parse_args()
    for r in [float(x) for x in args.rtol.split(",")]:
        solver = CVODE(rhs, method="BDF", rtol=r, atol=r, linsolver="dense",
                       max_num_steps=10_000_000)
        t0 = time.perf_counter()
        sol = solver.solve(np.array([0.0, T_END]), np.zeros(2 * N))
        wall = time.perf_counter() - t0
        y = sol.y[-1]
        err = max(abs(y[i - 1] - ref) for i, ref in REFERENCE)
        print(f"rtol {r:.0e}: success {sol.success}, t {sol.t[-1]:g}, {sol.nfev} RHS, "
              f"{sol.njev} Jacobians, steps {len(sol.t) - 1}, wall {wall:.2f} s "
              f"(Python RHS included), max error {err:.2e}", flush=True)
        print(f"  {sol.message}")


if __name__ == "__main__":
    main()
