#!/usr/bin/python3
"""Does the console disturb the bench? (issue #10) The same dynamic TE run on the in-process
simulated bench on the real clock (1 kHz SYNC), twice in one go: once with no browser, once with
N headless Chromium sessions on the console's live view (10-minute window). Per arm: SYNC
lateness p50/p99/max and the skipped SYNC periods (the bench's own figures, /api/status, fresh
daemon per arm), the samples lost (missed SYNCs, incomplete samples, log queue drops from
results.json), and in the browser arm each session's frame rate counted in the page over the
last 10 s (with the run's whole history in the plots). Prints the figures and the ratios
browsers/none; the issue's targets: ratios <= 1.1, >= 30 frames/s.

Usage: benchmarks/console/live_view_load.py BUILD_DIR [DURATION_S=600] [SESSIONS=5] [PAIRS=1]
With PAIRS > 1 the arms alternate (none first, then browsers first, ...) and the totals over all
pairs are compared, so that the machine's own noise averages out."""
import http.client
import json
import os
import re
import secrets
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import Select

here = os.path.dirname(os.path.abspath(__file__))
source = os.path.abspath(os.path.join(here, '..', '..'))


def real_clock_config(work):
    # A copy of the shipped configs, so that the bench config's relative paths still resolve.
    configs = os.path.join(work, 'configs')
    shutil.copytree(os.path.join(source, 'configs'), configs)
    path = os.path.join(configs, 'benches', 'sim-real-clock.yaml')
    text = open(os.path.join(configs, 'benches', 'sim.yaml')).read()
    open(path, 'w').write(re.sub(r'^clock: simulated', 'clock: real', text, flags=re.M))
    return path


class Daemon:
    def __init__(self, build, work, config):
        self.work = work
        self.token = secrets.token_hex(16)
        token_file = os.path.join(work, 'daemon.token')
        fd = os.open(token_file, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(fd, 'w') as f:
            f.write(self.token + '\n')
        self.process = subprocess.Popen(
            [os.path.join(build, 'src/daemon/wavebenchd'), '--config', config, '--listen',
             '127.0.0.1:0', '--runs', os.path.join(work, 'runs'), '--token-file', token_file,
             '--web-root', os.path.join(build, 'web')],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.port = None
        for line in self.process.stdout:
            m = re.search(r'listening on http://127\.0\.0\.1:(\d+)', line)
            if m:
                self.port = int(m.group(1))
                break
        if self.port is None:
            raise RuntimeError('wavebenchd did not start')
        threading.Thread(target=lambda: [None for _ in self.process.stdout], daemon=True).start()
        self.url = f'http://127.0.0.1:{self.port}'

    def call(self, method, path, body=None):
        c = http.client.HTTPConnection('127.0.0.1', self.port, timeout=60)
        headers = {'Host': f'127.0.0.1:{self.port}', 'Authorization': f'Bearer {self.token}'}
        data = None
        if body is not None:
            data = json.dumps(body)
            headers['Content-Type'] = 'application/json'
        c.request(method, path, body=data, headers=headers)
        r = c.getresponse()
        answer = json.loads(r.read() or b'null')
        c.close()
        return r.status, answer

    def stop(self):
        self.process.send_signal(signal.SIGTERM)
        try:
            self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.process.kill()


def browser(url, profile):
    options = webdriver.ChromeOptions()
    options.binary_location = '/usr/bin/chromium'
    for flag in ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic',
                 '--no-first-run', '--disable-background-networking',
                 '--disable-component-update', '--disable-sync', '--window-size=1400,1000',
                 f'--user-data-dir={profile}']:
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service('/usr/bin/chromedriver'), options=options)
    driver.get(url + '/')
    time.sleep(2)
    Select(driver.find_element('css selector', '#window')).select_by_value('600')
    return driver


def frame_rate(drivers, redraw_every_frame):
    """Animation frames and plot redraws per second, counted in each page over 10 s; with
    redraw_every_frame all four plots are redrawn at every animation frame (the worst case)."""
    script = ('window.wavebenchLive.redrawEveryFrame = arguments[0]; '
              'const s = window.wavebenchLive.stats(); '
              'return [performance.now(), s.ticks, s.draws, s.points, s.seconds];')
    first = [d.execute_script(script, redraw_every_frame) for d in drivers]
    time.sleep(10)
    last = [d.execute_script(script, False) for d in drivers]
    rates = []
    for a, b in zip(first, last):
        seconds = (b[0] - a[0]) / 1000
        rates.append({'redraw_every_frame': redraw_every_frame,
                      'frames_per_s': (b[1] - a[1]) / seconds,
                      'redraws_per_s': (b[2] - a[2]) / seconds, 'points': b[3],
                      'history_s': b[4]})
    return rates


def arm(build, config, duration, sessions):
    work = tempfile.mkdtemp(prefix='wavebench-liveload-')
    daemon = Daemon(build, work, config)
    drivers, profiles, rates = [], [], []
    try:
        for i in range(sessions):
            profiles.append(tempfile.mkdtemp(prefix='wavebench-liveload-chromium-'))
            drivers.append(browser(daemon.url, profiles[-1]))
        revolutions = max(1.0, duration / 60.0)  # 100 rpm input, ratio 100: 60 s per output turn
        status, answer = daemon.call('POST', '/api/runs', {
            'procedure': 'dynamic',
            'options': {'input_rpm': 100, 'output_revolutions': revolutions}})
        if status >= 300:
            raise RuntimeError(f'start refused: {status} {answer}')
        run_id = answer['run_id']
        while True:
            time.sleep(5)
            _, s = daemon.call('GET', '/api/status')
            if s.get('run') is None:
                break
            if drivers and (s['run'].get('progress') or 0) > 0.93 and not rates:
                rates = frame_rate(drivers, False) + frame_rate(drivers, True)
        if drivers and not rates:
            rates = frame_rate(drivers, False) + frame_rate(drivers, True)
        _, s = daemon.call('GET', '/api/status')
        _, detail = daemon.call('GET', f'/api/runs/{run_id}')
        acquisition = (detail.get('results') or {}).get('acquisition') or {}
        a = s['acquisition']
        return {
            'status': detail['run']['status'],
            'reason': detail['run'].get('reason'),
            'sync_lateness_p50_us': a['sync_lateness_p50_s'] * 1e6,
            'sync_lateness_p99_us': a['sync_lateness_p99_s'] * 1e6,
            'sync_lateness_max_us': a['sync_lateness_max_s'] * 1e6,
            'sync_skipped': a['sync_skipped'],
            'samples_lost': acquisition.get('missed_syncs', 0) +
                            acquisition.get('log_queue_dropped', 0),
            'incomplete_samples': acquisition.get('incomplete_samples', 0),
            'samples_logged': acquisition.get('samples_logged', 0),
            'browsers': rates,
        }
    finally:
        for d in drivers:
            d.quit()
        daemon.stop()
        for p in profiles:
            shutil.rmtree(p, ignore_errors=True)
        shutil.rmtree(work, ignore_errors=True)


def main():
    build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build')
    duration = float(sys.argv[2]) if len(sys.argv) > 2 else 600
    sessions = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    pairs = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    work = tempfile.mkdtemp(prefix='wavebench-liveload-config-')
    config = real_clock_config(work)
    plains, loadeds = [], []
    for p in range(pairs):
        order = [0, sessions] if p % 2 == 0 else [sessions, 0]
        for n in order:
            result = arm(build, config, duration, n)
            print(f'pair {p + 1}, {n} browsers:', json.dumps(result), flush=True)
            (loadeds if n else plains).append(result)
    shutil.rmtree(work, ignore_errors=True)

    def pooled(results):
        out = dict(results[0])
        for key in ['sync_skipped', 'samples_lost', 'incomplete_samples', 'samples_logged']:
            out[key] = sum(r[key] for r in results)
        for key in ['sync_lateness_p50_us', 'sync_lateness_p99_us']:
            out[key] = sorted(r[key] for r in results)[len(results) // 2]  # median over pairs
        out['sync_lateness_max_us'] = max(r['sync_lateness_max_us'] for r in results)
        out['browsers'] = [b for r in results for b in r['browsers']]
        return out
    plain, loaded = pooled(plains), pooled(loadeds)

    def ratio(key):
        return loaded[key] / plain[key] if plain[key] else float('inf') if loaded[key] else 1.0
    print(f'dynamic run of {duration:.0f} s on the real clock (1 kHz SYNC):')
    for key in ['sync_lateness_p50_us', 'sync_lateness_p99_us', 'sync_lateness_max_us']:
        print(f'  {key}: {plain[key]:.1f} none, {loaded[key]:.1f} with {sessions} browsers '
              f'(ratio {ratio(key):.2f})')
    for key in ['sync_skipped', 'samples_lost', 'incomplete_samples', 'samples_logged']:
        print(f'  {key}: {plain[key]} none, {loaded[key]} with {sessions} browsers')
    for i, r in enumerate(loaded['browsers']):
        mode = 'every frame redrawn' if r['redraw_every_frame'] else 'redrawn on new data'
        print(f'  browser {i % sessions + 1} ({mode}): {r["frames_per_s"]:.1f} frames/s, '
              f'{r["redraws_per_s"]:.1f} redraws/s, {r["points"]} points per plot over '
              f'{r["history_s"]:.0f} s of history')
    print(f'  p99 ratio {ratio("sync_lateness_p99_us"):.2f} (target <= 1.1); samples lost '
          f'{plain["samples_lost"]} -> {loaded["samples_lost"]}; min frame rate '
          f'{min((r["frames_per_s"] for r in loaded["browsers"]), default=0):.1f} (target >= 30)')


if __name__ == '__main__':
    main()
