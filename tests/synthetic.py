"""Test helpers: synthetic solver output (analytic fields with known values, no solving) and a writer
process to interrupt mid-write.

Pressure is the dry Hertz pressure of the case's contact, film thickness a paraboloid gap over a
constant central film; both are exact functions of (x, y), so a round trip can be checked value by value.
"""

from __future__ import annotations

from pathlib import Path
import signal
import subprocess
import sys
import textwrap

import numpy as np

from facegear_tehl.case import Case, load_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.points import contact_analysis
from facegear_tehl.results import RunResult
from facegear_tehl.solution import Field, Outcome, PointSolution

CASES = Path(__file__).resolve().parents[1] / "cases"
BALL_ON_DISC = CASES / "ball_on_disc.yaml"
H_C = 1.5e-7  # m, central film of the synthetic solution
CYCLES = 7


def ball_on_disc() -> Case:
    return load_case(BALL_ON_DISC)


def run_result(case: Case | None = None, **options) -> RunResult:
    """A RunResult of the ball-on-disc case holding one synthetic solution (options go to `solution`)."""
    case = case or ball_on_disc()
    return RunResult(case=case, points=(solution(contact_analysis(case).points[0], **options),))


def hertz_pressure(x: np.ndarray, y: np.ndarray, a: float, b: float, p_hertz: float) -> np.ndarray:
    """p = p_h sqrt(1 - (x/b)^2 - (y/a)^2) inside the ellipse, 0 outside; shape (ny, nx)."""
    xx, yy = np.meshgrid(x, y)
    return p_hertz * np.sqrt(np.clip(1.0 - (xx / b) ** 2 - (yy / a) ** 2, 0.0, None))


def film(x: np.ndarray, y: np.ndarray, radius_x: float, radius_y: float) -> np.ndarray:
    """h = h_c + x^2/(2 R_x) + y^2/(2 R_y); shape (ny, nx)."""
    xx, yy = np.meshgrid(x, y)
    return H_C + xx**2 / (2.0 * radius_x) + yy**2 / (2.0 * radius_y)


def solution(point: ContactPoint, *, nx: int = 33, ny: int = 17, converged: bool = True) -> PointSolution:
    """An analytic PointSolution for `point` on an (ny, nx) grid over the default domain."""
    hertz = point.hertz
    x = np.linspace(-4.5, 1.5, nx) * hertz.b
    y = np.linspace(-3.0, 3.0, ny) * hertz.a
    residuals = 10.0 ** -np.arange(1.0, CYCLES + 1.0)
    return PointSolution(
        name=point.name,
        outcome=Outcome.CONVERGED if converged else Outcome.NOT_CONVERGED,
        message="" if converged else "residual 1e-3 above tolerance 1e-5 after 40 cycles",
        scalars={
            "h_c": (H_C, "m"),
            "h_min": (0.6 * H_C, "m"),
            "p_max": (1.02 * hertz.p_max, "Pa"),
            "p_hertz": (hertz.p_max, "Pa"),
            "a": (hertz.a, "m"),
            "b": (hertz.b, "m"),
            "load_error": (2.5e-6, "1"),
            "iterations": (CYCLES, "1"),
            "work_units": (41.5, "1"),
            "wall_time": (0.25, "s"),
            "error_estimate_h_c": (0.004, "1"),
        },
        fields={
            "pressure": Field(hertz_pressure(x, y, hertz.a, hertz.b, hertz.p_max), "Pa", "pressure"),
            "film_thickness": Field(film(x, y, point.radius_x, point.radius_y), "m", "film thickness"),
        },
        axes={"x": Field(x, "m", "node coordinate along the minor axis"), "y": Field(y, "m", "along the major axis")},
        history={"residual_history": Field(residuals, "1", "relative pressure change per cycle")},
        models={"viscosity": "roelands (Roelands 1966)", "thermal": "off"},
    )


_STALLING_WRITER = textwrap.dedent(
    """
    import signal, sys, time
    sys.path.insert(0, {tests!r})
    import synthetic
    from facegear_tehl import results
    signal.signal(signal.SIGINT, signal.default_int_handler)
    write_point = results._write_point
    def write_and_stall(points, solution, *rest):
        write_point(points, solution, *rest)
        print("writing", flush=True)
        time.sleep(60)
    results._write_point = write_and_stall
    """
)


def sigint_as_in_a_terminal() -> None:
    """`preexec_fn` of a child that is sent Ctrl-C: SIGINT back to its default action. A process started in the
    background of a shell without job control (as some CI runners start the test command) inherits SIGINT
    ignored, and Python then leaves it ignored: the child would never see the interrupt the test sends."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def interrupt_while_writing(code: str, args: list[str], folder: Path, signum: int) -> tuple[int, str]:
    """Run `code` (which writes a result into `folder`) in a Python process whose writer stalls after the
    first point; send `signum` while the temporary file exists. Returns (exit code, stderr)."""
    script = _STALLING_WRITER.format(tests=str(Path(__file__).parent)) + textwrap.dedent(code)
    command = [sys.executable, "-c", script, *args]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as process:
        assert process.stdout.readline().strip() == "writing"
        assert len(list(folder.iterdir())) == 2  # the target and the temporary file next to it
        process.send_signal(signum)
        code = process.wait(timeout=30)
        return code, process.stderr.read()
