"""Study maps that cannot be misread: contours only over enough variants solved on one grid, resolved; otherwise a
marker per variant, its shape the grid, open where under-resolved; keys labelled with their units."""

from __future__ import annotations

import itertools
from pathlib import Path

from matplotlib.collections import PathCollection, QuadMesh
from matplotlib.contour import ContourSet
import numpy as np
import pytest

from facegear_tehl.key_units import key_label, key_unit
from facegear_tehl.plots.study_maps import plot_study
from facegear_tehl.study_file import load_study

from test_plots import _capture

HEADER = ("variant,gear.pinion_torque,gear.pinion_speed,point,status,converged,h_min [m],"
          "error_estimate_h_min [1],grid,file,message\n")


def _write(folder: Path, rows: list[tuple]) -> Path:
    text = HEADER + "".join(f"{i + 1},{t},{n},S1,ok,yes,{h},{e},{g},v{i}.h5,\n" for i, (t, n, h, e, g) in
                            enumerate(rows))
    (folder / "index.csv").write_text(text)
    return folder




def test_the_keys_carry_the_units_of_the_case_templates():
    """The units `tehl init` writes beside each key (N m, rpm, deg); none for a dimensionless count."""
    assert key_unit("gear.pinion_torque") == "N m" and key_unit("gear.pinion_speed") == "rpm"
    assert key_unit("gear.shaft_angle") == "deg" and key_unit("gear.pinion_teeth") is None
    assert key_label("gear.pinion_torque") == "pinion torque (N m)"


def test_few_variants_on_mixed_grids_are_markers_with_the_unresolved_one_open(tmp_path, monkeypatch):
    """The issue's study: 3 x 2 variants, one solved on a refined grid and under-resolved (the 0.179 µm 'dip'). No
    contour and no filled map; one marker shape per grid; the under-resolved variant drawn open; the axes say N m
    and rpm."""
    rows = [(100, 1500, 2.97e-7, 0.002, "513x65"), (200, 1500, 1.79e-7, 0.12, "1025x65"),
            (300, 1500, 2.40e-7, 0.003, "513x65"), (100, 3000, 3.5e-7, 0.002, "513x65"),
            (200, 3000, 3.2e-7, 0.002, "513x65"), (300, 3000, 3.0e-7, 0.002, "513x65")]
    figures = _capture(monkeypatch)
    plot_study(_write(tmp_path, rows), tmp_path / "maps", points=["S1"], dpi=60)
    ax = figures["map_h_min_S1"].axes[0]
    assert not [c for c in ax.collections if isinstance(c, (ContourSet, QuadMesh))]
    markers = [c for c in ax.collections if isinstance(c, PathCollection)]
    filled = [c for c in markers if len(c.get_facecolors())]
    open_ = [c for c in markers if not len(c.get_facecolors())]
    assert [tuple(map(tuple, c.get_offsets())) for c in open_] == [((200.0, 1500.0),)]
    assert len(filled) == 1 and len(filled[0].get_offsets()) == 5  # the five on 513x65
    shapes = [c.get_paths()[0].vertices for c in (filled[0], open_[0])]
    assert shapes[0].shape != shapes[1].shape or not np.allclose(*shapes), "the refined grid's marker differs"
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("513x65" in t for t in legend) and any("under-resolved" in t for t in legend)
    assert ax.get_xlabel() == "pinion torque (N m)" and ax.get_ylabel() == "pinion speed (rpm)"


def test_a_full_resolved_map_on_one_grid_has_contours(tmp_path, monkeypatch):
    """4 x 4 variants on one grid, all resolved: the filled map with contour lines, the values those of the index."""
    torques, speeds = (100, 200, 300, 400), (1000, 2000, 3000, 4000)
    rows = [(t, n, 1e-7 * (1 + n / 1000) / (1 + t / 1000), 0.002, "513x65")
            for n, t in itertools.product(speeds, torques)]
    figures = _capture(monkeypatch)
    plot_study(_write(tmp_path, rows), tmp_path / "maps", points=["S1"], dpi=60)
    ax = figures["map_h_min_S1"].axes[0]
    assert [c for c in ax.collections if isinstance(c, ContourSet)]
    mesh = next(c for c in ax.collections if isinstance(c, QuadMesh))
    expected = 1e6 * np.array([[h for t, n, h, _, _ in rows if n == speed] for speed in speeds])
    assert np.asarray(mesh.get_array()).reshape(4, 4) == pytest.approx(expected)


def test_variant_files_are_named_by_their_values_and_never_share_a_name(tmp_path):
    """'pinion_torque=250_pinion_speed=1500.h5'; a value with characters a file name cannot hold keeps the digest."""
    base = tmp_path / "case.yaml"
    base.write_text(Path("cases/facegear_110.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    study = tmp_path / "study.yaml"
    study.write_text("base: case.yaml\nvary:\n  gear.pinion_torque: [250, 500]\n  gear.pinion_speed: [1500, 3000]\n"
                     "  gear.points: [[S1, S3], [S2]]\n", encoding="utf-8")
    names = [variant.file_name for variant in load_study(study).variants]
    assert names[0].startswith("pinion_torque=250_pinion_speed=1500_points=_S1__S3__") and names[0].endswith(".h5")
    assert len(set(names)) == len(names) == 8
    simple = tmp_path / "simple.yaml"
    simple.write_text("base: case.yaml\nvary:\n  gear.pinion_torque: [250, 500]\n", encoding="utf-8")
    assert [v.file_name for v in load_study(simple).variants] == ["pinion_torque=250.h5", "pinion_torque=500.h5"]
