#!/usr/bin/python3
"""A bag write that fails (test/ros/record_error.test: file size limit, like a full disk) must
not abort the node: ERROR diagnostic naming the bag path and the OS's reason, recording stopped,
the simulation paused, the services still answering. A batch run (~steps) with a failing bag
ends at once with status 1 instead of waiting paused; a live one ended by Ctrl-C after the
failure exits with status 1, not killed by an uncaught rosbag exception (134)."""
import os
import signal
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest
from std_srvs.srv import Trigger

from ehd_test_helpers import ErrorDiagnostics, node_binary


class RecordErrorTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("ehd_capsule_record_error_test", anonymous=True)

    def test_write_failure_is_reported_and_the_node_survives(self):
        path = rospy.get_param("~bag")
        diagnostics = ErrorDiagnostics("/ehd_capsule")
        self.assertTrue(diagnostics.wait(60), "no ERROR diagnostic within 60 s")
        errors = diagnostics.errors
        self.assertIn("writing the bag", errors[-1].message)
        self.assertIn(path, errors[-1].message)
        self.assertIn(os.strerror(27), errors[-1].message)  # EFBIG: "File too large"
        self.assertIn("ulimit -f", errors[-1].message)
        # Paused, alive: resume answers (and succeeds: the simulation itself is fine).
        rospy.wait_for_service("/ehd_capsule/resume", timeout=10)
        res = rospy.ServiceProxy("/ehd_capsule/resume", Trigger)()
        self.assertTrue(res.success, res.message)
        # The incomplete bag keeps its .active name (rosbag reindex repairs it).
        self.assertTrue(os.path.exists(path + ".active"))
        self.assertLessEqual(os.path.getsize(path + ".active"), 200 * 1024)
        # Repaired, it holds /diagnostics (issue #44 item 6: a bag that failed within its first
        # second held none), the first from its start.
        import rosbag
        import shutil
        repaired = tempfile.mkdtemp(prefix="ehd_record_error_reindex_")
        copy = os.path.join(repaired, "failed.bag")
        shutil.copy(path + ".active", copy)
        subprocess.run(["rosbag", "reindex", "--output-dir", repaired, copy],
                       capture_output=True, timeout=60)
        with rosbag.Bag(copy) as bag:
            diagnostics = [m for _, m, _ in bag.read_messages(topics=["/diagnostics"])]
            states = bag.get_message_count("/ehd_capsule/state")
        shutil.rmtree(repaired)
        self.assertGreater(states, 0, "the repaired bag holds no state")
        self.assertTrue(diagnostics, "the failed bag holds no /diagnostics")
        first = {kv.key: kv.value for kv in diagnostics[0].status[0].values}
        self.assertEqual(first["step"], "0")
        os.remove(path + ".active")

    def start_limited(self, name, *args):
        """The node under a 200 kB file size limit, recording; returns (process, bag)."""
        node = node_binary()
        bag = os.path.join(tempfile.mkdtemp(prefix="ehd_record_error_"), name + ".bag")
        rospy.set_param("/%s/set" % name, {"N": 32, "M": 32})
        command = ["bash", "-c", 'ulimit -f 200; exec "$0" "$@"', node, "__name:=" + name,
                   "_record:=true", "_bag:=" + bag, "_progress_period:=0", *args]
        return subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True), bag

    def test_batch_run_ends_with_status_1(self):
        p, bag = self.start_limited("ehd_record_error_batch", "_steps:=1000000")
        try:
            out, _ = p.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            p.kill()
            out, _ = p.communicate()
            self.fail("a batch run with a failing bag did not end (paused?):\n" + out[-3000:])
        self.assertEqual(p.returncode, 1, out[-3000:])
        self.assertIn("File too large", out)
        self.assertIn("simulation stopped at step", out)
        self.assertIn("summary:", out)
        os.remove(bag + ".active")

    def test_live_run_stopped_after_a_failure_exits_1(self):
        diagnostics = ErrorDiagnostics("/ehd_record_error_live")
        p, bag = self.start_limited("ehd_record_error_live")
        try:
            self.assertTrue(diagnostics.wait(60, lambda: p.poll() is None),
                            "no ERROR diagnostic from the live run")
            p.send_signal(signal.SIGINT)
            out, _ = p.communicate(timeout=60)
        finally:
            if p.poll() is None:
                p.kill()
        self.assertEqual(p.returncode, 1, out[-3000:])
        self.assertNotIn("BagIOException", out)
        self.assertIn("summary: stopped (SIGINT", out)
        os.remove(bag + ".active")


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "record_error", RecordErrorTest, sys.argv)
