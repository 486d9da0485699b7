#!/usr/bin/python3
"""Fails when a script under scripts/ reads a metric or a run's end from ehd_sim's
human-readable output (progress, "N steps in X s (Y ms/step)", "simulation stopped: ...",
"steady: D_xy ...", the pipeline listing, converge's tables, ...) instead of
`ehd_sim run --summary-json` and the CSV time series (issue #30 item 5, docs/campaigns.md).

A grep: each line of a script that mentions one of the phrases below is a finding, except
comment lines and lines marked `# builds, not reads` (a message made with the same words). The
campaigns not yet converted to spec files are listed in NOT_YET_CONVERTED; such a script must
still contain a finding (when it is converted, remove it from the list), and no other script
may have one.

  test/sweep/no_log_scraping_test.py
"""
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SCRIPTS = os.path.join(REPO, "scripts")

# Phrases of ehd_sim's human output (src/cli/*.cpp) that a script would match to read a
# metric, a time or whether a run finished.
PHRASES = [
    r"steps in",                 # "%ld steps in %.2f s (%.3g ms/step)"
    r"ms/step\\?\)",             # the same line, by its tail
    r"simulation stopped",       # "ehd_sim run: simulation stopped: ..."
    r"steady: D_xy",             # the --until-steady line
    r"NOT steady",
    r"step cap",                 # "stopped at the step cap ..."
    r"run: error",               # "ehd_sim run: error: ..."
    r"time per stage",
    r"1\\?\. electric:",         # the pipeline listing
    r"mean edge ~",              # DescribeScene's mesh line
    r"vertices \\?\(mean edge",
    r"differences to the finest",  # ehd_sim converge's table
    r"Feng small-deformation",
    r"final: step",
]
PATTERN = re.compile("|".join("(?:%s)" % p for p in PHRASES))

# Campaigns still on their hand loop (issue #30 item 5, what is left: docs/campaigns.md).
NOT_YET_CONVERTED = {
    "validate_ehd_common.py",
    "validate_ehd_cost.py",
    "validate_ehd_speed.py",
}


def findings(path):
    out = []
    try:
        with open(path, errors="replace") as f:
            for i, line in enumerate(f, 1):
                text = line.strip()
                if text.startswith("#") or "# builds, not reads" in line:
                    continue
                if PATTERN.search(line):
                    out.append("%s:%d: %s" % (os.path.relpath(path, REPO), i, line.strip()))
    except IsADirectoryError:
        pass
    return out


def main():
    failed = False
    seen = set()
    for root, dirs, files in os.walk(SCRIPTS):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for name in sorted(files):
            path = os.path.join(root, name)
            rel = os.path.relpath(path, SCRIPTS)
            found = findings(path)
            if rel in NOT_YET_CONVERTED:
                seen.add(rel)
                if not found:
                    print("FAILED: scripts/%s no longer reads ehd_sim's human output: remove it "
                          "from NOT_YET_CONVERTED in %s" % (rel, os.path.relpath(__file__, REPO)))
                    failed = True
                continue
            for line in found:
                print("FAILED: reads ehd_sim's human output (use --summary-json or the CSV): "
                      + line)
                failed = True
    for rel in sorted(NOT_YET_CONVERTED - seen):
        print("FAILED: NOT_YET_CONVERTED names scripts/%s, which does not exist" % rel)
        failed = True
    print("some script reads ehd_sim's human output" if failed else
          "no script under scripts/ reads ehd_sim's human output (%d not yet converted)" %
          len(NOT_YET_CONVERTED))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
