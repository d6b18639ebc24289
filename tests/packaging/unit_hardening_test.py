#!/usr/bin/python3
"""The packaged systemd unit is hardened (issue #22, item 13): `systemd-analyze security
--offline=true` scores the unit written by the package's install step at most 4.0; every
exposure the analysis still reports names a directive that the unit either sets or explains in
a comment; `systemd-analyze verify` accepts the unit with the built daemon as its ExecStart.

Usage: unit_hardening_test.py SOURCE_DIR WORK_DIR WAVEBENCHD
"""
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import packaged_unit  # noqa: E402
from checks import check

MAX_EXPOSURE = 4.0


def main():
    source_dir, work, daemon = sys.argv[1], sys.argv[2], sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    analyze = shutil.which("systemd-analyze")
    check(analyze is not None, "systemd-analyze is installed (Debian package systemd)")

    unit = packaged_unit.write_unit(source_dir, "/usr", os.path.join(work, "usr"))
    check("ExecStart=/usr/bin/wavebenchd " in open(unit).read(),
          "the packaged unit starts /usr/bin/wavebenchd")
    score, analysis = packaged_unit.exposure(unit)
    print(analysis)
    check(score is not None, "systemd-analyze security --offline=true names an overall exposure")
    check(score <= MAX_EXPOSURE, f"exposure {score} <= {MAX_EXPOSURE}")

    text = open(unit).read()
    comments = "\n".join(line for line in text.splitlines() if line.lstrip().startswith("#"))
    set_keys = {k for k, _ in packaged_unit.settings(unit)}
    open_items = re.findall(r"^✗ (\S+?)=", analysis, re.M)
    unexplained = sorted({k for k in open_items if k not in set_keys and k + "=" not in comments})
    check(not unexplained,
          f"every open exposure ({len(open_items)}) is set or explained in a comment"
          f" (unexplained: {unexplained})")

    # verify checks that ExecStart names an executable: a prefix whose bin/ holds the daemon.
    prefix = os.path.join(work, "prefix")
    os.makedirs(os.path.join(prefix, "bin"))
    os.symlink(os.path.abspath(daemon), os.path.join(prefix, "bin", "wavebenchd"))
    verify_unit = packaged_unit.write_unit(source_dir, prefix, os.path.join(work, "verify"))
    result = subprocess.run([analyze, "verify", "--man=no", verify_unit], capture_output=True,
                            text=True)
    check(result.returncode == 0 and "wavebenchd.service" not in result.stderr,
          f"systemd-analyze verify accepts the unit ({result.stderr.strip() or 'no remarks'})")
    print(f"unit hardening: exposure {score}, all checks passed")


if __name__ == "__main__":
    main()
