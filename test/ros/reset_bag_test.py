#!/usr/bin/python3
"""~reset while recording (test/ros/reset_bag.test): the first bag is closed with one timeline
(increasing times), and the recording goes on in <stem>.1.bag, which starts again at t ~ 0."""
import os
import sys
import time
import unittest

import rosbag
import rospy
import rostest
from ehd_capsule.msg import CapsuleState
from std_srvs.srv import Trigger


class ResetBagTest(unittest.TestCase):
    def test_reset_starts_a_numbered_bag(self):
        rospy.init_node("ehd_capsule_reset_bag_test", anonymous=True)
        path = rospy.get_param("~bag")
        second = path[:-4] + ".1.bag"
        rospy.wait_for_message("/ehd_capsule/state", CapsuleState, timeout=30)
        time.sleep(1.0)
        rospy.wait_for_service("/ehd_capsule/reset", timeout=10)
        self.assertTrue(rospy.ServiceProxy("/ehd_capsule/reset", Trigger)().success)
        end = time.time() + 30
        # The first bag is renamed when closed, then the numbered one opened: wait for both (on a
        # loaded machine the check came between the two).
        while time.time() < end and not (os.path.exists(path) and
                                         os.path.exists(second + ".active")):
            time.sleep(0.1)
        self.assertTrue(os.path.exists(path), "first bag not closed under its name")
        self.assertTrue(os.path.exists(second + ".active"), "no numbered bag after the reset")
        with rosbag.Bag(path) as bag:
            times = [m.time for _, m, _ in bag.read_messages(topics=["/ehd_capsule/state"])]
        self.assertGreater(len(times), 2)
        self.assertEqual(times, sorted(times), "two timelines in the first bag")
        os.remove(path)
        os.remove(second + ".active")  # still open: the node's rename at shutdown then fails


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "reset_bag", ResetBagTest, sys.argv)
