#!/usr/bin/env python3
"""The unit3 panel in a real browser (docs/panel.md "The unit3 panel"): seed 001's PC program
(seed-001.md §7) on one simulated unit, Debian's chromium headless through selenium. Expected
counts come from the seed's send logic, steps = round(|mm| / pitch * 200 * 2^mode) and count =
steps * 32 / 2^mode, with the pitches docs/unit3.md decides (M2 0.4 and M6 1.0 mm from the
thesis; M3 0.5, M4 0.7, M5 0.8, M8 1.25, M10 1.5 the ISO coarse pitches), written out here, not
read from the code; the worked examples of seed-001.md §7 (M2 at 1/32, +1 mm: 16000 counts; M6
at full step, 1 mm: 6400) are run on the unit and its counter reports must say so.

usage: panel_browser_test.py AXISPROOF OUT_DIR
"""
import os
import sys
import time
import unittest
from decimal import ROUND_HALF_UP, Decimal

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "panel"))
from panel_driver import PanelDriver  # noqa: E402  (properties/panel, shared by the profiles' panel tests)
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select

AXISPROOF, OUT = sys.argv[1], sys.argv[2]
PITCH_MM = ["0.4", "0.5", "0.7", "0.8", "1.0", "1.25", "1.5"]  # digits 0..6: M2 M3 M4 M5 M6 M8 M10


def expected_count(mm, mode, thread):
    steps = (abs(Decimal(mm)) / Decimal(PITCH_MM[thread]) * 200 * (2 ** mode)).quantize(Decimal(1), rounding=ROUND_HALF_UP)
    return int(steps) * (32 // 2 ** mode)


class Unit3Panel(unittest.TestCase):
    def setUp(self):
        self.p = PanelDriver(AXISPROOF, "--profile", "unit3", height=900)
        self.d = self.p.driver
        self.wait(lambda: self.text("bus") == "unit on the bus", "the unit")

    def tearDown(self):
        self.p.close()

    def wait(self, cond, what, timeout=30.0):
        self.p.wait(cond, what, timeout)

    def state(self):
        return self.p.api("/api/state")[1]

    def text(self, id_):
        return self.p.text(id_)

    def counts(self):
        return [a["count"] for a in self.state()["axes"]]

    def set_axis(self, a, mm, mode, thread):
        Select(self.d.find_element(By.ID, "mode-%d" % a)).select_by_value(str(mode))
        Select(self.d.find_element(By.ID, "thread-%d" % a)).select_by_value(str(thread))
        e = self.d.find_element(By.ID, "mm-%d" % a)
        e.clear()
        e.send_keys(mm)

    def test_mm_to_count_for_every_step_mode_and_thread(self):
        self.set_axis(1, "0", 0, 0)
        self.set_axis(2, "0", 0, 0)
        checked = 0
        for thread in range(7):
            for mode in range(6):
                # A displacement with a remainder in every mode, alternating in sign.
                mm = ("-" if (mode + thread) % 2 else "") + "0.%03d" % (37 + 11 * thread + 7 * mode)
                self.set_axis(0, mm, mode, thread)
                # The PC's conversion is checked here, not the unit's motion (the worked examples
                # below are run): a send while the last move runs is refused by the unit (E20).
                before = len(self.d.find_elements(By.CSS_SELECTOR, "#sent li"))
                self.d.find_element(By.ID, "send").click()
                self.wait(lambda: len(self.d.find_elements(By.CSS_SELECTOR, "#sent li")) > before, "the send")
                want = expected_count(mm, mode, thread)
                sign = "-" if mm.startswith("-") and want else "+"
                self.assertEqual(self.text("count-0"), sign + str(want), "mode %d thread %d, %s mm" % (mode, thread, mm))
                # The position that count reaches (eq. 5: count / 6400 * pitch), to the µm.
                reach = (Decimal(want) / 6400 * Decimal(PITCH_MM[thread])).quantize(Decimal("0.001"), rounding=ROUND_HALF_UP)
                self.assertEqual(self.text("achieved-0"), ("-" if sign == "-" else "") + str(reach) + " mm")
                sent = self.d.find_elements(By.CSS_SELECTOR, "#sent li")[0].text
                if want:
                    self.assertIn("X%015d;" % want, sent)
                    self.assertIn("D%s++;" % sign, sent)
                checked += 1
        self.assertEqual(checked, 42)
        self.p.shot(OUT, "panel-unit3")

    def test_worked_examples_reach_the_unit_and_zero_clears(self):
        self.set_axis(0, "1.0", 5, 0)   # M2 (0.4 mm), 1/32 step, +1 mm
        self.set_axis(1, "1", 0, 4)     # M6 (1 mm), full step, 1 mm
        self.set_axis(2, "0", 0, 0)
        self.d.find_element(By.ID, "send").click()
        self.wait(lambda: self.counts()[:2] == [16000, 6400], "the counters of seed-001.md §7's examples", 120)
        self.wait(lambda: self.text("pos-0") == "1.000" and self.text("pos-1") == "1.000", "the positions (eq. 5)")
        self.d.find_element(By.ID, "zero").click()
        self.wait(lambda: self.text("pos-0") == "0.000" and self.text("counter-1") == "0", "0 0 0")
        self.assertIn("C;", self.d.find_elements(By.CSS_SELECTOR, "#sent li")[0].text)

    def test_the_units_settings_set_the_selection_boxes(self):
        self.set_axis(0, "0.1", 3, 2)
        self.set_axis(1, "0", 1, 5)
        self.set_axis(2, "0", 4, 6)
        self.d.find_element(By.ID, "send").click()
        self.wait(lambda: "M314;" in self.d.find_elements(By.CSS_SELECTOR, "#sent li")[0].text, "the settings sent")
        self.wait(lambda: self.state()["axes"][0]["mode"] == 3 and self.state()["axes"][2]["thread"] == 6, "the unit's settings reply")
        # The operator changes the boxes without sending; reading the unit's settings sets them back.
        for a in range(3):
            Select(self.d.find_element(By.ID, "mode-%d" % a)).select_by_value("0")
            Select(self.d.find_element(By.ID, "thread-%d" % a)).select_by_value("0")
        self.d.find_element(By.ID, "get").click()
        boxes = lambda: [(Select(self.d.find_element(By.ID, "mode-%d" % a)).first_selected_option.get_attribute("value"),
                          Select(self.d.find_element(By.ID, "thread-%d" % a)).first_selected_option.get_attribute("value"))
                         for a in range(3)]
        self.wait(lambda: boxes() == [("3", "2"), ("1", "5"), ("4", "6")], "the boxes set from the unit's reply")
        self.assertIn("G;", self.d.find_elements(By.CSS_SELECTOR, "#sent li")[0].text)

    def test_refusals_and_bad_input(self):
        before = self.state()["refused_requests"]
        for value, why in [("abc", "not a number"), ("1000", "outside"), ("", "empty"), ("1e2", "not a number")]:
            self.set_axis(0, value, 0, 0)
            self.d.find_element(By.ID, "send").click()
            self.wait(lambda: why in self.text("refusal"), "the refusal of '%s'" % value)
        self.assertEqual(self.state()["refused_requests"], before, "the page sent a value it should have refused")
        self.assertEqual(len(self.d.find_elements(By.CSS_SELECTOR, "#sent li")), 0)
        # The unit's own refusal: a second move while the first runs is E20 (busy), shown.
        self.set_axis(0, "5", 5, 0)
        self.set_axis(1, "0", 0, 0)
        self.set_axis(2, "0", 0, 0)
        self.d.find_element(By.ID, "send").click()
        self.wait(lambda: self.counts()[0] > 0, "the first move")
        self.d.find_element(By.ID, "send").click()
        self.wait(lambda: any(li.get_attribute("data-code") == "20" for li in self.d.find_elements(By.CSS_SELECTOR, "#refusals li")),
                  "the unit's busy refusal")
        self.assertIn("busy", self.d.find_elements(By.CSS_SELECTOR, "#refusals li")[0].text)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
