"""The systemd unit as the package installs it: packaging/write_unit.cmake, the step the .deb's
install runs, writes it for a prefix; its settings read back as (key, value) pairs."""
import os
import re
import subprocess
import time


def write_unit(source_dir, prefix, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    unit = os.path.join(out_dir, "wavebenchd.service")
    subprocess.run(["cmake", "-DUNIT_IN=" + os.path.join(source_dir, "packaging",
                                                         "wavebenchd.service.in"),
                    "-DPREFIX=" + prefix, "-DUNIT_OUT=" + unit, "-P",
                    os.path.join(source_dir, "packaging", "write_unit.cmake")], check=True)
    return unit


def settings(unit_path):
    """Every `Key=value` line (comments and sections left out), in order."""
    pairs = []
    for line in open(unit_path):
        line = line.strip()
        if not line or line.startswith(("#", ";", "[")) or "=" not in line:
            continue
        key, value = line.split("=", 1)
        pairs.append((key, value))
    return pairs


def values(unit_path, key):
    return [v for k, v in settings(unit_path) if k == key]


def exposure(unit_path):
    """(overall exposure or None, the analysis) from `systemd-analyze security --offline=true`."""
    result = subprocess.run(["systemd-analyze", "security", "--offline=true", "--no-pager",
                             unit_path], capture_output=True, text=True)
    m = re.search(r"Overall exposure level for wavebenchd\.service: (\d+\.\d+)", result.stdout)
    return (float(m.group(1)) if m else None), result.stdout + result.stderr


def listening_port(stdout, timeout_s=60):
    """The port wavebenchd says it listens on (its first lines on stdout), or None."""
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        line = stdout.readline()
        if not line:
            return None
        m = re.search(r"listening on http://127\.0\.0\.1:(\d+)", line)
        if m:
            return int(m.group(1))
    return None
