#!/usr/bin/env python3
"""Writes pair_deck.bdf (Nastran bulk data) and pair_mesh.msh (Gmsh MSH 4.1) describing the same
small solid model, for test "Nastran deck and Gmsh mesh give the same K and M".

Model (SI): a quadratic part (hex20 + wedge15 on its top face + tet10 on the wedge's front
triangle, conforming, steel, PSOLID 1) and a linear part shifted by x + 3 (hex8 + wedge6 + tet4,
aluminium-like, PSOLID 2). The bottom face z = 0 of the hex20 is fixed (SPC1 set 1 / physical
surface "fixed"); the tet4 apex is the physical point "tip".

Each element is defined once by its corners; mid-edge nodes come from one table keyed by the
corner pair, and each file lists them in its own convention's edge order, typed here from the
manuals independently of the C++ tables:
  Nastran QRG: CTETRA G5..G10 = 12 23 31 14 24 34; CHEXA G9..G20 = 12 23 34 41 15 26 37 48 56 67
               78 85; CPENTA G7..G15 = 12 23 31 14 25 36 45 56 64.
  Gmsh manual: tet10 = 01 12 20 03 23 13; hex20 = 01 03 04 12 15 23 26 37 45 47 56 67;
               prism15 = 01 02 03 12 14 25 34 35 45.
The Nastran deck lists some elements mirrored (Nastran accepts either orientation), places the
linear part's grids through a CORD2C system and mixes small, large and free field.
Run from this folder: python3 make_pair.py
"""
import math
from decimal import Decimal as D

NASTRAN = {
    "tet": [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
    "hex": [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5), (5, 6),
            (6, 7), (7, 4)],
    "wedge": [(0, 1), (1, 2), (2, 0), (0, 3), (1, 4), (2, 5), (3, 4), (4, 5), (5, 3)],
}
GMSH = {
    "tet": [(0, 1), (1, 2), (2, 0), (0, 3), (2, 3), (1, 3)],
    "hex": [(0, 1), (0, 3), (0, 4), (1, 2), (1, 5), (2, 3), (2, 6), (3, 7), (4, 5), (4, 7),
            (5, 6), (6, 7)],
    "wedge": [(0, 1), (0, 2), (0, 3), (1, 2), (1, 4), (2, 5), (3, 4), (3, 5), (4, 5)],
}
# Mirror permutations of the corners (reverse face winding).
FLIP = {"tet": [0, 2, 1, 3], "hex": [0, 3, 2, 1, 4, 7, 6, 5], "wedge": [0, 2, 1, 3, 5, 4]}

nodes = {}  # id -> (x, y, z) as exact decimal strings' values


def add(node_id, x, y, z):
    # Decimal coordinates: mid-edge positions stay short and both files print the same digits.
    nodes[node_id] = tuple(D(str(v)) if not isinstance(v, D) else v for v in (x, y, z))


# Quadratic part corners (ids 1..), slightly distorted.
add(1, 0.0, 0.0, 0.0); add(2, 1.0, 0.0, 0.0); add(3, 1.05, 0.95, 0.0); add(4, 0.0, 1.0, 0.0)
add(5, 0.0, 0.0, 1.0); add(6, 1.0, 0.0, 1.0); add(7, 1.1, 1.05, 1.15); add(8, 0.0, 1.0, 1.0)
add(9, 0.5, 0.0, 1.6); add(10, 0.5, 1.0, 1.6); add(11, 0.5, -0.8, 1.3)
# Linear part corners (ids 21..), x + 3.
add(21, 3.0, 0.0, 0.0); add(22, 4.0, 0.0, 0.0); add(23, 4.0, 1.0, 0.0); add(24, 3.0, 1.0, 0.0)
add(25, 3.0, 0.0, 1.0); add(26, 4.0, 0.0, 1.0); add(27, 4.0, 1.0, 1.0); add(28, 3.0, 1.0, 1.0)
add(29, 3.5, 0.0, 1.5); add(30, 3.5, 1.0, 1.5); add(31, 3.5, -0.75, 1.25)

# Elements by corners, in Gmsh order with positive volume; (kind, quadratic, eid, pid, corners).
elements = [
    ("hex", True, 1, 1, [1, 2, 3, 4, 5, 6, 7, 8]),
    ("wedge", True, 2, 1, [6, 5, 9, 7, 8, 10]),
    ("tet", True, 3, 1, [5, 6, 9, 11]),
    ("hex", False, 11, 2, [21, 22, 23, 24, 25, 26, 27, 28]),
    ("wedge", False, 12, 2, [26, 25, 29, 27, 28, 30]),
    ("tet", False, 13, 2, [25, 26, 29, 31]),
]
mirrored_in_deck = {1, 3, 12}

mid = {}
next_mid = 101
for kind, quadratic, eid, pid, corners in elements:
    if not quadratic:
        continue
    for a, b in GMSH[kind]:
        key = frozenset((corners[a], corners[b]))
        if key not in mid:
            mid[key] = next_mid
            pa, pb = nodes[corners[a]], nodes[corners[b]]
            add(next_mid, *[(u + v) / D(2) for u, v in zip(pa, pb)])
            next_mid += 1


def volume_sign(kind, c):
    p = [nodes[i] for i in c]
    sub = lambda u, v: [u[k] - v[k] for k in range(3)]
    if kind == "tet":
        a, b, d = sub(p[1], p[0]), sub(p[2], p[0]), sub(p[3], p[0])
    elif kind == "hex":
        a = [p[1][k] + p[2][k] + p[5][k] + p[6][k] - p[0][k] - p[3][k] - p[4][k] - p[7][k] for k in range(3)]
        b = [p[2][k] + p[3][k] + p[6][k] + p[7][k] - p[0][k] - p[1][k] - p[4][k] - p[5][k] for k in range(3)]
        d = [p[4][k] + p[5][k] + p[6][k] + p[7][k] - p[0][k] - p[1][k] - p[2][k] - p[3][k] for k in range(3)]
    else:
        a = [p[1][k] - p[0][k] + p[4][k] - p[3][k] for k in range(3)]
        b = [p[2][k] - p[0][k] + p[5][k] - p[3][k] for k in range(3)]
        d = [p[3][k] + p[4][k] + p[5][k] - p[0][k] - p[1][k] - p[2][k] for k in range(3)]
    a, b, d = [[float(v) for v in w] for w in (a, b, d)]
    det = (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
           + a[2] * (b[0] * d[1] - b[1] * d[0]))
    return det


for kind, quadratic, eid, pid, corners in elements:
    assert volume_sign(kind, corners) > 0, (eid, volume_sign(kind, corners))


def connectivity(kind, quadratic, corners, table):
    out = list(corners)
    if quadratic:
        out += [mid[frozenset((corners[a], corners[b]))] for a, b in table[kind]]
    return out


def fmt(v):
    s = str(v.normalize()) if v != 0 else "0."
    if "E" in s:
        s = format(v, "f")
    if "." not in s:
        s += "."
    return s


# ---- Nastran deck
cyl_origin = (3.0, 0.0, 0.0)
lines = ["$ Generated by make_pair.py: the same model as pair_mesh.msh.",
         "BEGIN BULK",
         "$ CID 7: cylindrical, origin (3, 0, 0), z along global z, x along global x.",
         "CORD2C         7       0      3.      0.      0.      3.      0.      1.",
         "              4.      0.      0."]


def small(fields):
    return "".join(f"{str(f):<8}" if i == 0 else f"{str(f):>8}" for i, f in enumerate(fields))


for node_id in sorted(nodes):
    x, y, z = nodes[node_id]
    if node_id >= 21 and node_id < 100:
        # Large field, position in CORD2C 7: r, theta [deg], z.
        x, y, z = float(x), float(y), float(z)
        r = math.hypot(x - cyl_origin[0], y - cyl_origin[1])
        th = math.degrees(math.atan2(y - cyl_origin[1], x - cyl_origin[0]))
        lines.append(f"{'GRID*':<8}{node_id:>16}{7:>16}{r:>16.13f}{th:>16.11f}")
        lines.append(f"{'*':<8}{z:>16.13f}")
    elif node_id % 2 == 0:
        lines.append(f"GRID,{node_id},,{fmt(x)},{fmt(y)},{fmt(z)}")
    else:
        lines.append(small(["GRID", node_id, "", fmt(x), fmt(y), fmt(z)]))

card = {"hex": "CHEXA", "wedge": "CPENTA", "tet": "CTETRA"}
for kind, quadratic, eid, pid, corners in elements:
    c = [corners[i] for i in FLIP[kind]] if eid in mirrored_in_deck else corners
    conn = connectivity(kind, quadratic, c, NASTRAN)
    fields = [card[kind], eid, pid] + conn
    # Small field with blank-first-field continuations every 8 data fields.
    first = small(fields[:9])
    lines.append(first)
    rest = fields[9:]
    while rest:
        lines.append(small([""] + rest[:8]))
        rest = rest[8:]

lines += [
    "PSOLID         1       1",
    "PSOLID         2       2",
    "$ steel",
    "MAT1           1  2.1+11              .3   7800.",
    "$ E and G: NU = E / 2G - 1 = 0.25",
    "MAT1,2,7.E10,2.8E10,,2700.",
]
fixed = sorted({1, 2, 3, 4} | {mid[frozenset(p)] for p in [(1, 2), (2, 3), (3, 4), (4, 1)]})
lines.append(small(["SPC1", 1, 123, fixed[0], "THRU", fixed[3]] + fixed[4:7]))
lines.append(small([""] + fixed[7:]))
lines.append("ENDDATA")
with open("pair_deck.bdf", "w") as f:
    f.write("\n".join(lines) + "\n")

# ---- Gmsh MSH 4.1
bottom = [1, 2, 3, 4]
bottom_mids = [mid[frozenset(p)] for p in [(1, 2), (2, 3), (3, 4), (4, 1)]]
surface_nodes = bottom + bottom_mids
point_nodes = [31]
vol1 = sorted(n for n in nodes if (n < 21 or n >= 100) and n not in surface_nodes)
vol2 = sorted(n for n in nodes if 21 <= n < 100 and n not in point_nodes)


def bbox(ids):
    xs = [nodes[i] for i in ids]
    return " ".join(fmt(min(p[k] for p in xs)) for k in range(3)) + " " + \
        " ".join(fmt(max(p[k] for p in xs)) for k in range(3))


out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat",
       "$PhysicalNames", "4",
       '0 4 "tip"', '2 3 "fixed"', '3 1 "quadratic_part"', '3 2 "linear_part"',
       "$EndPhysicalNames",
       "$Entities", "1 0 1 2",
       f"1 {' '.join(fmt(v) for v in nodes[31])} 1 4",
       f"1 {bbox(surface_nodes)} 1 3 0",
       f"1 {bbox(vol1)} 1 1 0",
       f"2 {bbox(vol2)} 1 2 0",
       "$EndEntities"]
blocks = [(0, 1, point_nodes), (2, 1, surface_nodes), (3, 1, vol1), (3, 2, vol2)]
all_ids = [n for _, _, ids in blocks for n in ids]
out += ["$Nodes", f"{len(blocks)} {len(all_ids)} {min(all_ids)} {max(all_ids)}"]
for dim, tag, ids in blocks:
    out.append(f"{dim} {tag} 0 {len(ids)}")
    out += [str(i) for i in ids]
    out += [" ".join(fmt(v) for v in nodes[i]) for i in ids]
out.append("$EndNodes")
gmsh_type = {("tet", True): 11, ("tet", False): 4, ("hex", True): 17, ("hex", False): 5,
             ("wedge", True): 18, ("wedge", False): 6}
eblocks = [(2, 1, 16, [(100, bottom + bottom_mids)]), (0, 1, 15, [(101, [31])])]
for vol in (1, 2):
    for kind, quadratic, eid, pid, corners in elements:
        if pid == vol:
            eblocks.append((3, vol, gmsh_type[(kind, quadratic)],
                            [(eid, connectivity(kind, quadratic, corners, GMSH))]))
n_el = sum(len(b[3]) for b in eblocks)
tags = [e for b in eblocks for e, _ in b[3]]
out += ["$Elements", f"{len(eblocks)} {n_el} {min(tags)} {max(tags)}"]
for dim, tag, t, els in eblocks:
    out.append(f"{dim} {tag} {t} {len(els)}")
    out += [" ".join(str(v) for v in [e] + conn) for e, conn in els]
out.append("$EndElements")
with open("pair_mesh.msh", "w") as f:
    f.write("\n".join(out) + "\n")
