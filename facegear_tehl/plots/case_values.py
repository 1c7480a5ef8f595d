"""What the figures take from the case the result was run with (the case text stored in the file): the
inlet temperature that temperature rises are measured from, and the solver tolerances the convergence
histories are judged by."""

from __future__ import annotations

from dataclasses import dataclass

from facegear_tehl.case import parse_case
from facegear_tehl.results import Result
from facegear_tehl.schema import CaseError
from facegear_tehl.settings import SolverSettings


@dataclass(frozen=True)
class CaseValues:
    """inlet_temperature: T_inlet (K); solver: the numerical settings, tolerances included."""

    inlet_temperature: float
    solver: SolverSettings


def case_values(result: Result) -> CaseValues | None:
    """The case values of `result`; None when its stored case text does not parse (a file written by an
    older tehl whose case keys have since changed)."""
    try:
        case = parse_case(result.case_yaml, result.case_name)
    except CaseError:
        return None
    return CaseValues(inlet_temperature=case.lubricant.inlet_temperature, solver=case.solver)
