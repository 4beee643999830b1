"""What every profile's panel browser test needs (docs/panel.md "Tests"): `axisproof panel` on a
free port, Debian's chromium headless on its page through selenium and chromium-driver, the
panel's JSON API, and a wait that retries while the page re-renders."""
import json
import os
import re
import subprocess
import time
import urllib.error
import urllib.request

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By


class PanelDriver:
    """One `axisproof panel` process (AXISPROOF panel --port 0 ARGS...) and one headless chromium on its page."""

    def __init__(self, axisproof, *args, width=1400, height=1100):
        self.proc = subprocess.Popen([axisproof, "panel", "--port", "0", *args], stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT, text=True)
        # Lines before the URL are the CLI's own (e.g. building the QEMU image first).
        seen = ""
        m = None
        while m is None:
            line = self.proc.stdout.readline()
            seen += line
            m = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
            if not line:
                self.proc.kill()
                self.proc.wait()
                self.proc.stdout.close()
                raise RuntimeError("axisproof panel did not start: " + seen)
        self.url = "http://127.0.0.1:%s/" % m.group(1)
        opts = webdriver.ChromeOptions()
        opts.binary_location = "/usr/bin/chromium"
        for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                  "--window-size=%d,%d" % (width, height)):
            opts.add_argument(a)
        try:
            self.driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)
            self.driver.get(self.url)
        except Exception:
            self.proc.kill()
            self.proc.wait()
            self.proc.stdout.close()
            raise

    def close(self):
        self.driver.quit()
        self.proc.terminate()
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        self.proc.stdout.close()

    def el(self, id_):
        return self.driver.find_element(By.ID, id_)

    def text(self, id_):
        return self.el(id_).text

    def click(self, id_):
        self.el(id_).click()

    def type(self, id_, value):
        e = self.el(id_)
        e.clear()
        e.send_keys(value)

    def wait(self, cond, what, timeout=20.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                if cond():
                    return
            except Exception:  # an element re-rendered under us: try again
                pass
            time.sleep(0.05)
        raise AssertionError("timed out waiting for " + what)

    def api(self, path, body=None):
        req = urllib.request.Request(self.url + path.lstrip("/"), data=None if body is None else json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=10) as r:
                return r.status, json.loads(r.read())
        except urllib.error.HTTPError as e:
            return e.code, json.loads(e.read())

    def shot(self, out_dir, name):
        os.makedirs(out_dir, exist_ok=True)
        self.driver.save_screenshot(os.path.join(out_dir, name + ".png"))
