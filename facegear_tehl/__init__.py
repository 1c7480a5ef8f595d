"""facegear_tehl: thermal EHL of non-orthogonal face gear pairs.

Data flows one way: case -> contact analysis -> ContactPoint -> EHL solver -> results -> plots.
"""

__version__ = "0.1.0"
