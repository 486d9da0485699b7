#!/usr/bin/env python3
"""The launch files: one launch (shear_field.launch) that takes scene:=, and one thin include of it
per shipped scene. Checks, without starting a node (roslaunch --dump-params resolves the
arguments and parameters exactly as a launch would):
  - every argument of every launch file has a doc= (roslaunch's ros-args option prints them);
  - every scene's launch file is a thin include: at most four arguments of its own, one include
    of shear_field.launch with pass_all_args, nothing else; its scene default names a shipped
    scene of its own name (config/scenes/<name>.yaml), and every shipped scene has one;
  - the node gets the scene of the file, or the one given by scene:= instead, and the arguments
    given on the command line (steps:=) pass through the include;
  - the 3D scenes' files pass the 3D rviz configuration;
  - on_record_error is an argument (stop by default with steps or until_steady, else pause).
Exit status 0 when every check passes."""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

from ehd_test_helpers import ROOT, check, finish

LAUNCH = os.path.join(ROOT, "launch")
SCENES = os.path.join(ROOT, "config", "scenes")


def dump_params(launch_file, *args):
    out = subprocess.run(["roslaunch", "--dump-params", launch_file, *args], capture_output=True,
                         text=True, timeout=60)
    if out.returncode != 0:
        return {"error": out.stdout + out.stderr}
    params = {}
    for line in out.stdout.splitlines():
        key, _, value = line.partition(": ")
        params[key] = value.strip()
    return params


def main():
    files = sorted(f for f in os.listdir(LAUNCH) if f.endswith(".launch"))
    scenes = sorted(f[:-5] for f in os.listdir(SCENES) if f.endswith(".yaml"))
    for f in files:
        root = ET.parse(os.path.join(LAUNCH, f)).getroot()
        undocumented = [a.get("name") for a in root.iter("arg")
                        if a.get("doc") is None and a.get("value") is None]
        check(not undocumented, f"{f}: every argument has doc= (missing: {undocumented})")
    for scene in scenes:
        check(f"{scene}.launch" in files, f"scene {scene} has a launch file")
    for f in files:
        name = f[:-7]
        if name in ("shear_field", "replay"):
            continue
        path = os.path.join(LAUNCH, f)
        root = ET.parse(path).getroot()
        args = [c for c in root if c.tag == "arg"]
        includes = [c for c in root if c.tag == "include"]
        others = [c.tag for c in root if c.tag not in ("arg", "include")]
        check(len(args) <= 4 and len(includes) == 1 and not others,
              f"{f}: a thin include ({len(args)} arguments, {len(includes)} include, {others})")
        if len(includes) == 1:
            inc = includes[0]
            check(inc.get("file", "").endswith("/launch/shear_field.launch") and
                  inc.get("pass_all_args") == "true" and len(list(inc)) == 0,
                  f"{f}: includes shear_field.launch with pass_all_args and nothing else")
        scene_default = next((a.get("default") for a in args if a.get("name") == "scene"), None)
        check(scene_default == name and name in scenes,
              f"{f}: scene default {scene_default} is the shipped scene {name}")
        params = dump_params(path, "steps:=7")
        check(params.get("/ehd_capsule/scene") == name and params.get("/ehd_capsule/steps") == "7",
              f"{f}: the node runs scene {name} for steps:=7 (got {params.get('/ehd_capsule/scene')}, "
              f"{params.get('/ehd_capsule/steps')}{params.get('error', '')})")
        other = "drop_shear" if name != "drop_shear" else "capsule_shear"
        params = dump_params(path, f"scene:={other}")
        check(params.get("/ehd_capsule/scene") == other,
              f"{f}: scene:={other} replaces the file's scene")
        three_d = "dimension: 3" in open(os.path.join(SCENES, name + ".yaml")).read()
        rviz = next((a.get("default") for a in args if a.get("name") == "rviz_config"), "")
        check(three_d == rviz.endswith("ehd_capsule_3d.rviz"),
              f"{f}: {'the 3D' if three_d else 'the 2D'} rviz configuration")
    params = dump_params(os.path.join(LAUNCH, "shear_field.launch"))
    check(params.get("/ehd_capsule/scene") == "shear_field", "shear_field.launch runs shear_field")
    # on_record_error: a launch argument; stop for a batch run (steps, until_steady), else pause.
    main_launch = os.path.join(LAUNCH, "shear_field.launch")
    for args, expect in (((), "pause"), (("steps:=7",), "stop"), (("until_steady:=1e-3",), "stop"),
                         (("steps:=7", "on_record_error:=pause"), "pause"),
                         (("on_record_error:=stop",), "stop")):
        params = dump_params(main_launch, *args)
        got = params.get("/ehd_capsule/on_record_error")
        check(got == expect, f"shear_field.launch {' '.join(args)}: on_record_error {got}, "
                             f"expected {expect}")
        # exit_on_error: true with steps or until_steady only (roslaunch's eval sees the
        # arguments as numbers: comparing them with '0' made it true always).
        if "on_record_error:=pause" not in args and "on_record_error:=stop" not in args:
            batch = "true" if args else "false"
            got = params.get("/ehd_capsule/exit_on_error")
            check(got == batch, f"shear_field.launch {' '.join(args)}: exit_on_error {got}, "
                                f"expected {batch}")
    got = dump_params(os.path.join(LAUNCH, "electric_drop.launch"), "on_record_error:=stop")
    check(got.get("/ehd_capsule/on_record_error") == "stop",
          "on_record_error passes through a scene's launch file")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
