"""What the bench scripts share: the source tree's root, the clock and the median they
time with, a timed subprocess run that stops the bench on failure, and the atomic
write of a JSON result (a .tmp file renamed over the target).

    from benchlib import ROOT, clock, median, run_timed, write_json_atomic
"""
import json
import os
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

clock = time.perf_counter
median = statistics.median


def run_timed(cmd, what=None, env=None):
    """Runs cmd (a list), returns its wall time [s]; on a non-zero exit stops the bench
    with "bench: WHAT failed (CODE):" and the command's stderr (WHAT: the command line)."""
    t0 = clock()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    wall = clock() - t0
    if p.returncode != 0:
        sys.exit("bench: %s failed (%d):\n%s" % (what or " ".join(cmd), p.returncode, p.stderr))
    return wall


def write_json_atomic(path, doc):
    """Writes doc as indented JSON to path (its directory created), through path + ".tmp"
    renamed over it; returns the text written (without the final newline)."""
    text = json.dumps(doc, indent=2)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path + ".tmp", "w") as f:
        f.write(text + "\n")
    os.replace(path + ".tmp", path)
    return text
