"""results.json of every procedure, as `wavebench run` writes it on the in-process simulated
bench, against docs/formats/results.schema.json, checked by an independent validator
(Debian's python3-jsonschema). A results.json with a wrong type, a missing required key or an
unknown key must be refused, so that the check itself can fail.

Every declared figure (src/figures, printed by FIGURE_DECLARATIONS) must resolve in a real
results.json of its procedure, its uncertainty where it says, and its path must be one the
schema describes.

Usage: /usr/bin/python3 results_schema_test.py WAVEBENCH_CLI SOURCE_DIR WORK_DIR FIGURE_DECLARATIONS
"""

import copy
import json
import shutil
import subprocess
import sys
from pathlib import Path

try:
    import jsonschema
except ImportError:
    sys.exit(
        "results_schema_test: FAIL: this Python (" + sys.executable + ") has no jsonschema module;"
        " install Debian's python3-jsonschema (scripts/install-deps.sh) and run it with /usr/bin/python3"
    )


def errors_of(validator, instance):
    return sorted(
        ("/".join(str(p) for p in e.absolute_path) or "(top)") + ": " + e.message
        for e in validator.iter_errors(instance)
    )


def resolve(node, parts):
    """Every value a declaration's path (keys, `name[*]` every element) reaches; null left out."""
    if not parts or not isinstance(node, dict):
        return []
    key, rest = parts[0], parts[1:]
    every = key.endswith("[*]")
    key = key[:-3] if every else key
    if key not in node:
        return []
    item = node[key]
    if every:
        return [v for e in item for v in resolve(e, rest)] if isinstance(item, list) and rest else []
    if rest:
        return resolve(item, rest)
    return [] if item is None else [item]


def schema_has(schema, node, parts):
    """The schema describes the path (properties, items and $ref followed)."""
    while isinstance(node, dict) and "$ref" in node:
        node = schema["$defs"][node["$ref"].split("/")[-1]]
    if not parts:
        return True
    key = parts[0]
    every = key.endswith("[*]")
    key = key[:-3] if every else key
    child = (node or {}).get("properties", {}).get(key)
    if child is None:
        return False
    if every:
        while isinstance(child, dict) and "$ref" in child:
            child = schema["$defs"][child["$ref"].split("/")[-1]]
        child = child.get("items")
    return schema_has(schema, child, parts[1:])


def check_declarations(declarations, produced, schema):
    failed = False
    by_procedure = {}
    for results in produced.values():
        by_procedure.setdefault(results.get("procedure"), []).append(results)
    procedures = {d["procedure"] for d in declarations if d["procedure"] != "*"}
    missing_runs = procedures - set(by_procedure)
    if missing_runs:
        print("FAIL figures declared for procedures no case runs:", sorted(missing_runs))
        failed = True
    for d in declarations:
        runs = [r for rs in by_procedure.values() for r in rs] if d["procedure"] == "*" \
            else by_procedure.get(d["procedure"], [])
        found = [v for r in runs for v in resolve(r, d["path"].split("."))]
        numbers = [v for v in found if isinstance(v, (int, float)) or
                   (isinstance(v, dict) and isinstance(v.get("value"), (int, float)))]
        if not numbers:
            print("FAIL figure", d["name"] + ": path", d["path"], "reaches no number in a",
                  d["procedure"], "results.json")
            failed = True
            continue
        if d["uncertainty_path"]:
            u = [v for r in runs for v in resolve(r, d["uncertainty_path"].split("."))]
            if not any(isinstance(v, dict) and "expanded" in v for v in u):
                print("FAIL figure", d["name"] + ": uncertainty_path", d["uncertainty_path"],
                      "reaches no uncertain figure")
                failed = True
                continue
        if not schema_has(schema, schema, d["path"].split(".")):
            print("FAIL figure", d["name"] + ": the schema does not describe", d["path"])
            failed = True
            continue
        print("ok   figure", d["name"], "at", d["path"], "=", json.dumps(numbers[0])[:60])
    return failed


def main():
    cli, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    schema = json.loads((source / "docs/formats/results.schema.json").read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)

    sim = "sim"
    encoder = str(source / "configs/benches/sim-input-encoder.yaml")
    cases = {
        "static, 4 positions, a limit": (sim, ["static", "--positions", "4", "--loads", "0,30", "--window", "0.1",
                                              "--no-twin", "--limit", "static_p2p_arcmin=100"]),
        "static with an extra channel": (encoder, ["static", "--positions", "4", "--loads", "0", "--window", "0.1",
                                                  "--no-twin"]),
        "static with the twin, its calibration and the report": (sim, ["static", "--positions", "4", "--loads",
                                                                       "0,30", "--window", "0.1", "--report"]),
        "dynamic, short, with the twin and a spec": (sim, ["dynamic", "--rpm", "600", "--revolutions", "1",
                                                           "--option", "run_in_s=0.2",
                                                           "--limit", "dynamic_rms_arcsec=1000",
                                                           "--spec", "sim-seed004"]),
        "lost motion": (sim, ["lost-motion", "--torques", "5,10,20,40", "--no-twin",
                              "--limit", "lost_motion_arcmin=100"]),
        "static, 2 repeats": (sim, ["static", "--positions", "4", "--loads", "0", "--window", "0.1",
                                   "--no-twin", "--option", "repeats=2"]),
        "endurance, 2 revolutions, with the twin and the report": (sim, ["endurance", "--option", "input_rpm=600",
                                                                    "--option", "output_revolutions=2",
                                                                    "--option", "run_in_s=0.2", "--report"]),
        "torsional, coarse steps, with the report": (sim, ["torsional", "--option", "twist_step_rad=0.0001",
                                                           "--option", "window_s=0.05", "--no-twin",
                                                           "--report"]),
    }
    failed = False
    produced = {}
    for name, (bench, args) in cases.items():
        report = "--report" in args
        args = [a for a in args if a != "--report"] + ([] if report else ["--no-report"])
        cmd = [cli, "run", *args, "--bench", bench, "--out", str(work / "runs"), "--quiet"]
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
        if done.returncode != 0:
            print("FAIL", name + ":", " ".join(cmd), "exited", done.returncode, "\n" + done.stdout + done.stderr)
            failed = True
            continue
        paths = [l[len("results: "):] for l in done.stdout.splitlines() if l.startswith("results: ")]
        if not paths:
            print("FAIL", name + ": no 'results: ' line in\n" + done.stdout)
            failed = True
            continue
        results = json.loads(Path(paths[0]).read_text())
        produced[name] = results
        errors = errors_of(validator, results)
        if errors:
            print("FAIL", name + ":", paths[0], "does not match the schema:\n  " + "\n  ".join(errors))
            failed = True
        else:
            print("ok  ", name + ":", results["procedure"], results["status"], "sections:",
                  ",".join(sorted(results)))

    # What the cases are there for actually appears in them (so that a schema that merely
    # allows a section is exercised on it).
    expected_sections = {
        "static, 4 positions, a limit": ["static", "lost_motion", "load_shift", "limit_checks", "acquisition"],
        "static with an extra channel": ["extra_channels"],
        "static with the twin, its calibration and the report": ["twin", "report"],
        "dynamic, short, with the twin and a spec": ["dynamic", "twin", "limit_checks", "spec", "verdict"],
        "lost motion": ["lost_motion_fit", "limit_checks"],
        "static, 2 repeats": ["repeats", "static"],
        "torsional, coarse steps, with the report": ["torsional", "report"],
        "endurance, 2 revolutions, with the twin and the report": ["endurance", "twin", "report"],
    }
    for name, keys in expected_sections.items():
        missing = [k for k in keys if name in produced and k not in produced[name]]
        if missing:
            print("FAIL", name + ": expected sections missing:", missing)
            failed = True
    for name in ("static with the twin, its calibration and the report",
                 "dynamic, short, with the twin and a spec"):
        twin = produced.get(name, {}).get("twin", {})
        if "error" in twin or "residual" not in twin:
            print("FAIL", name + ": the twin did not run through:", json.dumps(twin)[:300])
            failed = True
    # A spec's limits are checked (the twin residual among them) and give the verdict.
    spec_run = produced.get("dynamic, short, with the twin and a spec", {})
    checked = {c["limit"] for c in spec_run.get("limit_checks", [])}
    if spec_run and (spec_run.get("spec", {}).get("name") != "sim-seed004"
                     or spec_run.get("verdict") not in ("PASS", "FAIL")
                     or not {"dynamic_p2p_arcsec", "twin_residual_rms_arcsec", "dynamic_rms_arcsec"} <= checked
                     or spec_run["verdict"] != ("PASS" if spec_run["pass"] else "FAIL")):
        print("FAIL dynamic with a spec: spec", json.dumps(spec_run.get("spec"))[:200], "verdict",
              spec_run.get("verdict"), "checks", sorted(checked))
        failed = True
    elif spec_run:
        print("ok   spec", spec_run["spec"]["name"], "verdict", spec_run["verdict"], "checks", sorted(checked))
    base_no_spec = produced.get("static, 4 positions, a limit", {})
    if base_no_spec and (base_no_spec.get("spec", "absent") is not None or base_no_spec.get("verdict") != "PASS"):
        print("FAIL static without a spec: spec", base_no_spec.get("spec", "absent"), "verdict",
              base_no_spec.get("verdict"))
        failed = True
    twin = produced.get("static with the twin, its calibration and the report", {}).get("twin", {})
    if "calibration" not in twin:
        print("FAIL static with the twin: no twin.calibration")
        failed = True

    # The validator must refuse what breaks the schema.
    base = produced.get("static, 4 positions, a limit")
    if base is None:
        print("FAIL no static results to break")
        sys.exit(1)
    broken = {}
    b = copy.deepcopy(base); b["static"][0]["p2p_arcmin"] = "big"; broken["p2p as text"] = b
    b = copy.deepcopy(base); del b["status"]; broken["status missing"] = b
    b = copy.deepcopy(base); b["colour"] = "blue"; broken["unknown top-level key"] = b
    b = copy.deepcopy(base); b["options"]["positions"] = "4"; broken["positions as text"] = b
    b = copy.deepcopy(base); b["schema"] = "wavebench.results/1"; broken["another major version"] = b
    b = copy.deepcopy(base); b["static"][0]["uncertainty"]["p2p_arcmin"]["expanded"] = "small"
    broken["an expanded uncertainty as text"] = b
    b = copy.deepcopy(base); b["limit_checks"][0]["decision"] = "MAYBE"; broken["a check decision that is not PASS, FAIL or UNDECIDED"] = b
    b = copy.deepcopy(base); del b["static"]; broken["complete static run without its passes"] = b
    b = copy.deepcopy(base); b["acquisition"]["log_queue_dropped"] = -1; broken["negative count"] = b
    b = copy.deepcopy(base); b["status"] = "aborted"; broken["aborted without a reason"] = b
    b = copy.deepcopy(base); b["partial"] = {"from_aborted_run": True, "finished": 1, "planned": 2, "unit": "passes"}
    broken["a complete run marked partial"] = b
    b = copy.deepcopy(base); b["verdict"] = "MAYBE"; broken["a verdict that is not PASS, FAIL, UNDECIDED or null"] = b
    b = copy.deepcopy(base); b["spec"] = {"name": "../x", "model": "M", "lost_motion_at_percent": None,
                                          "limits": []}; broken["a spec name with a path"] = b
    for name, instance in broken.items():
        if validator.is_valid(instance):
            print("FAIL the schema accepts a results.json with", name)
            failed = True
        else:
            print("ok   refused:", name)
    # An aborted run has no procedure section, no verdict and a reason (the shape execute_run
    # writes after a trip; the simulated bench does not trip on request from the command line).
    if "lost motion" in produced:
        aborted = copy.deepcopy(produced["lost motion"])
        for key in ("lost_motion_fit", "limit_checks", "pass"):
            del aborted[key]
        aborted.update(status="aborted", reason="over-torque: 151 N*m > 150 N*m", verdict=None)
        errors = errors_of(validator, aborted)
        if errors:
            print("FAIL an aborted run's shape is refused:\n  " + "\n  ".join(errors))
            failed = True
        else:
            print("ok   accepted: an aborted lost-motion run")

    # An aborted static run with the passes it had finished (issue #22), marked partial.
    aborted = copy.deepcopy(base)
    for key in ("limit_checks", "pass", "undecided_counts_as"):
        aborted.pop(key, None)
    aborted.update(status="aborted", reason="EMCY from node 1 (servo drive)", verdict=None,
                   partial={"from_aborted_run": True, "finished": 2, "planned": 4, "unit": "passes"})
    errors = errors_of(validator, aborted)
    if errors:
        print("FAIL an aborted static run with its finished passes is refused:\n  " + "\n  ".join(errors))
        failed = True
    else:
        print("ok   accepted: an aborted static run with its finished passes, marked partial")

    # The torsional figures are uncertain figures; a plain number in their place is refused.
    if "torsional, coarse steps, with the report" in produced:
        b = copy.deepcopy(produced["torsional, coarse steps, with the report"])
        b["torsional"]["lost_motion_arcmin"] = 0.5
        if validator.is_valid(b):
            print("FAIL the schema accepts a torsional lost motion without its uncertainty")
            failed = True
        else:
            print("ok   refused: a torsional lost motion without its uncertainty")

    declarations = json.loads(subprocess.run([sys.argv[4]], capture_output=True, text=True,
                                             check=True).stdout)
    if not declarations:
        print("FAIL no figure declarations")
        failed = True
    failed = check_declarations(declarations, produced, schema) or failed

    if failed:
        sys.exit(1)
    shutil.rmtree(work, ignore_errors=True)
    print("results_schema_test: every results.json matches", schema["properties"]["schema"]["const"])


if __name__ == "__main__":
    main()
