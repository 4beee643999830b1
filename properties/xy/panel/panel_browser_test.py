#!/usr/bin/env python3
"""The XY panel in a real browser (docs/panel.md "Tests"): `axisproof panel` started on a free
port with one simulated board, Debian's chromium headless driven through selenium. What each test
expects comes from the operator's input and the thesis (seed-000.md §5, chapter 8 of the
original): a target typed in millimetres is where the carriage must end, a held arrow key jogs
and its release stops; the board's own position (the simulator's, `board_usteps` in /api/state,
which the page never shows) is the trace that proves the motion, not the page's text alone.

usage: panel_browser_test.py AXISPROOF OUT_DIR   (screenshots go to OUT_DIR)
"""
import os
import re
import subprocess
import sys
import time
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "panel"))
from panel_driver import PanelDriver  # noqa: E402  (properties/panel, shared by the profiles' panel tests)
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys

AXISPROOF, OUT = sys.argv[1], sys.argv[2]
# The simulated machine: 2 mm lead, 200 full steps, 16 microsteps (docs/sim.md "Machine",
# thesis Tab. 4-1), so 1 mm is 1600 microsteps.
USTEPS_PER_MM = 1600


class Panel(PanelDriver):
    """The XY panel with one simulated board, its page showing the board found."""

    def __init__(self, *args):
        t0 = time.monotonic()
        super().__init__(AXISPROOF, *args)
        self.wait(lambda: self.text("ble-indicator") == "not connected", "the page to find the board")
        self.ready_s = time.monotonic() - t0

    def board(self):
        return self.api("/api/state")[1]["boards"][0]

    def usteps(self, axis):
        return self.board()["axes"][axis]["board_usteps"]

    def outcomes(self):
        return [(li.get_attribute("data-command"), li.get_attribute("data-outcome"))
                for li in self.driver.find_elements(By.CSS_SELECTOR, "#outcomes li")]

    def connect(self):
        self.click("connect")
        self.wait(lambda: self.text("ble-indicator") == "connected", "the connection")

    def menu(self, name):
        self.driver.find_element(By.CSS_SELECTOR, ".menu[data-panel='%s']" % name).click()

    def go_absolute(self, x, y):
        """Automatic absolute: X and Y typed in mm, then Go."""
        self.menu("absolute")
        self.type("abs-x", x)
        self.type("abs-y", y)
        self.click("abs-go")

    def shot(self, name):
        super().shot(OUT, name)


class XyPanel(unittest.TestCase):
    def setUp(self):
        self.p = Panel()
        self.p.connect()

    def tearDown(self):
        self.p.close()

    def wait_rest(self, axis):
        """Until the board's carriage on `axis` stands (two samples 300 ms apart agree)."""
        last = [None]

        def still():
            now = self.p.usteps(axis)
            same = now == last[0]
            last[0] = now
            return same
        self.p.wait(lambda: (time.sleep(0.3) or still()), "axis %d to stand" % axis)

    def test_held_arrow_key_jogs_and_release_stops(self):
        x0 = self.p.usteps(0)
        chain = ActionChains(self.p.driver)
        chain.key_down(Keys.ARROW_RIGHT).perform()
        self.p.wait(lambda: self.p.usteps(0) > x0 + USTEPS_PER_MM // 10, "X to move on a held arrow key")
        # The page shows the motion too (its state arrives every 100 ms).
        self.p.wait(lambda: self.p.el("x-status").get_attribute("data-status") in ("accel", "const"), "the page to show the jog")
        ActionChains(self.p.driver).key_up(Keys.ARROW_RIGHT).perform()
        self.wait_rest(0)
        stopped_at = self.p.usteps(0)
        time.sleep(1.0)
        self.assertEqual(self.p.usteps(0), stopped_at, "the carriage moved on after the key was released")
        self.assertGreater(stopped_at, x0)
        self.p.shot("panel-manual")

    def test_two_held_keys_move_both_axes_at_once(self):
        x0, y0 = self.p.usteps(0), self.p.usteps(1)
        ActionChains(self.p.driver).key_down(Keys.ARROW_RIGHT).key_down(Keys.ARROW_UP).perform()
        self.p.wait(lambda: self.p.usteps(0) > x0 + 200 and self.p.usteps(1) > y0 + 200, "both axes to move")
        ActionChains(self.p.driver).key_up(Keys.ARROW_RIGHT).key_up(Keys.ARROW_UP).perform()
        self.wait_rest(0)
        self.wait_rest(1)

    def test_absolute_then_relative_move_reach_their_targets(self):
        self.p.go_absolute("12.5", "7.25")
        self.p.wait(lambda: self.p.text("x-pos") == "12.500" and self.p.text("y-pos") == "7.250", "the absolute target", 30)
        self.p.shot("panel-absolute")
        self.assertEqual(self.p.usteps(0), int(12.5 * USTEPS_PER_MM))
        self.assertEqual(self.p.usteps(1), int(7.25 * USTEPS_PER_MM))
        self.p.menu("relative")
        self.p.type("rel-x", "2.5")
        self.p.type("rel-y", "-1")
        self.p.click("rel-go")
        self.p.wait(lambda: self.p.text("x-pos") == "15.000" and self.p.text("y-pos") == "6.250", "the relative target", 30)
        self.assertEqual(self.p.usteps(0), 15 * USTEPS_PER_MM)
        self.assertEqual(self.p.usteps(1), int(6.25 * USTEPS_PER_MM))
        self.p.shot("panel-relative")
        done = [o for o in self.p.outcomes() if o[1] == "done"]
        self.assertGreaterEqual(len([o for o in done if o[0] == "goto"]), 2)
        self.assertGreaterEqual(len([o for o in done if o[0] == "move"]), 2)

    def test_home_references_the_axis(self):
        self.p.menu("relative")
        self.p.type("rel-x", "3")
        self.p.type("rel-y", "0")
        self.p.click("rel-go")
        self.p.wait(lambda: self.p.text("x-pos") == "3.000", "the move before homing")
        self.p.menu("manual")
        self.p.click("home-x")
        self.p.wait(lambda: self.p.el("x-status").get_attribute("data-status") == "homing", "homing to show")
        self.p.wait(lambda: self.p.text("x-pos") == "0.000" and self.p.el("x-status").get_attribute("data-status") == "reached",
                    "homing to end at 0", 30)
        self.assertIn(("home", "done"), self.p.outcomes())

    def test_dynamics_are_saved_and_survive_a_reboot(self):
        self.p.menu("dynamics")
        self.p.type("dyn-fast", "8")
        self.p.type("dyn-slow", "1.5")
        self.p.type("dyn-accel", "15")
        self.p.click("dyn-save")
        self.p.wait(lambda: self.p.text("p-fast") == "8.000" and self.p.text("p-slow") == "1.500" and self.p.text("p-accel") == "15.000",
                    "the stored dynamics")
        self.p.shot("panel-dynamics")
        status, r = self.p.api("/api/env", {"board": 0, "line": "reboot"})
        self.assertEqual(status, 200, r)
        # The parameter subscriber reads them again from the rebooted board within a few frames.
        time.sleep(2.0)
        self.assertEqual((self.p.text("p-fast"), self.p.text("p-slow"), self.p.text("p-accel")), ("8.000", "1.500", "15.000"))

    def test_sleep_locks_the_control_buttons(self):
        self.p.click("sleep")
        self.p.wait(lambda: self.p.el("x-status").get_attribute("data-status") == "sleeping", "the unit to sleep")
        self.p.wait(lambda: not self.p.el("abs-go").is_enabled() and not self.p.el("home-x").is_enabled(), "the lock")
        self.assertEqual(self.p.text("sleep"), "Wake")
        self.p.shot("panel-static-sleeping")
        x0 = self.p.usteps(0)
        ActionChains(self.p.driver).key_down(Keys.ARROW_RIGHT).perform()
        time.sleep(0.5)
        ActionChains(self.p.driver).key_up(Keys.ARROW_RIGHT).perform()
        self.assertEqual(self.p.usteps(0), x0, "an arrow key moved a sleeping unit")
        self.assertIn("sleeps", self.p.text("refusal"))
        self.p.click("sleep")
        self.p.wait(lambda: self.p.el("home-x").is_enabled(), "the wake")

    def test_usb_plug_shows_blocked_and_the_commands_blocked_outcome(self):
        self.p.el("info").click()
        ActionChains(self.p.driver).key_down(Keys.SHIFT).send_keys("V").key_up(Keys.SHIFT).perform()
        self.p.wait(lambda: self.p.el("dev").is_displayed(), "the developer extension on Shift+V")
        self.p.click("dev-usb-on")
        self.p.wait(lambda: "USB" in self.p.text("dev-reply") or "usb" in self.p.text("dev-reply"), "the USB plug")
        self.p.go_absolute("5", "5")
        self.p.wait(lambda: ("goto", "blocked") in self.p.outcomes(), "the blocked outcome")
        self.p.wait(lambda: self.p.text("x-status") == "blocked: USB connected", "the blocked status")
        self.assertEqual(self.p.usteps(0), 0)
        self.p.shot("panel-blocked-usb")

    def test_simulated_echo_updates_the_info_panel(self):
        ActionChains(self.p.driver).key_down(Keys.SHIFT).send_keys("V").key_up(Keys.SHIFT).perform()
        self.p.wait(lambda: self.p.el("dev").is_displayed(), "the developer extension")
        from selenium.webdriver.support.ui import Select
        Select(self.p.el("dev-status")).select_by_value("blk_charger")
        self.p.type("dev-pos", "42.5")
        self.p.click("dev-echo")
        self.p.wait(lambda: self.p.text("x-status") == "blocked: charger connected" and self.p.text("y-status") ==
                    "blocked: charger connected" and self.p.text("x-pos") == "42.500", "the simulated echo")
        # The message timer shows the outgoing frame: a held key's jog rides in it.
        self.p.click("dev-timer")
        ActionChains(self.p.driver).key_down(Keys.ARROW_LEFT).perform()
        self.p.wait(lambda: re.search(r"x=jog:-", self.p.text("dev-frame")), "the outgoing frame with the jog")
        ActionChains(self.p.driver).key_up(Keys.ARROW_LEFT).perform()
        self.p.shot("panel-developer")

    def test_rotation_graph_with_a_user_zero(self):
        # Seed 000 §9.4.2: the rotation subscriber in a graph that can be saved, with a zero the
        # user sets. The simulated platform turns to an absolute angle (docs/sim.md `rotate`).
        status, r = self.p.api("/api/env", {"board": 0, "line": "rotate 30000"})
        self.assertEqual(status, 200, r)
        self.p.wait(lambda: self.p.text("rotation-rel") == "30.0°", "the turn to 30°", 30)
        self.p.click("rotation-zero")
        self.p.wait(lambda: self.p.text("rotation-rel") == "0.0°", "the user's zero")
        self.p.api("/api/env", {"board": 0, "line": "rotate 15000"})
        self.p.wait(lambda: self.p.text("rotation-rel") == "-15.0°", "the turn back by 15°", 30)
        self.assertTrue(self.p.el("rotation-save").get_attribute("href").startswith("data:image/png;base64,"))
        self.p.shot("panel-rotation")

    def test_bad_input_is_refused_in_the_page_and_never_sent(self):
        self.p.menu("absolute")
        before = len(self.p.outcomes())
        refused_before = self.p.api("/api/state")[1]["refused_requests"]
        cases = [("abc", "not a number"), ("-5", "outside"), ("1000", "outside"), ("", "empty"), ("1e3", "not a number")]
        for value, why in cases:
            self.p.type("abs-x", value)
            self.p.type("abs-y", "1")
            self.p.click("abs-go")
            self.p.wait(lambda: why in self.p.text("refusal"), "the refusal of '%s'" % value)
        # Over-long: the field takes 12 characters; a longer value set by script is refused too.
        self.p.driver.execute_script("document.getElementById('abs-x').value = '1234567890.123';")
        self.p.click("abs-go")
        self.p.wait(lambda: "longer than 12" in self.p.text("refusal"), "the over-long refusal")
        time.sleep(0.5)
        self.assertEqual(len(self.p.outcomes()), before, "a refused value produced a command")
        self.assertEqual(self.p.api("/api/state")[1]["refused_requests"], refused_before,
                         "the page sent a value it should have refused itself")
        self.assertEqual(self.p.usteps(0), 0)
        # The server checks again: a request the page would never send is refused with its reason.
        for body, why in [({"board": 0, "part": "x", "key": "goto", "data": "12"}, "not an integer"),
                          ({"board": 0, "part": "x", "key": "goto", "data": -1}, "outside"),
                          ({"board": 0, "part": "x", "key": "pitch", "data": 2000}, "not an operator command"),
                          ({"board": 0, "part": "q", "key": "goto", "data": 1}, "part"),
                          ({"board": 0, "part": "x", "key": "goto" * 10, "data": 1}, "longer")]:
            status, r = self.p.api("/api/command", body)
            self.assertEqual(status, 400, body)
            self.assertIn(why, r["error"])
        self.assertEqual(self.p.usteps(0), 0)


class XyPanelOverABadLink(unittest.TestCase):
    """A link storm under the panel: the fault link of docs/sim.md between the session and the
    bus drops, corrupts, duplicates and delays frames both ways."""

    def test_storm_shows_retries_and_every_command_lands_once(self):
        p = Panel("--faults", "drop 30 %; corrupt 10 %; duplicate 10 %; delay 20 ms")
        try:
            p.connect()
            p.menu("relative")
            p.type("rel-y", "0")
            for k in range(1, 5):
                p.type("rel-x", "1")
                p.click("rel-go")
                # Relative moves one after another, each from where the last one ended: a move
                # run twice would leave the carriage a millimetre further.
                p.wait(lambda: p.text("x-pos") == "%d.000" % k and p.el("x-status").get_attribute("data-status") == "reached",
                       "move %d" % k, 60)
            time.sleep(1.0)
            self.assertEqual(p.usteps(0), 4 * USTEPS_PER_MM)
            moves = [o for o in p.outcomes() if o[0] == "move"]
            self.assertEqual(moves, [("move", "done")] * 4)
            m = re.search(r"(\d+) frames sent, (\d+) sent again", p.text("link-stats"))
            self.assertTrue(m, p.text("link-stats"))
            self.assertGreater(int(m.group(2)), 0, "no retry shown under a 30 % drop")
            p.shot("panel-link-storm")
        finally:
            p.close()


class XyPanelOnQemu(unittest.TestCase):
    """--target qemu: the board runs the XY release image under qemu-system-arm (docs/qemu.md);
    the first run builds the image (m4 preset)."""

    def test_moves_on_the_image(self):
        p = Panel("--target", "qemu")
        try:
            p.connect()
            p.go_absolute("3", "2")
            p.wait(lambda: p.text("x-pos") == "3.000" and p.text("y-pos") == "2.000", "the targets on the image", 60)
            self.assertEqual((p.usteps(0), p.usteps(1)), (3 * USTEPS_PER_MM, 2 * USTEPS_PER_MM))
            self.assertIn(("goto", "done"), p.outcomes())
        finally:
            p.close()


class XyPanelSessions(unittest.TestCase):
    def test_out_of_range_indicator(self):
        p = Panel()
        try:
            p.connect()
            # The BLE module leaves its data session (thesis Tab. 7-2): the board takes no frame
            # and answers none, so the indicator must turn.
            self.assertEqual(p.api("/api/env", {"board": 0, "line": "ble standby"})[0], 200)
            p.wait(lambda: p.text("ble-indicator") == "out of range", "the out-of-range indicator")
            p.shot("panel-out-of-range")
            self.assertEqual(p.api("/api/env", {"board": 0, "line": "ble session"})[0], 200)
            p.wait(lambda: p.text("ble-indicator") == "connected", "the unit back in range")
        finally:
            p.close()

    def test_second_tab_and_a_tab_closed_mid_command(self):
        p = Panel()
        try:
            p.connect()
            first = p.driver.current_window_handle
            p.driver.switch_to.new_window("tab")
            p.driver.get(p.url)
            p.wait(lambda: p.text("ble-indicator") == "connected", "the second tab to show the connection")
            p.go_absolute("20", "0")
            p.driver.close()  # the tab goes while its command is on its way
            p.driver.switch_to.window(first)
            # The command still lands, once, and the first tab shows its outcome and the result.
            p.wait(lambda: p.text("x-pos") == "20.000", "the closed tab's command to run", 30)
            p.wait(lambda: ("goto", "done") in p.outcomes(), "its outcome in the other tab")
            self.assertEqual(p.usteps(0), 20 * USTEPS_PER_MM)
        finally:
            p.close()

    def test_attached_board_that_leaves_the_bus(self):
        domain = 200 + os.getpid() % 30
        board = subprocess.Popen([AXISPROOF, "sim", "board", "--domain", str(domain), "--idle-timeout", "120"],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        p = None
        try:
            p = Panel("--attach", "--domain", str(domain))
            p.connect()
            p.go_absolute("2", "1")
            p.wait(lambda: p.text("x-pos") == "2.000", "the attached board to move", 30)
            board.kill()
            board.wait()
            p.wait(lambda: p.text("ble-indicator") == "board not on the bus", "the board's departure to show", 30)
            events = " ".join(li.text for li in p.driver.find_elements(By.CSS_SELECTOR, "#events li"))
            self.assertIn("BleDeviceDisconnectedEvent", events)
        finally:
            if p:
                p.close()
            if board.poll() is None:
                board.kill()
                board.wait()


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
