"""Issue #12 acceptance measurement: dynamic runs of 2, 20 and 60 output revolutions (60 = one
hour of bench time at 100 rpm on N = 100) on the in-process simulated bench, one after the
other in one go, each as its own `wavebench run` process; prints the wall time and the peak RSS
of each (the process's own, from wait4) and the ratios the issue asks for (60-rev RSS ≤ 150 MB
and ≤ 1.3 × the 2-rev RSS; 60-rev wall ≤ 32 × the 2-rev wall). Measures, never asserts.

Usage: /usr/bin/python3 benchmarks/long_runs/long_runs.py BUILD/src/cli/wavebench [WORK_DIR]
       [--revolutions 2,20,60] [--rpm 100] [--no-twin] [--no-report]
"""

import argparse
import os
import shutil
import subprocess
import tempfile
import time


def run_once(cli, revolutions, rpm, work, extra):
    out = os.path.join(work, "runs-%d" % revolutions)
    shutil.rmtree(out, ignore_errors=True)
    cmd = [cli, "run", "dynamic", "--rpm", str(rpm), "--revolutions", str(revolutions), "--bench", "sim",
           "--out", out, "--quiet", *extra]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    output = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    samples = 0
    for line in output.decode(errors="replace").splitlines():
        if line.startswith("results: "):
            import json
            with open(line[len("results: "):]) as f:
                samples = json.load(f).get("dynamic", {}).get("samples", 0)
    shutil.rmtree(out, ignore_errors=True)
    return proc.returncode, wall, usage.ru_maxrss / 1024.0, samples  # ru_maxrss: KiB on Linux


def main():
    p = argparse.ArgumentParser()
    p.add_argument("cli")
    p.add_argument("work", nargs="?")
    p.add_argument("--revolutions", default="2,20,60")
    p.add_argument("--rpm", type=float, default=100)
    p.add_argument("--no-twin", action="store_true")
    p.add_argument("--no-report", action="store_true")
    a = p.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="wavebench-long-runs-")
    os.makedirs(work, exist_ok=True)
    extra = (["--no-twin"] if a.no_twin else []) + (["--no-report"] if a.no_report else [])
    rows = []
    print("%12s %10s %10s %12s %6s" % ("revolutions", "wall [s]", "peak [MB]", "samples", "exit"))
    for revs in [int(r) for r in a.revolutions.split(",")]:
        code, wall, rss, samples = run_once(a.cli, revs, a.rpm, work, extra)
        rows.append((revs, wall, rss))
        print("%12d %10.1f %10.0f %12d %6d" % (revs, wall, rss, samples, code), flush=True)
    if len(rows) > 1:
        first, last = rows[0], rows[-1]
        print("last/first: wall x%.1f (revolutions x%.0f), peak RSS x%.2f" %
              (last[1] / first[1], last[0] / first[0], last[2] / first[2]))


if __name__ == "__main__":
    main()
