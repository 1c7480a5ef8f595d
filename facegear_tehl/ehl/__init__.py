"""The EHL numerical core: one elliptical contact, dimensionless inside (see `scaling.py`)."""
