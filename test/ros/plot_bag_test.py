#!/usr/bin/python3
"""scripts/plot_bag plots what means something for the bag's scene (issue #44 item 7), checked on
bags written here (rosbag and the package's messages; no master, no node) through its --describe
output (the choices as JSON), and on the PNG files it writes:
  - the t axis in the scene's time unit: t k with shear, t gamma / (mu a) for a drop without;
  - the title names the scene and the live Ca and Ca_E, and says when they changed mid-run
    ('Ca 0.04 -> 0.08 at t = 3'); no Ca without shear;
  - 2D with shear: D_xy, theta / pi, Ca_E and Ca; the markers in the x-y plane;
  - 2D without shear (electric_drop): the deformation along the field y, no theta;
  - 3D drop in a field along z without shear (electric_drop_3d): D_z (SurfaceState.d_field) and
    Ca_E only, no D_xy (~1e-6) and no theta (flipping between +-0.5); the shape is the section
    y = y_c cut from the surface mesh, in x-z, which shows the drop's elongation along z;
  - 3D with shear and field (sphere_shear_field): D_xy, theta, D_z, Ca_E and Ca; the shear-plane
    section (the shape topic);
  - an older bag (no scene, no SurfaceState, no mesh) is plotted with what it has, a one-line
    note on stderr for each fallback, exit status 0.
Exit status 0 when every check passes."""
import importlib.machinery
import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import rosbag
import rospy
from geometry_msgs.msg import Point, Point32, PolygonStamped
from std_msgs.msg import String

from ehd_capsule.msg import CapsuleState, SurfaceMesh, SurfaceState
from ehd_test_helpers import ROOT, check, finish

SCRIPT = os.path.join(ROOT, "scripts", "plot_bag")
NS = "/ehd_capsule"


def scene_text(name):
    """The scene as the node publishes it: a comment line, then the YAML."""
    with open(os.path.join(ROOT, "config", "scenes", name + ".yaml")) as f:
        return "# scene %s (%s.yaml)\n%s" % (name, name, f.read())


def ellipse(n, ax, ay):
    return [Point(ax * math.cos(2 * math.pi * k / n), ay * math.sin(2 * math.pi * k / n), 0.0)
            for k in range(n)]


def sphere_mesh(levels=2):
    """An octahedron subdivided `levels` times onto the unit sphere: (vertices, triangles)."""
    verts = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    tris = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    for _ in range(levels):
        middle, out = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = [(verts[a][i] + verts[b][i]) / 2 for i in range(3)]
                r = math.sqrt(sum(c * c for c in p))
                verts.append(tuple(c / r for c in p))
                middle[key] = len(verts) - 1
            return middle[key]

        for a, b, c in tris:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        tris = out
    return verts, [i for t in tris for i in t]


def write_bag(path, states, scene=None, mesh=None, surface=True, shape=True):
    """states: dicts of time, ca, ca_e, dxy, inclination, markers, d_field."""
    with rosbag.Bag(path, "w") as bag:
        t0 = rospy.Time(0)
        if scene:
            bag.write(NS + "/scene", String(data=scene), t0)
        if mesh:
            m = SurfaceMesh(vertex_count=len(states[0]["markers"]), triangles=mesh)
            bag.write(NS + "/surface_mesh", m, t0)
        for step, s in enumerate(states):
            stamp = rospy.Time.from_sec(s["time"])
            msg = CapsuleState(step=step, time=s["time"], markers=s["markers"], dxy=s["dxy"],
                               inclination=s["inclination"], ca=s["ca"], ca_e=s["ca_e"], area=1.0)
            msg.header.stamp = stamp
            bag.write(NS + "/state", msg, stamp)
            if shape:
                poly = PolygonStamped()
                poly.header.stamp = stamp
                poly.polygon.points = [Point32(p.x, p.y, 0.0) for p in s["markers"]
                                       if abs(p.z) < 0.3] or [Point32(1, 0, 0), Point32(0, 1, 0),
                                                              Point32(-1, 0, 0)]
                bag.write(NS + "/shape", poly, stamp)
            if surface and mesh:
                ss = SurfaceState(step=step, d_field=s["d_field"])
                ss.header.stamp = stamp
                bag.write(NS + "/surface_state", ss, stamp)


def plot(path, out_dir):
    """(exit status, the --describe JSON or None, stderr, the files a plain run wrote)."""
    d = subprocess.run(["/usr/bin/python3", SCRIPT, path, "--describe"], capture_output=True,
                       text=True, timeout=120)
    try:
        plan = json.loads(d.stdout)
    except ValueError:
        plan = None
    p = subprocess.run(["/usr/bin/python3", SCRIPT, path, "--out", out_dir], capture_output=True,
                       text=True, timeout=120)
    files = p.stdout.split()
    ok = (d.returncode == 0 and p.returncode == 0 and len(files) == 2
          and all(os.path.getsize(f) > 1000 for f in files))
    return ok, plan, d.stderr + p.stderr, files


def measures(plan):
    return [p["measure"] for p in plan["panels"]] if plan else []


def live_lines(plan):
    return [p.get("lines") for p in plan["panels"] if p["measure"] == "live"] if plan else []


def main():
    tmp = tempfile.mkdtemp(prefix="ehd_plot_bag_test_")
    times = [0.25 * k for k in range(25)]  # t = 0 .. 6

    # 2D, shear and field: Ca 0.04 -> 0.08 at t = 3.
    path = os.path.join(tmp, "run2d.bag")
    write_bag(path, [dict(time=t, ca=0.04 if t < 3 else 0.08, ca_e=0.3, dxy=0.05 * t,
                          inclination=0.25 * math.pi, d_field=0.0,
                          markers=ellipse(32, 1 + 0.02 * t, 1 / (1 + 0.02 * t))) for t in times],
              scene=scene_text("shear_field"))
    ok, plan, err, _ = plot(path, tmp)
    check(ok and plan is not None, "2D shear: plot_bag writes two PNGs and describes them", err)
    plan = plan or {"title": "", "time_label": "", "panels": [], "shape": {}}
    check(plan["time_label"] == "t k", "2D shear: the t axis is t k (got %r)" % plan["time_label"])
    check("shear_field" in plan["title"] and "Ca 0.04 -> 0.08 at t = 3" in plan["title"]
          and "Ca_E 0.3" in plan["title"] and "->" not in plan["title"].split("Ca_E")[1],
          "2D shear: the title names the scene, Ca's change and the steady Ca_E (got %r)"
          % plan["title"])
    check(measures(plan) == ["dxy", "theta", "live"] and live_lines(plan) == [["Ca_E", "Ca"]],
          "2D shear: D_xy, theta, Ca_E and Ca (got %s)" % plan["panels"])
    check(plan["shape"].get("source") == "markers" and plan["shape"].get("axes") == ["x", "y"],
          "2D shear: the markers in x-y (got %s)" % plan["shape"])

    # 2D electric drop, no shear: no theta, no Ca; the deformation along the field y.
    path = os.path.join(tmp, "drop2d.bag")
    write_bag(path, [dict(time=t, ca=0.0, ca_e=0.2, dxy=0.01 * t,
                          inclination=0.5 * math.pi if int(4 * t) % 2 else -0.499 * math.pi,
                          d_field=0.0, markers=ellipse(32, 1.0, 1.0)) for t in times],
              scene=scene_text("electric_drop"))
    ok, plan, err, _ = plot(path, tmp)
    check(ok and plan is not None, "2D drop: plot_bag writes two PNGs and describes them", err)
    plan = plan or {"title": "", "time_label": "", "panels": [], "shape": {}}
    check(plan["time_label"] == "t gamma / (mu a)",
          "2D drop: the t axis is t gamma / (mu a) (got %r)" % plan["time_label"])
    check(measures(plan) == ["d_along_y", "live"] and live_lines(plan) == [["Ca_E"]],
          "2D drop: D along the field y and Ca_E, no theta, no Ca (got %s)" % plan["panels"])
    check("electric_drop" in plan["title"] and "Ca_E 0.2" in plan["title"]
          and "Ca " not in plan["title"], "2D drop: no Ca in the title (got %r)" % plan["title"])

    # 3D drop in a field along z, no shear: prolate along z (1.2 : 1), Ca_E 0.1 -> 0.2 at t = 2.
    verts, tris = sphere_mesh(3)
    stretch = 1.2
    markers = [Point(x / math.sqrt(stretch), y / math.sqrt(stretch), z * stretch)
               for x, y, z in verts]
    path = os.path.join(tmp, "drop3d.bag")
    write_bag(path, [dict(time=t, ca=0.0, ca_e=0.1 if t < 2 else 0.2, dxy=1e-6,
                          inclination=(0.5 if int(4 * t) % 2 else -0.5) * math.pi,
                          d_field=0.01 * t, markers=markers) for t in times],
              scene=scene_text("electric_drop_3d"), mesh=tris)
    ok, plan, err, _ = plot(path, tmp)
    check(ok and plan is not None, "3D drop: plot_bag writes two PNGs and describes them", err)
    plan = plan or {"title": "", "time_label": "", "panels": [], "shape": {}}
    check(plan["time_label"] == "t gamma / (mu a)",
          "3D drop: the t axis is t gamma / (mu a) (got %r)" % plan["time_label"])
    check(measures(plan) == ["d_field", "live"] and live_lines(plan) == [["Ca_E"]],
          "3D drop: D_z and Ca_E only, no D_xy, no theta (got %s)" % plan["panels"])
    check("electric_drop_3d" in plan["title"] and "Ca_E 0.1 -> 0.2 at t = 2" in plan["title"]
          and "field along z" in plan["title"], "3D drop: the title (got %r)" % plan["title"])
    check(plan["shape"].get("source") == "mesh" and plan["shape"].get("axes") == ["x", "z"]
          and plan["shape"].get("ylabel") == "z / a",
          "3D drop: the section containing the field, in x-z (got %s)" % plan["shape"])
    # The section itself: the drop's x-z outline, 2.4 tall and 2 / sqrt(1.2) wide.
    loader = importlib.machinery.SourceFileLoader("plot_bag", SCRIPT)
    spec = importlib.util.spec_from_loader("plot_bag", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    section = module.section_y(markers, tris, 0.0)
    xs, zs = [p[0] for p in section], [p[1] for p in section]
    check(len(section) >= 32 and abs(max(zs) - min(zs) - 2 * stretch) < 0.02
          and abs(max(xs) - min(xs) - 2 / math.sqrt(stretch)) < 0.02,
          "3D drop: the y = 0 section is one closed loop %.3f tall, %.3f wide (%d points)"
          % (max(zs) - min(zs), max(xs) - min(xs), len(section)) if section else "3D: no section")

    # 3D shear and field: D_xy, theta, D_z; the shear-plane section.
    path = os.path.join(tmp, "shear3d.bag")
    write_bag(path, [dict(time=t, ca=0.075, ca_e=0.9, dxy=0.01 * t, inclination=0.2 * math.pi,
                          d_field=-0.01 * t, markers=markers) for t in times],
              scene=scene_text("sphere_shear_field"), mesh=tris)
    ok, plan, err, _ = plot(path, tmp)
    check(ok and plan is not None, "3D shear: plot_bag writes two PNGs and describes them", err)
    plan = plan or {"title": "", "time_label": "", "panels": [], "shape": {}}
    check(plan["time_label"] == "t k", "3D shear: the t axis is t k (got %r)" % plan["time_label"])
    check(measures(plan) == ["dxy", "theta", "d_field", "live"]
          and live_lines(plan) == [["Ca_E", "Ca"]],
          "3D shear: D_xy, theta, D_z, Ca_E and Ca (got %s)" % plan["panels"])
    check("sphere_shear_field" in plan["title"] and "Ca 0.075, Ca_E 0.9" in plan["title"],
          "3D shear: the title (got %r)" % plan["title"])
    check(plan["shape"].get("source") == "shape" and plan["shape"].get("axes") == ["x", "y"],
          "3D shear: the shear-plane section (got %s)" % plan["shape"])

    # An older 3D bag: no scene, no SurfaceState, no mesh.
    path = os.path.join(tmp, "old3d.bag")
    write_bag(path, [dict(time=t, ca=0.0, ca_e=0.1, dxy=1e-6, inclination=0.5 * math.pi,
                          d_field=0.0, markers=markers) for t in times])
    ok, plan, err, _ = plot(path, tmp)
    check(ok and plan is not None, "old 3D bag: plotted all the same", err)
    plan = plan or {"title": "", "time_label": "", "panels": [], "shape": {}}
    notes = [line for line in err.splitlines() if line.startswith("plot_bag: ")]
    check(any("no scene" in n for n in notes) and any("SurfaceState" in n for n in notes)
          and any("surface mesh" in n for n in notes) and "Traceback" not in err,
          "old 3D bag: one note per fallback on stderr", err)
    check(measures(plan) == ["dxy", "theta", "live"] and plan["shape"].get("source") == "shape"
          and "old3d" in plan["title"] and plan["time_label"].startswith("t ("),
          "old 3D bag: D_xy and theta, the z = z_c section, the stem as title (got %s)" % plan)

    # An older 2D bag without the scene: the shear guessed from Ca > 0.
    path = os.path.join(tmp, "old2d.bag")
    write_bag(path, [dict(time=t, ca=0.04, ca_e=0.0, dxy=0.01 * t, inclination=0.2,
                          d_field=0.0, markers=ellipse(32, 1.0, 1.0)) for t in times])
    ok, plan, err, _ = plot(path, tmp)
    plan = plan or {"title": "", "time_label": "", "panels": [], "shape": {}}
    check(ok and plan["time_label"] == "t k" and measures(plan) == ["dxy", "theta", "live"]
          and live_lines(plan) == [["Ca"]] and "no scene" in err,
          "old 2D bag: shear guessed from Ca, t k, no Ca_E (got %s)" % plan, err)

    shutil.rmtree(tmp, ignore_errors=True)
    return finish()


if __name__ == "__main__":
    sys.exit(main())
