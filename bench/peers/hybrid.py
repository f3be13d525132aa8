#!/usr/bin/env python3
"""heyoka on the hybrid benchmark's two problems, as its users write them.

Usage: python3 hybrid.py --tol 1e-12
Prints one JSON object with, for each problem, the fastest time of
--repeat runs (the integrator built before the clock starts) and the
values the Rust side checks:

- ball: a ball dropped from 10 m, g = 9.81, restitution 0.8, to its 20th
  bounce: a terminal event on h (falling) whose callback reverses and
  scales the speed and lets the integration go on; the bounce times.
- sampled_pi: x' = -2x + 3u, u held, a PI controller (kp 0.8, ki 1.5,
  set point 1) sampled every 1 ms for 1 s: propagate_until each instant,
  then the controller sets the runtime parameter u (heyoka has no
  clocks); x at the end.
"""
import argparse, json, time

import heyoka as hy


def ball(tol, bounces=20, e=0.8, g=9.81, h0=10.0):
    h, v = hy.make_vars("h", "v")
    times = []

    def rebound(ta, d_sgn):
        times.append(ta.time)
        ta.state[1] = -e * ta.state[1]
        return len(times) < bounces

    event = hy.t_event(h, callback=rebound, direction=hy.event_direction.negative)
    ta = hy.taylor_adaptive([(h, v), (v, hy.expression(-g))], [h0, 0.0], t_events=[event], tol=tol)
    return ta, times


def sampled_pi(tol):
    x = hy.make_vars("x")
    ta = hy.taylor_adaptive([(x, -2.0 * x + 3.0 * hy.par[0])], [0.0], tol=tol)
    return ta


def run_sampled_pi(ta, samples=1000, period=1e-3, kp=0.8, ki=1.5, r=1.0):
    integral = 0.0
    for k in range(samples):
        e = r - ta.state[0]
        integral += ki * period * e
        ta.pars[0] = kp * e + integral
        ta.propagate_until((k + 1) * period)
    return ta.state[0]


def fastest(build, run, repeat):
    best, result = float("inf"), None
    for _ in range(repeat):
        made = build()
        start = time.perf_counter()
        result = run(made)
        best = min(best, time.perf_counter() - start)
    return best, result


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tol", type=float, default=1e-12)
    ap.add_argument("--repeat", type=int, default=21)
    args = ap.parse_args()

    def run_ball(made):
        ta, times = made
        ta.propagate_until(100.0)
        return times

    ball_s, times = fastest(lambda: ball(args.tol), run_ball, args.repeat)
    pi_s, x_end = fastest(lambda: sampled_pi(args.tol), run_sampled_pi, args.repeat)
    print(json.dumps({
        "tol": args.tol,
        "ball": {"seconds": ball_s, "bounce_times": times},
        "sampled_pi": {"seconds": pi_s, "x_end": x_end},
    }))


if __name__ == "__main__":
    main()
