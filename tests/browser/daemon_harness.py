"""wavebenchd on the in-process simulated bench for the browser tests: an ephemeral port, a
throw-away runs folder and token file; stopped (SIGTERM, then SIGKILL) when done."""
import os
import re
import secrets
import signal
import subprocess
import tempfile
import threading

from selenium import webdriver
from selenium.webdriver.chrome.service import Service


class Daemon:
    def __init__(self, wavebenchd, web_root):
        self.dir = tempfile.TemporaryDirectory(prefix='wavebench-browser-')
        self.token = secrets.token_hex(16)
        self.token_file = os.path.join(self.dir.name, 'daemon.token')
        fd = os.open(self.token_file, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(fd, 'w') as f:
            f.write(self.token + '\n')
        args = [wavebenchd, '--config', 'sim', '--listen', '127.0.0.1:0',
                '--runs', os.path.join(self.dir.name, 'runs'),
                '--token-file', self.token_file, '--web-root', web_root]
        self.process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        text=True)
        self.output = []
        self.port = None
        for line in self.process.stdout:
            self.output.append(line)
            m = re.search(r'listening on http://127\.0\.0\.1:(\d+)', line)
            if m:
                self.port = int(m.group(1))
                break
        if self.port is None:
            self.stop()
            raise RuntimeError('wavebenchd did not start:\n' + ''.join(self.output))
        # Keep draining its output so that it never blocks on a full pipe.
        threading.Thread(target=self._drain, daemon=True).start()
        self.url = f'http://127.0.0.1:{self.port}'

    def _drain(self):
        for line in self.process.stdout:
            self.output.append(line)

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.dir.cleanup()


def chromium(profile, height=1000):
    """Debian's headless Chromium through chromedriver, 1400 px wide, profile in `profile`."""
    options = webdriver.ChromeOptions()
    options.binary_location = '/usr/bin/chromium'
    for flag in ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
                 '--disable-background-networking', '--disable-component-update', '--disable-sync',
                 f'--window-size=1400,{height}', f'--user-data-dir={profile}']:
        options.add_argument(flag)
    return webdriver.Chrome(service=Service('/usr/bin/chromedriver'), options=options)
