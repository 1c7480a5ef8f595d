"""`tehl report`: one self-contained HTML page of a result file, checked against the file it reads and, in the slow
set, rendered in headless Chromium."""

from __future__ import annotations

import base64
from html.parser import HTMLParser
import io
import re

from click.testing import CliRunner
import numpy as np
from PIL import Image
import pytest

from facegear_tehl.browser_check import browser, render
from facegear_tehl.cli import tehl
from facegear_tehl.report_page import overview_rows
from facegear_tehl.results import read_result

FACE_GEAR = "cases/facegear_110.yaml"


class _Page(HTMLParser):
    """The page's sections (h2 titles), image sources and every other resource reference."""

    def __init__(self) -> None:
        super().__init__()
        self.sections: list[str] = []
        self.images: list[str] = []
        self.links: list[str] = []
        self._in_h2 = False

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self._in_h2 = tag == "h2"
        if tag == "img":
            self.images.append(attrs.get("src", ""))
        self.links += [attrs[k] for k in ("href", "src") if k in attrs and tag != "img"]
        if tag == "script":
            self.links.append("script")

    def handle_data(self, data):
        if self._in_h2:
            self.sections.append(data)
            self._in_h2 = False


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """`tehl run` of the shipped face gear at S1, S3 (grid 33), then `tehl report`: the file and the page."""
    folder = tmp_path_factory.mktemp("report")
    runner = CliRunner()
    run = runner.invoke(tehl, ["run", FACE_GEAR, "--grid", "33", "--points", "S1,S3", "--jobs", "1", "-o",
                               str(folder / "gear.h5")])
    assert run.exit_code == 0, run.output
    made = runner.invoke(tehl, ["report", str(folder / "gear.h5")])
    assert made.exit_code == 0, made.output
    page = folder / "gear.html"
    assert made.output == f"report: {page}\n"
    return read_result(folder / "gear.h5"), page


def test_the_page_is_self_contained_with_every_section(report):
    _, page = report
    parsed = _Page()
    parsed.feed(page.read_text(encoding="utf-8"))
    assert parsed.sections == ["Provenance", "Inputs", "Verdict", "Results per meshing point", "Figures",
                               "Solve summary"]
    assert parsed.links == [], "no script, stylesheet or link to load"
    assert len(parsed.images) >= 4
    for source in parsed.images:
        assert source.startswith("data:image/png;base64,")
        with Image.open(io.BytesIO(base64.b64decode(source.split(",", 1)[1]))) as image:
            assert image.format == "PNG" and min(image.size) > 200


def test_each_number_carries_the_error_bound_of_the_file_or_unresolved(report):
    """h_min in µm and μ, each ± its relative bound times the value as the file holds them (computed here from the SI
    values), or "(unresolved)" where the file flags it (33 nodes leave every figure unresolved), never a number."""
    result, page = report
    text = page.read_text(encoding="utf-8")
    for point in result.points.values():
        h_min = 1e6 * point.scalars["h_min"]
        for value, name in ((h_min, "h_min"), (point.scalars["mu"], "mu")):
            if point.scalars[f"unresolved_{name}"] == 1.0:
                assert f"{value:.4g} (unresolved)" in text and f"{value:.4g} ±" not in text
            else:
                assert f"{value:.4g} ± {point.scalars[f'error_bound_{name}'] * value:.2g}" in text
        grid = f"{len(point.axes['x'].values)}x{len(point.axes['y'].values)}"
        assert re.search(rf"<td>{point.name}</td><td>yes</td><td>{grid}</td>", text)


def test_inputs_in_engineering_units_and_the_solve_record(report):
    """The module 0.00635 m of the case reads 6.35 mm, the torque in N m; each stage of the record is listed."""
    result, page = report
    text = page.read_text(encoding="utf-8")
    assert "<td>gear.module</td><td>6.35</td><td>mm</td>" in text
    assert "<td>gear.pinion_torque</td><td>500.0</td><td>N m</td>" in text
    for point in result.points.values():
        for stage in point.record.stages:
            assert f"<td>{stage.stage.value}</td><td>{stage.nx}x{stage.ny}</td>" in text
    assert result.tehl_version in text and result.created in text


def test_a_long_cycle_shows_six_points_on_the_overview_the_ends_among_them():
    names = [f"P{i:02d}" for i in range(1, 42)]
    assert overview_rows(names) == ["P01", "P09", "P17", "P25", "P33", "P41"]
    assert overview_rows(names[:5]) == names[:5]


def test_a_missing_file_exits_2(tmp_path):
    made = CliRunner().invoke(tehl, ["report", str(tmp_path / "none.h5")])
    assert made.exit_code == 2 and made.output.startswith("error: ") and not list(tmp_path.iterdir())


@pytest.mark.slow
@pytest.mark.skipif(browser() is None, reason="no Chromium (apt-get install chromium)")
def test_the_page_renders_in_headless_chromium(report, tmp_path):
    """No console or loading error, every image decoded, a tall page, a screenshot that is not blank."""
    _, page = report
    seen = render(page, tmp_path / "shot.png")
    assert seen.errors == ()
    assert seen.images >= 4 and seen.decoded == seen.images
    assert seen.height > 2000
    with Image.open(seen.screenshot) as image:
        assert float(np.asarray(image.convert("L"), dtype=float).std()) > 5.0
