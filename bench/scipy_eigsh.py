#!/usr/bin/python3
"""Reference timing: the 30 lowest modes of the benchmark gear sector with scipy's eigsh.

Compares geardyn's shift-invert Lanczos on CHOLMOD (eig::solve_symmetric, the case
BM_SectorModes30 of bench/solid_bench.cpp) with scipy.sparse.linalg.eigsh in shift-invert mode
(ARPACK; the factorisation of K - sigma M is SuperLU's LU via scipy.sparse.linalg.splu), on the
same matrices and the same shift sigma = eig::automatic_shift(K, M).

First write the matrices with the exporter (it also times geardyn on them and stores the
figures and its 30 frequencies in sector.json):
    build-bench/bench/geardyn_export_matrices /tmp/gd_sector
then
    /usr/bin/python3 bench/scipy_eigsh.py /tmp/gd_sector
Prints the scipy wall and CPU time, the ratio to geardyn's, and the largest relative frequency
difference (elastic modes; the six rigid-body modes are compared in absolute terms).
Not part of any test; see docs/performance.md ("Solid components").
"""
import argparse
import json
import math
import os
import time

import numpy as np
import scipy
import scipy.io
import scipy.sparse.linalg as sla


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", help="folder with K.mtx, M.mtx and sector.json")
    parser.add_argument("--tol", type=float, default=1e-10, help="ARPACK tolerance (geardyn: 1e-10)")
    args = parser.parse_args()

    with open(os.path.join(args.folder, "sector.json")) as f:
        meta = json.load(f)
    start = time.perf_counter()
    K = scipy.io.mmread(os.path.join(args.folder, "K.mtx")).tocsc()
    M = scipy.io.mmread(os.path.join(args.folder, "M.mtx")).tocsc()
    print(f"read {K.shape[0]} DOFs, nnz(K) {K.nnz} in {time.perf_counter() - start:.1f} s")
    sigma = meta["sigma"]
    k = meta["n_modes"]

    wall0, cpu0 = time.perf_counter(), time.process_time()
    values, _ = sla.eigsh(K, k=k, M=M, sigma=sigma, which="LM", tol=args.tol)
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0

    f_scipy = np.sqrt(np.maximum(np.sort(values), 0.0)) / (2.0 * math.pi)
    f_geardyn = np.array(meta["geardyn_frequencies_hz"])
    elastic = f_geardyn > 1e-3 * f_geardyn.max()
    rel = np.abs(f_scipy[elastic] - f_geardyn[elastic]) / f_geardyn[elastic]
    rigid = np.abs(f_scipy[~elastic] - f_geardyn[~elastic])
    print(f"scipy {scipy.__version__} eigsh (ARPACK shift-invert, SuperLU), sigma = {sigma:.6g}: "
          f"{wall:.2f} s wall, {cpu:.2f} s CPU")
    print(f"geardyn solve_symmetric (CHOLMOD): {meta['geardyn_seconds']:.2f} s wall, "
          f"{meta['geardyn_cpu_seconds']:.2f} s CPU")
    print(f"ratio scipy / geardyn: {wall / meta['geardyn_seconds']:.2f} (wall), "
          f"{cpu / meta['geardyn_cpu_seconds']:.2f} (CPU)")
    print(f"frequencies: {elastic.sum()} elastic, max relative difference {rel.max():.2e}; "
          f"{(~elastic).sum()} rigid-body, max |f| difference {rigid.max() if rigid.size else 0:.2e} Hz")
    print("mode  geardyn_hz        scipy_hz")
    for i in range(k):
        print(f"{i + 1:4d}  {f_geardyn[i]:16.8f}  {f_scipy[i]:16.8f}")
    if rel.max() > 1e-6:
        print("WARNING: frequencies differ by more than 1e-6")


if __name__ == "__main__":
    main()
