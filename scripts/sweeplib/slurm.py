"""Submitting a sweep to Slurm as one job array (one task per unfinished run)."""
import os
import re
import shlex
import subprocess
import sys
import time

from . import runner

TEMPLATE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "slurm_template.sbatch")
FIELDS = ("JOB_NAME", "ARRAY", "OUTPUT", "TIME", "MEM", "CPUS", "PARTITION_LINE", "SBATCH_LINES",
          "COMMAND")


class SlurmError(Exception):
    pass


def array_spec(indices, max_parallel=0):
    """[0, 1, 2, 5, 7, 8] -> '0-2,5,7-8' (with '%N' to run at most N tasks at once)."""
    parts, start, prev = [], None, None
    for i in sorted(indices):
        if start is None:
            start = prev = i
        elif i == prev + 1:
            prev = i
        else:
            parts.append("%d-%d" % (start, prev) if prev > start else "%d" % start)
            start = prev = i
    if start is not None:
        parts.append("%d-%d" % (start, prev) if prev > start else "%d" % start)
    return ",".join(parts) + ("%%%d" % max_parallel if max_parallel else "")


def fill_template(text, values):
    for field in FIELDS:
        text = text.replace("@%s@" % field, values[field])
    leftover = sorted(set(re.findall(r"@([A-Z][A-Z_]*)@", text)))
    if leftover:
        raise SlurmError("template: unknown field(s) @%s@ (known: %s)" % (
            "@, @".join(leftover), ", ".join(FIELDS)))
    return text


def _tool(name):
    for folder in ("/usr/bin", "/usr/local/bin"):
        path = os.path.join(folder, name)
        if os.access(path, os.X_OK):
            return path
    for folder in os.environ.get("PATH", "").split(os.pathsep):
        path = os.path.join(folder, name)
        if os.access(path, os.X_OK):
            return path
    raise SlurmError("'%s' not found: --slurm needs the Slurm client tools (Debian: apt-get install "
                     "slurm-client, or slurm-wlm for a one-node cluster)" % name)


def submit(sweep, out, args, command):
    """Writes the batch script and submits the unfinished runs as one array; returns the job id
    (None when every run is finished)."""
    pending = [r.index for r in sweep.runs if not _finished(out, r, args.retry_failed)]
    if not pending:
        print("sweep %s: all %d runs are finished; nothing to submit" % (sweep.name,
                                                                         len(sweep.runs)))
        return None
    template_path = args.slurm_template or TEMPLATE
    try:
        template = open(template_path).read()
    except OSError as e:
        raise SlurmError("--slurm-template %s: %s" % (template_path, e.strerror))
    folder = os.path.join(out, "slurm")
    os.makedirs(folder, exist_ok=True)
    values = {
        "JOB_NAME": "sweep-" + sweep.name,
        "ARRAY": array_spec(pending, args.max_parallel),
        "OUTPUT": os.path.join(folder, "%A_%a.out"),
        "TIME": args.time,
        "MEM": args.mem,
        "CPUS": str(args.threads),
        "PARTITION_LINE": "#SBATCH --partition=%s" % args.partition if args.partition else "",
        "SBATCH_LINES": "\n".join("#SBATCH %s" % a for a in args.sbatch_arg),
        "COMMAND": " ".join(shlex.quote(c) for c in command),
    }
    script = fill_template(template, values)
    stamp = time.strftime("%Y%m%d-%H%M%S")
    script_path = os.path.join(folder, "%s-%s.sbatch" % (sweep.name, stamp))
    with open(script_path, "w") as f:
        f.write(script)
    proc = subprocess.run([_tool("sbatch"), "--parsable", script_path], capture_output=True,
                          text=True)
    if proc.returncode != 0:
        raise SlurmError("sbatch %s failed (exit %d): %s" % (script_path, proc.returncode,
                                                              proc.stderr.strip()))
    job = proc.stdout.strip().split(";")[0]
    with open(os.path.join(folder, "jobs.txt"), "a") as f:
        f.write("%s %s %s %s\n" % (job, stamp, values["ARRAY"], script_path))
    print("sweep %s: submitted %d of %d runs as Slurm job array %s (--array=%s), script %s, "
          "task logs %s" % (sweep.name, len(pending), len(sweep.runs), job, values["ARRAY"],
                            script_path, values["OUTPUT"]))
    return job


def wait(job, poll=2.0, stream=sys.stdout):
    """Polls squeue until the job array has left the queue (accounting need not be enabled)."""
    squeue = _tool("squeue")
    last = None
    while True:
        proc = subprocess.run([squeue, "-h", "-j", job, "-o", "%t"], capture_output=True,
                              text=True)
        if proc.returncode != 0 and "Invalid job id" not in proc.stderr:
            raise SlurmError("squeue -j %s failed: %s" % (job, proc.stderr.strip()))
        states = proc.stdout.split()
        if not states:
            return
        text = ", ".join("%d %s" % (states.count(s), s) for s in sorted(set(states)))
        if text != last:
            stream.write("sweep: job %s: %s\n" % (job, text))
            stream.flush()
            last = text
        time.sleep(poll)


def _finished(out, run, retry_failed):
    s = runner.read_summary(out, run)
    return s is not None and (s["status"] == "ok" or not retry_failed)
