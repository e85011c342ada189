#!/usr/bin/python3
"""Reference timing: the 500-speed dynamic-mesh sweep of geardyn, done with scipy.integrate.solve_ivp.

Same model as src/geardyn/gear/dynamic_mesh.hpp (docs/theory.md §13) and the same case as the C++ test
DynamicMesh.FiveHundredSpeedSweep (tests/gear_dynamics/dynamic_mesh_test.cpp):

    m x'' + c x' + k(t) x H(x) = F_s,   m = 1 kg, F_s = 1000 N, zeta = 0.05,
    k = 3.2e8 N/m over the first 0.6 of each mesh period, 2.0e8 N/m for the rest,
    500 mesh frequencies from 0.1 f_n to 3.0 f_n, swept up (and down with --both), each speed
    starting from the previous speed's steady state.

Same steady-state criterion: the scaled change of the Poincare point after p mesh cycles,
sqrt((dx/x_s)^2 + (dv/(omega x_s))^2) < tol, x_s = F_s/k_mean, for the smallest p <= 8 (period-p
subharmonics; plain time marching: scipy has no monodromy to accelerate with). The integrator never steps across a discontinuity: every cycle is
split at the stiffness step, and contact loss / re-contact (x = 0) are terminal events after
which the integration restarts in the other contact state, as the C++ solver does.

Not part of any test. Run:
    /usr/bin/python3 bench/scipy_mesh_sweep.py [--speeds 500] [--both] [--tol 1e-8] [--rtol 1e-10]
Prints the wall time and a few rows to compare with the C++ sweep.
"""
import argparse
import math
import time

import numpy as np
from scipy.integrate import solve_ivp

M = 1.0
FORCE = 1000.0
K_HIGH, K_LOW, DOUBLE_CONTACT = 3.2e8, 2.0e8, 0.6
ZETA = 0.05
K_MEAN = DOUBLE_CONTACT * K_HIGH + (1.0 - DOUBLE_CONTACT) * K_LOW
C = 2.0 * ZETA * math.sqrt(K_MEAN * M)
OMEGA = math.sqrt(K_MEAN / M)
FN = OMEGA / (2.0 * math.pi)
X_S = FORCE / K_MEAN


def integrate_segment(t0, t1, y, k, contact, rtol, record):
    """Integrates from t0 to t1 with stiffness k, switching contact state at x = 0."""
    t = t0
    while t < t1:
        def rhs(_t, s, kk=k if contact else 0.0):
            return [s[1], (FORCE - C * s[1] - kk * s[0]) / M]

        def crossing(_t, s):
            return s[0]

        crossing.terminal = True
        # Leaving contact: x falls through 0; re-contact: x rises through 0.
        crossing.direction = -1 if contact else 1
        sol = solve_ivp(rhs, (t, t1), y, method="DOP853", rtol=rtol, atol=[rtol * X_S, rtol * X_S * OMEGA],
                        events=crossing, max_step=(t1 - t0) / 4.0, dense_output=record is not None)
        if record is not None:
            record.append(sol.sol)
        if sol.status == 1 and len(sol.t_events[0]) > 0 and sol.t_events[0][0] < t1:
            t = sol.t_events[0][0]
            y = [0.0, sol.y_events[0][0][1]]
            contact = not contact
        else:
            t = t1
            y = list(sol.y[:, -1])
    return y, contact


def one_cycle(y, period, rtol, record=None):
    contact = y[0] > 0.0 or (y[0] == 0.0 and y[1] >= 0.0)
    y, contact = integrate_segment(0.0, DOUBLE_CONTACT * period, y, K_HIGH, contact, rtol, record)
    y, contact = integrate_segment(DOUBLE_CONTACT * period, period, y, K_LOW, contact, rtol, record)
    return y


def scaled(a, b):
    return math.hypot((a[0] - b[0]) / X_S, (a[1] - b[1]) / (X_S * OMEGA))


def steady_state(fm, y0, tol, rtol, max_cycles, max_period=8):
    """Marches until the Poincare point repeats after p <= max_period cycles (as the C++ solver)."""
    period = 1.0 / fm
    history = [list(y0)]
    found = 0
    for cycle in range(1, max_cycles + 1):
        history.append(one_cycle(history[-1], period, rtol))
        change = scaled(history[-1], history[-2])
        if change < tol:
            found = 1
            break
        # Period p > 1 only if the one-cycle changes repeat too (not a converging spiral).
        for p in range(2, min(max_period, len(history) - 2) + 1):
            if scaled(history[-1], history[-1 - p]) < tol:
                earlier = scaled(history[-1 - p], history[-2 - p])
                if change > 100 * tol and abs(change - earlier) <= 1e-3 * change:
                    found = p
                    break
        if found:
            break
        history = history[-(max_period + 2):]
    y = history[-1]
    # Record the steady orbit (found cycles) densely for the statistics.
    cycles = max(found, 1)
    xs = []
    start = list(y)
    for _ in range(cycles):
        pieces = []
        start = one_cycle(start, period, rtol, pieces)
        t = np.linspace(0.0, period, 2001)
        x = np.empty_like(t)
        for piece in pieces:
            inside = (t >= piece.t_min) & (t <= piece.t_max)
            x[inside] = piece(t[inside])[0]
        xs.append(x)
    t = np.linspace(0.0, period, 2001)
    mean = sum(np.trapz(x, t) for x in xs) / (cycles * period)
    mean_square = sum(np.trapz(x * x, t) for x in xs) / (cycles * period)
    rms = math.sqrt(max(0.0, mean_square - mean * mean))
    return y, cycle, mean, rms, max(x.max() for x in xs), found


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--speeds", type=int, default=500)
    parser.add_argument("--both", action="store_true", help="sweep up and down (1000 solves)")
    parser.add_argument("--tol", type=float, default=1e-8, help="Poincare change tolerance")
    parser.add_argument("--rtol", type=float, default=1e-10)
    parser.add_argument("--max-cycles", type=int, default=20000)
    args = parser.parse_args()

    freqs = FN * (0.1 + 2.9 * np.arange(args.speeds) / (args.speeds - 1))
    sweeps = [("up", freqs)] + ([("down", freqs[::-1])] if args.both else [])
    start = time.perf_counter()
    total_cycles = 0
    rows = []
    for name, fs in sweeps:
        y = [FORCE / K_HIGH, 0.0]
        for fm in fs:
            y, cycles, mean, rms, xmax, ok = steady_state(fm, y, args.tol, args.rtol, args.max_cycles)
            total_cycles += cycles
            rows.append((name, fm / FN, mean, rms, xmax, cycles, ok))
    elapsed = time.perf_counter() - start
    solves = len(rows)
    print(f"scipy solve_ivp (DOP853, rtol {args.rtol:g}), tol {args.tol:g}: {solves} solves in {elapsed:.1f} s "
          f"({1e3 * elapsed / solves:.1f} ms per speed, {total_cycles} mesh cycles)")
    print("sweep  f_m/f_n  dte_mean_m   dte_rms_m    dte_max_m    cycles period (0: not converged)")
    for r in rows[:: max(1, solves // 12)]:
        print(f"{r[0]:5s}  {r[1]:7.4f}  {r[2]:.6e} {r[3]:.6e} {r[4]:.6e} {r[5]:6d} {r[6]}")


if __name__ == "__main__":
    main()
