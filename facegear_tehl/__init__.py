"""facegear_tehl: thermal EHL of non-orthogonal face gear pairs.

Data flows one way: case -> contact analysis -> ContactPoint -> EHL solver -> results -> plots.

For notebooks: `from facegear_tehl import load_case, run_case, read_result`.
"""

import importlib

from facegear_tehl import kernel_cache

__version__ = "0.1.0"
kernel_cache.prepare()  # before any kernel module imports Numba: a writable cache, or a temporary one

# Re-exported on first use, so that importing the package (as every `tehl` command does) stays light.
_EXPORTS = {"load_case": "facegear_tehl.case", "run_case": "facegear_tehl.run", "read_result": "facegear_tehl.results"}
__all__ = ["__version__", *_EXPORTS]


def __getattr__(name: str):
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'facegear_tehl' has no attribute {name!r}")
