#!/usr/bin/python3
"""The console's live view frame rate with 10 minutes of 1 kHz history (issue #10): wavebenchd
on the simulated bench, the console in headless Chromium with the 10-minute window; the page
is given 10 minutes of 1 kHz history as the stream sends it (min/max per column of the plot's
width, 600 000 samples -> 2 rows per column), then counts, in the browser, animation frames
and redraws per second over 10 s while the live stream keeps arriving.

Usage: benchmarks/console/live_fps.py BUILD_DIR   (prints the figures; no assertion)"""
import os
import shutil
import sys
import tempfile
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import Select

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, '..', '..', 'tests', 'browser'))
from daemon_harness import Daemon  # noqa: E402

def measure(driver):
    start = driver.execute_script('const s = window.wavebenchLive.stats(); '
                                  'return [performance.now(), s.frames, s.draws];')
    time.sleep(10)
    end = driver.execute_script('const s = window.wavebenchLive.stats(); return '
                                '[performance.now(), s.frames, s.draws, s.fps, s.points, s.seconds];')
    seconds = (end[0] - start[0]) / 1000
    return ((end[2] - start[2]) / seconds, end[3], end[4], end[5], (end[1] - start[1]) / seconds)


build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build')
daemon = Daemon(os.path.join(build, 'src/daemon/wavebenchd'), os.path.join(build, 'web'))
profile = tempfile.mkdtemp(prefix='wavebench-fps-')
options = webdriver.ChromeOptions()
options.binary_location = '/usr/bin/chromium'
for flag in ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
             '--disable-background-networking', '--disable-component-update', '--disable-sync',
             '--window-size=1400,1800', f'--user-data-dir={profile}']:
    options.add_argument(flag)
driver = webdriver.Chrome(service=Service('/usr/bin/chromedriver'), options=options)
try:
    driver.get(daemon.url + '/')
    time.sleep(2)
    Select(driver.find_element('css selector', '#window')).select_by_value('600')
    time.sleep(1)
    # 10 minutes at 1 kHz, decimated as the daemon does: two rows per column, ending now.
    driver.execute_script('''
      const live = window.wavebenchLive;
      const columns = live.columns();
      const width = 600 / columns;
      const tEnd = live.t.length ? live.t[0] : 600;
      const rows = {t: [], te_arcsec: [], input_speed_rad_s: [], torque_nm: [], brake_current_a: []};
      for (let c = 0; c < columns; c += 1) {
        const t0 = tEnd - 600 + c * width;
        for (const h of [0.25, 0.75]) {
          const t = t0 + h * width;
          rows.t.push(t);
          const te = 60 * Math.sin(2 * Math.PI * t / 3.6) + (h < 0.5 ? -5 : 5);
          rows.te_arcsec.push(te);
          rows.input_speed_rad_s.push(10.47 + (h < 0.5 ? -0.1 : 0.1));
          rows.torque_nm.push(20 + 3 * Math.sin(t));
          rows.brake_current_a.push(0.4);
        }
      }
      const t = live.t, v = live.values;
      live.t = []; live.values = v.map(() => []);
      live.take({rows});
      for (let i = 0; i < t.length; i += 1) live.t.push(t[i]);
      v.forEach((s, k) => { for (const x of s) live.values[k].push(x); });
    ''')
    results = {}
    for mode in ['as data arrives', 'every animation frame (worst case)']:
        driver.execute_script('window.wavebenchLive.redrawEveryFrame = arguments[0];',
                              mode.startswith('every'))
        results[mode] = measure(driver)
    for mode, (draws, fps, points, span, stream) in results.items():
        print(f'redraw {mode}: {fps} animation frames/s, {draws:.1f} redraws/s of 4 plots, '
              f'{stream:.1f} stream frames/s; {points} points per plot over {span:.0f} s')
    driver.save_screenshot(os.path.join(build, 'live_fps.png'))
finally:
    driver.quit()
    daemon.stop()
    shutil.rmtree(profile, ignore_errors=True)
