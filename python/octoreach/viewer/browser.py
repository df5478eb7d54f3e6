"""Headless Chromium (through Selenium and chromedriver) for screenshots and clicks on the viewer's page.

Needs Debian's `chromium` and `chromium-driver` (scripts/install_deps.sh) and Selenium (the `viewer` extra).
"""
from __future__ import annotations

import os
import shutil
import time

import numpy as np


def chromium_missing() -> str | None:
    """Why the browser cannot run here, or None."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "selenium is not installed (pip install 'octoreach[viewer]')"
    if not (shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")):
        return "chromium is not installed (scripts/install_deps.sh installs it)"
    if not shutil.which("chromedriver"):
        return "chromedriver is not installed (Debian package chromium-driver)"
    return None


def _png_pixels(data: bytes) -> np.ndarray:
    import io

    from matplotlib import image

    return (image.imread(io.BytesIO(data), format="png")[..., :3] * 255).round().astype(np.uint8)


# WebGL on SwiftShader (software, no GPU needed); the page itself composited in software and the GPU thread in
# the browser process: with SwiftShader compositing the page too, the GPU process's one thread is busy with
# the page's layers while WebGL waits for it (an empty viewer page took 1.2 s to draw instead of 0.7 s, and its
# shader compiles waited 10x longer).
FLAGS = ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--use-angle=swiftshader",
         "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist", "--hide-scrollbars", "--disable-gpu-compositing",
         "--in-process-gpu")


class Browser:
    """One headless Chromium window of width x height pixels."""

    def __init__(self, width: int = 1280, height: int = 800, flags=None):
        """`flags`: Chromium command-line flags instead of FLAGS (the window size is added)."""
        reason = chromium_missing()
        if reason:
            raise RuntimeError(reason)
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service

        opts = webdriver.ChromeOptions()
        binary = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
        opts.binary_location = binary
        for a in (*(FLAGS if flags is None else flags), f"--window-size={width},{height}"):
            opts.add_argument(a)
        try:
            self.driver = webdriver.Chrome(options=opts, service=Service(shutil.which("chromedriver")))
        except Exception as e:  # noqa: BLE001  (selenium's WebDriverException and whatever the driver raised)
            first = (str(e).strip().splitlines() or [type(e).__name__])[0][:300]
            raise RuntimeError(f"cannot start headless Chromium through chromedriver ({first}); check that "
                               "`chromium --headless` and `chromedriver --version` run here") from None
        self.driver.set_window_size(width, height)
        inner = self.driver.execute_script("return [window.innerWidth, window.innerHeight];")
        self.driver.set_window_size(2 * width - inner[0], 2 * height - inner[1])  # the page gets width x height
        self.width, self.height = width, height

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self) -> None:
        self.driver.quit()

    def open(self, url: str, viewer=None, timeout: float = 30.0) -> None:
        """Loads the page and waits until the scene is drawn: a client connected (when `viewer` is given)
        and two screenshots in a row that agree and are not blank."""
        self.driver.get(url)
        t_end = time.time() + timeout
        # viser's notifications (e.g. "software WebGL rendering") would cover part of the screenshot.
        self.driver.execute_script(
            "const s = document.createElement('style');"
            "s.textContent = '.mantine-Notifications-root { display: none !important; }';"
            "document.head.appendChild(s);")
        if viewer is not None:
            while not viewer.server.get_clients() and time.time() < t_end:
                time.sleep(0.05)
        last = None
        while time.time() < t_end:
            time.sleep(0.4)
            px = self.pixels()
            if last is not None and px.shape == last.shape and np.abs(px.astype(int) - last).mean() < 0.05 \
                    and px.std() > 5:
                return
            last = px.astype(int)
        raise TimeoutError(f"the page {url} showed no steady scene within {timeout} s")

    def pixels(self) -> np.ndarray:
        """(H, W, 3) uint8 screenshot of the window."""
        return _png_pixels(self.driver.get_screenshot_as_png())

    def screenshot(self, path) -> str:
        """Writes a PNG of the window to `path`, atomically (a device or link there is refused, never replaced)."""
        from ..atomic_write import write_atomically

        write_atomically(path, self.driver.get_screenshot_as_png(), "screenshot")
        return os.fspath(path)

    def canvas(self):
        from selenium.webdriver.common.by import By

        return self.driver.find_element(By.TAG_NAME, "canvas")

    def project(self, camera, point) -> tuple[float, float]:
        """Pixel (x, y) in the canvas of a world point seen by a viser client's camera."""
        c = self.canvas()
        w, h = c.size["width"], c.size["height"]
        eye, target = np.asarray(camera.position, float), np.asarray(camera.look_at, float)
        up = np.asarray(camera.up_direction, float)
        f = target - eye
        f /= np.linalg.norm(f)
        r = np.cross(f, up)
        r /= np.linalg.norm(r)
        u = np.cross(r, f)
        d = np.asarray(point, float) - eye
        x, y, z = d @ r, d @ u, d @ f
        t = np.tan(camera.fov / 2.0)
        ndc_x, ndc_y = x / (z * t * (w / h)), y / (z * t)
        return (ndc_x + 1) / 2 * w, (1 - ndc_y) / 2 * h

    def click(self, x: float, y: float) -> None:
        """A real mouse click at canvas pixel (x, y)."""
        from selenium.webdriver.common.action_chains import ActionChains

        c = self.canvas()
        w, h = c.size["width"], c.size["height"]
        ActionChains(self.driver).move_to_element_with_offset(c, int(x - w / 2), int(y - h / 2)).click().perform()
