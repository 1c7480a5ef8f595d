"""Constants of the lubricant's pressure-temperature laws (SI units) and the integer codes that select a law
inside the Numba kernels (lubricant_laws.py): shared by the Lubricant dataclass (lubricant.py) and the kernels."""

# Roelands (1966): reference pressure and the asymptotic viscosity ln(eta_inf / Pa s) = -9.67.
ROELANDS_PRESSURE = 1.96e8  # Pa
ROELANDS_LN_ETA_INF = -9.67  # ln(Pa s)
# Roelands (1966) temperature law: viscosity tends to infinity at 138 K.
ROELANDS_T_INF = 138.0  # K
# Dowson & Higginson (1966) density constants as written by Venner & Lubrecht (2000).
DH_P1 = 5.9e8  # Pa
DH_RATIO = 1.34  # rho(p -> inf)/rho_0
# Integer codes used inside Numba kernels.
ROELANDS, BARUS = 0, 1
DOWSON_HIGGINSON, INCOMPRESSIBLE = 0, 1
