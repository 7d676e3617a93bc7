"""State layout, end conditions and status codes shared by the chain kernels
(:mod:`fpucore.simulate.kernels`, :mod:`fpucore.simulate.rkn`, :mod:`fpucore.simulate.observer`).

First-order state ``y`` (length 2L+2) for a chain of L springs (sites n = 1…L of eq. Riemann_data
are indices 0…L−1) joining particles 0…L (paper eq. FPUsystem, strain–velocity form):

    y[0:L]       strains   w_n                 ẇ_n = v_n − v_{n−1}
    y[L:2L+1]    velocities v_j, j = 0…L        v̇_j = f(w_{j+1}) − f(w_j)
    y[2L+1]      displacement u_0 of particle 0 (only enters the dead-load energy)

The ghost forces f(w_0) = ``fL`` and f(w_{L+1}) = ``fR`` close the chain:
  * ``BC_LOAD`` with fL = fR = 0: stress-free ends (literal free ends);
  * ``BC_LOAD`` with fL = f(w_left), fR = f(w_right): fixed boundary strains (eq. fixedBCs) — a
    constant (dead) load on the end particles;
  * ``BC_FIXED_PARTICLES``: end particles held at rest, v_0 = v_L = 0 (in strain form: zero strain
    gradient, w_0 = w_1, w_{L+1} = w_L).

The RKN stepper uses the second-order form instead (see :mod:`fpucore.simulate.rkn`).
"""

BC_LOAD = 0
BC_FIXED_PARTICLES = 1

ST_OK = 0
ST_BUDGET = 2
ST_LEFT_CONVEX = 3
ST_STEP_UNDERFLOW = 4
ST_NONFINITE = 5
