"""The choices the ``fpu`` parser offers, as plain data: building the parser (and printing
``fpu ... --help``) imports neither NumPy nor Numba.  Each tuple equals the core's own
(tests/cli/test_cli_startup.py checks them against floquet.METHODS, simulate.METHODS ...)."""

FLOQUET_METHODS = ("dense", "structured")  # fpucore.floquet.METHODS
DEFAULT_FLOQUET_METHOD = "structured"  # fpucore.floquet.DEFAULT_METHOD
METHOD_HELP = (
    "each spectrum's eigenvalue route (default structured: quarter size for "
    "reversible waves, else half size, 0.2-0.8x the dense call; dense: the LAPACK "
    "reference)"
)
SIMULATE_METHODS = ("rkn12", "dop853", "dopri5", "rkn8", "symplectic")  # fpucore.simulate.METHODS
BOUNDARIES = ("fixed_particles", "fixed_strain", "free")  # fpucore.simulate.BOUNDARIES
GUARDS = ("convex", "bounded")  # fpucore.simulate.GUARDS
# fpucore.warm.LAZY: the kernel groups `fpu warm --essential` leaves to the server
LAZY_WARM = (
    "floquet-structured",
    "wave-pwl",
    "simulate",
    "simulate-dopri5",
    "simulate-symplectic",
)
