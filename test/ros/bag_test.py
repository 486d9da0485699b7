#!/usr/bin/python3
"""A recorded run (test/ros/bag.test) holds exactly steps/publish_every + 1 CapsuleState messages
with consecutive published step numbers from step 0 (the state the run starts from), the scene
once as a latched connection (so `rosbag play` latches it again), a /diagnostics from its start, one shape and marker array per state,
one clock tick per state (not per step: at publish_every 100 per-step clocks were 40% of a
bag), the frame's latched static transform, the field layer, and is closed (readable, not
.active) when the node stops; scripts/plot_bag turns it into PNG plots."""
import os
import sys
import unittest

import rosbag
import rospy
import rostest

from ehd_test_helpers import wait_for_closed_bag


class BagTest(unittest.TestCase):
    def test_bag_has_one_state_per_published_step(self):
        rospy.init_node("ehd_capsule_bag_test", anonymous=True)
        path = rospy.get_param("~bag")
        steps = rospy.get_param("~steps")
        every = rospy.get_param("~publish_every")
        # The node closes the bag when it reaches ~steps: wait for the file to be complete.
        wait_for_closed_bag(path, "/ehd_capsule/state", 1, timeout=150)
        self.assertTrue(os.path.exists(path),
                        "no closed bag at %s after 150 s (did the node die before closing it?)"
                        % path)
        self.assertFalse(os.path.exists(path + ".active"), "bag was not closed")
        with rosbag.Bag(path) as bag:
            states = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/state"])]
            counts = {t: bag.get_message_count(t) for t in
                      ("/ehd_capsule/shape", "/ehd_capsule/markers", "/ehd_capsule/scene", "/clock",
                       "/tf_static", "/ehd_capsule/field")}
            tf = [(m, c) for _, m, _, c in bag.read_messages(topics=["/tf_static"],
                                                              return_connection_header=True)]
            scene = [(m, c) for _, m, _, c in bag.read_messages(
                topics=["/ehd_capsule/scene"], return_connection_header=True)]
            diagnostics = [m for _, m, _ in bag.read_messages(topics=["/diagnostics"])]
            fields = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/field"])]
            markers = [m for _, m, _ in bag.read_messages(topics=["/ehd_capsule/markers"])]
        # scripts/plot_bag turns the same bag into the two PNG files it names.
        import subprocess
        import tempfile
        import rospkg
        script = os.path.join(rospkg.RosPack().get_path("ehd_capsule"), "scripts", "plot_bag")
        out_dir = tempfile.mkdtemp(prefix="ehd_plot_bag_")
        run = subprocess.run(["/usr/bin/python3", script, path, "--out", out_dir],
                             capture_output=True, text=True, timeout=120)
        self.assertEqual(run.returncode, 0, run.stderr)
        written = run.stdout.split()
        self.assertEqual(len(written), 2, run.stdout)
        for png in written:
            self.assertGreater(os.path.getsize(png), 1000, png)
        # Its choices for this 2D shear-and-field bag (issue #44 item 7).
        import json
        run = subprocess.run(["/usr/bin/python3", script, path, "--describe"],
                             capture_output=True, text=True, timeout=120)
        self.assertEqual(run.returncode, 0, run.stderr)
        plan = json.loads(run.stdout)
        self.assertEqual(plan["time_label"], "t k")
        self.assertIn("shear_field", plan["title"])
        self.assertIn("Ca 0.04, Ca_E 0.3", plan["title"])
        self.assertEqual([p["measure"] for p in plan["panels"]], ["dxy", "theta", "live"])
        os.remove(path)
        self.assertEqual(len(states), steps // every + 1)
        self.assertEqual([m.step for m in states], list(range(0, steps + 1, every)))
        self.assertEqual(states[0].time, 0.0)
        self.assertEqual(counts["/ehd_capsule/shape"], len(states))
        self.assertEqual(counts["/ehd_capsule/markers"], len(states))
        self.assertEqual(counts["/ehd_capsule/scene"], 1)
        # Latched in the bag as on the wire (issue #44 item 3).
        self.assertIn(scene[0][1].get("latching"), ("1", b"1"), str(scene[0][1]))
        self.assertIn("shear_field", scene[0][0].data)
        # The bag's first diagnostic is from its start (step 0).
        steps_of = [{kv.key: kv.value for kv in d.status[0].values}["step"] for d in diagnostics]
        self.assertEqual(steps_of[0], "0")
        self.assertEqual(counts["/clock"], len(states))
        # The frame's static transform, latched, so a replay gives rviz the frame.
        self.assertEqual(counts["/tf_static"], 1)
        message, header = tf[0]
        self.assertIn(header.get("latching"), ("1", b"1"), str(header))
        self.assertEqual(message.transforms[0].child_frame_id, "ehd")
        self.assertEqual(message.transforms[0].header.frame_id, "world")
        # The field layer (|E| here): throttled in wall time, and the final state's.
        self.assertGreaterEqual(counts["/ehd_capsule/field"], 1)
        cells = [m for m in fields[-1].markers if m.ns == "field"][0]
        self.assertEqual(len(cells.points), 32 * 32)  # N = 32: one square per cell
        self.assertEqual(len(cells.colors), len(cells.points))
        # Walls drawn; force arrows with heads (3 segments, 6 points per marker).
        names = {m.ns: m for m in markers[-1].markers}
        self.assertEqual(len(names["walls"].points), 4)
        self.assertEqual(len(names["electric_force"].points) % 6, 0)
        self.assertIn("\n", names["status"].text)


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "bag_contents", BagTest, sys.argv)
