#!/usr/bin/python3
"""The scene test/ros/wall_touching.yaml starts the capsule on the 2 h margin of a wall, which the
shear carries it across at step 12: the run must stop (the immersed-boundary stencil would leave
the domain). The node must report it
(ERROR diagnostic naming the wall), close its bag, and stay up: its services still answer."""
import os
import sys
import unittest

import rosbag
import rospy
import rostest
from std_srvs.srv import Trigger

from ehd_test_helpers import ErrorDiagnostics


class FailureTest(unittest.TestCase):
    def test_error_stops_stepping_but_not_the_node(self):
        rospy.init_node("ehd_capsule_failure_test", anonymous=True)
        path = rospy.get_param("~bag")
        diagnostics = ErrorDiagnostics("/ehd_capsule")  # status "/ehd_capsule: simulation"
        self.assertTrue(diagnostics.wait(60), "no ERROR diagnostic within 60 s")
        errors = diagnostics.errors
        # The marker stage's check (within 2 h of a wall) stops it.
        self.assertRegex(errors[0].message, r"step 12: marker \d+ at y = .* within 2h of the wall")
        values = {kv.key: kv.value for kv in errors[0].values}
        for key in ("step_rate_hz", "gmres_iterations", "area_drift"):
            self.assertIn(key, values)

        # The node is still alive and says why it does not step.
        rospy.wait_for_service("/ehd_capsule/pause", timeout=10)
        res = rospy.ServiceProxy("/ehd_capsule/pause", Trigger)()
        self.assertFalse(res.success)
        self.assertRegex(res.message, r"within 2h of the wall")

        # The bag is closed and readable.
        self.assertTrue(os.path.exists(path), "no bag at %s" % path)
        self.assertFalse(os.path.exists(path + ".active"), "bag left open")
        with rosbag.Bag(path) as bag:
            self.assertEqual(bag.get_message_count("/ehd_capsule/scene"), 1)
        os.remove(path)


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "failure_handling", FailureTest, sys.argv)
