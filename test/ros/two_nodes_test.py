#!/usr/bin/python3
"""Two ehd_capsule nodes (test/ros/two_nodes.test): with one clock owner, /clock is monotone
(two owners made it jump back 115 times in 3 s, the nodes' times differing), only one node
publishes it, and each node's diagnostic status is named after the node."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from rosgraph_msgs.msg import Clock


class TwoNodesTest(unittest.TestCase):
    def test_one_clock_owner_and_distinct_diagnostics(self):
        rospy.init_node("ehd_capsule_two_nodes_test", anonymous=True)
        lock = threading.Lock()
        clocks, names, publishers = [], set(), set()

        def on_clock(msg):
            with lock:
                clocks.append(msg.clock.to_sec())
                publishers.add(msg._connection_header["callerid"])

        def on_diag(msg):
            with lock:
                for s in msg.status:
                    names.add(s.name)

        rospy.Subscriber("/clock", Clock, on_clock, queue_size=10000)
        rospy.Subscriber("/diagnostics", DiagnosticArray, on_diag, queue_size=100)
        end = time.time() + 60
        while time.time() < end:
            with lock:
                if len(clocks) > 500 and len(names) >= 2:
                    break
            time.sleep(0.1)
        time.sleep(2.0)
        with lock:
            c = list(clocks)
            n = set(names)
            p = set(publishers)
        self.assertGreater(len(c), 500, "too few /clock messages")
        backwards = sum(1 for x, y in zip(c, c[1:]) if y < x)
        self.assertEqual(backwards, 0, "/clock ran backwards %d times" % backwards)
        self.assertEqual(p, {"/a/ehd_capsule"}, "publishers of /clock: %s" % p)
        self.assertIn("/a/ehd_capsule: simulation", n, n)
        self.assertIn("/b/ehd_capsule: simulation", n, n)


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "two_nodes", TwoNodesTest, sys.argv)
