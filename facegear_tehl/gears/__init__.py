"""Face gear pair contact analysis (docs/method.md §1; Litvin & Fuentes 2004, Gear Geometry and Applied Theory):
geometry, tooth contact analysis, curvatures, kinematics and loads; `analysis.analyse_gear_pair` is the entry
point. Pure geometry and kinematics: nothing here knows about lubrication."""
