"""Shared helpers of the validate_ehd_*.py scripts: run `ehd_sim run` (one OpenMP thread, at
most two runs at a time), read its CSV time series and its VTK frames, and print Markdown tables.

Every script takes --ehd-sim (default: $EHD_SIM or /tmp/build-ehd/bin/ehd_sim), --work (a scratch
directory; finished runs are kept there and reused unless --fresh) and --jobs (parallel runs,
default 2: the machine is shared)."""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import subprocess
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def parser(description):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--ehd-sim", default=os.environ.get("EHD_SIM", "/tmp/build-ehd/bin/ehd_sim"))
    p.add_argument("--work", default="/tmp/ehd_validation")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--fresh", action="store_true", help="rerun even if a finished run exists")
    p.add_argument("--shipped-ib", action="store_true",
                   help="run with the scenes' immersed boundary (the retracted default of issue "
                   "#42) instead of the points and the cosine kernel the tables were made with")
    return p


class Run:
    """One `ehd_sim run` with its overrides; `key` names its files in the work directory."""

    def __init__(self, key, scene, sets, stop, vtk_every=0, csv_every=10):
        self.key, self.scene, self.sets, self.stop = key, scene, list(sets), list(stop)
        self.vtk_every, self.csv_every = vtk_every, csv_every
        self.rows, self.log, self.wall, self.steps, self.ms_per_step = [], "", float("nan"), 0, 0
        self.cpu = float("nan")  # process CPU s (user + sys), nan for runs logged without it
        self.error, self.steady = "", False
        self.vtk_dir = None

    def command(self, args):
        cmd = [args.ehd_sim, "run", self.scene, "--quiet", "--csv", self.csv_path(args),
               "--csv-every", str(self.csv_every), "--set", "numerics.threads=1"]
        if not getattr(args, "shipped_ib", False):
            # The tables were made with the immersed boundary at the points with the cosine
            # kernel (before the retraction and kernel of issue #42 became the default).
            cmd += ["--set", "numerics.ib_kernel=cosine", "--set", "numerics.ib_retraction=0"]
        for s in self.sets:
            cmd += ["--set", s]
        cmd += self.stop
        if self.vtk_every:
            cmd += ["--vtk", self.vtk_path(args), "--vtk-every", str(self.vtk_every)]
        return cmd

    def csv_path(self, args):
        return os.path.join(args.work, self.key + ".csv")

    def log_path(self, args):
        return os.path.join(args.work, self.key + ".log")

    def vtk_path(self, args):
        return os.path.join(args.work, self.key + "_vtk")

    def execute(self, args):
        log = self.log_path(args)
        done = os.path.exists(log) and "steps in" in open(log).read() and not args.fresh
        failed = os.path.exists(log) and "simulation stopped" in open(log).read() and not args.fresh
        if not (done or failed):
            env = dict(os.environ, OMP_NUM_THREADS="1")
            start = time.time()
            with open(log + ".tmp", "w") as out:
                out.write("$ " + " ".join(self.command(args)) + "\n")
                out.flush()
                p = subprocess.Popen(self.command(args), cwd=REPO, env=env, stdout=out,
                                     stderr=subprocess.STDOUT)
                # CPU time of this child alone (user + sys): on a shared machine the wall time
                # depends on other jobs' load, the CPU time much less.
                _, status, usage = os.wait4(p.pid, 0)
                wall = time.time() - start
                out.write("\nprocess wall %.3f s, process cpu %.3f s, exit %d, load %s\n" % (
                    wall, usage.ru_utime + usage.ru_stime, os.waitstatus_to_exitcode(status),
                    " ".join(load_average())))
            os.replace(log + ".tmp", log)
        self.parse(args)
        return self

    def parse(self, args):
        self.log = open(self.log_path(args)).read()
        m = re.search(r"(\d+) steps in ([0-9.]+) s \(([0-9.e+-]+) ms/step\)", self.log)
        if m:
            self.steps, self.wall, self.ms_per_step = int(m.group(1)), float(m.group(2)), float(
                m.group(3))
        m = re.search(r"process cpu ([0-9.]+) s", self.log)
        if m:
            self.cpu = float(m.group(1))
        m = re.search(r"simulation stopped: (.*)", self.log)
        if m:
            self.error = m.group(1).strip()
        self.steady = "steady: D_xy" in self.log
        with open(self.csv_path(args)) as f:
            self.rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
        if self.vtk_every:
            self.vtk_dir = self.vtk_path(args)


def run_all(args, runs):
    os.makedirs(args.work, exist_ok=True)
    start = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(r.execute, args) for r in runs]
        for f in concurrent.futures.as_completed(futures):
            r = f.result()
            print("  done %-40s %8d steps %8.1f s wall %8.1f s cpu %s" % (
                r.key, r.steps, r.wall, r.cpu, r.error), flush=True)
    print("  all runs: %.0f s wall" % (time.time() - start), flush=True)
    return runs


def load_average():
    try:
        return open("/proc/loadavg").read().split()[:3]
    except OSError:
        return ["?"] * 3


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    for r in rows:
        out.append("| " + " | ".join(str(c) for c in r) + " |")
    return "\n".join(out)


def signed_d(row):
    """D signed as in song2019 sec. 4.2.2: + major axis along the field (y), - across it."""
    return row["dxy"] if abs(row["inclination"]) > math.pi / 4 else -row["dxy"]


def row_at(rows, t):
    """The last CSV row with time <= t."""
    best = rows[0]
    for r in rows:
        if r["t"] <= t + 1e-12:
            best = r
    return best


def read_vti_velocity(path):
    """(nx, ny, origin, spacing, ux[j][i], uy[j][i]) from an ASCII .vti frame of ehd_sim."""
    text = open(path).read()
    ext = re.search(r'WholeExtent="0 (\d+) 0 (\d+)', text)
    nx, ny = int(ext.group(1)) + 1, int(ext.group(2)) + 1
    origin = [float(v) for v in re.search(r'Origin="([^"]+)"', text).group(1).split()[:2]]
    spacing = float(re.search(r'Spacing="([^ ]+)', text).group(1))
    block = re.search(r'Name="velocity"[^>]*>\n(.*?)</DataArray>', text, re.S).group(1)
    vals = [float(v) for v in block.split()]
    ux = [[vals[3 * (j * nx + i)] for i in range(nx)] for j in range(ny)]
    uy = [[vals[3 * (j * nx + i) + 1] for i in range(nx)] for j in range(ny)]
    return nx, ny, origin, spacing, ux, uy


def last_vti(directory):
    frames = sorted(f for f in os.listdir(directory) if f.startswith("fluid_") and f.endswith(
        ".vti"))
    return os.path.join(directory, frames[-1])
