#!/usr/bin/python3
"""The 3D CSV columns d_field and area (the enclosed volume) against the mesh that the same run
writes to VTK (issue #47): an independent computation, in numpy, of the volume and of the
equivalent ellipsoid's deformation along z (D_z = (a_z - a_perp) / (a_z + a_perp), the semi-axes
a_i = sqrt(5 lambda_i / V) of the second-moment tensor, docs/validation_3d_ehd.md) from the
membrane frames' vertices (Float64, units of a) and triangles.

The run: electric_drop_3d (Case B, prolate) shrunk to N = 20, L = 2.5 a, 40 steps, a frame every
10 steps (about a second). Each frame's D_z and volume / (4 pi a^3 / 3) must match the CSV's
d_field and area to 1e-8 relative (the CSV prints 10 digits; measured 3e-10 and below), D_z must
grow (a prolate drop: +1.4e-4 at step 10, +9.3e-4 at step 40), surface_flow must be 0 at step 0
(no marker step yet) and finite and nonzero after. surface_flow reads the vertex velocities of
the last marker step, which no frame holds (a drop's vertices move with the normal velocity
only): its value is checked against Taylor's case dependence in
test/coupling/ehd_physics_test.cpp. Shown once: the semi-axes without the square root double D_z
and fail every frame after step 0.

  test/cli/field_columns_3d_test.py [--ehd-sim PATH]
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
FAILURES = []
SPHERE = 4 * math.pi / 3  # the CSV's volume unit, in units of a^3


def check(condition, what):
    print("%s: %s" % ("ok" if condition else "FAILED", what), flush=True)
    if not condition:
        FAILURES.append(what)


def read_vtp(path):
    """Vertices (n x 3) and triangles (m x 3) of a membrane frame (appended raw, UInt64 heads)."""
    with open(path, "rb") as f:
        raw = f.read()
    head, _, data = raw.partition(b'<AppendedData encoding="raw">\n_')
    offsets = [int(o) for o in re.findall(rb'offset="(\d+)"', head)]

    def block(offset, dtype):
        n = int(np.frombuffer(data, np.uint64, 1, offset)[0])
        return np.frombuffer(data, dtype, n // np.dtype(dtype).itemsize, offset + 8)

    return block(offsets[0], np.float64).reshape(-1, 3), block(offsets[1], np.int64).reshape(-1, 3)


def volume_and_dz(p, tri):
    """The enclosed volume and D_z, by the tetrahedra of each triangle with the origin."""
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    vol6 = np.einsum("ij,ij->i", a, np.cross(b, c))
    volume = vol6.sum() / 6
    centroid = ((a + b + c) * vol6[:, None]).sum(0) / 24 / volume
    s = a + b + c  # int x x^T over a tetrahedron (0, a, b, c): V/20 (sum v v^T + s s^T)
    second = sum(np.einsum("t,ti,tj->ij", vol6 / 120, v, v) for v in (a, b, c, s))
    second -= volume * np.outer(centroid, centroid)
    lam, vec = np.linalg.eigh(second)
    axes = np.sqrt(5 * lam / volume)
    k = int(np.argmax(abs(vec[2, :])))  # the principal axis closest to z
    across = np.delete(axes, k).mean()
    return volume, (axes[k] - across) / (axes[k] + across)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--ehd-sim", default=os.path.join(REPO, "build", "bin", "ehd_sim"))
    args = p.parse_args()
    with tempfile.TemporaryDirectory(prefix="field_columns_3d_") as tmp:
        csv_path, vtk = os.path.join(tmp, "run.csv"), os.path.join(tmp, "vtk")
        cmd = [args.ehd_sim, "run", os.path.join(REPO, "config", "scenes", "electric_drop_3d.yaml"),
               "--set", "N=20", "--set", "geometry.half_width=2.5", "--steps", "40", "--quiet",
               "--csv", csv_path, "--vtk", vtk, "--vtk-every", "10"]
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           universal_newlines=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
        check(r.returncode == 0, "`%s` runs (%s)" % (" ".join(cmd), r.stdout[-500:].strip()))
        if r.returncode != 0:
            return 1
        with open(csv_path, newline="") as f:
            rows = {int(row["step"]): row for row in csv.DictReader(f)}
        previous = 0.0
        for step in range(0, 41, 10):
            row = rows[step]
            volume, dz = volume_and_dz(*read_vtp(os.path.join(vtk, "membrane_%09d.vtp" % step)))
            d_field, area = float(row["d_field"]), float(row["area"])
            check(abs(dz - d_field) <= 1e-8 * abs(d_field) + 1e-15,
                  "step %d: d_field %s = the mesh's D_z %.10g (%.2g relative)"
                  % (step, row["d_field"], dz, abs(dz / d_field - 1) if d_field else dz))
            check(abs(volume / SPHERE - area) <= 1e-8 * area,
                  "step %d: area %s = the mesh's volume / (4 pi a^3 / 3) %.10g"
                  % (step, row["area"], volume / SPHERE))
            if step > 0:
                check(dz > previous, "step %d: D_z grows (%.4g > %.4g)" % (step, dz, previous))
                flow = float(row["surface_flow"])
                check(math.isfinite(flow) and flow != 0,
                      "step %d: surface_flow %s finite, nonzero" % (step, row["surface_flow"]))
            else:
                check(float(row["surface_flow"]) == 0, "step 0: surface_flow 0 (no marker step)")
            previous = dz
    if FAILURES:
        print("\nFAILED:\n  " + "\n  ".join(FAILURES))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
