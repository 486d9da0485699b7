#!/usr/bin/python3
"""~reset while recording (test/ros/reset_bag.test): the first bag is closed with one timeline
(increasing times), and the recording goes on in <stem>.1.bag, which starts again at t ~ 0.

Issue #44 items 2, 3 and 6, on a node of the test's own: with an earlier run's <stem>.1.bag in
the way the reset takes <stem>.2.bag (it went on unrecorded); a reset whose bag cannot be opened
is refused with the reason and the recording goes on; each bag starts with step 0 and the scene
as a latched connection; the summary's steps/s is over the steps since the reset and the time
spent stepping them, not the paused time."""
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import rosbag
import rospy
import rostest
from ehd_capsule.msg import CapsuleState
from std_srvs.srv import Trigger

from ehd_test_helpers import node_binary


class ResetBagTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("ehd_capsule_reset_bag_test", anonymous=True)

    def test_reset_starts_a_numbered_bag(self):
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

    def test_reset_takes_a_free_number_or_is_refused_and_records_step_0(self):
        name = "ehd_reset_free"
        scratch = tempfile.mkdtemp(prefix="ehd_reset_free_")
        bag = os.path.join(scratch, "run.bag")
        with open(os.path.join(scratch, "run.1.bag"), "w") as f:
            f.write("an earlier run")
        rospy.set_param("/%s/set" % name, {"N": 32, "M": 32})
        steps, lock = [], threading.Lock()

        def on_state(m):
            with lock:
                steps.append(m.step)

        rospy.Subscriber("/%s/state" % name, CapsuleState, on_state, queue_size=1000)
        p = subprocess.Popen([node_binary(), "__name:=" + name, "_record:=true", "_bag:=" + bag,
                              "_max_step_rate:=100", "_progress_period:=0"],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

        def wait_steps(predicate, timeout=60):
            end = time.time() + timeout
            while time.time() < end and p.poll() is None:
                with lock:
                    if predicate(list(steps)):
                        return True
                time.sleep(0.05)
            return False

        try:
            self.assertTrue(wait_steps(lambda s: s and s[-1] >= 20), "no state within 60 s")
            reset = rospy.ServiceProxy("/%s/reset" % name, Trigger)
            rospy.wait_for_service("/%s/reset" % name, timeout=10)
            with lock:
                at_reset = len(steps)  # the step-0 state may come before the answer
            res = reset()
            self.assertTrue(res.success, res.message)
            self.assertIn("run.2.bag", res.message)
            self.assertTrue(wait_steps(lambda s: len(s) > at_reset and 0 in s[at_reset:] and
                                       s[-1] >= 20), "no states after the reset")
            # A bag that cannot be opened (its directory gone): the reset is refused, the run
            # and its recording go on (the open bag moves with the directory).
            with lock:
                at_refusal = len(steps)
            os.rename(scratch, scratch + ".moved")
            try:
                res = reset()
            finally:
                os.rename(scratch + ".moved", scratch)
            self.assertFalse(res.success, "a reset without a bag to record it accepted")
            self.assertIn("reset refused", res.message)
            self.assertIn("still recording to " + os.path.join(scratch, "run.2.bag.active"),
                          res.message)
            self.assertTrue(wait_steps(lambda s: len(s) > at_refusal + 100))
            with lock:
                self.assertNotIn(0, steps[at_refusal:], "the refused reset reset the run")
            # Paused for a while: not in the summary's rate.
            rospy.ServiceProxy("/%s/pause" % name, Trigger)()
            time.sleep(2.0)
            p.send_signal(signal.SIGINT)
            out, _ = p.communicate(timeout=60)
        finally:
            if p.poll() is None:
                p.kill()
                p.communicate()
        self.assertEqual(p.returncode, 0, out[-3000:])
        with open(os.path.join(scratch, "run.1.bag")) as f:
            self.assertEqual(f.read(), "an earlier run", "an earlier run's bag overwritten")
        for path in (bag, os.path.join(scratch, "run.2.bag")):
            self.assertTrue(os.path.exists(path), "%s not closed:\n%s" % (path, out[-3000:]))
            with rosbag.Bag(path) as b:
                states = [m.step for _, m, _ in b.read_messages(topics=["/%s/state" % name])]
                latching = {c.topic: c.header.get("latching") for c in b._get_connections()}
            self.assertEqual(states[0], 0, "%s does not start with step 0" % path)
            self.assertEqual(states, sorted(states), "two timelines in %s" % path)
            self.assertIn(latching.get("/%s/scene" % name), ("1", b"1"), path)
        summary = re.search(r"summary: .*; ([0-9.]+) s wall, (\d+) steps in ([0-9.]+) s of "
                            r"stepping since the last reset \((\d+) steps/s\)", out)
        self.assertIsNotNone(summary, out[-3000:])
        wall, count, stepping, rate = (float(summary.group(1)), int(summary.group(2)),
                                       float(summary.group(3)), int(summary.group(4)))
        self.assertGreater(count, 120)
        self.assertLess(stepping, wall - 2.0, "paused or pre-reset time counted")
        self.assertLessEqual(rate, 130, "faster than max_step_rate 100?")
        # The rate is the steps over the stepping time (printed to 0.1 s, the rate to 1 step/s).
        self.assertAlmostEqual(count / rate, stepping, delta=0.06 + 0.01 * count / rate)
        for f in os.listdir(scratch):
            os.remove(os.path.join(scratch, f))
        os.rmdir(scratch)


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "reset_bag", ResetBagTest, sys.argv)
