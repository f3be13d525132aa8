#!/usr/bin/env python3
"""heyoka's ensemble propagation on the benchmark's Kepler ensemble.

Usage: python3 ensemble.py --members 10000 --tol 1e-12 --workers 1
Prints one JSON object: members, workers, tol, setup_s (the JIT build),
solve_s (the ensemble, fastest of --repeat), the energy errors |E + 1/2|
(median, largest) and the final states of the first five members.

Member i is an orbit of semi-major axis 1 from its pericentre, with the
eccentricity 0.9 * u_i, u_i from SplitMix64 of i (as bench/src/ensemble.rs
and examples/ensemble.rs draw it), integrated to t = 20 pi by
heyoka.ensemble_propagate_until (algorithm "thread", max_workers workers).
"""
import argparse, json, math, statistics, time

import heyoka as hy
import numpy as np

MASK = (1 << 64) - 1


def eccentricity(i):
    z = ((i + 1) * 0x9E3779B97F4A7C15) & MASK
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    z ^= z >> 31
    return 0.9 * (z >> 11) / float(1 << 53)


def start(e):
    return [1.0 - e, 0.0, 0.0, math.sqrt((1.0 + e) / (1.0 - e))]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--members", type=int, default=10000)
    ap.add_argument("--tol", type=float, default=1e-12)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--batch", type=int, default=1,
                    help="members stepped together (heyoka's batch mode, SIMD lanes)")
    a = ap.parse_args()
    q1, q2, p1, p2 = hy.make_vars("q1", "q2", "p1", "p2")
    r3 = (q1 * q1 + q2 * q2) ** -1.5
    sys = [(q1, p1), (q2, p2), (p1, -q1 * r3), (p2, -q2 * r3)]
    t1 = 20 * math.pi
    L = a.batch
    t0 = time.perf_counter()
    if L == 1:
        ta = hy.taylor_adaptive(sys, start(0.5), tol=a.tol)
    else:
        ta = hy.taylor_adaptive_batch(sys, np.array([start(0.5)] * L).T.copy(), tol=a.tol)
    setup = time.perf_counter() - t0

    def gen(ta_copy, i):
        ta_copy.time = 0.0
        ta_copy.state[:] = start(eccentricity(i))
        return ta_copy

    def gen_batch(ta_copy, b):
        ta_copy.set_time(0.0)
        ta_copy.state[:] = np.array([start(eccentricity(b * L + l)) for l in range(L)]).T
        return ta_copy

    best, results = math.inf, None
    for _ in range(a.repeat):
        t0 = time.perf_counter()
        if L == 1:
            results = hy.ensemble_propagate_until(
                ta, t1, a.members, gen, algorithm="thread", max_workers=a.workers)
        else:
            results = hy.ensemble_propagate_until_batch(
                ta, t1, a.members // L, gen_batch, algorithm="thread", max_workers=a.workers)
        best = min(best, time.perf_counter() - t0)
    states = []
    for r in results:
        y = np.asarray(r[0].state)
        states.extend([list(y)] if L == 1 else [list(y[:, l]) for l in range(L)])
    errors = []
    finals = []
    for k, y in enumerate(states):
        energy = 0.5 * (y[2] ** 2 + y[3] ** 2) - 1.0 / math.hypot(y[0], y[1])
        errors.append(abs(energy + 0.5))
        if k < 5:
            finals.append([float(v) for v in y])
    print(json.dumps(dict(members=len(states), batch=L, workers=a.workers, tol=a.tol, setup_s=setup,
                          solve_s=best, median_energy_error=statistics.median(errors),
                          max_energy_error=max(errors), first_finals=finals,
                          heyoka=hy.__version__)))


if __name__ == "__main__":
    main()
