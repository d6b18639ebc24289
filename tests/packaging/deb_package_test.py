#!/usr/bin/python3
"""The Debian package, end to end: cpack builds it from this build tree; its control data and
file list are where Debian expects them; dpkg-deb unpacks it into a throw-away root; the
wavebenchd inside that root starts from there (finding its configs and console inside the root,
not in the source tree) and serves the console and the API on the simulated bench.

Usage: deb_package_test.py BUILD_DIR WORK_DIR
"""
import glob
import http.client
import json
import os
import re
import shutil
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import packaged_unit  # noqa: E402
from checks import check, fail


def get(port, path, host=None):
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=20)
    connection.request("GET", path, headers={"Host": host or f"127.0.0.1:{port}"})
    response = connection.getresponse()
    body = response.read()
    connection.close()
    return response.status, dict(response.getheaders()), body


def main():
    build_dir, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    package_dir = os.path.join(work, "package")
    subprocess.run(["cpack", "-G", "DEB", "-B", package_dir], cwd=build_dir, check=True,
                   stdout=subprocess.DEVNULL)
    debs = glob.glob(os.path.join(package_dir, "wavebench_*_*.deb"))
    check(len(debs) == 1, f"cpack made one package ({debs})")
    deb = debs[0]

    control = subprocess.run(["dpkg-deb", "-f", deb], check=True, capture_output=True,
                             text=True).stdout
    check(re.search(r"^Package: wavebench$", control, re.M) is not None, "package name")
    check(re.search(r"^Depends: .*libmodbus5", control, re.M) is not None,
          "dependencies found by dpkg-shlibdeps (libmodbus5 among them)")
    files = subprocess.run(["dpkg-deb", "-c", deb], check=True, capture_output=True,
                           text=True).stdout
    for path in ["./usr/bin/wavebench", "./usr/bin/wavebenchd",
                 "./usr/lib/systemd/system/wavebenchd.service",
                 "./usr/share/wavebench/configs/benches/sim.yaml",
                 "./usr/share/wavebench/web/index.html",
                 "./usr/share/wavebench/web/vendor/uPlot.iife.min.js",
                 "./usr/share/wavebench/wavebenchd.env",
                 "./usr/share/doc/wavebench/README.md"]:
        check(re.search(r"\s" + re.escape(path) + r"$", files, re.M) is not None,
              f"package holds {path}")
    check("/usr/local" not in files and "/home/" not in files and "/work/" not in files,
          "nothing outside the FHS paths of a package")

    root = os.path.join(work, "root")
    subprocess.run(["dpkg-deb", "-x", deb, root], check=True)
    unit = open(os.path.join(root, "usr/lib/systemd/system/wavebenchd.service")).read()
    check("ExecStart=/usr/bin/wavebenchd " in unit, "the unit starts /usr/bin/wavebenchd")
    check(re.search(r"^User=wavebench$", unit, re.M) is not None and
          re.search(r"^StateDirectory=wavebench$", unit, re.M) is not None,
          "the unit runs as its own user with its state under /var/lib/wavebench")
    score, analysis = packaged_unit.exposure(
        os.path.join(root, "usr/lib/systemd/system/wavebenchd.service"))
    check(score is not None and score <= 4.0,
          f"the packaged unit's exposure in systemd-analyze security is {score} <= 4.0"
          + ("" if score is not None else "\n" + analysis))
    scripts = os.path.join(work, "control")
    subprocess.run(["dpkg-deb", "-e", deb, scripts], check=True)
    for script in ["postinst", "prerm", "postrm"]:
        subprocess.run(["sh", "-n", os.path.join(scripts, script)], check=True)
    check("adduser --system" in open(os.path.join(scripts, "postinst")).read(),
          "postinst creates the system user")
    check("deluser --quiet --system wavebench" in open(os.path.join(scripts, "postrm")).read(),
          "postrm purge deletes it")

    daemon = os.path.join(root, "usr/bin/wavebenchd")
    version = subprocess.run([daemon, "--version"], check=True, capture_output=True,
                             text=True).stdout.strip()
    check(re.fullmatch(r"wavebenchd \d+\.\d+\.\d+ \(commit [0-9a-f]{12}(\+dirty)?\)|"
                       r"wavebenchd \d+\.\d+\.\d+ \(commit unknown\)", version) is not None,
          f"--version names version and commit ({version})")

    env = {k: v for k, v in os.environ.items()
           if k not in ("WAVEBENCH_CONFIG_DIR", "WAVEBENCH_WEB_DIR")}
    runs = os.path.join(work, "runs")
    token = os.path.join(work, "token")
    log = open(os.path.join(work, "wavebenchd.out"), "w+")
    process = subprocess.Popen([daemon, "--config", "sim", "--listen", "127.0.0.1:0",
                                "--runs", runs, "--token-file", token],
                               stdout=subprocess.PIPE, stderr=log, text=True, env=env,
                               cwd=work)
    try:
        port = packaged_unit.listening_port(process.stdout)
        if port is None:
            log.seek(0)
            fail("the installed wavebenchd did not start:\n" + log.read())
        log.flush()
        log.seek(0)
        started = log.read()
        check(os.path.join(root, "usr/share/wavebench/configs/benches/sim.yaml") in started,
              "the installed daemon reads the simulated bench config from its own root")
        check(os.path.join(root, "usr/share/wavebench/web") in started,
              "the installed daemon serves the console from its own root")

        status, _, body = get(port, "/api/status")
        check(status == 200, "GET /api/status")
        software = json.loads(body)["software"]
        check(software["version"] in version and software["commit"] in version,
              f"/api/status names the same version and commit ({software})")
        status, headers, body = get(port, "/")
        installed_index = open(os.path.join(root, "usr/share/wavebench/web/index.html"),
                               "rb").read()
        check(status == 200 and body == installed_index and
              headers.get("Content-Type", "").startswith("text/html"),
              "GET / serves the installed console page")
        status, headers, body = get(port, "/vendor/uPlot.iife.min.js")
        check(status == 200 and len(body) > 10000, "the console's chart library is served")
        status, _, _ = get(port, "/", host="evil.example:8470")
        check(400 <= status < 500, f"a foreign Host header is refused ({status})")
    finally:
        process.send_signal(signal.SIGTERM)
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
            fail("the installed wavebenchd did not stop on SIGTERM")
    check(process.returncode == 0, "the installed wavebenchd stops cleanly on SIGTERM")
    print("deb package: all checks passed")


if __name__ == "__main__":
    main()
