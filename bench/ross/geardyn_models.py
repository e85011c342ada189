"""Writes geardyn model files of the comparison rotor that ross_rotor.py builds in ROSS.

Same rotor, same theory: steel shaft 1.5 m x 50 mm in N Timoshenko elements (shear coefficient:
geardyn's default, Cowper's per element, which is ROSS's `shear_method_calc="cowper"`; rotary
inertia and gyroscopic terms on in both), two disks from geometry (70 mm wide, 50 mm bore,
280 mm OD at node int(N/3), 350 mm OD at node int(2N/3)), bearings k = 1e6 N/m at nodes 0
and N (c = 100 N s/m for unbalance, none for Campbell), unbalance 1e-4 kg m at node int(N/3).

  python3 geardyn_models.py OUT_DIR N [N ...]   writes OUT_DIR/{campbell,unbalance}_N.toml
"""
import math
import os
import sys

MAX_DIVISIONS = 1000  # geardyn's limit per shaft section: longer meshes use equal sections


def sections(n_el):
    count = max(1, math.ceil(n_el / MAX_DIVISIONS))
    if n_el % count:
        raise SystemExit(f"{n_el} elements do not split into {count} equal sections")
    return [(1.5 / count, n_el // count)] * count


def rotor(n_el, damping):
    disk0, disk1 = int(n_el / 3), int(2 * n_el / 3)
    lines = [f"# comparison rotor with ROSS (bench/ross/README.md), {n_el} elements",
             "version = 1", f'title = "ROSS comparison rotor, {n_el} elements"', "",
             "[[materials]]", 'name = "steel"', "youngs_modulus = 211e9",
             "shear_modulus = 81.2e9", "density = 7810", "",
             "[[shafts]]", 'name = "shaft"', 'material = "steel"', "axis = [0, 0, 1]"]
    for length, divisions in sections(n_el):
        lines += ["  [[shafts.elements]]", f"  length = {length!r}", "  outer_diameter = 0.05",
                  f"  divisions = {divisions}"]
    for name, node, outer in (("disk0", disk0, 0.28), ("disk1", disk1, 0.35)):
        lines += ["", "[[disks]]", f'name = "{name}"', f'node = "shaft.{node}"',
                  f"outer_diameter = {outer}", "inner_diameter = 0.05", "thickness = 0.07",
                  'material = "steel"']
    for name, node in (("b0", 0), ("b1", n_el)):
        lines += ["", "[[bearings]]", f'name = "{name}"', f'node = "shaft.{node}"', "kxx = 1e6",
                  "kyy = 1e6"]
        if damping:
            lines += [f"cxx = {damping}", f"cyy = {damping}"]
    lines += ["", "[[unbalances]]", 'name = "u0"', f'node = "shaft.{disk0}"',
              "mass_eccentricity = 1e-4", "phase_deg = 0"]
    for name, node, dof in (("d0_x", disk0, "ux"), ("d0_y", disk0, "uy"),
                            ("d1_x", disk1, "ux"), ("d1_y", disk1, "uy")):
        lines += ["", "[[sensors]]", f'name = "{name}"', f'node = "shaft.{node}"', f'dof = "{dof}"']
    return lines + [""]


def campbell(n_el):
    return rotor(n_el, 0.0) + [
        "[[analyses]]", 'name = "campbell"', 'type = "campbell"', "speed_start_rpm = 0",
        "speed_stop_rpm = 4000", "speed_count = 100", "n_modes = 6", "engine_orders = [1]", ""]


def unbalance(n_el, count=1000):
    # ROSS's speeds: numpy.linspace(10 rad/s, 4000 rpm, count)
    return rotor(n_el, 100.0) + [
        "[[analyses]]", 'name = "unbalance"', 'type = "unbalance"',
        f"speed_start_rpm = {10.0 * 30.0 / math.pi!r}", "speed_stop_rpm = 4000",
        f"speed_count = {count}", ""]


def write(out_dir, n_el):
    os.makedirs(out_dir, exist_ok=True)
    paths = {}
    for kind, lines in (("campbell", campbell(n_el)), ("unbalance", unbalance(n_el))):
        paths[kind] = os.path.join(out_dir, f"{kind}_{n_el}.toml")
        with open(paths[kind], "w") as f:
            f.write("\n".join(lines))
    return paths


if __name__ == "__main__":
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    for n in sys.argv[2:]:
        print(write(sys.argv[1], int(n)))
