#!/usr/bin/python3
"""The fleet page (/fleet) in headless Chromium against wavebenchd on the in-process simulated
bench, without a shared store (the bench's own): three short static runs against the simulated
unit's spec, then
- the page picks their gear model, draws the trend with one point per run and the individuals
  chart, and its SPC table shows the n and the mean GET /api/fleet/spc gives;
- one pass (forward, 0 N*m) and the newest 2 runs give 2 points; a USL given is drawn;
- a model no run has says so, honestly.
Screenshots go to <build>/test-output/browser/.

Usage: test_fleet_page.py WAVEBENCHD WEB_ROOT OUTPUT_DIR
"""
import sys
import time
import unittest
import urllib.parse

from selenium.webdriver.common.by import By

from test_run_pages import OUTPUT, STATIC_OPTIONS, WAVEBENCHD, ConsolePageTest

SPEC = "sim-seed004"
MODEL = "Bench unit (seed 004)"


class FleetPageTest(ConsolePageTest):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.runs = []
        for _ in range(3):
            run_id, status = cls.daemon.run("static", STATIC_OPTIONS, spec=SPEC)
            assert status == "complete", f"static run {run_id} ended {status}"
            cls.runs.append(run_id)
        cls.start_browser()

    def api_spc(self, **params):
        params = {"figure": "static_te_p2p", "model": MODEL, **params}
        # The outbox summarises each run just after it ends: wait until all three are there.
        for _ in range(100):
            status, body = self.daemon.request("GET", "/api/fleet/spc?" + urllib.parse.urlencode(params))
            self.assertEqual(status, 200, body)
            if len(body["points"]) >= min(3, int(params.get("last", 3))):
                return body
            time.sleep(0.2)
        self.fail(f"runs not in the store: {body}")

    def spc_cell(self, key):
        return self.browser.find_element(By.CSS_SELECTOR, f"#spc-table tr[data-key='{key}'] td")

    def test_1_trend_and_spc_of_the_runs(self):
        api = self.api_spc()
        self.open("/fleet")
        self.shot("fleet")
        self.assertEqual(self.browser.find_element(By.NAME, "model").get_attribute("value"), MODEL)
        self.assertIn("own results store", self.browser.find_element(By.ID, "store").text)
        trend = self.browser.find_element(By.ID, "trend-plot")
        self.assertEqual(trend.get_attribute("data-points"), "3")
        self.assertEqual(len(trend.find_elements(By.TAG_NAME, "canvas")), 1)
        # One series per bench: the simulated bench only (x is the first legend row).
        self.assertEqual(len(trend.find_elements(By.CSS_SELECTOR, ".u-legend tr.u-series")), 1 + 1)
        self.assertEqual(self.spc_cell("n").text, "3")
        self.assertEqual(float(self.spc_cell("mean").get_attribute("data-value")), api["spc"]["mean"])
        self.assertEqual(float(self.spc_cell("ucl").get_attribute("data-value")), api["spc"]["ucl"])
        self.assertEqual(float(self.spc_cell("usl").get_attribute("data-value")), api["limits"]["upper"])
        self.assertIn("spec sim-seed004", self.browser.find_element(By.ID, "spc-table").text)
        chart = self.browser.find_element(By.ID, "individuals-plot")
        self.assertEqual(chart.get_attribute("data-points"), "3")
        legend = chart.find_element(By.CLASS_NAME, "u-legend").text
        for line in ("UCL", "CL", "LCL"):
            self.assertIn(line, legend)
        # The spec's 7 arcmin is far above this process: named, not drawn.
        self.assertNotIn("USL", legend)
        self.assertIn("USL 7 arcmin", self.browser.find_element(By.ID, "limits-not-drawn").text)

    def test_2_one_pass_the_newest_two_and_limits_given(self):
        api = self.api_spc(direction="forward", load="0", last="2")
        self.assertEqual(len(api["points"]), 2)
        # Just above the points and the UCL, by half the control band: inside the chart's span
        # whatever the two runs' spread (two nearly equal runs make a narrow band; a fixed
        # offset above the points then lands "far above" and is named, not drawn).
        spc = api["spc"]
        usl = max([spc["ucl"]] + [p["value"] for p in api["points"]]) + 0.5 * (spc["ucl"] - spc["lcl"])
        query = urllib.parse.urlencode({"model": MODEL, "figure": "static_te_p2p", "direction": "forward",
                                        "load": "0", "last": "2", "usl": repr(usl)})
        self.open("/fleet?" + query)
        self.shot("fleet-one-pass")
        self.assertEqual(self.browser.find_element(By.ID, "trend-plot").get_attribute("data-points"), "2")
        self.assertEqual(self.spc_cell("n").text, "2")
        self.assertEqual(float(self.spc_cell("mean").get_attribute("data-value")), api["spc"]["mean"])
        self.assertEqual(float(self.spc_cell("usl").get_attribute("data-value")), usl)
        self.assertIn("USL (command line)", self.browser.find_element(By.ID, "spc-table").text)
        legend = self.browser.find_element(By.CSS_SELECTOR, "#individuals-plot .u-legend").text
        self.assertIn("USL", legend)
        self.assertEqual(self.browser.find_elements(By.ID, "limits-not-drawn"), [])

    def test_4_the_figure_selector_offers_every_declared_trend(self):
        # The trends come from the figure declarations (src/figures) through /api/fleet/figures
        # and /api/procedures: each declared fleet trend is offered, nothing else.
        _, served = self.daemon.request("GET", "/api/fleet/figures")
        _, catalogue = self.daemon.request("GET", "/api/procedures")
        declared = {f["fleet"]["name"] for p in catalogue["procedures"] for f in p["figures"] if f["fleet"]}
        self.assertEqual({f["name"] for f in served["figures"]}, declared)
        self.api_spc()
        self.open("/fleet?" + urllib.parse.urlencode({"model": "CSG-99", "figure": "static_te_p2p"}))
        options = [o.get_attribute("value") for o in
                   self.browser.find_elements(By.CSS_SELECTOR, "#fleet-form select[name=figure] option")]
        self.assertEqual(set(options), declared)

    def test_3_a_model_without_runs_says_so(self):
        self.api_spc()
        self.open("/fleet?" + urllib.parse.urlencode({"model": "CSG-99", "figure": "static_te_p2p"}))
        self.shot("fleet-empty")
        text = self.browser.find_element(By.ID, "message").text
        self.assertIn("No complete runs of model CSG-99", text)
        self.assertEqual(self.browser.find_elements(By.ID, "trend-plot"), [])


if __name__ == "__main__":
    if not WAVEBENCHD or not OUTPUT:
        sys.exit(__doc__)
    unittest.main(argv=[sys.argv[0], "-v"])
