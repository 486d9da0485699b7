#!/usr/bin/python3
"""SIGTERM (kill, timeout, systemd, docker, roslaunch's escalation), SIGINT (Ctrl-C) and
`rosnode kill` end a recording node cleanly (test/ros/signals.test): exit status 0, the bag
closed under its name (no <bag>.active left), the summary and the "bag ... closed" line printed,
and the bag's last /diagnostics saying why it stopped."""
import os
import signal
import subprocess
import sys
import tempfile
import unittest

import rosbag
import rospy
import rostest
from ehd_capsule.msg import CapsuleState

from ehd_test_helpers import node_binary


class SignalsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("ehd_capsule_signals_test", anonymous=True)
        cls.node = node_binary()

    def run_and_end(self, name, end):
        """Starts a recording node, waits for its first state, ends it with end(process) and
        returns (exit status, output, bag path)."""
        bag = os.path.join(tempfile.mkdtemp(prefix="ehd_signals_"), name + ".bag")
        rospy.set_param("/%s/set" % name, {"N": 32, "M": 32})  # a dictionary: not on the command line
        p = subprocess.Popen([self.node, "__name:=" + name, "_scene:=shear_field",
                              "_record:=true", "_bag:=" + bag,
                              "_progress_period:=0"],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            rospy.wait_for_message("/%s/state" % name, CapsuleState, timeout=60)
            end(p)
            out, _ = p.communicate(timeout=60)
        finally:
            if p.poll() is None:
                p.kill()
        return p.returncode, out, bag

    def check_clean_end(self, name, reason, end):
        status, out, bag = self.run_and_end(name, end)
        self.assertEqual(status, 0, "exit status %s; output:\n%s" % (status, out))
        self.assertFalse(os.path.exists(bag + ".active"), "<bag>.active left")
        self.assertTrue(os.path.exists(bag), "no bag at " + bag)
        self.assertIn("summary: stopped (%s" % reason, out)
        self.assertIn("bag %s closed with" % bag, out)
        with rosbag.Bag(bag) as b:
            states = b.get_message_count("/%s/state" % name)
            diags = [m for _, m, _ in b.read_messages(topics=["/diagnostics"])]
        self.assertGreater(states, 0)
        self.assertIn("bag %s closed with %d states" % (bag, states), out)
        self.assertTrue(diags, "no /diagnostics in the bag")
        last = diags[-1].status[0]
        self.assertTrue(last.message.startswith("stopped: " + reason), last.message)
        os.remove(bag)

    def test_sigterm(self):
        self.check_clean_end("ehd_signal_term", "SIGTERM", lambda p: p.send_signal(signal.SIGTERM))

    def test_sigint(self):
        self.check_clean_end("ehd_signal_int", "SIGINT", lambda p: p.send_signal(signal.SIGINT))

    def test_rosnode_kill(self):
        def kill(p):
            subprocess.run(["rosnode", "kill", "/ehd_signal_kill"], capture_output=True,
                           timeout=30)
        self.check_clean_end("ehd_signal_kill", "shutdown request", kill)


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "signals", SignalsTest, sys.argv)
