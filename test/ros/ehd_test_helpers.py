"""Helpers shared by the ROS tests in test/ros/ (the rostest scripts and the plain scripts that
CTest runs): one copy of what each of them used to write again.

  Checks           check(ok, what, output="") prints ok:/FAIL:, keeps the failures; finish()
                   prints the count and returns the exit status.
  Environment      ROOT (the repository), master_env(port) (a master of its own, away from any
                   running roscore), run(cmd, env, cwd) (status and merged output).
  roscore          Roscore(port): a context manager that starts one and waits until it answers.
  The node         node_binary() (catkin_find's ehd_capsule_node).
  Bags             wait_for_closed_bag(path, topic, count, timeout): until the bag is closed (not
                   .active) and holds `count` messages of `topic`.
  Diagnostics      ErrorDiagnostics(prefix): collects the ERROR statuses of the nodes named so.
rospy and rosbag are imported only where needed, so the plain scripts run without a master."""
import os
import signal
import subprocess
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
failures = []


def check(ok, what, output=""):
    """Prints 'ok: what' or 'FAIL: what' (and the tail of `output`); keeps the failures."""
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)
        if output:
            print(output[-4000:])
    return ok


def finish():
    """The summary line; the exit status (1 when a check failed)."""
    print(f"{len(failures)} failure(s)" if failures else "all checks passed")
    return 1 if failures else 0


def master_env(port, **extra):
    """The environment for a master of its own on `port` (roslaunch starts one there)."""
    return dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOSTNAME="localhost",
                **extra)


def run(cmd, env=None, cwd=ROOT, timeout=180):
    """Runs cmd; returns (exit status, stdout and stderr together)."""
    out = subprocess.run(list(cmd), cwd=cwd, env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True, timeout=timeout)
    return out.returncode, out.stdout


class Roscore:
    """with Roscore(port, env): a roscore on the port for the block, answering when it starts."""

    def __init__(self, port, env=None):
        self.env = env or master_env(port)
        self.port = port

    def __enter__(self):
        self.process = subprocess.Popen(["roscore", "-p", str(self.port)], env=self.env,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                        start_new_session=True)
        for _ in range(60):
            if subprocess.run(["rosparam", "list"], env=self.env,
                              capture_output=True).returncode == 0:
                break
            time.sleep(0.5)
        return self

    def __exit__(self, *exc):
        os.killpg(self.process.pid, signal.SIGINT)
        try:
            self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait()
        return False


def node_binary():
    """The built ehd_capsule_node (catkin_find --libexec)."""
    libexec = subprocess.run(["catkin_find", "--libexec", "ehd_capsule"],
                             capture_output=True, text=True).stdout.split()
    return os.path.join(libexec[0], "ehd_capsule_node")


def wait_for_closed_bag(path, topic="/ehd_capsule/state", count=1, timeout=150):
    """Waits until the bag at `path` is closed (no .active) and holds at least `count` messages
    of `topic`; returns whether it did within `timeout` seconds."""
    import rosbag
    end = time.time() + timeout
    while time.time() < end:
        if os.path.exists(path) and not os.path.exists(path + ".active"):
            try:
                with rosbag.Bag(path) as bag:
                    if bag.get_message_count(topic) >= count:
                        return True
            except Exception:
                pass
        time.sleep(0.2)
    return False


class ErrorDiagnostics:
    """Subscribes to /diagnostics and keeps, in .errors, the ERROR statuses whose name starts
    with `prefix` (a status is named "<node name>: simulation")."""

    def __init__(self, prefix):
        import rospy
        from diagnostic_msgs.msg import DiagnosticArray
        self.prefix = prefix
        self.errors = []
        self.subscriber = rospy.Subscriber("/diagnostics", DiagnosticArray, self._on_diagnostics)

    def _on_diagnostics(self, msg):
        from diagnostic_msgs.msg import DiagnosticStatus
        self.errors.extend(s for s in msg.status
                           if s.name.startswith(self.prefix) and s.level == DiagnosticStatus.ERROR)

    def wait(self, timeout, while_=lambda: True):
        """Waits up to `timeout` seconds for an error (and while while_() holds)."""
        end = time.time() + timeout
        while time.time() < end and not self.errors and while_():
            time.sleep(0.1)
        return bool(self.errors)
