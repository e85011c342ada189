#!/usr/bin/env python3
"""Writes ste.csv, the static transmission error of the example's 25/50 spur pair over one mesh
cycle at two torques (README.md, "The model"). Analytic, not from a tooth contact analysis:

  mesh stiffness   k(theta)   = k_m (1 + alpha cos theta),   k_m = 3e8 N/m, alpha = 0.03
  unloaded TE      e_g(theta) = e_a (sin theta - 1),         e_a = 1 um
  loaded STE       e(theta)   = e_g(theta) + F_s / k(theta), F_s = T / r_b1

theta = 2 pi x (pinion angle) / (360 deg / z1) is the phase in the mesh cycle. The mesh is
linear (k independent of the torque), so the curves at 50 and 400 N m give the same k(theta)
at any torque between them: geardyn interpolates the STE linearly in the torque and reads
k = F_s / (e - e_g) and e_g back (docs/input-files.md section 2).
Run: python3 make_ste.py > ste.csv
"""
import math

Z1 = 25              # gear_pairs[0].teeth1
MODULE = 3e-3        # m
ALPHA = math.radians(20.0)
TORQUES = (50.0, 400.0)  # N m
K_MEAN = 3e8         # N/m
VARIATION = 0.03     # alpha: first harmonic of k(theta) / k_m
TE_AMPLITUDE = 1e-6  # e_a [m]
ROWS = 360           # open cycle: the last row is one spacing before the next cycle

r_b1 = 0.5 * MODULE * Z1 * math.cos(ALPHA)
cycle_deg = 360.0 / Z1
print("# Static transmission error of the 25/50 spur pair of examples/gear_rattle at 50 and")
print("# 400 N m on the pinion, over one mesh cycle (14.4 deg of pinion rotation), open layout.")
print("# ANALYTIC (make_ste.py): k = 3e8 (1 + 0.03 cos theta) N/m at both torques, unloaded TE")
print("# e_g = 1 um (sin theta - 1), STE = e_g + F_s / k, F_s = T / r_b1 (r_b1 = 35.238 mm).")
print("angle_deg, " + ", ".join(f"ste_um@{t:g}Nm" for t in TORQUES) + ", geometric_te_um")
for i in range(ROWS):
    theta = 2.0 * math.pi * i / ROWS
    k = K_MEAN * (1.0 + VARIATION * math.cos(theta))
    e_g = TE_AMPLITUDE * (math.sin(theta) - 1.0)
    ste = ", ".join(f"{(e_g + t / r_b1 / k) * 1e6:.10f}" for t in TORQUES)
    print(f"{cycle_deg * i / ROWS:.6f}, {ste}, {e_g * 1e6:.10f}")
