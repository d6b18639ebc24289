#!/usr/bin/python3
"""Stop everywhere, always (issue #21): in headless Chromium against wavebenchd on the in-process
simulated bench, a long dynamic run is started through the API with the token, then
- on each page (console, history, run, compare, fleet, login) Esc, and the stop bar's STOP
  button, stop the bench within 0.5 s (GET /api/status polled): the run ends aborted "stopped
  by operator", the bench is not in fault and the next run starts without a reset;
- the stop works for a console that never logged in and for one whose session expired (a
  daemon with a 1 s session timeout);
- a page of another origin still cannot start a run (and requests with Origin:
  http://evil.example get 403);
- after the daemon restarts, the page shows "the daemon restarted at HH:MM:SS - log in again"
  and the stop still works.
Screenshots of each page with the stop bar go to <build>/test-output/browser/stop-*.png.

Usage: test_stop_everywhere.py WAVEBENCHD WEB_ROOT OUTPUT_DIR
"""
import http.server
import json
import os
import shutil
import sys
import tempfile
import threading
import time
import unittest
import urllib.error
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_run_pages as pages  # noqa: E402  (its Daemon and chromium())

from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402
from selenium.webdriver.support.ui import WebDriverWait  # noqa: E402

WAVEBENCHD, WEB_ROOT, OUTPUT = (sys.argv[1:4] + [None] * 3)[:3]
pages.WAVEBENCHD, pages.WEB_ROOT, pages.OUTPUT = WAVEBENCHD, WEB_ROOT, OUTPUT
# Long on the simulated clock: many output revolutions at a low input speed.
LONG_DYNAMIC = {"input_rpm": 300, "run_in_s": 0.2, "output_revolutions": 200}
STOP_WITHIN_S = 0.5
PAGES = [("console", "/"), ("history", "/history.html"), ("run", None),
         ("compare", None), ("fleet", "/fleet.html"), ("login", "/login.html")]


class StopDaemon(pages.Daemon):
    def __init__(self, extra=()):
        self.extra = list(extra)
        super().__init__()

    def status(self):
        return self.request("GET", "/api/status")[1]

    def start_long_run(self):
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            status, body = self.request("POST", "/api/runs",
                                        {"procedure": "dynamic", "options": LONG_DYNAMIC})
            if status in (201, 202):
                break
            time.sleep(0.1)  # the previous stop still settling
        else:
            raise RuntimeError(f"long run not started: {status} {body}")
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            s = self.status()
            if s.get("state") == "running" and s.get("run") and s["run"].get("id"):
                return body.get("run_id")
            time.sleep(0.05)
        raise RuntimeError("the long run is not running")


def patch_daemon_args(extra):
    """pages.Daemon builds its own argument list: wrap Popen to add ours."""
    import subprocess
    real = subprocess.Popen

    def popen(args, *a, **k):
        if args and args[0] == WAVEBENCHD:
            args = list(args) + list(extra)
        return real(args, *a, **k)
    pages.subprocess.Popen = popen
    return lambda: setattr(pages.subprocess, "Popen", real)


class StopEverywhereTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(OUTPUT, exist_ok=True)
        cls.daemon = StopDaemon()
        cls.profile = tempfile.mkdtemp(prefix="wavebench-chromium-")
        cls.browser = pages.chromium(cls.profile)
        # A finished run for the run page and two for compare.
        cls.run_ids = [cls.daemon.run("static", pages.STATIC_OPTIONS)[0] for _ in range(2)]
        cls.timings = {}

    @classmethod
    def tearDownClass(cls):
        cls.browser.quit()
        shutil.rmtree(cls.profile, ignore_errors=True)
        cls.daemon.stop()
        print("stop timings (s):", json.dumps(cls.timings, indent=1))

    def path_of(self, name, path):
        if name == "run":
            return f"/run.html?id={self.run_ids[0]}"
        if name == "compare":
            return "/compare.html?ids=" + ",".join(self.run_ids)
        return path

    def open(self, path):
        self.browser.get(self.daemon.url + path)
        WebDriverWait(self.browser, 30).until(
            lambda b: b.execute_script("return !!document.getElementById('stop-bar')"))

    def shot(self, name):
        self.browser.save_screenshot(os.path.join(OUTPUT, name + ".png"))

    def wait_stopped(self, run_id, pressed_at):
        """Seconds from the press until /api/status shows nothing running."""
        while time.monotonic() - pressed_at < 10:
            s = self.daemon.status()
            if s.get("state") != "running":
                return time.monotonic() - pressed_at, s
            time.sleep(0.02)
        self.fail("the bench did not stop")

    def check_stopped_cleanly(self, run_id):
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            s = self.daemon.status()
            if s.get("run") is None and s.get("state") == "ready":
                break
            self.assertNotEqual(s.get("state"), "fault", s.get("fault_reason"))
            time.sleep(0.05)
        self.assertEqual(s.get("state"), "ready", s)
        self.assertEqual(s.get("lifecycle"), "inactive")
        # The aborted run's post-run work (its results) goes on in the background.
        while time.monotonic() < deadline + 120:
            s = self.daemon.status()
            if (s.get("last_run") or {}).get("status") != "processing":
                break
            time.sleep(0.1)
        last = s.get("last_run") or {}
        if run_id:
            self.assertEqual(last.get("id"), run_id)
        self.assertEqual(last.get("status"), "aborted")
        self.assertIn("stopped by operator", last.get("reason", ""))

    def stop_from(self, name, path, how):
        self.open(path)
        run_id = self.daemon.start_long_run()
        # The bar shows the run before the press (screenshot of the page with its stop bar).
        WebDriverWait(self.browser, 5).until(
            lambda b: "running" in b.find_element(By.ID, "stop-bar-state").text)
        if how == "esc":
            self.shot(f"stop-{name}")
        pressed = time.monotonic()
        if how == "esc":
            self.browser.switch_to.active_element.send_keys(Keys.ESCAPE)
        else:
            self.browser.find_element(By.ID, "stop").click()
        elapsed, _ = self.wait_stopped(run_id, pressed)
        self.timings[f"{name}-{how}"] = round(elapsed, 3)
        self.assertLess(elapsed, STOP_WITHIN_S, f"{name} {how}")
        self.check_stopped_cleanly(run_id)

    def test_1_esc_and_button_on_every_page_without_a_session(self):
        # Never logged in: the stop needs no session.
        for name, path in PAGES:
            with self.subTest(page=name):
                self.stop_from(name, self.path_of(name, path), "esc")
                self.stop_from(name, self.path_of(name, path), "button")

    def test_2_stop_when_idle_is_harmless(self):
        self.open("/history.html")
        self.browser.switch_to.active_element.send_keys(Keys.ESCAPE)
        time.sleep(1)
        s = self.daemon.status()
        self.assertEqual(s["state"], "ready", s)
        self.assertEqual(s["lifecycle"], "inactive")

    def test_3_cross_origin_cannot_start(self):
        # Requests that say they come from another site.
        for path, body in [("/api/runs", {"procedure": "static", "options": pages.STATIC_OPTIONS}),
                           ("/api/stop", {}), ("/api/session", {"token": self.daemon.token})]:
            req = urllib.request.Request(self.daemon.url + path, data=json.dumps(body).encode(),
                                         method="POST")
            req.add_header("Authorization", "Bearer " + self.daemon.token)
            req.add_header("X-Wavebench-Request", "console")
            req.add_header("Content-Type", "application/json")
            req.add_header("Origin", "http://evil.example")
            with self.assertRaises(urllib.error.HTTPError) as refused:
                urllib.request.urlopen(req, timeout=10)
            self.assertEqual(refused.exception.code, 403, path)
        # A page served at another origin, trying with the console's header and credentials.
        evil = tempfile.mkdtemp(prefix="wavebench-evil-")
        with open(os.path.join(evil, "index.html"), "w") as f:
            f.write(f"""<!doctype html><body><script>
window.results = [];
fetch('{self.daemon.url}/api/runs', {{method: 'POST', credentials: 'include',
  headers: {{'X-Wavebench-Request': 'console', 'Content-Type': 'application/json'}},
  body: JSON.stringify({{procedure: 'static'}})}})
  .then(r => window.results.push('status ' + r.status), e => window.results.push('blocked'));
fetch('{self.daemon.url}/api/runs', {{method: 'POST', mode: 'no-cors', credentials: 'include',
  body: JSON.stringify({{procedure: 'static'}})}})
  .then(r => window.results.push('opaque'), e => window.results.push('blocked'));
</script></body>""")
        handler = lambda *a, **k: http.server.SimpleHTTPRequestHandler(*a, directory=evil, **k)
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        try:
            runs_before = self.daemon.request("GET", "/api/runs")[1]["total"]
            self.browser.get(f"http://127.0.0.1:{server.server_address[1]}/index.html")
            WebDriverWait(self.browser, 10).until(
                lambda b: len(b.execute_script("return window.results")) == 2)
            time.sleep(0.5)
            self.assertEqual(self.daemon.status()["state"], "ready")
            self.assertEqual(self.daemon.request("GET", "/api/runs")[1]["total"], runs_before)
        finally:
            server.shutdown()
            shutil.rmtree(evil, ignore_errors=True)


class ExpiredSessionAndRestartTest(unittest.TestCase):
    """A daemon whose sessions live 1 s idle: log in, let it expire, stop still works; then the
    daemon restarts and the page shows it."""

    @classmethod
    def setUpClass(cls):
        restore = patch_daemon_args(["--session-idle-timeout", "1"])
        try:
            cls.daemon = StopDaemon()
        finally:
            restore()
        cls.profile = tempfile.mkdtemp(prefix="wavebench-chromium-")
        cls.browser = pages.chromium(cls.profile)

    @classmethod
    def tearDownClass(cls):
        cls.browser.quit()
        shutil.rmtree(cls.profile, ignore_errors=True)
        cls.daemon.stop()

    def login(self):
        self.browser.get(self.daemon.url + "/login")
        WebDriverWait(self.browser, 10).until(lambda b: b.find_element(By.ID, "token").is_displayed())
        self.browser.find_element(By.ID, "token").send_keys(self.daemon.token)
        self.browser.find_element(By.ID, "login").click()
        WebDriverWait(self.browser, 10).until(
            lambda b: "logged in as" in b.find_element(By.ID, "stop-bar-who").text)

    def test_1_expired_session_still_stops(self):
        self.login()
        self.browser.get(self.daemon.url + "/history.html")
        time.sleep(2.5)  # past the 1 s idle timeout
        self.browser.execute_script("return fetch('/api/session').then(r => r.json())")
        self.assertFalse(self.browser.execute_script(
            "return fetch('/api/session').then(r => r.json()).then(j => j.authenticated)"))
        self.daemon.start_long_run()
        pressed = time.monotonic()
        self.browser.switch_to.active_element.send_keys(Keys.ESCAPE)
        while self.daemon.status().get("state") == "running":
            self.assertLess(time.monotonic() - pressed, 5)
            time.sleep(0.02)
        elapsed = time.monotonic() - pressed
        print(f"expired session: stopped {elapsed:.3f} s after Esc")
        self.assertLess(elapsed, STOP_WITHIN_S)
        # Also without any cookie at all.
        self.browser.delete_all_cookies()
        self.daemon.start_long_run()
        pressed = time.monotonic()
        self.browser.find_element(By.ID, "stop").click()
        while self.daemon.status().get("state") == "running":
            self.assertLess(time.monotonic() - pressed, 5)
            time.sleep(0.02)
        self.assertLess(time.monotonic() - pressed, STOP_WITHIN_S)

    def test_2_restart_is_shown_and_stop_still_works(self):
        self.login()
        self.browser.get(self.daemon.url + "/fleet.html")
        WebDriverWait(self.browser, 10).until(
            lambda b: b.find_element(By.ID, "stop-bar-state").text not in ("", "…"))
        port = self.daemon.url.rsplit(":", 1)[1]
        old = self.daemon
        # The same port: the browser's page keeps talking to "its" daemon.
        restore = patch_daemon_args([])
        try:
            old.process.terminate()
            old.process.wait(20)
            import subprocess
            real = subprocess.Popen

            def popen(args, *a, **k):
                args = [x if x != "127.0.0.1:0" else f"127.0.0.1:{port}" for x in args]
                return real(args, *a, **k)
            pages.subprocess.Popen = popen
            type(self).daemon = StopDaemon()
        finally:
            restore()
        WebDriverWait(self.browser, 15).until(
            lambda b: b.find_element(By.ID, "stop-bar-banner").is_displayed())
        text = self.browser.find_element(By.ID, "stop-bar-banner").text
        self.assertRegex(text, r"the daemon restarted at \d\d:\d\d:\d\d")
        self.assertIn("log in again", text)
        self.shot("stop-restart-banner")
        self.daemon.start_long_run()
        pressed = time.monotonic()
        self.browser.switch_to.active_element.send_keys(Keys.ESCAPE)
        while self.daemon.status().get("state") == "running":
            self.assertLess(time.monotonic() - pressed, 5)
            time.sleep(0.02)
        self.assertLess(time.monotonic() - pressed, STOP_WITHIN_S)
        old.process.stdout.close()
        old.log.close()
        shutil.rmtree(old.dir, ignore_errors=True)

    def shot(self, name):
        self.browser.save_screenshot(os.path.join(OUTPUT, name + ".png"))


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]], verbosity=2)
