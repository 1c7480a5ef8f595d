"""Render a `tehl report` page in headless Chromium and check it (facegear_tehl.browser_check): no page errors,
every image decoded, a page of some height, a screenshot that is not blank.

    python scripts/check_report.py report.html [--screenshot shot.png]
"""

from __future__ import annotations

import argparse
from pathlib import Path
import sys

import numpy as np
from PIL import Image

from facegear_tehl.browser_check import render


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("page", type=Path)
    parser.add_argument("--screenshot", type=Path, default=Path("report_screenshot.png"))
    args = parser.parse_args()
    seen = render(args.page, args.screenshot)
    with Image.open(seen.screenshot) as image:
        spread = float(np.asarray(image.convert("L"), dtype=float).std())
    print(f"images decoded {seen.decoded} of {seen.images}; page height {seen.height} px; "
          f"screenshot {seen.screenshot} (grey-level spread {spread:.1f})")
    for line in seen.errors:
        print(f"error: {line}")
    ok = not seen.errors and seen.images > 0 and seen.decoded == seen.images and seen.height > 1000 and spread > 5
    print("ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
