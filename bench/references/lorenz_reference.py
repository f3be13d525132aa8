"""The Lorenz attractor's state at t = 20 from (1, 0, 0) (sigma = 10,
r = 28, b = 8/3), the problem of ../../shared/peers/peer.py, for the
benchmark (no published value exists for this start).

A Taylor series method in mpmath's arbitrary precision: fixed steps, the
coefficients by the recurrences of the three quadratic right-hand sides,
each step's series summed to order ORDER. Two runs with different
precision, order and step must agree: the chaotic flow amplifies errors
by about e^(0.9 t) = 7e7 to t = 20, so both carry 40 or more digits and
local errors far below their precision. Run: python3 lorenz_reference.py
(a few minutes).
"""
import sys
from mpmath import mp, mpf


def taylor_run(dps, order, steps, t1=20):
    mp.dps = dps
    sigma, r, b = mpf(10), mpf(28), mpf(8) / 3
    x, y, z = mpf(1), mpf(0), mpf(0)
    h = mpf(t1) / steps
    for _ in range(steps):
        X, Y, Z = [x], [y], [z]
        for k in range(order):
            xz = sum(X[j] * Z[k - j] for j in range(k + 1))
            xy = sum(X[j] * Y[k - j] for j in range(k + 1))
            X.append(sigma * (Y[k] - X[k]) / (k + 1))
            Y.append((r * X[k] - xz - Y[k]) / (k + 1))
            Z.append((xy - b * Z[k]) / (k + 1))
        # Horner's rule at h.
        x, y, z = (sum(c * h**k for k, c in enumerate(S)) for S in (X, Y, Z))
    return x, y, z


def main():
    a = taylor_run(dps=50, order=30, steps=2000)
    b = taylor_run(dps=60, order=36, steps=2500)
    mp.dps = 60
    for name, u, v in zip("xyz", a, b):
        print(f"{name}(20) = {mp.nstr(v, 30)}   runs differ by {mp.nstr(abs(u - v), 3)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
