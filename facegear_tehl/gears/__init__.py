"""Face gear pair contact analysis (FACEGEAR.md): geometry, tooth contact analysis, curvatures,
kinematics and loads; `analysis.analyse_gear_pair` is the entry point. Pure geometry and kinematics:
nothing here knows about lubrication."""
