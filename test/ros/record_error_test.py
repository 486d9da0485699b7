#!/usr/bin/python3
"""A bag write that fails (test/ros/record_error.test: file size limit, like a full disk) must
not abort the node: ERROR diagnostic naming the bag path and the cause, recording stopped, the
simulation paused, the services still answering."""
import os
import sys
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from std_srvs.srv import Trigger


class RecordErrorTest(unittest.TestCase):
    def test_write_failure_is_reported_and_the_node_survives(self):
        rospy.init_node("ehd_capsule_record_error_test", anonymous=True)
        path = rospy.get_param("~bag")
        errors = []

        def on_diag(msg):
            for s in msg.status:
                if s.name.startswith("/ehd_capsule") and s.level == DiagnosticStatus.ERROR:
                    errors.append(s)

        rospy.Subscriber("/diagnostics", DiagnosticArray, on_diag)
        end = time.time() + 60
        while time.time() < end and not errors:
            time.sleep(0.1)
        self.assertTrue(errors, "no ERROR diagnostic within 60 s")
        self.assertIn("writing the bag", errors[-1].message)
        self.assertIn(path, errors[-1].message)
        # Paused, alive: resume answers (and succeeds: the simulation itself is fine).
        rospy.wait_for_service("/ehd_capsule/resume", timeout=10)
        res = rospy.ServiceProxy("/ehd_capsule/resume", Trigger)()
        self.assertTrue(res.success, res.message)
        # The incomplete bag keeps its .active name (rosbag reindex repairs it).
        self.assertTrue(os.path.exists(path + ".active"))
        self.assertLessEqual(os.path.getsize(path + ".active"), 200 * 1024)
        os.remove(path + ".active")


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "record_error", RecordErrorTest, sys.argv)
