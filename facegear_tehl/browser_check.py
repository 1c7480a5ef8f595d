"""Render a `tehl report` page in headless Chromium and check it: no console or loading errors, every image
decoded, a page of some height. Used by scripts/check_report.py and the slow test of the report."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
import re
import shutil
import subprocess
import tempfile

BROWSERS = ("chromium", "chromium-browser", "google-chrome")
# Injected into a copy of the page only (the report itself holds no script): after loading, the title reports the
# images decoded, the images in total and the page height in CSS pixels.
PROBE = ("<script>window.addEventListener('load', () => { const images = [...document.images]; "
         "document.title = 'probe ' + images.filter(i => i.complete && i.naturalWidth > 0).length + ' ' + "
         "images.length + ' ' + document.body.scrollHeight; });</script>")
TIMEOUT = 120.0  # s for one headless render on a loaded 2-core machine (3 s when quiet)
# Chromium's own complaints that are not the page's (no D-Bus session, no GPU, the sandbox in a container).
NOISE = ("dbus", "D-Bus", "gpu", "GPU", "sandbox", "idle_linux", "Fontconfig", "vaapi", "viz", "gles")


@dataclass(frozen=True)
class Rendering:
    """What the browser saw: images decoded of the images in total, the page height (CSS px), the error lines of
    its log that concern the page, and the screenshot written."""

    decoded: int
    images: int
    height: int
    errors: tuple[str, ...]
    screenshot: Path


def browser() -> str | None:
    """The headless browser on this machine (Chromium from the system packages), or None."""
    return next((path for name in BROWSERS if (path := shutil.which(name))), None)


def render(page: Path, screenshot: Path, width: int = 1200, height: int = 2400) -> Rendering:
    """Load `page` in headless Chromium: the probe's counts from the DOM, the page's errors from the log, and a
    screenshot of the first `height` pixels; RuntimeError when no browser is installed."""
    program = browser()
    if program is None:
        raise RuntimeError("no Chromium found (apt-get install chromium)")
    with tempfile.TemporaryDirectory() as folder:
        probe = Path(folder) / page.name
        probe.write_text(page.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"), encoding="utf-8")
        common = [program, "--headless", "--no-sandbox", "--disable-gpu", "--enable-logging=stderr", "--v=0",
                  "--virtual-time-budget=10000", f"--window-size={width},{height}"]
        dom = subprocess.run([*common, "--dump-dom", probe.as_uri()], capture_output=True, text=True,
                             timeout=TIMEOUT, check=False)
        shot = subprocess.run([*common, f"--screenshot={screenshot}", page.resolve().as_uri()], capture_output=True,
                              text=True, timeout=TIMEOUT, check=False)
    match = re.search(r"<title>probe (\d+) (\d+) (\d+)</title>", dom.stdout)
    errors = tuple(line for line in (dom.stderr + shot.stderr).splitlines()
                   if ("ERROR" in line or "CONSOLE" in line) and not any(word in line for word in NOISE))
    if match is None:
        errors += ("the probe did not run: the page did not finish loading",)
    decoded, images, height_px = (int(g) for g in match.groups()) if match else (0, 0, 0)
    return Rendering(decoded, images, height_px, errors, screenshot)
