"""Text from a file is drawn as written (plots.common.plain): a case named with mathtext specials (`$`, `^`, `{`)
passes validate and run, and `tehl plot` draws its figures instead of failing on a mathtext parse error."""

from __future__ import annotations

from click.testing import CliRunner
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.plots.common import plain

import synthetic

NAME = "q$x^{$q"


@pytest.fixture
def fake_solver(monkeypatch):
    monkeypatch.setattr("facegear_tehl.run.ehl_solver",
                        lambda: (lambda point, lubricant, settings: synthetic.solution(point)))


def _draw(text: str) -> None:
    figure = Figure()
    figure.text(0.5, 0.5, text)
    FigureCanvasAgg(figure).draw()


def test_plain_text_renders_as_written():
    with pytest.raises(ValueError):
        _draw(NAME)  # as mathtext: a parse error
    _draw(plain(NAME))
    assert plain(NAME) == r"q\$x^{\$q"


def test_a_case_named_with_dollars_is_plotted(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    case = tmp_path / "c.yaml"
    case.write_text(synthetic.BALL_ON_DISC.read_text().replace("name: ball_on_disc", f'name: "{NAME}"'),
                    encoding="utf-8")
    assert CliRunner().invoke(tehl, ["run", str(case), "-o", "r.h5"]).exit_code == 0
    result = CliRunner().invoke(tehl, ["plot", "r.h5", "--what", "centreline,convergence", "-o", "figures"])
    assert result.exit_code == 0, result.output
    assert sorted(p.suffix for p in (tmp_path / "figures").iterdir()) == [".png", ".png"]
