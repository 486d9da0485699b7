#!/usr/bin/python3
"""The node on a 3D scene (test/ros/node_3d.test), read back from its bag:
- one CapsuleState per step with the 642 vertices as 3D points (z spans the drop: not a 2D
  state) and, with the field, a 3D electric force per vertex whose resultant is small against
  its total magnitude (a neutral drop in a uniform field);
- the membrane marker array holds the surface as a TRIANGLE_LIST of 3 points per triangle
  (1280 triangles) and the shear-plane section as a closed LINE_STRIP of radius about 1 (lengths
  are in units of a);
- the shape polygon is that section; the field layer is published on the mid plane;
- Ca_E changed through dynamic_reconfigure while the node runs (0.3 -> 0.6) shows in the
  states, and the electric force, linear in Ca_E = eps E^2 a / gamma, doubles (within 5 %:
  the drop moves a little between the two solves);
- the triangles once in the bag (SurfaceMesh: 1280 triangles on the 642 vertices, every index
  in range, each edge shared by two triangles), a SurfaceState per state with the same steps and
  a drop's surface drift below 1 %; the marker array with every ~markers_every-th state only;
- the bag is closed (readable, not .active) when the node stops at ~steps.
"""
import math
import os
import time
import unittest

import dynamic_reconfigure.client
import rosbag
import rospy
import rostest
from visualization_msgs.msg import Marker

from ehd_capsule.msg import CapsuleState

from ehd_test_helpers import wait_for_closed_bag

NODE = "/ehd_capsule"


def force_magnitude_sum(state):
    return sum(math.sqrt(f.x ** 2 + f.y ** 2 + f.z ** 2) for f in state.electric_force)


class Node3dTest(unittest.TestCase):
    def test_three_d_state_markers_and_bag(self):
        rospy.init_node("ehd_capsule_node_3d_test", anonymous=True)
        path = rospy.get_param("~bag")
        steps = rospy.get_param("~steps")
        markers_every = rospy.get_param("~markers_every")
        seen = []
        rospy.Subscriber(NODE + "/state", CapsuleState, lambda m: seen.append(m.step),
                         queue_size=100)
        client = dynamic_reconfigure.client.Client(NODE, timeout=60)
        end = time.time() + 60
        while time.time() < end and not seen:
            time.sleep(0.02)
        self.assertTrue(seen, "no state within 60 s")
        self.assertLess(seen[-1], steps // 2, "the node ran too fast to change Ca_E mid-run")
        client.update_configuration({"Ca_E": 0.6})
        wait_for_closed_bag(path, "/ehd_capsule/state", steps, timeout=150)
        self.assertTrue(os.path.exists(path), "no closed bag at %s" % path)
        with rosbag.Bag(path) as bag:
            states = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/state"])]
            markers = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/markers"])]
            shapes = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/shape"])]
            fields = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/field"])]
            meshes = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/surface_mesh"])]
            latching = {c.topic: c.header.get("latching") for c in bag._get_connections()}
            surfaces = [m for _, m, _ in
                        bag.read_messages(topics=["/ehd_capsule/surface_state"])]
        # From step 0, the state the run starts from (issue #44 item 3).
        self.assertEqual([s.step for s in states], list(range(0, steps + 1)))
        ca_e = [s.ca_e for s in states]
        self.assertAlmostEqual(ca_e[0], 0.3)
        self.assertAlmostEqual(ca_e[-1], 0.6)
        changed = next(i for i, c in enumerate(ca_e) if abs(c - 0.6) < 1e-12)
        self.assertTrue(all(abs(c - 0.3) < 1e-12 for c in ca_e[:changed]))
        ratio = force_magnitude_sum(states[changed]) / force_magnitude_sum(states[changed - 1])
        self.assertAlmostEqual(ratio, 2.0, delta=0.1,
                               msg="force ratio %.3f after Ca_E 0.3 -> 0.6" % ratio)
        last = states[-1]
        self.assertEqual(len(last.markers), 642)
        zs = [p.z for p in last.markers]
        self.assertGreater(max(zs) - min(zs), 1.8, "vertices must span the drop in z")
        self.assertEqual(len(last.electric_force), 642)
        magnitude = force_magnitude_sum(last)
        self.assertGreater(magnitude, 0.0)
        self.assertTrue(any(abs(f.z) > 0 for f in last.electric_force))
        total = last.electric_force_total
        resultant = math.sqrt(total.x ** 2 + total.y ** 2 + total.z ** 2)
        self.assertLess(resultant, 0.05 * magnitude / 642 * 4 * math.pi,
                        "a neutral drop in a uniform field feels no net force")
        self.assertEqual(len(meshes), 1, "the triangles go into the bag once")
        # Latched in the bag as on the wire, so a replay gives a late subscriber (rviz) the
        # triangles and the scene (issue #44 item 3).
        for topic in ("/ehd_capsule/surface_mesh", "/ehd_capsule/scene", "/tf_static"):
            self.assertIn(latching.get(topic), ("1", b"1"), "%s not latched in the bag" % topic)
        mesh = meshes[0]
        self.assertEqual(mesh.vertex_count, 642)
        self.assertEqual(len(mesh.triangles), 3 * 1280)
        self.assertTrue(all(0 <= i < 642 for i in mesh.triangles))
        edges = {}
        for k in range(0, len(mesh.triangles), 3):
            t = mesh.triangles[k:k + 3]
            for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                edges[(min(a, b), max(a, b))] = edges.get((min(a, b), max(a, b)), 0) + 1
        self.assertTrue(all(c == 2 for c in edges.values()), "not a closed surface")
        self.assertEqual([s.step for s in surfaces], list(range(0, steps + 1)))
        self.assertTrue(all(abs(s.surface_drift) < 0.01 for s in surfaces))
        self.assertEqual(len(markers), (steps + 1 + markers_every - 1) // markers_every,
                         "marker arrays with every %d-th state" % markers_every)
        array = markers[-1]
        by_ns = {m.ns: m for m in array.markers}
        self.assertIn("surface", by_ns)
        surface = by_ns["surface"]
        self.assertEqual(surface.type, Marker.TRIANGLE_LIST)
        self.assertEqual(len(surface.points), 3 * 1280)
        # ~surface_colour speed: one colour per point, spread over the ramp (the drop's
        # circulation moves its poles and equator at different speeds).
        self.assertEqual(len(surface.colors), len(surface.points))
        reds = [c.r for c in surface.colors]
        self.assertGreater(max(reds) - min(reds), 0.3)
        section = by_ns["membrane"]
        self.assertEqual(section.type, Marker.LINE_STRIP)
        self.assertGreater(len(section.points), 10)
        radii = [math.hypot(p.x, p.y) for p in section.points]
        self.assertLess(max(radii), 1.15)
        self.assertGreater(min(radii), 0.85)
        self.assertGreater(len(shapes[-1].polygon.points), 10)
        self.assertTrue(fields, "no field layer published")
        cells = [m for m in fields[-1].markers if m.ns == "field"]
        self.assertTrue(cells and len(cells[0].points) > 0)
        # scripts/plot_bag on this bag (issue #44 item 7): D_z and Ca_E against t gamma / (mu a),
        # no D_xy or theta (no shear), Ca_E's change in the title, the x-z section.
        import json
        import subprocess
        import rospkg
        script = os.path.join(rospkg.RosPack().get_path("ehd_capsule"), "scripts", "plot_bag")
        run = subprocess.run(["/usr/bin/python3", script, path, "--describe"],
                             capture_output=True, text=True, timeout=120)
        self.assertEqual(run.returncode, 0, run.stderr)
        plan = json.loads(run.stdout)
        self.assertEqual([p["measure"] for p in plan["panels"]], ["d_field", "live"])
        self.assertEqual(plan["time_label"], "t gamma / (mu a)")
        self.assertIn("electric_drop_3d", plan["title"])
        self.assertIn("Ca_E 0.3 -> 0.6 at t = %.4g" % states[changed].time, plan["title"])
        self.assertEqual(plan["shape"]["axes"], ["x", "z"])


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "node_3d", Node3dTest)
