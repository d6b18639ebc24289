#!/usr/bin/env python3
"""Issue #21 point 4 on wavebenchd --config sim, over HTTP with the bearer token:

1. After a dynamic 100 rpm run, the next start is accepted <= 5 s after its recording ends,
   while its post-run work (twin, calibration, verdict, results.json, unit twin, report)
   finishes in the background; its results.json and verdict appear afterwards, complete.
2. /api/status sampled every 0.25 s through a static and a dynamic run (recording and
   post-run): remaining_s >= 0.8 x the true remaining time at every sample (true: the measured
   end of that part - the sample's time). Samples closer than 0.5 s to the end (two sampling
   intervals: the end itself is known only to 0.25 s) are counted but not judged.

usage: test_post_run_background.py WAVEBENCHD WEB_ROOT"""
import json
import sys
import threading
import time
import urllib.error
import urllib.request

sys.path.insert(0, __import__('os').path.dirname(__file__))
from daemon_harness import Daemon  # noqa: E402

POLL_S = 0.25
RESOLUTION_S = 2 * POLL_S


def api(d, method, path, body=None):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(d.url + path, data=data, method=method)
    req.add_header('Authorization', 'Bearer ' + d.token)
    if data is not None:
        req.add_header('Content-Type', 'application/json')
    try:
        with urllib.request.urlopen(req, timeout=30) as r:
            return r.status, json.loads(r.read() or b'null')
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read() or b'null')


class Sampler(threading.Thread):
    def __init__(self, d):
        super().__init__(daemon=True)
        self.d, self.samples, self.stop = d, [], False

    def run(self):
        while not self.stop:
            t = time.monotonic()
            try:
                code, s = api(self.d, 'GET', '/api/status')
            except OSError as e:
                print(f'status read failed: {e}')
                code = None
            if code == 200:
                self.samples.append((t, s))
            time.sleep(max(0, POLL_S - (time.monotonic() - t)))


def start(d, procedure, options):
    code, body = api(d, 'POST', '/api/runs', {'procedure': procedure, 'options': options})
    return code, body


def wait(predicate, timeout, what):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        v = predicate()
        if v:
            return v
        time.sleep(0.05)
    raise AssertionError('timed out waiting for ' + what)


def status(d):
    return api(d, 'GET', '/api/status')[1]


def ends(samples):
    """Per run id: the first sample time its recording is gone, the first its post-run is."""
    rec_seen, post_seen, rec_end, post_end = set(), set(), {}, {}
    for t, s in samples:
        rid = (s.get('run') or {}).get('id')
        posts = {p['run_id'] for p in s.get('post_runs', [])}
        for r in list(rec_seen):
            if r != rid and r not in rec_end:
                rec_end[r] = t
        for r in list(post_seen):
            if r not in posts and r not in post_end:
                post_end[r] = t
        if rid:
            rec_seen.add(rid)
        post_seen |= posts
    return rec_end, post_end


def judge(samples):
    rec_end, post_end = ends(samples)
    worst, judged, skipped, bad = float('inf'), 0, 0, []
    per_part = {}
    for t, s in samples:
        parts = []
        run = s.get('run')
        if run and run.get('id') in rec_end:
            parts.append(('recording', run['id'], run.get('remaining_s'), rec_end[run['id']]))
        for p in s.get('post_runs', []):
            if p['run_id'] in post_end:
                parts.append(('post-run ' + p['phase'], p['run_id'], p.get('remaining_s'),
                              post_end[p['run_id']]))
        for what, rid, stated, end in parts:
            true = end - t
            if true < RESOLUTION_S:
                skipped += 1
                continue
            judged += 1
            ratio = (stated if stated is not None else 0) / true
            worst = min(worst, ratio)
            key = (rid, what.split(' ')[0])
            per_part[key] = min(per_part.get(key, float('inf')), ratio)
            if ratio < 0.8:
                bad.append(f'{rid} {what}: stated {stated} s, true {true:.2f} s')
    for (rid, what), r in sorted(per_part.items()):
        print(f'  {rid} {what}: worst stated/true {r:.2f}')
    return worst, judged, skipped, bad


def main():
    wavebenchd, web_root = sys.argv[1], sys.argv[2]
    d = Daemon(wavebenchd, web_root)
    failures = []
    try:
        wait(lambda: status(d).get('state') == 'ready', 30, 'the bench to be ready')
        sampler = Sampler(d)
        sampler.start()

        # A static run, then the dynamic one, each with its post-run work to the end.
        code, body = start(d, 'static', {'positions': 8, 'loads_nm': [0]})
        assert code in (200, 201, 202), (code, body)
        static_id = body['run_id']
        wait(lambda: not any(p['run_id'] == static_id for p in status(d)['post_runs'])
             and (status(d).get('run') or {}).get('id') != static_id, 600, 'the static run')

        code, body = start(d, 'dynamic', {'input_rpm': 100})
        assert code in (200, 201, 202), (code, body)
        first = body['run_id']
        t0 = time.monotonic()
        recording_end = wait(
            lambda: time.monotonic() if (status(d).get('run') or {}).get('id') != first else None,
            300, 'the dynamic recording to end')
        print(f'dynamic {first}: recording {recording_end - t0:.1f} s')
        # The next unit, at once: accepted while the first run's post-run work goes on.
        deadline = recording_end + 30
        while True:
            code, body = start(d, 'dynamic', {'input_rpm': 100})
            if code in (200, 201, 202) or time.monotonic() > deadline:
                break
            time.sleep(0.1)
        accepted = time.monotonic()
        second = body.get('run_id') if isinstance(body, dict) else None
        delay = accepted - recording_end
        pending = any(p['run_id'] == first for p in status(d)['post_runs'])
        print(f'next start accepted {delay:.2f} s after the recording ended '
              f'(HTTP {code}, run {second}); first run still processing: {pending}')
        if code not in (200, 201, 202) or delay > 5:
            failures.append(f'next start: HTTP {code} {body} after {delay:.2f} s (at most 5 s)')
        if not pending:
            failures.append('the first run\'s post-run work was not in the background')
        code, detail = api(d, 'GET', f'/api/runs/{first}')
        if detail['run']['status'] == 'complete' and pending:
            failures.append('the first run was complete before its results were written')

        # Both finish, in order; the first's results arrive complete with a verdict.
        wait(lambda: not status(d)['post_runs'] and not status(d).get('run'), 900,
             'the post-run work of both runs')
        time.sleep(1)
        sampler.stop = True
        sampler.join()
        for rid in (static_id, first, second):
            code, detail = api(d, 'GET', f'/api/runs/{rid}')
            run, results = detail['run'], detail.get('results') or {}
            print(f'{rid}: index {run["status"]}, results.json status {results.get("status")}, '
                  f'verdict {results.get("verdict")}, post-run timing '
                  f'{json.dumps((results.get("timing") or {}).get("post_run"))}')
            if run['status'] != 'complete' or results.get('status') != 'complete':
                failures.append(f'{rid}: index {run["status"]}, results {results.get("status")}')
            if 'twin' not in results or 'limit_checks' not in results:
                failures.append(f'{rid}: results.json lacks twin or limit_checks')
        last = status(d)['last_run']
        if not last or last['id'] != second:
            failures.append(f'last_run is {last}, expected the newest run {second}')

        # The recording's phases as sampled: where the time goes, for the estimates.
        last = None
        for t, s in sampler.samples:
            run = s.get('run') or {}
            key = (run.get('id'), run.get('phase'))
            if run and key != last:
                print(f'  {t:.2f} {key[0]} {key[1]}: stated {run.get("remaining_s")} s left')
                last = key
        worst, judged, skipped, bad = judge(sampler.samples)
        print(f'remaining_s: {judged} samples judged, worst stated/true {worst:.2f} '
              f'({skipped} within {RESOLUTION_S} s of an end not judged)')
        failures += bad[:20]
    except Exception as e:  # noqa: BLE001 - the daemon's log says why
        failures.append(f'{type(e).__name__}: {e}')
    finally:
        d.stop()
    if failures:
        print('FAIL:\n  ' + '\n  '.join(failures))
        print(''.join(d.output[-60:]))
        return 1
    print('1 passed, 0 failed')
    return 0


if __name__ == '__main__':
    sys.exit(main())
