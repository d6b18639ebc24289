#!/usr/bin/python3
"""The console's manual panel (issue #21) in headless Chromium against wavebenchd on the
in-process simulated bench:
- jog: the input turns only while ▶ is held (pointer) or Space is held on it; released, it
  stands within 0.2 s (measured from the release, printed);
- a lost connection (the page's requests stop reaching the daemon; the API's keep-alives
  stop) stops it within the daemon's stated bound (status manual.stop_within_s, printed);
- over-limit speeds and torques are refused with 400 naming the key, before anything moves;
- the servo reads in plain words: "servo off", "moving 30 rpm", "servo on, holding";
- a run is refused while the panel holds the servo on; go to an output angle arrives there.
Screenshots: manual-idle, manual-jogging, manual-after (and -panel crops) in OUTPUT.

Usage: test_manual_panel.py WAVEBENCHD WEB_ROOT OUTPUT_DIR
"""
import math
import os
import sys
import time
import unittest

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import WebDriverWait

from test_run_pages import OUTPUT, WAVEBENCHD, ConsolePageTest

RELEASE_BOUND_S = 0.2
STANDING_RPM = 0.5
# The words for a 30 rpm jog: the speed is measured, and a loaded machine's simulated bench may
# read 29.4 for a moment.
MOVING_30 = {"moving 29 rpm", "moving 30 rpm", "moving 31 rpm"}


# Whether the element's centre hits the element itself (or a child), twice 100 ms apart at the
# same place: a press aimed there reaches it.
HIT_AT_CENTRE = """
const e = arguments[0];
const at = () => { const r = e.getBoundingClientRect(); return [r.left + r.width / 2, r.top + r.height / 2]; };
const [x, y] = at();
const hit = document.elementFromPoint(x, y);
if (!hit || !(hit === e || e.contains(hit))) return false;
return new Promise((resolve) => setTimeout(() => {
  const [x2, y2] = at();
  resolve(x2 === x && y2 === y);
}, 100));
"""


def rpm(status):
    latest = status.get("latest") or {}
    speed = latest.get("input_speed_rad_s")
    return None if speed is None else speed * 60 / (2 * math.pi)


class ManualPanelTest(ConsolePageTest):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.start_browser()
        cls.browser.get(cls.daemon.url + "/login")
        cls.browser.find_element(By.ID, "token").send_keys(cls.daemon.token)
        cls.browser.find_element(By.ID, "login").click()
        WebDriverWait(cls.browser, 20).until(
            lambda b: b.current_url.rstrip("/") == cls.daemon.url)
        WebDriverWait(cls.browser, 20).until(
            lambda b: b.find_element(By.ID, "manual-servo").text == "servo off")

    def status(self):
        code, body = self.daemon.request("GET", "/api/status")
        self.assertEqual(code, 200)
        return body

    def until(self, what, condition, timeout=10):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            value = condition()
            if value:
                return value
            time.sleep(0.01)
        self.fail(f"not within {timeout} s: {what}\n{self.situation()}")

    def situation(self):
        """What the daemon and the page said when a wait failed: the words alone do not tell a
        press that never reached the page from a jog the daemon stopped."""
        s = self.status()
        page = {id_: self.panel_text(id_) for id_ in ("manual-servo", "manual-note", "manual-error")}
        page_state = self.browser.execute_script(
            "const m = window.wavebenchManual; return [m.jogging, m.presses || 0, m.stopCause,"
            " document.activeElement && document.activeElement.id, document.hasFocus()]")
        return (f"daemon: lifecycle={s.get('lifecycle')} servo={s.get('servo')!r} "
                f"input={rpm(s)} rpm manual={s.get('manual')}\npage: {page} [jogging, presses, "
                f"stop cause, focus, page focused]={page_state}")

    def wait_standing(self, start, bound):
        """Polls the status until the input stands; returns the seconds since `start` and keeps
        the wall-clock time it was seen standing."""
        deadline = start + bound + 2
        while time.monotonic() < deadline:
            speed = rpm(self.status())
            if speed is not None and abs(speed) < STANDING_RPM:
                self.standing_at = time.time()
                return time.monotonic() - start
        self.fail(f"the input still turns {deadline - start:.1f} s after {bound} s were allowed")

    def released_at(self):
        return self.browser.execute_script("return window.wavebenchManual.releasedAt || 0")

    def since_page_release(self, before):
        """Seconds from the page's own release event (its stop sent) to the input seen standing,
        both on this machine's wall clock. The promise is the page's and the daemon's: the time
        WebDriver takes to deliver the release on a loaded machine is not in it (printed
        beside). The page must have seen the release, or the input stopped for another reason."""
        released = self.released_at()
        self.assertNotEqual(released, before, "the page never saw the release")
        return self.standing_at - released / 1000

    def panel_text(self, id_):
        return self.browser.find_element(By.ID, id_).text

    def shot_panel(self, name):
        self.shot(name)
        self.browser.find_element(By.ID, "manual-panel").screenshot(
            os.path.join(OUTPUT, name + "-panel.png"))

    def press(self, element):
        """A pointer press held on `element`, centred in the view first: WebDriver scrolls an
        element to the top edge, under the console's sticky header, which then takes the
        press. Waits until the button's centre is the button itself (nothing laid over it, no
        layout still moving)."""
        self.browser.execute_script("arguments[0].scrollIntoView({block: 'center'})", element)
        self.until("the button on top at its centre, in place",
                   lambda: self.browser.execute_script(HIT_AT_CENTRE, element), 5)
        ActionChains(self.browser).reset_actions()
        return ActionChains(self.browser).move_to_element(element).click_and_hold()

    def hold(self, element, direction):
        """Holds `element` until the page says it jogs. A press that never reached the button
        (the page counted no pointerdown) or that the page ended by itself (its stop cause is
        printed) left the input standing: not the property under test, so it is tried again,
        twice at most, each miss printed."""
        for attempt in range(3):
            presses = self.browser.execute_script("return window.wavebenchManual.presses || 0")
            self.press(element).perform()
            deadline = time.monotonic() + 3
            while time.monotonic() < deadline:
                if self.browser.execute_script("return window.wavebenchManual.jogging") == direction:
                    return
                time.sleep(0.02)
            after = self.browser.execute_script("return window.wavebenchManual.presses || 0")
            seen = self.situation()
            ActionChains(self.browser).release().perform()
            # Either way the input stands (the safe side); the jog is then tried again.
            what = "was taken and ended" if after != presses else "did not reach the button"
            print(f"press {attempt + 1} {what}: {seen}", flush=True)
        self.fail("three presses did not hold the jog button")

    def set_field(self, id_, value):
        field = self.browser.find_element(By.ID, id_)
        field.clear()
        field.send_keys(str(value))

    def reset_bench(self):
        if self.status()["lifecycle"] == "fault":
            self.daemon.request("POST", "/api/reset", {})
        self.until("servo off", lambda: self.status()["servo"] == "servo off")

    def test_1_jog_moves_only_while_held_and_stops_on_release(self):
        self.reset_bench()
        self.assertEqual(self.panel_text("manual-servo"), "servo off")
        self.assertEqual(self.panel_text("manual-brake"), "brake off")
        self.shot_panel("manual-idle")

        self.set_field("jog-speed", 30)
        forward = self.browser.find_element(By.ID, "jog-forward")
        self.hold(forward, 1)
        self.until("moving", lambda: self.status()["servo"] in MOVING_30)
        # Held for 1.5 s (five times the keep-alive timeout): it keeps turning at 30 rpm.
        speeds, words = [], set()
        end = time.monotonic() + 1.5
        while time.monotonic() < end:
            s = self.status()
            speeds.append(rpm(s))
            words.add(s["servo"])
            time.sleep(0.05)
        self.assertTrue(all(v is not None and abs(v - 30) < 3 for v in speeds), speeds)
        self.assertTrue(words <= MOVING_30, words)
        self.until("page shows moving",
                   lambda: self.panel_text("manual-servo") in MOVING_30, 3)
        self.assertEqual(self.status()["lifecycle"], "active")
        self.shot_panel("manual-jogging")

        before = self.released_at()
        start = time.monotonic()
        ActionChains(self.browser).release().perform()
        latency = self.wait_standing(start, RELEASE_BOUND_S)
        from_page = self.since_page_release(before)
        print(f"\njog released -> input standing {from_page * 1000:.0f} ms after the page's "
              f"pointerup, {latency * 1000:.0f} ms after the WebDriver release was sent "
              f"(bound {RELEASE_BOUND_S * 1000:.0f} ms)", flush=True)
        self.assertLessEqual(from_page, RELEASE_BOUND_S)
        # The servo was on for the jog only: off again.
        self.until("servo off after", lambda: self.status()["servo"] == "servo off", 3)
        self.until("page shows servo off",
                   lambda: self.panel_text("manual-servo") == "servo off", 3)
        self.assertEqual(self.status()["lifecycle"], "inactive")
        self.shot_panel("manual-after")

    def test_1b_page_connection_lost_stops_within_the_heartbeat_timeout(self):
        self.reset_bench()
        bound = self.status()["manual"]["stop_within_s"]
        # The page: the jog held, then its requests never reach the daemon (a cable pulled):
        # no stop is sent, the daemon's timeout stops it.
        forward = self.browser.find_element(By.ID, "jog-forward")
        self.hold(forward, 1)
        try:
            self.until("moving", lambda: (rpm(self.status()) or 0) > 25)
        except AssertionError:
            print("panel:", self.browser.execute_script(
                "return [window.wavebenchManual.jogging, document.activeElement.id,"
                " document.hasFocus()]"), self.status()["manual"], flush=True)
            raise
        self.browser.execute_script("window.fetch = () => new Promise(() => {});")
        cut = time.monotonic()
        latency = self.wait_standing(cut, bound)
        print(f"page connection lost -> input standing {latency * 1000:.0f} ms after "
              f"(heartbeat timeout {bound * 1000:.0f} ms)", flush=True)
        self.assertLessEqual(latency, bound)
        ActionChains(self.browser).release().perform()
        self.browser.refresh()  # fetch back
        WebDriverWait(self.browser, 20).until(
            lambda b: b.find_element(By.ID, "manual-servo").text == "servo off")

    def test_6_keyboard_hold_jogs_reverse(self):
        self.reset_bench()
        self.set_field("jog-speed", 30)
        reverse = self.browser.find_element(By.ID, "jog-reverse")
        reverse.click()  # focus (a click is a short hold: it stops at once)
        self.until("standing", lambda: abs(rpm(self.status()) or 0) < STANDING_RPM, 3)
        ActionChains(self.browser).key_down(Keys.SPACE).perform()
        try:
            self.until("moving reverse", lambda: (rpm(self.status()) or 0) < -25, 3)
            # The measured speed, once the drive has settled after its ramp.
            self.until("words", lambda: self.status()["servo"] in {w.replace("g ", "g -") for w in MOVING_30}, 3)
        finally:
            before = self.released_at()
            start = time.monotonic()
            ActionChains(self.browser).key_up(Keys.SPACE).perform()
        latency = self.wait_standing(start, RELEASE_BOUND_S)
        from_page = self.since_page_release(before)
        print(f"\nkeyboard jog released -> standing {from_page * 1000:.0f} ms after the page's "
              f"keyup, {latency * 1000:.0f} ms after the WebDriver key up was sent", flush=True)
        self.assertLessEqual(from_page, RELEASE_BOUND_S)

    def test_3_lost_connection_stops_within_the_heartbeat_timeout(self):
        self.reset_bench()
        bound = self.status()["manual"]["stop_within_s"]
        # Direct API: keep-alives for 1 s, then silence.
        last = None
        end = time.monotonic() + 1.0
        while time.monotonic() < end:
            last = time.monotonic()
            code, body = self.daemon.request("POST", "/api/manual/jog", {"speed_rpm": 30})
            self.assertEqual(code, 200, body)
            time.sleep(0.1)
        self.assertGreater(rpm(self.status()) or 0, 25)
        latency = self.wait_standing(last, bound)
        print(f"\nAPI keep-alives stopped -> input standing {latency * 1000:.0f} ms after the "
              f"last one (heartbeat timeout {bound * 1000:.0f} ms)", flush=True)
        self.assertLessEqual(latency, bound)
        self.assertIn("no keep-alive", self.status()["manual"]["last_stop"])


    def test_4_over_limit_requests_are_refused_before_anything_moves(self):
        self.reset_bench()
        for action, body, key in [("jog", {"speed_rpm": 500}, "speed_rpm"),
                                  ("jog", {"speed_rpm": -61}, "speed_rpm"),
                                  ("goto", {"angle_deg": 5, "speed_rpm": 5000}, "speed_rpm"),
                                  ("goto", {"angle_deg": 1e6}, "angle_deg"),
                                  ("brake", {"torque_nm": 1000}, "torque_nm")]:
            code, answer = self.daemon.request("POST", "/api/manual/" + action, body)
            self.assertEqual(code, 400, answer)
            self.assertTrue(answer["detail"].startswith(key + ": got "), answer)
            self.assertIn("expected", answer["detail"])
        # Through the page: the field says 500, the daemon's refusal is shown.
        self.set_field("jog-speed", 500)
        forward = self.browser.find_element(By.ID, "jog-forward")
        self.press(forward).pause(0.3).release().perform()
        try:
            self.until("refusal shown",
                       lambda: "speed_rpm: got 500" in self.panel_text("manual-error"), 5)
        except AssertionError:
            print("panel:", self.panel_text("manual-panel"), self.browser.execute_script(
                "return [window.wavebenchManual.jogging, document.activeElement.id]"), flush=True)
            raise
        s = self.status()
        self.assertEqual(s["servo"], "servo off")
        self.assertLess(abs(rpm(s) or 0), STANDING_RPM)
        self.set_field("jog-speed", 30)

    def test_5_servo_on_holds_refuses_a_run_and_goes_to_an_angle(self):
        self.reset_bench()
        self.browser.find_element(By.ID, "servo-toggle").click()
        self.until("holding", lambda: self.status()["servo"] == "servo on, holding", 5)
        self.until("page holding",
                   lambda: self.panel_text("manual-servo") == "servo on, holding", 3)
        code, answer = self.daemon.request("POST", "/api/runs", {"procedure": "static"})
        self.assertEqual(code, 409, answer)
        self.assertIn("manual panel", answer["detail"])

        here = math.degrees(self.status()["latest"]["theta_out_rad"]) % 360
        target = round((here + 2.0) % 360, 1)
        self.set_field("goto-angle", target)
        self.set_field("jog-speed", 60)
        self.browser.find_element(By.CSS_SELECTOR, "#manual-goto button").click()
        def off_target(status):
            angle = math.degrees(status["latest"]["theta_out_rad"])
            return abs((angle - target + 180) % 360 - 180)
        self.until("arrived", lambda: off_target(self.status()) < 0.05
                   and self.status()["manual"]["goto_deg"] is None, 20)
        self.assertEqual(self.status()["servo"], "servo on, holding")

        self.set_field("brake-torque", 5)
        self.browser.find_element(By.CSS_SELECTOR, "#manual-brake-form button").click()
        self.until("brake words", lambda: self.status()["brake"].startswith("brake "), 5)
        self.shot_panel("manual-holding")
        print(f"went to {target}°; brake reads '{self.status()['brake']}'", flush=True)

        self.browser.find_element(By.ID, "servo-toggle").click()
        self.until("off", lambda: self.status()["servo"] == "servo off", 5)
        s = self.status()
        self.assertEqual(s["lifecycle"], "inactive")
        self.assertEqual(s["brake"], "brake off")


if __name__ == "__main__":
    if not WAVEBENCHD or not OUTPUT:
        sys.exit(__doc__)
    unittest.main(argv=[sys.argv[0], "-v"])
