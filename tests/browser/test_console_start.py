#!/usr/bin/python3
"""Nothing moves without a deliberate start (issue #21), in a real headless Chromium against
wavebenchd on the in-process simulated bench: a scanned serial and its Enter never start a run
(also with a scanner's trailing CR LF); a second scan replaces the first; the focus is then on
Start; Start without a spec asks first and starts only after confirming; Space on the focused
Start starts; a new run clears the last verdict; the verdict names serial, procedure and time;
during a static run the TE-against-output-angle plot gains a point per settled position; the
live plots' axes have units, at least four ticks and unclipped labels; no hint cites bench.md.
Screenshots of each step go to --out."""
import argparse
import json
import os
import re
import shutil
import sys
import tempfile
import time
import unittest
import urllib.request

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import Select, WebDriverWait

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_harness import Daemon, chromium  # noqa: E402

ARGS = None
WAIT_S = 60       # a guard against hanging, not a timing assertion
RUN_WAIT_S = 400  # a whole run with its post-run work (twin calibration, report)
IDLE_S = 2.0      # how long a scan must leave the bench idle


class ConsoleStartTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.daemon = Daemon(ARGS.wavebenchd, ARGS.web_root)
        cls.profile = tempfile.mkdtemp(prefix='wavebench-chromium-')
        cls.driver = chromium(cls.profile, height=1500)
        cls.driver.set_script_timeout(30)
        os.makedirs(ARGS.out, exist_ok=True)

    @classmethod
    def tearDownClass(cls):
        cls.driver.quit()
        cls.daemon.stop()
        shutil.rmtree(cls.profile, ignore_errors=True)

    # -- helpers ---------------------------------------------------------------------------
    def shot(self, name):
        self.driver.save_screenshot(os.path.join(ARGS.out, f'start-{name}.png'))

    def until(self, condition, what, timeout=WAIT_S):
        try:
            return WebDriverWait(self.driver, timeout, poll_frequency=0.1).until(
                lambda d: condition())
        except Exception:
            self.shot('failed-' + what.replace(' ', '-'))
            raise AssertionError(f'never happened: {what}')

    def get_json(self, path):
        with urllib.request.urlopen(self.daemon.url + path) as r:
            return json.load(r)

    def status(self):
        return self.get_json('/api/status')

    def runs(self):
        return self.get_json('/api/runs')['runs']

    def el(self, css):
        return self.driver.find_element(By.CSS_SELECTOR, css)

    def js(self, script):
        return self.driver.execute_script(script)

    def active_id(self):
        return self.js('return document.activeElement && document.activeElement.id')

    def assert_stays_idle(self, what, runs_before=0):
        """The bench takes no run for IDLE_S: no active run, nothing new in /api/runs."""
        deadline = time.time() + IDLE_S
        while time.time() < deadline:
            self.assertIsNone(self.status()['run'], f'{what}: a run started')
            self.assertEqual(len(self.runs()), runs_before, f'{what}: a run was recorded')
            time.sleep(0.1)

    def scan(self, serial, suffix=Keys.ENTER):
        """As a barcode scanner: keystrokes into whatever has the focus, then Enter."""
        ActionChains(self.driver).send_keys(serial + suffix).perform()

    def open_console(self):
        self.driver.get(self.daemon.url + '/')
        self.until(lambda: self.js('return window.wavebenchLive && window.wavebenchLive.frames > 0'),
                   'live stream')
        self.until(lambda: len(self.driver.find_elements(By.CSS_SELECTOR, '#procedure option')) > 0,
                   'procedures listed')

    def login(self):
        self.driver.get(self.daemon.url + '/login')
        self.el('#token').send_keys(self.daemon.token)
        self.el('#login').click()
        self.until(lambda: self.driver.current_url.rstrip('/') == self.daemon.url,
                   'back on the console')
        self.open_console()
        self.until(lambda: self.el('#start').is_enabled(), 'start enabled')

    def set_option(self, name, value):
        # The options are under "Advanced" (opened by script: a click right after a <select>
        # choice may land on the select's popup in headless Chromium).
        self.driver.execute_script("document.getElementById('advanced').open = true")
        field = self.el(f'#opt-{name}')
        field.clear()
        field.send_keys(value)

    def wait_run_done(self):
        self.until(lambda: self.status()['run'] is None, 'run finished', RUN_WAIT_S)

    # -- tests, in order (one browser, one daemon) -------------------------------------------
    def test_1_fresh_page_layout_and_hints(self):
        self.login()
        self.shot('1-fresh-page')
        # Serial, spec and Start come before the procedure options, which are folded away.
        order = self.js('''
            const ids = ['unit-serial', 'spec', 'start', 'options'];
            const all = [...document.querySelectorAll('#run-panel *')];
            return ids.map((id) => all.indexOf(document.getElementById(id)));''')
        self.assertEqual(order, sorted(order), f'form order {order}')
        self.assertIsNone(self.el('#advanced').get_attribute('open'))
        # No hint, description or option cites a document the user does not have.
        self.assertNotIn('bench.md', json.dumps(self.get_json('/api/procedures')))
        for name in [o.get_attribute('value') for o in
                     self.driver.find_elements(By.CSS_SELECTOR, '#procedure option')]:
            Select(self.el('#procedure')).select_by_value(name)
            text = self.js("return document.getElementById('run-panel').textContent")
            self.assertNotIn('bench.md', text, f'procedure {name}')
            self.assertNotIn('§', text, f'procedure {name}')
        Select(self.el('#procedure')).select_by_value('static')
        # The text checked holds the option hints too (folded away, but in the page).
        self.assertIn('equally spaced over one output revolution',
                      self.js("return document.getElementById('run-panel').textContent"))
        # The header names no unit yet (not the bench config's seed serial).
        seed = (self.status().get('bench') or {}).get('unit_serial')
        if seed:
            self.assertNotIn(seed, self.el('#unit-mounted').text)

    def test_2_a_scan_and_its_enter_do_not_start(self):
        self.el('#unit-serial').click()
        self.scan('SN-SCAN-0001')
        self.assertEqual(self.el('#unit-serial').get_attribute('value'), 'SN-SCAN-0001')
        self.assertEqual(self.active_id(), 'start', 'focus after the scan')
        self.assert_stays_idle('first scan')
        self.shot('2-after-scan')
        # A second scan, typed into Start (where the focus is), replaces the first.
        self.scan('SN-SCAN-0002')
        self.assertEqual(self.el('#unit-serial').get_attribute('value'), 'SN-SCAN-0002')
        self.assertEqual(self.active_id(), 'start', 'focus after the second scan')
        self.assert_stays_idle('second scan')
        # A scanner that ends with CR LF: the second Enter lands on Start, and must not count.
        self.scan('SN-SCAN-0003', Keys.ENTER + Keys.ENTER)
        self.assertEqual(self.el('#unit-serial').get_attribute('value'), 'SN-SCAN-0003')
        self.assert_stays_idle('scan with CR LF')
        # A scan into the field itself, after clicking it, replaces what it held too, even a
        # serial typed by hand and left without Enter (the click selects it all).
        self.el('#unit-serial').click()
        ActionChains(self.driver).send_keys('TYPED-BY-HAND').perform()
        self.el('#start-form h2').click()
        self.el('#unit-serial').click()
        self.scan('SN-SCAN-0004')
        self.assertEqual(self.el('#unit-serial').get_attribute('value'), 'SN-SCAN-0004')
        self.assert_stays_idle('scan into the field')
        self.assertIn('SN-SCAN-0004', self.el('#unit-mounted').text)
        summary = self.el('#run-summary').text
        self.assertIn('SN-SCAN-0004', summary)
        self.assertIn('Static TE', summary)
        self.assertIn('none: no verdict', summary)
        self.shot('2-after-second-scan')

    def test_3_without_a_spec_start_asks_first_and_the_xy_plot_grows(self):
        Select(self.el('#spec')).select_by_value('')
        self.set_option('positions', '6')
        self.set_option('loads_nm', '0, 60')
        self.set_option('window_s', '0.1')
        self.set_option('brake_settle_s', '0.1')
        self.el('#start').click()
        self.until(lambda: self.el('#no-spec-dialog').get_attribute('open') is not None,
                   'confirmation shown')
        self.assertIn('no verdict', self.el('#no-spec-dialog').text)
        self.assertEqual(self.active_id(), 'no-spec-cancel')
        self.shot('3-confirmation')
        self.assert_stays_idle('confirmation open')
        self.el('#no-spec-cancel').click()
        self.until(lambda: self.el('#no-spec-dialog').get_attribute('open') is None, 'dialog closed')
        self.assert_stays_idle('confirmation cancelled')
        self.el('#start').click()
        self.until(lambda: self.el('#no-spec-dialog').get_attribute('open') is not None,
                   'confirmation shown again')
        self.el('#no-spec-confirm').click()
        self.until(lambda: self.status()['run'] is not None, 'run started after confirming')
        # The settled points arrive in /api/status and in the page's XY plot, one by one.
        self.until(lambda: len((self.status()['run'] or {}).get('points', [])) >= 2,
                   'two settled points in the status')
        first = self.js('return window.wavebenchXY.count')
        self.until(lambda: self.js('return window.wavebenchXY.count') >= max(first + 3, 6),
                   'XY plot gains points', RUN_WAIT_S)
        self.assertTrue(self.el('#xy-panel').is_displayed())
        point = self.status()['run']['points'][0]
        for key in ['output_angle_deg', 'te_arcsec', 'load_nm', 'direction']:
            self.assertIn(key, point)
        self.assertGreaterEqual(point['output_angle_deg'], 0)
        self.assertLess(point['output_angle_deg'], 360)
        self.check_live_axes()
        self.shot('3-static-running-xy')
        self.measured_xy = self.js('return window.wavebenchXY.count')
        self.wait_run_done()
        self.until(lambda: self.el('#last-run').is_displayed() and
                   'SN-SCAN-0004' in self.el('#verdict-of').text, 'verdict of the first run')
        # Pending while the post-run work goes on in the background, then the verdict.
        self.until(lambda: 'pending' not in self.el('#verdict').text, 'results of the first run',
                   RUN_WAIT_S)
        self.assertIn('no verdict', self.el('#verdict').text)
        # The points stay on screen after the run (until the next one starts).
        self.assertTrue(self.el('#xy-panel').is_displayed())
        self.assertGreaterEqual(self.js('return window.wavebenchXY.count'), self.measured_xy)
        print(f"XY plot: {self.js('return window.wavebenchXY.count')} points", file=sys.stderr)
        self.shot('3-no-verdict')

    def check_live_axes(self):
        """Each live plot: a y label with its unit, at least 4 ticks, labels inside the axis."""
        axes = self.js('''
            const ctx = document.createElement('canvas').getContext('2d');
            return window.wavebenchLive.plots.map((u) => {
              const a = u.axes[1];
              ctx.font = a.font ? a.font[0] : '12px sans-serif';
              const labels = (a._values || []).filter((v) => v !== null && v !== '');
              return { label: a.label, ticks: labels.length, size: a._size, values: labels,
                       height: u.bbox.height / devicePixelRatio,
                       widest: Math.max(0, ...labels.map((v) => ctx.measureText(String(v)).width)) };
            });''')
        for a in axes:
            self.assertRegex(a['label'], r'\[.+\]', f'axis {a}')
            self.assertGreaterEqual(a['ticks'], 4, f'axis {a}')
            self.assertLessEqual(a['widest'] + 10, a['size'], f'axis {a}: labels clipped')
        print('live y axes:', axes, file=sys.stderr)

    def test_4_a_new_run_clears_the_verdict_and_the_verdict_names_the_run(self):
        specs = [o.get_attribute('value') for o in
                 self.driver.find_elements(By.CSS_SELECTOR, '#spec option')]
        spec = 'sim-seed004' if 'sim-seed004' in specs else specs[-1]
        Select(self.el('#spec')).select_by_value(spec)
        self.set_option('positions', '4')
        self.set_option('loads_nm', '0')
        self.set_option('move_speed_rad_s', '300')
        self.assertTrue(self.el('#last-run').is_displayed())
        runs_before = len(self.runs())
        self.el('#unit-serial').click()
        self.scan('SN-NEXT-0005')
        self.assertEqual(self.active_id(), 'start')
        self.assert_stays_idle('scan of the next unit', runs_before)
        # The second, explicit key on the focused Start starts (a spec: no question).
        ActionChains(self.driver).send_keys(Keys.SPACE).perform()
        self.until(lambda: self.status()['run'] is not None or len(self.runs()) > runs_before,
                   'run started by Space on Start')
        self.until(lambda: not self.el('#last-run').is_displayed(), 'last verdict cleared')
        self.assertEqual(self.el('#verdict').text, '')
        self.assertIn('SN-NEXT-0005', self.el('#unit-mounted').text)
        self.shot('4-new-run-verdict-cleared')
        self.wait_run_done()
        self.until(lambda: self.el('#verdict').text in ('PASS', 'FAIL', 'UNDECIDED'), 'verdict',
                   RUN_WAIT_S)
        of = self.el('#verdict-of').text
        self.assertIn('SN-NEXT-0005', of)
        self.assertIn('Static TE', of)
        self.assertRegex(of, r'\d{4}-\d{2}-\d{2} \d{2}:\d{2}:\d{2}')
        self.assertIn('SN-NEXT-0005', self.el('#unit-mounted').text)
        # Figures to the digits their uncertainty supports: value and U end at the same decimal.
        for text in [e.text for e in self.driver.find_elements(By.CSS_SELECTOR, '#static-table .uncertain')]:
            m = re.fullmatch(r'-?\d+(?:\.(\d+))? ± \d+(?:\.(\d+))?', text)
            self.assertIsNotNone(m, text)
            self.assertEqual(len(m.group(1) or ''), len(m.group(2) or ''), text)
        self.shot('4-verdict')
        print(f'verdict: {self.el("#verdict").text} · {of}', file=sys.stderr)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument('--wavebenchd', required=True)
    parser.add_argument('--web-root', required=True)
    parser.add_argument('--out', required=True)
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == '__main__':
    main()
