#!/usr/bin/python3
"""The run page, the history and compare in headless Chromium against wavebenchd on the
in-process simulated bench: two short static runs are made through the API, then
- the run page shows the header, the verdict, the static table and its plots, and the trace
  endpoint's TE plot; in print media the navigation and buttons are gone;
- the figure table shows every figure the procedure declares (GET /api/procedures), and a
  figure declared anew (here: injected into /api/procedures' answer) shows without a JS edit;
- the history's procedures come from /api/procedures; it lists both runs, a procedure filter with no match shows none, and ticking both
  opens compare, which draws both runs' static curves on one plot with a legend per run.
Screenshots go to <build>/test-output/browser/.

Usage: test_run_pages.py WAVEBENCHD WEB_ROOT OUTPUT_DIR
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.error
import urllib.request

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait

from daemon_harness import chromium

WAVEBENCHD, WEB_ROOT, OUTPUT = (sys.argv[1:4] + [None] * 3)[:3]
STATIC_OPTIONS = {"positions": 4, "loads_nm": [0], "window_s": 0.05}
# Short on the simulated clock: one output revolution at 2400 rpm (the sim's limit is 3000).
DYNAMIC_OPTIONS = {"input_rpm": 2400, "run_in_s": 0.2, "output_revolutions": 1}


class Daemon:
    def __init__(self):
        self.dir = tempfile.mkdtemp(prefix="wavebench-pages-")
        token_file = os.path.join(self.dir, "token")
        args = [WAVEBENCHD, "--config", "sim", "--listen", "127.0.0.1:0",
                "--runs", os.path.join(self.dir, "runs"), "--token-file", token_file]
        if WEB_ROOT:
            args += ["--web-root", WEB_ROOT]
        self.log = open(os.path.join(self.dir, "daemon.log"), "w+")
        self.process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=self.log, text=True)
        deadline = time.monotonic() + 60
        self.url = None
        while time.monotonic() < deadline:
            line = self.process.stdout.readline()
            if not line:
                break
            match = re.search(r"listening on (http://127\.0\.0\.1:\d+)", line)
            if match:
                self.url = match.group(1)
                break
        if not self.url:
            self.stop()
            raise RuntimeError("wavebenchd did not say where it listens")
        with open(token_file) as f:
            self.token = f.read().strip()

    def request(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.url + path, data=data, method=method)
        req.add_header("Authorization", "Bearer " + self.token)
        req.add_header("X-Wavebench-Request", "test")
        if data is not None:
            req.add_header("Content-Type", "application/json")
        try:
            with urllib.request.urlopen(req, timeout=60) as r:
                return r.status, json.loads(r.read())
        except urllib.error.HTTPError as e:
            return e.code, json.loads(e.read() or b"{}")

    def run(self, procedure, options, spec=None, **fields):
        """Starts a run (`fields`: unit_serial, operator, ...) and waits until it is finished,
        its post-run work included; returns its id and final status."""
        request = {"procedure": procedure, "options": options, **fields}
        if spec:
            request["spec"] = spec
        status, body = self.request("POST", "/api/runs", request)
        if status not in (201, 202):
            raise RuntimeError(f"start {procedure}: {status} {body}")
        run_id = body.get("run_id")
        deadline = time.monotonic() + 400
        while time.monotonic() < deadline:
            _, s = self.request("GET", "/api/status")
            last = s.get("last_run") or {}
            # Finished: recorded and its post-run work done (not `processing`).
            if (s.get("run") is None and last.get("id") and (run_id is None or last["id"] == run_id)
                    and last.get("status") not in ("running", "processing")):
                return last["id"], last["status"]
            time.sleep(0.2)
        raise RuntimeError(f"{procedure} run did not finish")

    def stop(self):
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process.stdout.close()
        self.log.close()
        shutil.rmtree(self.dir, ignore_errors=True)


class ConsolePageTest(unittest.TestCase):
    """A page test's browser and daemon: subclasses make their runs in setUpClass (after this
    one's) on self.daemon, then open pages and save screenshots."""

    @classmethod
    def setUpClass(cls):
        cls.daemon = Daemon()
        cls.profile = tempfile.mkdtemp(prefix="wavebench-chromium-")
        cls.browser = None
        os.makedirs(OUTPUT, exist_ok=True)

    @classmethod
    def start_browser(cls):
        cls.browser = chromium(cls.profile)

    @classmethod
    def tearDownClass(cls):
        if cls.browser:
            cls.browser.quit()
        shutil.rmtree(cls.profile, ignore_errors=True)
        cls.daemon.stop()

    def open(self, path):
        self.browser.get(self.daemon.url + path)
        WebDriverWait(self.browser, 30).until(
            lambda b: b.execute_script("return document.body.dataset.ready === 'true'"
                                       " || !!document.querySelector('.message.error')"))
        errors = self.browser.find_elements(By.CSS_SELECTOR, ".message.error")
        self.assertEqual([e.text for e in errors if e.is_displayed()], [], path)

    def shot(self, name):
        self.browser.save_screenshot(os.path.join(OUTPUT, name + ".png"))


class RunPagesTest(ConsolePageTest):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.runs = []
        for _ in range(2):
            run_id, status = cls.daemon.run("static", STATIC_OPTIONS)
            cls.runs.append(run_id)
            assert status == "complete", f"static run {run_id} ended {status}"
        cls.dynamic, status = cls.daemon.run("dynamic", DYNAMIC_OPTIONS)
        assert status == "complete", f"dynamic run {cls.dynamic} ended {status}"
        cls.start_browser()

    def canvases(self, figure_id):
        return self.browser.find_elements(By.CSS_SELECTOR, f"#{figure_id} canvas")

    def test_run_page_shows_header_tables_and_plots(self):
        run_id = self.runs[0]
        self.open(f"/run?id={run_id}")
        self.shot("run-page")
        head = self.browser.find_element(By.CSS_SELECTOR, ".run-head").text
        self.assertIn(run_id, head)
        self.assertIn("complete", head)
        verdict = self.browser.find_element(By.ID, "verdict")
        self.assertTrue(verdict.is_displayed())
        self.assertGreater(verdict.size["height"], 40)  # shown large
        rows = self.browser.find_elements(By.CSS_SELECTOR, "#static-table > tbody > tr")
        self.assertEqual(len(rows), 2)  # forward and reverse at 0 N*m
        self.assertEqual({r.find_elements(By.TAG_NAME, "td")[0].text for r in rows},
                         {"forward", "reverse"})
        self.assertEqual(len(self.canvases("static-plot")), 1)
        self.assertEqual(len(self.canvases("lost-motion-plot")), 1)
        # The record's TE comes from the trace endpoint.
        WebDriverWait(self.browser, 20).until(lambda b: self.canvases("trace-plot"))
        note = self.browser.find_element(By.ID, "trace-note").text
        self.assertRegex(note, r"samples")
        legend = self.browser.find_element(By.CSS_SELECTOR, "#static-plot .u-legend").text
        self.assertIn("forward", legend)
        self.assertIn("reverse", legend)

    def figure_rows(self):
        return {r.find_element(By.CSS_SELECTOR, "td span").get_attribute("title"): r
                for r in self.browser.find_elements(By.CSS_SELECTOR, "#figure-table tbody tr")}

    def test_figure_table_shows_the_declared_figures(self):
        _, catalogue = self.daemon.request("GET", "/api/procedures")
        static = next(p for p in catalogue["procedures"] if p["name"] == "static")
        own = {f["name"] for f in static["figures"] if f["procedure"] == "static"}
        every = {f["name"] for f in static["figures"]}  # with the twin's, when it calibrated
        self.assertIn("static_te_p2p", own)
        self.open(f"/run?id={self.runs[0]}")
        rows = self.browser.find_elements(By.CSS_SELECTOR, "#figure-table tbody tr")
        names = [r.find_element(By.CSS_SELECTOR, "td span").get_attribute("title") for r in rows]
        self.assertLessEqual(own, set(names))
        self.assertLessEqual(set(names), every)
        self.assertEqual(names.count("static_te_p2p"), 2)  # per pass: forward and reverse

    def test_a_newly_declared_figure_shows_without_js_edits(self):
        # A declaration the daemon does not (yet) serve, added to its answer before the page's
        # scripts run: the page must draw it from the declaration alone.
        probe = {"name": "probe_p2p_arcsec", "procedure": "static", "path": "static[*].p2p_arcmin",
                 "uncertainty_path": "static[*].uncertainty.p2p_arcmin",
                 "label": "Probe: static TE p2p in arcsec", "unit": "arcmin", "display_unit": "arcsec",
                 "display_scale": 60, "display_digits": 4, "limit": None,
                 "fleet": {"name": "probe", "column": "probe_arcsec", "what": "probe"}, "plot": "per_element"}
        script = """
const realFetch = window.fetch;
window.fetch = async (input, init) => {
  const r = await realFetch(input, init);
  if (!String(input).endsWith('/api/procedures')) return r;
  const body = await r.clone().json();
  for (const p of body.procedures) if (p.name === 'static') p.figures.push(%s);
  return new Response(JSON.stringify(body), { status: r.status, headers: { 'Content-Type': 'application/json' } });
};""" % json.dumps(probe)
        added = self.browser.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": script})
        try:
            self.open(f"/run?id={self.runs[0]}")
            self.shot("run-page-declared-figure")
            rows = [r for r in self.browser.find_elements(By.CSS_SELECTOR, "#figure-table tbody tr")
                    if r.find_element(By.CSS_SELECTOR, "td span").get_attribute("title") == probe["name"]]
            self.assertEqual(len(rows), 2)
            _, detail = self.daemon.request("GET", f"/api/runs/{self.runs[0]}")
            passes = detail["results"]["static"]
            for row, p in zip(rows, passes):
                cells = [c.text for c in row.find_elements(By.TAG_NAME, "td")]
                self.assertEqual(cells[0], probe["label"])
                self.assertEqual(cells[3], "arcsec")
                shown = float(cells[2].split(" ")[0])
                self.assertAlmostEqual(shown, p["p2p_arcmin"] * 60, delta=abs(p["p2p_arcmin"] * 60) * 0.01 + 1e-9)
                self.assertEqual(cells[5], "probe")
        finally:
            self.browser.execute_cdp_cmd("Page.removeScriptToEvaluateOnNewDocument",
                                         {"identifier": added["identifier"]})

    def test_dynamic_run_page_draws_spectrum_twin_and_zooms_to_every_sample(self):
        self.open(f"/run?id={self.dynamic}")
        self.assertEqual(len(self.canvases("spectrum-plot")), 1)
        peaks = self.browser.find_elements(By.CSS_SELECTOR, "#peaks-table tbody tr")
        self.assertGreater(len(peaks), 0)
        self.assertIn("1/rev", self.browser.find_element(By.ID, "peaks-table").text)
        self.assertEqual(len(self.canvases("twin-plot")), 1)
        self.assertEqual(len(self.canvases("twin-residual-plot")), 1)
        # Which twin ran beside the bench (the unit's own or the nominal case) is said.
        twin_table = self.browser.find_element(By.ID, "twin-table").text
        self.assertRegex(twin_table, r"Twin beside the bench\s+(unit twin|nominal twin case)")
        note = self.browser.find_element(By.ID, "trace-note")
        WebDriverWait(self.browser, 20).until(lambda b: "min/max" in note.text)
        self.shot("run-page-dynamic")
        # Drag over a twentieth of the record: the page fetches that range again, now every
        # sample of it.
        over = self.browser.find_element(By.CSS_SELECTOR, "#trace-plot .u-over")
        width = over.size["width"]
        ActionChains(self.browser).move_to_element_with_offset(over, -width // 40, 0) \
            .click_and_hold().move_by_offset(width // 20, 0).release().perform()
        WebDriverWait(self.browser, 20).until(lambda b: note.text.startswith("every sample"))
        self.shot("run-page-dynamic-zoomed")

    def test_run_page_prints_without_navigation(self):
        self.open(f"/run?id={self.runs[1]}")
        self.browser.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "print"})
        try:
            self.shot("run-page-print")
            self.assertFalse(self.browser.find_element(By.CSS_SELECTOR, ".topnav").is_displayed())
            self.assertFalse(self.browser.find_element(By.ID, "print").is_displayed())
            self.assertTrue(self.browser.find_element(By.CSS_SELECTOR, ".certificate-title").is_displayed())
            pdf = self.browser.execute_cdp_cmd("Page.printToPDF", {"paperWidth": 8.27, "paperHeight": 11.69,
                                                                 "preferCSSPageSize": True})
            self.assertGreater(len(pdf["data"]), 1000)
        finally:
            self.browser.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": ""})

    def test_history_lists_filters_and_compares(self):
        self.open("/history")
        ids = [r.get_attribute("data-id") for r in self.browser.find_elements(By.CSS_SELECTOR, "#runs tbody tr")]
        for run_id in self.runs:
            self.assertIn(run_id, ids)
        self.shot("history")

        # A filter with no match empties the table; the page's URL keeps the filter.
        select = Select(self.browser.find_element(By.CSS_SELECTOR, "#filters select[name=procedure]"))
        select.select_by_visible_text("lost-motion")
        self.browser.find_element(By.CSS_SELECTOR, "#filters button[type=submit]").click()
        WebDriverWait(self.browser, 10).until(
            lambda b: "No runs match" in b.find_element(By.ID, "message").text)
        self.assertEqual(len(self.browser.find_elements(By.CSS_SELECTOR, "#runs tbody tr")), 0)
        self.assertIn("procedure=lost-motion", self.browser.current_url)
        select.select_by_visible_text("static")
        self.browser.find_element(By.CSS_SELECTOR, "#filters button[type=submit]").click()
        WebDriverWait(self.browser, 10).until(
            lambda b: len(b.find_elements(By.CSS_SELECTOR, "#runs tbody tr")) >= 2)
        shown = [r.get_attribute("data-id") for r in self.browser.find_elements(By.CSS_SELECTOR, "#runs tbody tr")]
        self.assertNotIn(self.dynamic, shown)

        # A run's link opens its page.
        link = self.browser.find_element(By.CSS_SELECTOR, f"#runs tr[data-id='{self.runs[0]}'] a")
        self.assertTrue(link.get_attribute("href").endswith(f"/run?id={self.runs[0]}"))

        compare = self.browser.find_element(By.ID, "compare")
        self.assertFalse(compare.is_enabled())
        for run_id in self.runs:
            self.browser.find_element(By.CSS_SELECTOR, f"#runs tr[data-id='{run_id}'] input[type=checkbox]").click()
        self.assertTrue(compare.is_enabled())
        compare.click()
        WebDriverWait(self.browser, 10).until(lambda b: "/compare?ids=" in b.current_url)
        WebDriverWait(self.browser, 30).until(
            lambda b: b.execute_script("return document.body.dataset.ready === 'true'"))
        self.shot("compare")
        self.assertEqual(len(self.browser.find_elements(By.CSS_SELECTOR, "#compare-table > tbody > tr")), 2)
        # Figures with their expanded uncertainty, as on the run page.
        self.assertIn("±", self.browser.find_element(By.ID, "compare-table").text)
        self.assertEqual(len(self.canvases("static-plot")), 1)
        self.assertEqual(len(self.canvases("lost-motion-plot")), 1)
        # One legend entry per run and pass (x is the first): 2 runs x (forward, reverse).
        entries = self.browser.find_elements(By.CSS_SELECTOR, "#static-plot .u-legend tr.u-series")
        self.assertEqual(len(entries), 1 + 4)

    def test_compare_with_one_run_says_what_is_needed(self):
        self.browser.get(self.daemon.url + f"/compare?ids={self.runs[0]}")
        WebDriverWait(self.browser, 10).until(
            lambda b: b.find_elements(By.CSS_SELECTOR, ".message.error"))
        self.assertIn("two or more", self.browser.find_element(By.CSS_SELECTOR, ".message.error").text)


if __name__ == "__main__":
    if not WAVEBENCHD or not OUTPUT:
        sys.exit(__doc__)
    unittest.main(argv=[sys.argv[0], "-v"])
