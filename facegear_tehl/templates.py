"""Commented case templates that `tehl init` writes: a plain elliptical contact and a face gear pair.

Each template is a valid case as written; its optional keys appear commented out with their defaults, taken
from the dataclasses that define them (the one source of every default).
"""

from __future__ import annotations

from facegear_tehl.gears.spec import GearSpec
from facegear_tehl.lubricant import DENSITY_MODELS, KELVIN, RHEOLOGY_MODELS, VISCOSITY_MODELS, Lubricant
from facegear_tehl.materials import Solid
from facegear_tehl.schema import defaults
from facegear_tehl.scuffing import LUBRICATION_METHODS
from facegear_tehl.settings import THERMAL_MODELS, SolverSettings

_SOLID, _LUBRICANT, _SOLVER, _GEAR = defaults(Solid), defaults(Lubricant), defaults(SolverSettings), defaults(GearSpec)

_CONTACT = """\
# A plain elliptical contact: a steel ball on a steel disc (the circular reference case of Venner & Lubrecht
# 2000, Moes M = 20, L = 10). Check it with `tehl validate {file}`, solve it with `tehl run {file}`.
# Units: SI (m, N, Pa, m/s), angles in degrees, temperatures in degC.
name: ball_on_disc
description: Steel ball (R = 12.7 mm) on a steel disc, 6.27 N, 0.64 m/s, pure rolling
contact:
  radius_x: 0.0127            # m, reduced radius of curvature along x, the entrainment (minor axis)
  radius_y: 0.0127            # m, reduced radius along y (radius_y >= radius_x)
  load: 6.272                 # N, normal load
  entrainment_speed: 0.6383   # m/s, |u1 + u2|/2
  slide_roll_ratio: 0.0       # (u1 - u2)/u_e; 0: pure rolling
  entrainment_angle: 0.0      # deg, entrainment to the x axis
"""

_GEAR_BLOCK = """\
# A non-orthogonal face gear pair (shaft angle 110 deg) driven by a spur involute pinion: Litvin's face-gear
# example (25/28/160 teeth, diametral pitch 4 1/in, 25 deg). Check it with `tehl validate {file}` and
# `tehl contact {file}` (the contact analysis), solve it with `tehl run {file}`.
# Units: SI (m, N m), angles in degrees, speed in rpm, temperatures in degC.
name: facegear
description: Face gear 25/28/160, m = 6.35 mm, 25 deg, shaft angle 110 deg, 3000 rpm, 500 N m
gear:
  pinion_teeth: 25            # N1
  shaper_teeth: 28            # Ns = N1 + 1..3: localised (point) contact
  face_gear_teeth: 160        # N2
  module: 0.00635             # m
  pressure_angle: 25.0        # deg
  shaft_angle: 110.0          # deg, 0 < shaft_angle < 180 (90: orthogonal)
  pinion_addendum: 0.00635    # m (default: the module)
  face_gear_addendum: 0.00635 # m (default: the module)
  inner_radius: 0.468         # m, face width from inner to outer radius of the face gear, inside the
  outer_radius: 0.548         # m  undercut and pointing limits (tehl validate names them if not)
  pinion_speed: 3000.0        # rpm
  pinion_torque: 500.0        # N m
  # load_sharing: {load_sharing}      # iso_linear | equal | one coefficient per point
  # transition_side: {transition_side}   # single | double: the share exactly at S2 and S4
  # points: [{points}]  # any of these, or a count of evenly spaced points
"""

_MATERIALS = """\
materials:                    # body_1: {body_1}, body_2: {body_2}; {steel}
  body_1:
    elastic_modulus: {modulus:<11} # Pa
    poisson_ratio: 0.3
    # density: {density}         # kg/m^3
    # thermal_conductivity: {thermal_conductivity}  # W/(m K)
    # specific_heat: {specific_heat}     # J/(kg K)
    {roughness_line}
  body_2: {{elastic_modulus: {modulus}, poisson_ratio: 0.3{body_2_roughness}}}
"""

# The flanks' roughness: the film parameter lambda = h_min/sigma, the regime and the friction correlations read it.
_GEAR_ROUGHNESS = "roughness: 3.0e-7            # m, RMS R_q: a ground flank (R_a 0.24 um); lambda = h_min/sigma"
_CONTACT_ROUGHNESS = "# roughness: {roughness}          # m, RMS R_q: the film parameter lambda = h_min/sigma"

_CONTACT_LUBRICANT = """\
lubricant:                    # the mineral oil of Venner & Lubrecht (2000)
  viscosity: 0.04             # Pa s at the inlet temperature and p = 0
  inlet_temperature: 40.0     # degC (not kelvin)
  pressure_viscosity: 2.2e-8  # 1/Pa, Barus alpha
  viscosity_model: roelands   # {viscosity_models}
  density_model: dowson_higginson  # {density_models}
  rheology: newtonian         # {rheology_models} (then eyring_stress, Pa, is required)
"""

_GEAR_LUBRICANT = """\
lubricant:                    # an ISO VG 100 mineral gear oil, given as its datasheet gives it: tehl validate prints
  grade: VG100                # the SI values derived from it (docs/verdict.md); or nu40: in mm^2/s at 40 degC
  nu100: 11.1                 # mm^2/s at 100 degC (datasheet; VG 100 mineral oils of viscosity index ~97)
  density_15: 880.0           # kg/m^3 at 15 degC (datasheet)
  oil_type: mineral           # mineral | pao | ester | pag (ester: give pressure_viscosity, 1/Pa)
  inlet_temperature: 80.0     # degC (not kelvin)
  fzg_scuffing_stage: 12      # FZG A/8.3/90 failure load stage (datasheet): scuffing by ISO/TS 6336-20/-21
  micropitting_stage: 9       # FZG GF-C/8.3/90 failure load stage (datasheet): micropitting by ISO/TS 6336-22
  lubrication: dip            # {lubrication_methods}: the standards' bulk temperature
  viscosity_model: roelands   # {viscosity_models}
  density_model: dowson_higginson  # {density_models}
  rheology: ree_eyring        # {rheology_models}
  eyring_stress: 1.0e7        # Pa, tau_0 (Johnson & Tevaarwerk 1977: a few MPa to about 10 MPa)
"""

_OPTIONAL_LUBRICANT = """\
  # density: {density}            # kg/m^3 at the inlet temperature
  # temperature_viscosity: {temperature_viscosity}  # 1/K, -d ln(eta)/dT (the thermal models need it)
  # thermal_expansion: {thermal_expansion}      # 1/K
  # thermal_conductivity: {thermal_conductivity}  # W/(m K)
  # specific_heat: {specific_heat}       # J/(kg K)
"""

_SOLVER_BLOCK = """\
solver:
  grid: {grid}                   # nodes per side, 2^n + 1 (65 for a quick look, 257 or 513 for results)
  {grid_y_line}
  thermal: {thermal}            # {thermal_models}
  # domain: {{x: [-4.5, 1.5], y: [-3.0, 3.0]}}  # in semi-axes b (x) and a (y); default: automatic
  # tolerance: {tolerance}          # relative pressure change per cycle to stop
  # load_tolerance: {load_tolerance}     # relative load-balance error to accept
  # max_cycles: {max_cycles}            # V-cycles on the finest grid
  # thermal_layers: {thermal_layers}         # layer nodes across the film (odd), thermal full
output:
  file: {result}             # result file, relative to this case file
"""

TEMPLATES = ("contact", "gear")


def case_template(kind: str, file_name: str) -> str:
    """The commented template of a `kind` case ('contact' or 'gear') for the file `file_name`."""
    models = {"viscosity_models": " | ".join(VISCOSITY_MODELS), "density_models": " | ".join(DENSITY_MODELS),
              "rheology_models": " | ".join(RHEOLOGY_MODELS)}
    stem = file_name.rsplit("/", 1)[-1].rsplit(".", 1)[0] or "case"
    solver = {**_SOLVER, "thermal_models": " | ".join(THERMAL_MODELS), "result": f"{stem}.h5"}
    if kind == "gear":
        head = _GEAR_BLOCK.format(file=file_name, points=", ".join(_GEAR["points"]),
                                  load_sharing=_GEAR["load_sharing"], transition_side=_GEAR["transition_side"])
        materials = _MATERIALS.format(body_1="pinion", body_2="face gear", modulus="2.06e11",
                                      steel="case-carburised gear steel, nominal values", **_SOLID,
                                      roughness_line=_GEAR_ROUGHNESS, body_2_roughness=", roughness: 3.0e-7")
        lubricant = _GEAR_LUBRICANT.format(**models, lubrication_methods=" | ".join(LUBRICATION_METHODS))
        # a long contact ellipse: 4 times fewer nodes along its major axis; the full thermal model
        solver.update(grid_y_line="grid_y: 65                  # nodes along the major axis y (default: as grid)",
                      thermal="full")
    else:
        head = _CONTACT.format(file=file_name)
        materials = _MATERIALS.format(body_1="ball", body_2="disc", modulus="2.0e11",
                                      steel="bearing steel as Venner & Lubrecht (2000): E' = 2.198e11 Pa", **_SOLID,
                                      roughness_line=_CONTACT_ROUGHNESS.format(**_SOLID), body_2_roughness="")
        lubricant = _CONTACT_LUBRICANT.format(**models) + _OPTIONAL_LUBRICANT.format(
            **{**_LUBRICANT, "inlet_temperature": _LUBRICANT["inlet_temperature"] - KELVIN})
        solver.update(grid_y_line="# grid_y: null              # nodes along the major axis y (default: as grid)")
    return head + materials + lubricant + _SOLVER_BLOCK.format(**solver)
