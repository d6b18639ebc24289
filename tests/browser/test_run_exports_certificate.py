#!/usr/bin/python3
"""Exports, compare of many runs, the certificate and the history's serial prefix, in headless
Chromium against wavebenchd on the in-process simulated bench (issue #21). Six short static
runs against the simulated unit's spec and one aborted run are made through the API, then
- compare of all six draws every run (a daemon that serves two reads at once answers the
  others "busy": the page queues and retries, and shows no error);
- the run page's export buttons download files that independent readers open: the .mat in
  Octave, the HDF5 in h5py, the CSV and JSON in Python; each holds the run's sample count;
- the certificate of a run with a spec prints on exactly one A4 page (Chromium's PDF), with
  the limits' display names and units and times to the second; the aborted run's says it is
  not a certificate;
- the history's unit filter is a prefix ("0042" finds "0042-A"; "0042_" does not find
  "0042-B": LIKE wildcards in the text are literal);
- the fleet page warns that SPC from fewer than 25 runs is rough, and prints Cpk to 2 decimals.
Screenshots (and the certificate PDFs, with PNGs of them when pdftoppm is there) go to
<build>/test-output/browser/.

Usage: test_run_exports_certificate.py WAVEBENCHD WEB_ROOT OUTPUT_DIR
"""
import base64
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.request

from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

from test_run_pages import OUTPUT, STATIC_OPTIONS, WAVEBENCHD, ConsolePageTest

SPEC = "sim-seed004"
SERIALS = ["0042-A", "0042-B", "0042_X", "1042-A", "0043-C", "0042-A"]
# Long enough to abort while it records.
LONG_STATIC = {"positions": 64, "loads_nm": [0, 10, 20], "window_s": 0.5}


def pdf_pages(data):
    return len(re.findall(rb"/Type\s*/Page(?!s)", data))


class RunExportsCertificateTest(ConsolePageTest):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.runs = []
        for serial in SERIALS:
            run_id, status = cls.daemon.run("static", STATIC_OPTIONS, SPEC, unit_serial=serial,
                                            operator="A. Tester")
            assert status == "complete", f"static run {run_id} ended {status}"
            cls.runs.append(run_id)
        cls.aborted, cls.running_view = cls.make_aborted_run()
        cls.start_browser()

    @classmethod
    def make_aborted_run(cls):
        """A long static run, aborted while it records; what its run record said meanwhile."""
        status, body = cls.daemon.request("POST", "/api/runs", {
            "procedure": "static", "options": LONG_STATIC, "spec": SPEC, "unit_serial": "0099-ABORT"})
        assert status in (201, 202), body
        run_id = body.get("run_id")
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            _, s = cls.daemon.request("GET", "/api/status")
            if s.get("run"):
                run_id = run_id or (s["run"].get("id") or s["run"].get("run_id"))
                break
            time.sleep(0.05)
        time.sleep(1.0)
        _, detail = cls.daemon.request("GET", f"/api/runs/{run_id}")
        status, body = cls.daemon.request("POST", "/api/abort", {})
        assert status in (200, 202), body
        # Recorded, then its results made in the background (status processing meanwhile).
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline:
            _, s = cls.daemon.request("GET", "/api/status")
            if s.get("run") is None and (s.get("last_run") or {}).get("status") != "processing":
                break
            time.sleep(0.1)
        _, after = cls.daemon.request("GET", f"/api/runs/{run_id}")
        assert after["run"]["status"] == "aborted", after["run"]
        return run_id, detail

    def wait_ready(self, timeout=60):
        WebDriverWait(self.browser, timeout).until(
            lambda b: b.execute_script("return document.body.dataset.ready === 'true'"
                                       " || !!document.querySelector('.message.error')"))

    def fetch(self, path):
        req = urllib.request.Request(self.daemon.url + path)
        req.add_header("Authorization", "Bearer " + self.daemon.token)
        req.add_header("X-Wavebench-Request", "test")
        for _ in range(100):
            try:
                with urllib.request.urlopen(req, timeout=60) as r:
                    return r.read(), dict(r.headers)
            except urllib.error.HTTPError as e:
                if e.code != 503:
                    raise
                time.sleep(0.2)
        raise RuntimeError(f"{path}: busy for 20 s")

    def sample_count(self, run_id):
        _, page = self.daemon.request("GET", f"/api/runs/{run_id}/samples?from=0&limit=1")
        return page["total"]

    def print_pdf(self, name):
        pdf = self.browser.execute_cdp_cmd("Page.printToPDF", {
            "paperWidth": 8.27, "paperHeight": 11.69, "printBackground": True,
            "marginTop": 0, "marginBottom": 0, "marginLeft": 0, "marginRight": 0,
            "preferCSSPageSize": True})
        data = base64.b64decode(pdf["data"])
        path = os.path.join(OUTPUT, name + ".pdf")
        with open(path, "wb") as f:
            f.write(data)
        if shutil.which("pdftoppm"):
            subprocess.run(["pdftoppm", "-png", "-r", "80", path, os.path.join(OUTPUT, name)], check=True)
        return data

    def test_compare_of_six_runs_draws_all(self):
        self.open("/compare?ids=" + ",".join(self.runs))
        self.shot("compare-6")
        rows = self.browser.find_elements(By.CSS_SELECTOR, "#compare-table > tbody > tr")
        self.assertEqual(len(rows), 6)
        entries = self.browser.find_elements(By.CSS_SELECTOR, "#static-plot .u-legend tr.u-series")
        self.assertEqual(len(entries), 1 + 6 * 2)  # x, then 6 runs x (forward, reverse)
        self.assertEqual([e.text for e in self.browser.find_elements(By.CSS_SELECTOR, ".message.error")], [])

    def test_export_buttons_download_files_octave_and_h5py_read(self):
        run_id = self.runs[0]
        samples = self.sample_count(run_id)
        self.assertGreater(samples, 100)
        self.open(f"/run?id={run_id}")
        self.shot("run-page-exports")
        links = {a.get_attribute("data-format"): a for a in
                 self.browser.find_elements(By.CSS_SELECTOR, "#exports-bar a.export")}
        self.assertEqual(set(links), {"mat", "hdf5", "csv", "json"})

        # A run's samples need a login (issue #22): without one the page says so.
        links["csv"].click()
        WebDriverWait(self.browser, 30).until(
            lambda b: "log in" in b.find_element(By.ID, "export-note").text)
        self.shot("run-page-exports-needs-login")
        self.browser.get(self.daemon.url + "/login")
        self.browser.find_element(By.ID, "token").send_keys(self.daemon.token)
        self.browser.find_element(By.ID, "login").click()
        WebDriverWait(self.browser, 30).until(lambda b: "/login" not in b.current_url)
        self.open(f"/run?id={run_id}")
        links = {a.get_attribute("data-format"): a for a in
                 self.browser.find_elements(By.CSS_SELECTOR, "#exports-bar a.export")}

        # A click saves the file through Chromium's download folder.
        downloads = tempfile.mkdtemp(prefix="wavebench-downloads-")
        try:
            self.browser.execute_cdp_cmd("Browser.setDownloadBehavior",
                                         {"behavior": "allow", "downloadPath": downloads})
            links["mat"].click()
            WebDriverWait(self.browser, 60).until(
                lambda b: [f for f in os.listdir(downloads) if f.endswith(".mat")])
            WebDriverWait(self.browser, 10).until(
                lambda b: "saved" in b.find_element(By.ID, "export-note").text)
            clicked = os.path.join(downloads, [f for f in os.listdir(downloads) if f.endswith(".mat")][0])
            time.sleep(0.5)
            self.assertGreater(os.path.getsize(clicked), 1000)

            files = {}
            for fmt, link in links.items():
                data, headers = self.fetch(link.get_attribute("href").replace(self.daemon.url, ""))
                self.assertEqual(int(headers["X-Wavebench-Samples"]), samples, fmt)
                files[fmt] = os.path.join(downloads, f"export.{fmt}")
                with open(files[fmt], "wb") as f:
                    f.write(data)

            for path in (clicked, files["mat"]):
                out = subprocess.run(
                    ["octave-cli", "--no-gui", "--quiet", "--eval",
                     f"load('{path}'); printf('%d %d\\n', numel(theta_out), numel(torque));"],
                    capture_output=True, text=True, timeout=120)
                self.assertEqual(out.returncode, 0, out.stderr)
                self.assertEqual(out.stdout.split()[-2:], [str(samples)] * 2, out.stdout)
            out = subprocess.run(
                ["/usr/bin/python3", "-c",
                 "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); "
                 "print(len(f['samples/theta_out']), len(f['samples/torque']))", files["hdf5"]],
                capture_output=True, text=True, timeout=60)
            self.assertEqual(out.returncode, 0, out.stderr)
            self.assertEqual(out.stdout.split(), [str(samples)] * 2)
            with open(files["csv"], newline="") as f:
                rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
            self.assertEqual(len(rows) - 1, samples)  # a header line, then one row a sample
            with open(files["json"]) as f:
                doc = json.load(f)
            listed = doc["samples"] if isinstance(doc, dict) else doc
            self.assertEqual(len(listed), samples)
        finally:
            shutil.rmtree(downloads, ignore_errors=True)

    def test_running_run_page_disables_exports_with_a_reason(self):
        # The aborted run's record while it was still recording.
        self.assertEqual(self.running_view["run"]["status"], "running")
        self.browser.get(self.daemon.url + f"/run?id={self.aborted}")
        self.wait_ready()
        # Now it is aborted: exports are there (what it recorded).
        self.assertEqual(len(self.browser.find_elements(By.CSS_SELECTOR, "#exports-bar a.export")), 4)
        # The page's rule for a run still recording, on the record as it was.
        reason = self.browser.execute_script(
            "return import('/js/run_exports.js').then((m) => { const bar = m.exportButtons(arguments[0]);"
            " return [...bar.querySelectorAll('button[disabled]')].map((b) => b.title); });",
            self.running_view["run"])
        self.assertEqual(len(reason), 4)
        self.assertIn("still recording", reason[0])

    def test_certificate_is_one_a4_page_with_display_names(self):
        run_id = self.runs[0]
        self.open(f"/certificate?id={run_id}")
        self.shot("certificate")
        sheet = self.browser.find_element(By.ID, "sheet")
        self.assertEqual(sheet.get_attribute("data-certificate"), "true")
        text = sheet.text
        for expected in ["0042-A", "Bench unit (seed 004)", "sim-seed004",
                         "Static transmission error, peak-to-peak [arcmin]", "A. Tester",
                         "Approved by", "output encoder", "SIM-ENC-2026-001", "2027-06-30",
                         "Config hash"]:
            self.assertIn(expected, text)
        self.assertNotIn("static_p2p_arcmin", text)
        times = re.findall(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d(\.\d+)? UTC", text)
        self.assertEqual(len(times), 2, text)  # started, finished
        self.assertEqual([t for t in times if t], [], "times to the second")
        # Each figure ± U, U to two significant digits and the value at its last decimal.
        for cell in self.browser.find_elements(By.CSS_SELECTOR, "#cert-limits tbody tr td:nth-child(4)"):
            if cell.text.endswith("(no U stated)"):  # a model-fit figure (the twin residual)
                continue
            m = re.fullmatch(r"(-?\d+(?:\.(\d+))?) ± (\d+(?:\.(\d+))?)", cell.text)
            self.assertIsNotNone(m, cell.text)
            self.assertEqual(len(m.group(2) or ""), len(m.group(4) or ""), cell.text)
        self.assertEqual(len(self.browser.find_elements(By.CSS_SELECTOR, "#cert-verdict")), 1)

        data = self.print_pdf("certificate")
        self.assertEqual(pdf_pages(data), 1)

    def test_aborted_run_prints_not_a_certificate(self):
        self.open(f"/certificate?id={self.aborted}")
        self.shot("certificate-aborted")
        sheet = self.browser.find_element(By.ID, "sheet")
        self.assertEqual(sheet.get_attribute("data-certificate"), "false")
        banner = self.browser.find_element(By.ID, "not-certificate").text
        self.assertIn("NOT A CERTIFICATE", banner)
        self.assertRegex(banner, r"run aborted: .*abort")
        self.assertEqual(self.browser.find_elements(By.ID, "cert-verdict"), [])
        self.assertEqual(self.browser.find_elements(By.ID, "cert-approval"), [])
        self.browser.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "print"})
        try:
            self.assertTrue(self.browser.find_element(By.ID, "not-certificate").is_displayed())
        finally:
            self.browser.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": ""})
        data = self.print_pdf("certificate-aborted")
        self.assertEqual(pdf_pages(data), 1)

    def test_history_filters_by_serial_prefix(self):
        self.open("/history")
        box = self.browser.find_element(By.CSS_SELECTOR, "#filters input[name=unit]")
        box.send_keys("0042")
        self.browser.find_element(By.CSS_SELECTOR, "#filters button[type=submit]").click()
        WebDriverWait(self.browser, 10).until(lambda b: "unit=0042" in b.current_url)
        WebDriverWait(self.browser, 10).until(
            lambda b: len(b.find_elements(By.CSS_SELECTOR, "#runs tbody tr")) == 4)
        self.shot("history-prefix")
        units = sorted(r.find_elements(By.TAG_NAME, "td")[2].text
                       for r in self.browser.find_elements(By.CSS_SELECTOR, "#runs tbody tr"))
        self.assertEqual(units, ["0042-A", "0042-A", "0042-B", "0042_X"])
        # "_" in the filter is a character, not LIKE's any-character.
        _, page = self.daemon.request("GET", "/api/runs?unit=0042_")
        self.assertEqual([r["unit_serial"] for r in page["runs"]], ["0042_X"])
        _, page = self.daemon.request("GET", "/api/runs?unit=0042%25")
        self.assertEqual(page["runs"], [])

    def test_fleet_warns_below_25_runs_and_rounds_cpk(self):
        for _ in range(100):
            _, body = self.daemon.request("GET", "/api/fleet/runs?limit=100")
            if len([r for r in body["runs"] if r.get("status") == "complete"]) >= 6:
                break
            time.sleep(0.2)
        self.open("/fleet")
        WebDriverWait(self.browser, 20).until(lambda b: b.find_elements(By.ID, "spc-warning"))
        self.shot("fleet-spc-warning")
        warning = self.browser.find_element(By.ID, "spc-warning").text
        self.assertIn("fewer than 25 runs", warning)
        cpk = self.browser.find_element(By.CSS_SELECTOR, "#spc-table tr[data-key='cpk'] td").text
        self.assertRegex(cpk, r"^-?\d+\.\d\d$|^–$")


if __name__ == "__main__":
    if not WAVEBENCHD or not OUTPUT:
        sys.exit(__doc__)
    unittest.main(argv=[sys.argv[0], "-v"])
