"""Hairer and Wanner's RODAS: a stiffly accurate Rosenbrock method of order 4 (3) with
a continuous extension of order 3 (Solving ODEs II, VI.4; the coefficients of their
code ``rodas.f``, ``RODCOE`` with ``METH = 1``), for numba.

A Rosenbrock step solves one linear system per stage with the matrix
I / (gamma h) - J (J = df/dy at the step's start), so it is stable on stiff flows
(L-stable) without a Newton iteration; f_t (= df/dt there) enters with the ``d``
coefficients. The form is the code's: with k_i the stages,

    (I / (gamma h) - J) k_i = f(t + c_i h, y + sum_j a_ij k_j) + sum_j (c_ij / h) k_j + h d_i f_t,

y_new = y + sum_i b_i k_i (the last stage's point plus k_5 + k_6: stiffly accurate),
the error estimate is k_6, and the dense output on x = (t - t_step) / h in [0, 1] is
(1 - x) y + x (y_new + (1 - x) (q_1 + x q_2)) with q_r = sum_i h_ri k_i.

As :mod:`._dop853`: plain functions that numba compiles where a compiled engine calls
them (``register_jitable``); :func:`for_flow` closes the step over the right-hand side
``fun(t, y, args, out)``, its derivatives ``jac(t, y, args, J, f_t)`` and the solution
of the stage systems (``decompose``, ``solve``: the flow knows J's structure).
"""

import math

import numpy as np
from numba.extending import register_jitable

GAMMA = 0.25
#: stage rows a_ij (y's increments of the stage points), lower triangular (6, 6)
A = np.zeros((6, 6))
A[1, :1] = (1.544,)
A[2, :2] = (0.9466785280815826, 0.2557011698983284)
A[3, :3] = (3.314825187068521, 2.896124015972201, 0.9986419139977817)
A[4, :4] = (1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895)
A[5, :5] = (*A[4, :4], 1.0)
#: c_ij (the stages' coupling, divided by h), lower triangular (6, 6)
CC = np.zeros((6, 6))
CC[1, :1] = (-5.6688,)
CC[2, :2] = (-2.430093356833875, -0.2063599157091915)
CC[3, :3] = (-0.1073529058151375, -9.594562251023355, -20.47028614809616)
CC[4, :4] = (7.496443313967647, -10.24680431464352, -33.99990352819905, 11.7089089320616)
CC[5, :5] = (8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136, -6.058818238834054)
#: the stages' times [-] and their factors on h f_t
C = np.array([0.0, 0.386, 0.21, 0.63, 1.0, 1.0])
DT = np.array([0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0])
B = np.array([*A[4, :4], 1.0, 1.0])
#: the continuous extension's q_1, q_2 (2, 5) on k_1..k_5
H = np.array([[10.12623508344586, -7.487995877610167, -34.80091861555747, -7.992771707568823, 1.025137723295662],
              [-0.6762803392801253, 6.087714651680015, 16.43084320892478, 24.76722511418386, -6.594389125716872]])
N_STAGES = 6
#: the error estimate is of order 3: the step grows as error ** (-1 / 4)
ERROR_EXPONENT = -1.0 / 4.0
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 6.0


@register_jitable
def error_norm(K, scale):
    """The RMS of the error estimate k_6 (row 6 of ``K``), each component over its
    ``scale`` (n,) (< 1: accept)."""
    n = scale.shape[0]
    total = 0.0
    for i in range(n):
        total += (K[N_STAGES, i] / scale[i]) ** 2
    return math.sqrt(total / n)


@register_jitable
def factor(norm, accepted):
    """The next step over this one [-] from the error norm."""
    if norm == 0.0:
        return MAX_FACTOR
    value = SAFETY * norm ** ERROR_EXPONENT
    return min(MAX_FACTOR, max(MIN_FACTOR, value)) if accepted else max(MIN_FACTOR, min(1.0, value))


@register_jitable
def dense_value(F, y, x, i):
    """Component ``i`` of the continuous extension at x in [0, 1]: F rows (y_new - y,
    q_1, q_2)."""
    return y[i] + x * (F[0, i] + (1.0 - x) * (F[1, i] + x * F[2, i]))


def for_flow(fun, jac, decompose, solve):
    """``(jacobian, step, dense_coefficients)`` for the compiled right-hand side ``fun(t,
    y, args, out)``. ``jacobian(args, t, y, K, J)`` fills J = df/dy (n, n) and K[7] =
    df/dt at (t, y) (``jac``). ``step(args, t, y, h, K, y_new, work, J, M)``: one step
    of size ``h`` [s] from (t, y) with K[0] = f(t, y) and (J, K[7]) there: the stages
    k_1..k_6 in K rows 1-6 (row 6: the error estimate), y_new; K[8] is scratch and
    ``M`` holds what ``decompose(J, 1 / (gamma h), M)`` makes of I / (gamma h) - J for
    ``solve(J, 1 / (gamma h), M, x)`` (x <- its inverse times x).
    ``dense_coefficients(y, y_new, K, F)`` fills the rows of :func:`dense_value`."""

    @register_jitable
    def jacobian(args, t, y, K, J):
        jac(t, y, args, J, K[7])

    @register_jitable
    def step(args, t, y, h, K, y_new, work, J, M):
        n = y.shape[0]
        alpha = 1.0 / (GAMMA * h)
        decompose(J, alpha, M)
        for s in range(N_STAGES):
            if s == 0:
                f = K[0]
            else:
                for i in range(n):
                    acc = 0.0
                    for j in range(s):
                        acc += A[s, j] * K[1 + j, i]
                    work[i] = y[i] + acc
                fun(t + C[s] * h, work, args, K[8])
                f = K[8]
            row = K[1 + s]
            for i in range(n):
                acc = 0.0
                for j in range(s):
                    acc += CC[s, j] * K[1 + j, i]
                row[i] = f[i] + acc / h + h * DT[s] * K[7, i]
            solve(J, alpha, M, row)
        for i in range(n):
            acc = 0.0
            for j in range(N_STAGES):
                acc += B[j] * K[1 + j, i]
            y_new[i] = y[i] + acc

    @register_jitable
    def dense_coefficients(y, y_new, K, F):
        n = y.shape[0]
        for i in range(n):
            F[0, i] = y_new[i] - y[i]
            for r in range(2):
                acc = 0.0
                for j in range(5):
                    acc += H[r, j] * K[1 + j, i]
                F[1 + r, i] = acc

    return jacobian, step, dense_coefficients
