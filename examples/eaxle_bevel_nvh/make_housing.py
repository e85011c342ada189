#!/usr/bin/env python3
"""Writes housing.bdf of examples/eaxle_bevel_nvh: a closed box-shaped gearbox housing of
aluminium, walls 8 mm thick, meshed with one layer of 20-node hexahedra (CHEXA with mid-edge
grids, quadratic through the wall so that the walls bend correctly), with case-control node sets
for the four bearing seats, the four mounting feet, two accelerometer points and the outer skin.

Box: x from -0.110 to 0.130 m, y from -0.110 to 0.110 m, z from -0.070 to 0.090 m (outer faces).
The wheel axis is the global z axis (seats on the bottom and top walls), the pinion axis runs
along x at y = 0, z = r_m1 = 19.67 mm (the pinion's mean pitch radius; seats on the x = 0.130 wall).

Run from this folder: python3 make_housing.py (the deck is committed; rerun only to change it).
"""

T = 0.008                        # wall thickness, m
X_OUT = (-0.110, 0.130)
Y_OUT = (-0.110, 0.110)
Z_OUT = (-0.070, 0.090)
Z_PINION = 0.019668              # pinion axis height (mean pitch radius r_m1 of the pair)
E, NU, RHO = "7.0E10", "0.33", "2700."  # aluminium (Nastran reals)

SEAT_PAD = 0.0275                # half width of a bearing-seat pad (one element around the axis)
CARTRIDGE = 0.055                # outer half width of the pinion cartridge flange ring
FOOT = 0.036                     # half width of a mounting foot around a bottom corner


def axis(outer, splits):
    """Grid coordinates: the two wall layers at each end and `splits` = [(to, cells), ...]
    dividing the inside evenly between the given stations."""
    c = [outer[0], outer[0] + T]
    for to, cells in splits:
        start = c[-1]
        c += [start + (to - start) * (k + 1) / cells for k in range(cells)]
    c.append(outer[1])
    return c


XS = axis(X_OUT, [(0.0, 4), (X_OUT[1] - T, 5)])
YS = axis(Y_OUT, [(0.0, 4), (Y_OUT[1] - T, 4)])
ZS = axis(Z_OUT, [(Z_PINION, 3), (Z_OUT[1] - T, 3)])


def in_wall(i, j, k):
    return i in (0, len(XS) - 2) or j in (0, len(YS) - 2) or k in (0, len(ZS) - 2)


def build():
    cells = [(i, j, k) for k in range(len(ZS) - 1) for j in range(len(YS) - 1)
             for i in range(len(XS) - 1) if in_wall(i, j, k)]
    ids = {}
    coords = []

    def node(key, xyz):
        if key not in ids:
            ids[key] = len(coords) + 1
            coords.append(xyz)
        return ids[key]

    def corner(i, j, k):
        return node(("c", i, j, k), (XS[i], YS[j], ZS[k]))

    def mid(a, b):
        key = ("m",) + tuple(sorted((a, b)))
        pa, pb = coords[a - 1], coords[b - 1]
        return node(key, tuple((u + v) / 2 for u, v in zip(pa, pb)))

    elements = []
    for (i, j, k) in cells:
        c = [corner(i, j, k), corner(i + 1, j, k), corner(i + 1, j + 1, k), corner(i, j + 1, k),
             corner(i, j, k + 1), corner(i + 1, j, k + 1), corner(i + 1, j + 1, k + 1),
             corner(i, j + 1, k + 1)]
        # Nastran CHEXA order: corners 1-8, then the mid-edge grids of 1-2, 2-3, 3-4, 4-1,
        # 1-5, 2-6, 3-7, 4-8, 5-6, 6-7, 7-8, 8-5.
        edges = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7),
                 (4, 5), (5, 6), (6, 7), (7, 4)]
        elements.append(c + [mid(c[a], c[b]) for a, b in edges])
    return coords, elements


def main():
    coords, elements = build()
    eps = 1e-9

    def select(pred):
        return [n + 1 for n, p in enumerate(coords) if pred(*p)]

    def nearest_on(pred, target):
        cand = select(pred)
        return [min(cand, key=lambda n: sum((a - b) ** 2 for a, b in zip(coords[n - 1], target)))]

    x_wall = X_OUT[1] - T - eps   # the pinion-side wall: x >= 0.122
    sets = {
        # Bearing seats: both faces of the wall within one element of the axis.
        1: select(lambda x, y, z: z <= Z_OUT[0] + T + eps and abs(x) <= SEAT_PAD and
                  abs(y) <= SEAT_PAD),                                  # wheel, bottom wall
        2: select(lambda x, y, z: z >= Z_OUT[1] - T - eps and abs(x) <= SEAT_PAD and
                  abs(y) <= SEAT_PAD),                                  # wheel, top wall
        3: select(lambda x, y, z: x >= x_wall and abs(y) <= SEAT_PAD and
                  abs(z - Z_PINION) <= SEAT_PAD),                       # pinion A, in the wall
        4: select(lambda x, y, z: x >= x_wall and
                  SEAT_PAD < max(abs(y), abs(z - Z_PINION)) <= CARTRIDGE),  # pinion B flange
        # Mounting feet: the outer bottom face at the four corners.
        5: select(lambda x, y, z: abs(z - Z_OUT[0]) < eps and
                  min(abs(x - X_OUT[0]), abs(x - X_OUT[1])) <= FOOT and
                  min(abs(y - Y_OUT[0]), abs(y - Y_OUT[1])) <= FOOT),
        # Accelerometers: one grid on the outer face of the top wall and of the +y side wall.
        21: nearest_on(lambda x, y, z: abs(z - Z_OUT[1]) < eps, (0.06, 0.06, Z_OUT[1])),
        22: nearest_on(lambda x, y, z: abs(y - Y_OUT[1]) < eps, (-0.04, Y_OUT[1], 0.04)),
        # The outer skin: every grid on the outer faces of the box (the radiating surface).
        30: select(lambda x, y, z: abs(x - X_OUT[0]) < eps or abs(x - X_OUT[1]) < eps or
                   abs(y - Y_OUT[0]) < eps or abs(y - Y_OUT[1]) < eps or
                   abs(z - Z_OUT[0]) < eps or abs(z - Z_OUT[1]) < eps),
    }
    with open("housing.bdf", "w") as f:
        f.write("$ e-axle housing (aluminium box, 8 mm walls, CHEXA20): generated by "
                "make_housing.py, do not edit\n")
        f.write(f"$ {len(coords)} grids, {len(elements)} elements\n")
        f.write("SOL 103\nCEND\n")
        for s in sorted(sets):
            ids = [str(n) for n in sets[s]]
            rows = [", ".join(ids[r:r + 12]) for r in range(0, len(ids), 12)]
            f.write(f"SET {s} = " + ",\n    ".join(rows) + "\n")
        f.write("BEGIN BULK\n")
        f.write(f"MAT1,1,{E},,{NU},{RHO}\n")
        f.write("PSOLID,1,1\n")
        for n, (x, y, z) in enumerate(coords, start=1):
            f.write(f"GRID,{n},,{x:.6f},{y:.6f},{z:.6f}\n")
        for e, g in enumerate(elements, start=1):
            f.write(f"CHEXA,{e},1," + ",".join(str(v) for v in g[:6]) + "\n")
            f.write("," + ",".join(str(v) for v in g[6:14]) + "\n")
            f.write("," + ",".join(str(v) for v in g[14:]) + "\n")
        f.write("ENDDATA\n")
    for s in sorted(sets):
        print(f"SET {s}: {len(sets[s])} grids")
    print(f"{len(coords)} grids, {len(elements)} elements")


main()
