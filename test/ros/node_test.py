#!/usr/bin/python3
"""Integration test of ehd_capsule_node (run by rostest from test/ros/node.test).

What must hold, and why:
- every step publishes one CapsuleState, so consecutive messages have consecutive step numbers;
- the electric force density is linear in E^2, i.e. in Ca_E, for a fixed shape: doubling Ca_E
  doubles it (up to the small shape change between two steps), and Ca_E = 0 gives none;
- a neutral capsule in a uniform field feels no net electric force: the resultant is small
  against the total magnitude of the force density;
- a change made through dynamic_reconfigure shows in the next message; Ca = 0 is refused (it
  would freeze the time, counted in units of 1/k);
- a refused value is reported back: the configuration returned is the one the node runs with,
  /diagnostics says WARN with the refusal; the ranges and defaults dynamic_reconfigure shows are
  the scene's (issue #44 item 1);
- ~state_throttled follows at a wall-clock rate of at most 20 Hz;
- pause stops the steps, advance takes exactly `advance_steps` steps, advance_by exactly the
  steps of its request, resume continues; ~state_throttled is latched, so a subscriber that
  comes while paused gets the state the run stands at (issue #44 item 5);
- an invalid scene makes the node exit non-zero with a message naming the problem.
"""
import math
import os
import subprocess
import sys
import tempfile
import threading
import unittest

import rospy
import rostest
import dynamic_reconfigure.client
from std_srvs.srv import Trigger
from ehd_capsule.msg import CapsuleState

from ehd_test_helpers import ROOT, node_binary

NODE = "/ehd_capsule"


class StateRecorder:
    def __init__(self):
        self.lock = threading.Lock()
        self.messages = []
        self.sub = rospy.Subscriber(NODE + "/state", CapsuleState, self.on_state, queue_size=1000)

    def on_state(self, msg):
        with self.lock:
            self.messages.append(msg)

    def snapshot(self):
        with self.lock:
            return list(self.messages)

    def wait_for(self, predicate, timeout=60.0):
        import time  # wall clock: sim time stands still while paused
        end = time.time() + timeout
        while time.time() < end and not rospy.is_shutdown():
            msgs = self.snapshot()
            for m in msgs:
                if predicate(m):
                    return m
            time.sleep(0.02)
        return None

    def wait_count(self, n, timeout=60.0):
        import time
        end = time.time() + timeout
        while time.time() < end and len(self.snapshot()) < n:
            time.sleep(0.02)
        return self.snapshot()


def force_magnitude_sum(msg):
    return sum(math.hypot(f.x, f.y) for f in msg.electric_force)


class NodeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("ehd_capsule_node_test", anonymous=True)
        cls.rec = StateRecorder()
        rospy.wait_for_service(NODE + "/pause", timeout=60)
        cls.client = dynamic_reconfigure.client.Client(NODE, timeout=60)

    def call(self, name):
        rospy.wait_for_service(NODE + "/" + name, timeout=30)
        return rospy.ServiceProxy(NODE + "/" + name, Trigger)()

    def test_1_consecutive_steps(self):
        msgs = self.rec.wait_count(30)
        self.assertGreaterEqual(len(msgs), 30, "fewer than 30 states in 60 s")
        steps = [m.step for m in msgs[:30]]
        for a, b in zip(steps, steps[1:]):
            self.assertEqual(b, a + 1, "steps %s are not consecutive" % steps)
        times = [m.time for m in msgs[:30]]
        self.assertTrue(all(t2 > t1 for t1, t2 in zip(times, times[1:])))
        for m in msgs[:30]:
            self.assertEqual(len(m.markers), 32)
            self.assertTrue(math.isfinite(m.dxy) and 0.0 <= m.dxy < 1.0)

    def test_2_ca_e_changes_force(self):
        self.client.update_configuration({"Ca_E": 0.0})
        m0 = self.rec.wait_for(lambda m: m.ca_e == 0.0)
        self.assertIsNotNone(m0, "Ca_E = 0 never showed in a state message")
        later = self.rec.wait_for(lambda m: m.ca_e == 0.0 and m.step > m0.step)
        self.assertLess(force_magnitude_sum(later), 1e-12, "force at Ca_E = 0")

        self.client.update_configuration({"Ca_E": 0.1})
        m1 = self.rec.wait_for(lambda m: abs(m.ca_e - 0.1) < 1e-12)
        self.assertIsNotNone(m1, "Ca_E = 0.1 never showed in a state message")
        f1 = force_magnitude_sum(m1)
        self.assertGreater(f1, 0.0)
        # Neutral capsule: net force small against the total force density.
        net = math.hypot(m1.electric_force_total.x, m1.electric_force_total.y)
        per_length = f1 / len(m1.electric_force) * 2.0 * math.pi  # ~ total magnitude on r = a
        self.assertLess(net, 0.05 * per_length, "net electric force %g vs %g" % (net, per_length))

        self.client.update_configuration({"Ca_E": 0.2})
        m2 = self.rec.wait_for(lambda m: abs(m.ca_e - 0.2) < 1e-12)
        self.assertIsNotNone(m2)
        f2 = force_magnitude_sum(m2)
        self.assertAlmostEqual(f2 / f1, 2.0, delta=0.2)

    def test_3_ca_changes(self):
        msgs = self.rec.snapshot()
        old = msgs[-1].ca
        new = old * 0.5 if old > 0 else 0.01
        self.client.update_configuration({"Ca": new})
        m = self.rec.wait_for(lambda m: abs(m.ca - new) < 1e-12)
        self.assertIsNotNone(m, "Ca change never showed")

    def test_4_refuses_out_of_range(self):
        from rosgraph_msgs.msg import Log
        logs = []
        sub = rospy.Subscriber("/rosout", Log, lambda m: logs.append(m.msg), queue_size=100)
        # The subscription must be connected before the first refusal is logged (on a loaded
        # machine the first message was lost).
        import time
        deadline = time.time() + 10.0
        while sub.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)
        last = self.rec.snapshot()[-1]
        # 100 is far above the scene's range and above the old slider limit (20), which
        # dynamic_reconfigure clamped to silently: the refusal must name what was asked for.
        self.client.update_configuration({"Ca_E": 100.0})
        self.client.update_configuration({"Ca_E": -0.5})
        import time
        time.sleep(1.0)
        sub.unregister()
        self.assertTrue(any("refused Ca_E = 100" in m for m in logs),
                        "refusal of Ca_E = 100 not logged with the value asked for: %s" % logs)
        msgs = self.rec.snapshot()
        self.assertTrue(all(m.ca_e >= 0.0 for m in msgs), "a negative Ca_E was applied")
        self.assertTrue(all(m.ca_e <= 5.0 for m in msgs), "Ca_E = 100 was applied")
        cfg = self.client.get_configuration(timeout=10)
        self.assertGreaterEqual(cfg["Ca_E"], 0.0, "refused value still shown as set")
        self.assertGreater(msgs[-1].step, last.step, "node stopped after a refused value")

    def test_4a_refusal_reported_back_and_scene_ranges(self):
        # Issue #44 item 1: update_configuration returned Ca_E 50 while the node kept 0.6.
        from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
        import time
        kept = self.client.get_configuration(timeout=10)["Ca_E"]
        statuses = []
        sub = rospy.Subscriber("/diagnostics", DiagnosticArray,
                               lambda m: statuses.extend(s for s in m.status
                                                         if s.name.startswith(NODE + ":")))
        deadline = time.time() + 10.0
        while sub.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)
        returned = self.client.update_configuration({"Ca_E": 50.0})
        self.assertEqual(returned["Ca_E"], kept, "the refused Ca_E = 50 returned as set")
        self.assertEqual(self.client.get_configuration(timeout=10)["Ca_E"], kept)
        returned = self.client.update_configuration({"Ca": -1.0})
        self.assertGreater(returned["Ca"], 0.0, "the refused Ca = -1 returned as set")
        # The refusal in /diagnostics: WARN, the value asked for and why, the key "refused".
        deadline = time.time() + 10.0
        warned = []
        while time.time() < deadline and not warned:
            warned = [s for s in list(statuses) if s.level == DiagnosticStatus.WARN and
                      "refused Ca = -1" in s.message]
            time.sleep(0.05)
        self.assertTrue(warned, "no WARN diagnostic for the refused Ca = -1: %s" %
                        [(s.level, s.message) for s in statuses[-3:]])
        values = {kv.key: kv.value for kv in warned[-1].values}
        self.assertIn("out of range", values.get("refused", ""))
        # An accepted change ends the warning.
        self.client.update_configuration({"Ca_E": kept})
        returned = self.client.update_configuration({"Ca_E": 0.25})
        self.assertAlmostEqual(returned["Ca_E"], 0.25)
        count = len(statuses)
        deadline = time.time() + 10.0
        while time.time() < deadline and not any(s.level == DiagnosticStatus.OK
                                                 for s in statuses[count:]):
            time.sleep(0.05)
        sub.unregister()
        self.assertTrue(any(s.level == DiagnosticStatus.OK for s in statuses[count:]),
                        "still WARN after an accepted change: %s" % statuses[-1].message)
        # The ranges and defaults shown (rqt_reconfigure's sliders) are the scene's (shear_field:
        # Ca_E 0.3, Ca 0.04, electric.max_Ca_E 3, max_Ca 0.15), not the .cfg's +-1e9.
        descriptions = {p["name"]: p for p in self.client.get_group_descriptions()["parameters"]}
        ca_e, ca = descriptions["Ca_E"], descriptions["Ca"]
        self.assertEqual((ca_e["min"], ca_e["max"], ca_e["default"]), (0.0, 3.0, 0.3))
        self.assertEqual((ca["min"], ca["default"]), (0.0, 0.04))
        self.assertGreater(ca["max"], 0.04)
        self.assertLessEqual(ca["max"], 0.15)

    def test_4b_refuses_ca_zero(self):
        # Time is in units of 1/k: Ca = 0 would freeze it while the steps go on.
        self.client.update_configuration({"Ca": 0.0})
        import time
        time.sleep(1.0)
        msgs = self.rec.snapshot()
        self.assertTrue(all(m.ca > 0.0 for m in msgs), "Ca = 0 was applied")
        self.assertGreater(msgs[-1].time, msgs[-20].time, "time stood still")

    def test_4c_throttled_state_at_a_wall_clock_rate(self):
        # ~state_throttled carries the latest state at most ~throttled_rate (20) times per wall
        # second, while ~state runs at the step rate (thousands per second).
        import time
        got = []
        sub = rospy.Subscriber(NODE + "/state_throttled", CapsuleState, lambda m: got.append(m),
                               queue_size=100)
        time.sleep(0.5)
        del got[:]
        start = len(self.rec.snapshot())
        time.sleep(3.0)
        sub.unregister()
        per_step = len(self.rec.snapshot()) - start
        self.assertGreater(len(got), 10, "throttled topic silent")
        self.assertLess(len(got), 3.0 * 20 * 1.25, "throttled topic faster than 20 Hz")
        self.assertGreater(per_step, len(got), "~state slower than the throttled topic")
        steps = [m.step for m in got]
        self.assertEqual(steps, sorted(steps))

    def test_5_pause_advance_resume(self):
        import time
        self.assertTrue(self.call("pause").success)
        time.sleep(0.5)
        a = self.rec.snapshot()[-1].step
        time.sleep(1.0)
        b = self.rec.snapshot()[-1].step
        self.assertEqual(a, b, "steps advanced while paused")
        self.client.update_configuration({"advance_steps": 5})
        self.assertTrue(self.call("advance").success)
        m = self.rec.wait_for(lambda m: m.step == b + 5, timeout=30)
        self.assertIsNotNone(m, "advance did not reach step %d" % (b + 5))
        time.sleep(0.5)
        self.assertEqual(self.rec.snapshot()[-1].step, b + 5, "advance overshot")
        # ~advance_by takes the count in the request.
        from ehd_capsule.srv import Advance
        rospy.wait_for_service(NODE + "/advance_by", timeout=10)
        advance_by = rospy.ServiceProxy(NODE + "/advance_by", Advance)
        self.assertFalse(advance_by(0).success, "advance_by 0 accepted")
        self.assertTrue(advance_by(7).success)
        m = self.rec.wait_for(lambda m: m.step == b + 12, timeout=30)
        self.assertIsNotNone(m, "advance_by did not reach step %d" % (b + 12))
        time.sleep(0.5)
        self.assertEqual(self.rec.snapshot()[-1].step, b + 12, "advance_by overshot")
        # Issue #44 item 5: `rostopic echo -n1 ~state_throttled` while paused waited for ever. A
        # new subscriber gets the latched state the run stands at.
        late = rospy.wait_for_message(NODE + "/state_throttled", CapsuleState, timeout=10)
        self.assertEqual(late.step, b + 12, "~state_throttled does not hold the paused state")
        self.assertTrue(self.call("resume").success)
        m = self.rec.wait_for(lambda m: m.step > b + 17, timeout=30)
        self.assertIsNotNone(m, "did not resume")

    def test_6_reset(self):
        self.assertTrue(self.call("reset").success)
        start = len(self.rec.snapshot())
        import time
        end = time.time() + 30
        found = None
        while time.time() < end and found is None:
            for m in self.rec.snapshot()[start:]:
                if m.step == 1:
                    found = m
                    break
            time.sleep(0.05)
        self.assertIsNotNone(found, "no step-1 state after reset")
        # Issue #47: the live values changed by tests 2 and 3 (Ca_E 0.2, Ca halved) return to
        # the scene's (config/scenes/shear_field.yaml, read here), in the state and in
        # dynamic_reconfigure.
        import yaml
        with open(os.path.join(ROOT, "config", "scenes", "shear_field.yaml")) as f:
            scene = yaml.safe_load(f)
        self.assertEqual(found.ca, scene["Ca"])
        self.assertEqual(found.ca_e, scene["Ca_E"])
        config = self.client.get_configuration(timeout=10)
        self.assertEqual(config["Ca"], scene["Ca"])
        self.assertEqual(config["Ca_E"], scene["Ca_E"])

    def test_7_invalid_scene_exits_with_message(self):
        import re
        import rospkg
        node = node_binary()
        shipped = os.path.join(rospkg.RosPack().get_path("ehd_capsule"), "config", "scenes",
                               "shear_field.yaml")
        with open(shipped) as f:
            text = f.read()
        cases = []
        for pattern, replacement, expect in (
                (r"(?m)^Ca_E:.*$", "Ca_E: [not, a, number]", "Ca_E"),  # wrong type
                (r"(?m)^Ca:.*$", "Ca: -0.1", "Ca"),                    # out of range
                (r"(?m)^N:.*$", "N: 64\nbogus_key: 1", "bogus_key")):  # unknown key
            with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
                f.write(re.sub(pattern, replacement, text))
                cases.append((f.name, expect))
        cases.append(("/nonexistent/scene.yaml", "scene"))
        for scene, expect in cases:
            p = subprocess.run([node, "__name:=ehd_bad_scene", "_scene:=" + scene],
                               capture_output=True, text=True, timeout=60)
            self.assertNotEqual(p.returncode, 0, "node accepted %s" % scene)
            self.assertIn(expect, p.stdout + p.stderr)

    def test_8_existing_bag_is_not_overwritten(self):
        # A new run on an existing bag path used to replace it silently: now it refuses at start
        # (exit status != 0, message naming the path and the way out) unless ~overwrite is true.
        node = node_binary()
        with tempfile.NamedTemporaryFile(suffix=".bag", delete=False) as f:
            f.write(b"an earlier run")
            path = f.name
        p = subprocess.run([node, "__name:=ehd_overwrite_test", "_record:=true", "_bag:=" + path,
                            "_steps:=5"],
                           capture_output=True, text=True, timeout=60)
        self.assertNotEqual(p.returncode, 0, "node overwrote an existing bag")
        self.assertIn("exists", p.stdout + p.stderr)
        with open(path, "rb") as f:
            self.assertEqual(f.read(), b"an earlier run")
        p = subprocess.run([node, "__name:=ehd_overwrite_test", "_record:=true", "_bag:=" + path,
                            "_steps:=5", "_overwrite:=true"],
                           capture_output=True, text=True, timeout=60)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertFalse(os.path.exists(path + ".active"), "bag left .active after closing")
        import rosbag
        with rosbag.Bag(path) as bag:
            # Steps 0 (the state the run starts from) to 5.
            self.assertEqual(bag.get_message_count("/ehd_overwrite_test/state"), 6)
        os.remove(path)


if __name__ == "__main__":
    rostest.rosrun("ehd_capsule", "node_behaviour", NodeTest, sys.argv)
