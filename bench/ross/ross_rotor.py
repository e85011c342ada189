"""Runs one case of the comparison rotor in ROSS and prints its timings (one case per process).

The rotor (same in geardyn_models.py): a steel shaft (E 211 GPa, G 81.2 GPa, density 7810 kg/m^3,
ROSS's `steel`) 1.5 m long, 50 mm outer diameter, in N equal Timoshenko elements; two disks from
geometry (70 mm wide, 50 mm bore, 280 mm OD at node int(N/3), 350 mm OD at node int(2N/3)); two
isotropic bearings k = 1e6 N/m at nodes 0 and N (damped c = 100 N s/m for the unbalance case,
undamped for Campbell); unbalance 1e-4 kg m, phase 0, at node int(N/3).

  python3 ross_rotor.py campbell N [OUT.csv]       100 speeds 0..4000 rpm, 6 frequencies
  python3 ross_rotor.py unbalance N [SPEEDS [OUT.csv]]   SPEEDS (1000) from 10 rad/s to 4000 rpm

Needs PYTHONPATH=<bench/ross/shims>:<ROSS checkout>. The warm-up call (one modal analysis) is
not timed, so the "compute" figure is the analysis alone. OUT.csv: the damped natural
frequencies (Campbell) or the complex displacement at the disks (unbalance), for the comparison.
"""
import sys
import time

t_start = time.perf_counter()
import numpy as np  # noqa: E402
import ross as rs  # noqa: E402
from ross.materials import steel  # noqa: E402

IMPORT_S = time.perf_counter() - t_start
TOP_SPEED = 4000.0 * np.pi / 30.0  # rad/s


def build(n_el, c):
    shaft = [rs.ShaftElement(L=1.5 / n_el, material=steel, n=i, idl=0.0, odl=0.05)
             for i in range(n_el)]
    disks = [rs.DiskElement.from_geometry(n=int(n_el / 3), material=steel, width=0.07,
                                          i_d=0.05, o_d=0.28),
             rs.DiskElement.from_geometry(n=int(2 * n_el / 3), material=steel, width=0.07,
                                          i_d=0.05, o_d=0.35)]
    bearings = [rs.BearingElement(n=node, kxx=1e6, kyy=1e6, cxx=c, cyy=c) for node in (0, n_el)]
    return rs.Rotor(shaft, disks, bearings)


def timed(f):
    """Wall-clock seconds of f(); the CPU seconds of the process go to CPU_SECONDS."""
    t, c = time.perf_counter(), time.process_time()
    value = f()
    CPU_SECONDS.append(time.process_time() - c)
    return value, time.perf_counter() - t


CPU_SECONDS = []  # per timed step: on a loaded machine CPU time is the fairer comparison


def campbell(n_el, out):
    rotor, t_build = timed(lambda: build(n_el, 0.0))
    _, t_warm = timed(lambda: rotor.run_modal(TOP_SPEED, num_modes=12))
    speeds = np.linspace(0.0, TOP_SPEED, 100)
    result, t_compute = timed(lambda: rotor.run_campbell(speeds, frequencies=6))
    if out:
        wd = np.asarray(result.wd)
        header = "speed_rpm," + ",".join(f"wd{i + 1}_rad_s" for i in range(wd.shape[1]))
        np.savetxt(out, np.column_stack([speeds * 30.0 / np.pi, wd]), delimiter=",",
                   header=header, comments="")
    return t_build, t_warm, t_compute


def unbalance(n_el, n_speeds, out):
    rotor, t_build = timed(lambda: build(n_el, 100.0))
    _, t_warm = timed(lambda: rotor.run_modal(0.0))
    speeds = np.linspace(10.0, TOP_SPEED, n_speeds)
    node = int(n_el / 3)
    result, t_compute = timed(lambda: rotor.run_unbalance_response(
        node=node, unbalance_magnitude=1e-4, unbalance_phase=0.0, frequency=speeds))
    if out:
        n_dof = rotor.number_dof
        columns, names = [speeds * 30.0 / np.pi], ["speed_rpm"]
        for label, at in (("d0", int(n_el / 3)), ("d1", int(2 * n_el / 3))):
            for j, axis in enumerate("xy"):
                z = result.forced_resp[n_dof * at + j, :]
                columns += [z.real, z.imag]
                names += [f"{label}_{axis}_re", f"{label}_{axis}_im"]
        np.savetxt(out, np.column_stack(columns), delimiter=",", header=",".join(names),
                   comments="")
    return t_build, t_warm, t_compute


def main(argv):
    kind, n_el = argv[1], int(argv[2])
    if kind == "campbell":
        times = campbell(n_el, argv[3] if len(argv) > 3 else None)
    elif kind == "unbalance":
        n_speeds = int(argv[3]) if len(argv) > 3 else 1000
        times = unbalance(n_el, n_speeds, argv[4] if len(argv) > 4 else None)
    else:
        raise SystemExit(__doc__)
    print(f"ROSS {kind} n_el={n_el} import={IMPORT_S:.3f}s build={times[0]:.3f}s "
          f"warmup={times[1]:.3f}s compute={times[2]:.3f}s compute_cpu={CPU_SECONDS[-1]:.3f}s",
          flush=True)


if __name__ == "__main__":
    main(sys.argv)
