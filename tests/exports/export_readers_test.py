"""Exports read back by independent readers (issue #12): a dynamic run on the in-process
simulated bench, exported without a daemon (`wavebench export --runs`) as .mat, HDF5, CSV and
JSON; the .mat file read by Octave (octave-cli, Debian's octave), the HDF5 file by h5py
(Debian's python3-h5py). Each reader computes the TE from the exported angles in the gear's
sense over the dynamic record (results.json dynamic.record) and must find results.json's mean
and p2p within 1e-9 arcsec. Then the hostile side: a bad format, a folder the export did not
write. Fails, not skips, when a reader is missing.

Usage: /usr/bin/python3 export_readers_test.py WAVEBENCH_CLI SOURCE_DIR WORK_DIR
"""

import csv
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

try:
    import h5py
    import numpy as np
except ImportError as e:
    sys.exit("export_readers_test: FAIL: " + str(e) + "; install Debian's python3-h5py and python3-numpy "
             "(scripts/install-deps.sh) and run it with /usr/bin/python3")

TOLERANCE_ARCSEC = 1e-9
failures = []
passes = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    (passes if ok else failures).append(what)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=900, **kw)


def record_te(t_ns, theta_in, theta_out, first_ns, last_ns, ratio, sign):
    """The dynamic procedure's record (metrology::dynamic_te_input) and its TE [arcsec]."""
    keep = (t_ns >= first_ns) & (t_ns <= last_ns) & ~np.isnan(theta_in) & ~np.isnan(theta_out)
    ti, to, tk = theta_in[keep], theta_out[keep], t_ns[keep]
    direction = -1.0 if to[-1] < to[0] else 1.0
    sel, last_t, last_o = [], None, 0.0
    for i in range(len(ti)):
        if last_t is not None and (tk[i] <= last_t or not (to[i] - last_o) * direction > 0):
            continue
        sel.append(i)
        last_t, last_o = tk[i], to[i]
    te = sign * to[sel] - ti[sel] / ratio
    turn = 2 * math.pi / ratio
    q = te / turn
    te = te - turn * np.where(q >= 0, np.floor(q + 0.5), np.ceil(q - 0.5))  # std::round
    arcsec = te * (180.0 * 3600.0 / math.pi)
    total = 0.0
    for v in arcsec:  # in order, as the analysis sums
        total += float(v)
    return len(arcsec), total / len(arcsec), float(arcsec.max() - arcsec.min())


def main():
    cli, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    octave = shutil.which("octave-cli")
    if octave is None:
        sys.exit("export_readers_test: FAIL: octave-cli not found; install Debian's octave (scripts/install-deps.sh)")
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    runs = work / "runs"
    done = run([cli, "run", "dynamic", "--rpm", "600", "--revolutions", "1", "--option", "run_in_s=0.2",
                "--no-twin", "--no-report", "--bench", "sim", "--out", str(runs), "--quiet"])
    if done.returncode != 0:
        sys.exit("export_readers_test: FAIL: the dynamic run exited " + str(done.returncode) + "\n" +
                 done.stdout + done.stderr)
    run_id = next(p.name for p in runs.iterdir() if p.is_dir())
    results = json.loads((runs / run_id / "results.json").read_text())
    dyn = results["dynamic"]
    first_ns, last_ns = dyn["record"]["first_receive_time_ns"], dyn["record"]["last_receive_time_ns"]
    ratio, sign = results["gear"]["ratio"], results["gear"]["direction_sign"]

    outs = {}
    for fmt in ("mat", "hdf5", "csv", "json"):
        out = work / ("export-" + fmt)
        done = run([cli, "export", run_id, "--runs", str(runs), "--format", fmt, "--out", str(out)])
        check(done.returncode == 0, "export --format " + fmt + " exits 0: " + done.stdout.strip() + done.stderr.strip())
        outs[fmt] = out
        leftovers = [p.name for p in out.iterdir() if ".tmp" in p.name] if out.exists() else []
        check(not leftovers, fmt + ": no temporary files left: " + str(leftovers))
        check((out / "results.json").exists() and (out / "run.json").exists(), fmt + ": results.json and run.json beside")

    # CSV: the row count every other form is checked against.
    with open(outs["csv"] / "samples.csv") as f:
        rows = list(csv.DictReader(f))
    total = len(rows)
    check(total > 1000, "csv: %d rows" % total)
    check(len(json.loads((outs["json"] / "samples.json").read_text())) == total, "json: as many samples as csv rows")

    # HDF5 through h5py.
    with h5py.File(outs["hdf5"] / "samples.h5", "r") as h5:
        s = h5["samples"]
        t_ns = s["receive_time_ns"][()]
        check(t_ns.dtype == np.int64 and len(t_ns) == total, "hdf5: receive_time_ns int64, %d rows" % len(t_ns))
        check(s["sync_counter"].dtype == np.uint32 and s["flags"].dtype == np.uint32, "hdf5: sync_counter, flags uint32")
        unit = s["theta_in"].attrs["unit"]
        unit = unit.decode() if isinstance(unit, bytes) else unit
        check(unit == "rad", "hdf5: theta_in unit attribute " + repr(unit))
        t_unit = s["torque"].attrs["unit"]
        t_unit = t_unit.decode() if isinstance(t_unit, bytes) else t_unit
        check(t_unit == "N*m", "hdf5: torque unit attribute " + repr(t_unit))
        text = h5["results_json"][()]
        text = text.decode() if isinstance(text, bytes) else text
        check(json.loads(text) == results, "hdf5: results_json is results.json")
        check(float(h5["results/dynamic/p2p_arcsec"][()]) == dyn["p2p_arcsec"], "hdf5: results/dynamic/p2p_arcsec")
        check(int(s["sync_counter"][0]) == int(rows[0]["sync_counter"]) and
              int(t_ns[-1]) == int(rows[-1]["receive_time_ns"]), "hdf5: first counter and last timestamp as the csv")
        n, mean, p2p = record_te(t_ns, s["theta_in"][()], s["theta_out"][()], first_ns, last_ns, ratio, sign)
    check(n == dyn["samples"] - dyn["skipped_invalid"] - dyn["skipped_out_of_order"] - dyn["skipped_not_advancing"],
          "h5py: %d samples in the record" % n)
    check(abs(mean - dyn["mean_arcsec"]) <= TOLERANCE_ARCSEC,
          "h5py: TE mean %.12f arcsec, results.json %.12f (|diff| %.3g)" % (mean, dyn["mean_arcsec"], abs(mean - dyn["mean_arcsec"])))
    check(abs(p2p - dyn["p2p_arcsec"]) <= TOLERANCE_ARCSEC,
          "h5py: TE p2p %.12f arcsec, results.json %.12f" % (p2p, dyn["p2p_arcsec"]))

    # .mat through Octave.
    t0 = int(rows[0]["receive_time_ns"])
    done = run([octave, "--quiet", "--norc", "--path", str(source / "tests/exports"), "--eval",
                "read_export('%s', %d, %d)" % (outs["mat"] / "samples.mat", first_ns - t0, last_ns - t0)])
    check(done.returncode == 0, "octave-cli read the .mat file" + ("" if done.returncode == 0 else ":\n" + done.stdout + done.stderr))
    got = dict(line.split(" ", 1) for line in done.stdout.splitlines() if " " in line)
    print(done.stdout, end="")
    if "mean_arcsec" in got:
        m = float(got["mean_arcsec"])
        check(abs(m - dyn["mean_arcsec"]) <= TOLERANCE_ARCSEC,
              "octave: TE mean %.12f arcsec, results.json %.12f (|diff| %.3g)" % (m, dyn["mean_arcsec"], abs(m - dyn["mean_arcsec"])))
        check(abs(float(got["p2p_arcsec"]) - dyn["p2p_arcsec"]) <= TOLERANCE_ARCSEC, "octave: TE p2p as results.json")
        check(int(got["samples"]) == n, "octave: the record has %s samples" % got["samples"])
        check(float(got["results_mean_arcsec"]) == dyn["mean_arcsec"], "octave: results.dynamic.mean_arcsec")
        check(got.get("unit_theta_in") == "rad" and got.get("unit_torque") == "N*m", "octave: units struct")
        check(int(got["rows"]) == total, "octave: %s rows" % got["rows"])
        check(got.get("class_sync_counter") == "uint32" and got.get("class_flags") == "uint32", "octave: integer classes")
        check(got.get("run_id") == run_id, "octave: run_id")
    else:
        check(False, "octave printed no mean")

    # Hostile input: a bad format names the option and the value, exit 2, nothing written.
    done = run([cli, "export", run_id, "--runs", str(runs), "--format", "xlsx", "--out", str(work / "bad")])
    check(done.returncode == 2 and "--format" in done.stderr and "xlsx" in done.stderr and not (work / "bad").exists(),
          "bad format: exit %d, %s" % (done.returncode, done.stderr.strip()))
    # A folder the export did not write is never touched.
    foreign = work / "foreign"
    foreign.mkdir()
    (foreign / "samples.csv").write_text("mine\n")
    done = run([cli, "export", run_id, "--runs", str(runs), "--format", "csv", "--out", str(foreign)])
    check(done.returncode == 2 and (foreign / "samples.csv").read_text() == "mine\n" and "--out" in done.stderr,
          "foreign folder: exit %d, file kept, %s" % (done.returncode, done.stderr.strip()))
    # Its own folder is written again.
    done = run([cli, "export", run_id, "--runs", str(runs), "--format", "mat", "--out", str(outs["csv"])])
    check(done.returncode == 0 and (outs["csv"] / "samples.mat").exists(), "own folder: exported again")
    # A run id that leaves the store is refused.
    done = run([cli, "export", "../runs", "--runs", str(runs), "--format", "csv", "--out", str(work / "escape")])
    check(done.returncode == 2 and "run_id" in done.stderr, "run id '../runs': exit %d" % done.returncode)

    print("%d passed, %d failed" % (len(passes), len(failures)))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
