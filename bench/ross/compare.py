"""Runs the comparison rotor in ROSS and in geardyn and prints the table of issue #19.

  python3 compare.py --ross /path/to/ross-checkout --geardyn /path/to/build/apps/geardyn/geardyn
                     [--kinds unbalance campbell] [--sizes 6 48 192] [--work DIR] [--reuse-ross]

For each kind and size: writes the geardyn model (geardyn_models.py), runs `geardyn run` and
reads the analysis's run_time_s from manifest.json, runs ross_rotor.py in a fresh Debian python3
(PYTHONPATH = shims + checkout) and reads its compute time, then compares the results: unbalance,
the complex displacement at both disks (x and y) relative to the largest amplitude; Campbell, each
ROSS damped frequency against the nearest geardyn damped frequency at that speed, relative.
ROSS's results do not change with geardyn: --reuse-ross takes them from a previous run in DIR.
Unbalance at 192 elements is not run in ROSS: it keeps three dense n_dof^2 x n_speeds complex
arrays (about 64 GB for 1000 speeds); geardyn still runs, without a ratio.
CPU seconds are printed next to wall seconds: on a shared machine CPU time is the fairer figure.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import geardyn_models  # noqa: E402

ROSS_TOO_BIG = {("unbalance", 192)}


def run_geardyn(binary, model, out):
    start = os.times()
    # A status other than ok (e.g. "unstable") exits non-zero but still writes every result:
    # the table shows the status, and only a missing manifest is an error.
    subprocess.run([binary, "run", "-q", "-o", out, model], check=False, capture_output=True)
    end = os.times()
    analysis = json.load(open(os.path.join(out, "manifest.json")))["analyses"][0]
    cpu = (end.children_user - start.children_user) + (end.children_system - start.children_system)
    return {"compute": analysis["run_time_s"], "status": analysis["status"], "process_cpu": cpu}


def run_ross(checkout, kind, n_el, dump):
    env = dict(os.environ, PYTHONPATH=os.path.join(HERE, "shims") + os.pathsep + checkout)
    args = [sys.executable, os.path.join(HERE, "ross_rotor.py"), kind, str(n_el)]
    args += ["1000", dump] if kind == "unbalance" else [dump]
    line = subprocess.run(args, check=True, env=env, capture_output=True, text=True).stdout
    fields = dict(re.findall(r"(\w+)=([\d.]+)s", line))
    return {"compute": float(fields["compute"]), "compute_cpu": float(fields["compute_cpu"])}


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def unbalance_difference(ross_csv, geardyn_out):
    ross = read_csv(ross_csv)
    ours = read_csv(os.path.join(geardyn_out, "unbalance", "response.csv"))
    worst, scale = 0.0, 0.0
    for r, g in zip(ross, ours):
        for probe in ("d0_x", "d0_y", "d1_x", "d1_y"):
            z = complex(float(r[probe + "_re"]), float(r[probe + "_im"]))
            # geardyn reports amplitude and phase lag: X = A exp(-i lag)
            lag = math.radians(float(g[probe + "_phase_deg"]))
            x = float(g[probe + "_amplitude_m"]) * complex(math.cos(lag), -math.sin(lag))
            worst = max(worst, abs(x - z))
            scale = max(scale, abs(z))
    return worst / scale


def campbell_difference(ross_csv, geardyn_out):
    ross = read_csv(ross_csv)
    ours = read_csv(os.path.join(geardyn_out, "campbell", "campbell.csv"))
    by_speed = {}
    for g in ours:
        by_speed.setdefault(round(float(g["speed_rpm"]), 6), []).append(
            2 * math.pi * float(g["damped_frequency_hz"]))
    worst = 0.0
    for r in ross:
        ours_here = by_speed.get(round(float(r["speed_rpm"]), 6))
        if not ours_here:
            continue
        for key, value in r.items():
            if key.startswith("wd") and float(value) > 0:
                nearest = min(ours_here, key=lambda w: abs(w - float(value)))
                worst = max(worst, abs(nearest - float(value)) / float(value))
    return worst


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--ross", required=True, help="ROSS checkout (commit 631a249a)")
    p.add_argument("--geardyn", required=True, help="the geardyn executable")
    p.add_argument("--kinds", nargs="+", default=["unbalance", "campbell"])
    p.add_argument("--sizes", nargs="+", type=int, default=[6, 48, 192])
    p.add_argument("--work", default="ross_comparison")
    p.add_argument("--reuse-ross", action="store_true")
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    print("| work | elements | ROSS compute (cpu) [s] | geardyn run_time_s (process cpu) [s] | "
          "ratio | "
          "max difference |")
    print("|---|---|---|---|---|---|")
    for kind in a.kinds:
        for n in a.sizes:
            model = geardyn_models.write(a.work, n)[kind]
            out = os.path.join(a.work, f"geardyn_{kind}_{n}")
            ours = run_geardyn(a.geardyn, model, out)
            dump = os.path.join(a.work, f"ross_{kind}_{n}.csv")
            times = os.path.join(a.work, f"ross_{kind}_{n}.json")
            if (kind, n) in ROSS_TOO_BIG:
                print(f"| {kind} | {n} | not run (~64 GB) | {ours['compute']:.4g} "
                      f"({ours['process_cpu']:.4g}) | - | - |")
                continue
            if a.reuse_ross and os.path.exists(times):
                ross = json.load(open(times))
            else:
                ross = run_ross(a.ross, kind, n, dump)
                json.dump(ross, open(times, "w"))
            diff = (unbalance_difference if kind == "unbalance" else campbell_difference)(dump, out)
            status = "" if ours["status"] == "ok" else f" [{ours['status']}]"
            print(f"| {kind} | {n} | {ross['compute']:.4g} ({ross['compute_cpu']:.4g}) | "
                  f"{ours['compute']:.4g} ({ours['process_cpu']:.4g}) | "
                  f"{ross['compute'] / ours['compute']:.0f}x | "
                  f"{diff:.2g}{status} |", flush=True)


if __name__ == "__main__":
    main()
