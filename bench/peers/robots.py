#!/usr/bin/env python3
"""Pinocchio on the robots of tests/robots/, as references for daegen.

Usage:
  python3 robots.py --reference   writes tests/robots/pinocchio.json
  python3 robots.py --timing      prints one JSON object of timings

Needs `python3 -m pip install pin` (Pinocchio's binding). Models are
built from the plain URDF files with pin.buildModelFromUrdf, a free-flyer
root for floating-base robots; no SRDF, so armature is 0. pin.aba ignores
the URDF's <dynamics damping friction>.

The reference holds, per robot: each joint's body in Pinocchio's order
(its parent, its placement in the parent's frame at zero motion, its
mass, centre of mass and inertia about it in its own frame), and
N_STATES random states (q within the URDF limits, v and tau N(0, 1), from
numpy's default_rng(SEED + robot index), independent of Pinocchio's own
generator) with ddq = pin.aba(q, v, tau), M = pin.crba(q) made symmetric
and nle = pin.nonLinearEffects(q, v), and the world position of the origin
of each link a fixed joint welds to another (`welded_links`). Conventions: a free-flyer's q is
(x, y, z, qx, qy, qz, qw), its v (v_lin, omega) and tau (force, torque)
in the base's own frame, and its ddq the spatial acceleration there.
Numbers are written in Python's shortest exact form.
"""
import argparse
import json
import os
import site
import statistics
import sysconfig
import timeit

import numpy as np
import pinocchio as pin

HERE = os.path.dirname(os.path.abspath(__file__))
ROBOTS_DIR = os.path.join(HERE, "..", "..", "tests", "robots")
N_STATES = 5
SEED = 20240601
# (name, file, floating base?). `erd:` files are example-robot-data's own,
# read where pip installed it (TALOS's licence, CC BY-NC-ND, keeps them out
# of the repository): `python3 -m pip install example-robot-data==5.0.0`.
ROBOTS = [("ur5", "ur5.urdf", False), ("panda", "panda.urdf", False), ("solo12", "solo12.urdf", True),
          ("talos_arm", "erd:talos_data/robots/talos_left_arm.urdf", False),
          ("talos", "erd:talos_data/robots/talos_reduced.urdf", False)]


def robot_path(file):
    if file.startswith("erd:"):
        candidates = [sysconfig.get_paths()["purelib"], site.getusersitepackages()]
        candidates += site.getsitepackages()
        for base in candidates:
            share = os.path.join(base, "cmeel.prefix", "share", "example-robot-data", "robots")
            if os.path.isdir(share):
                return os.path.join(share, file[4:])
        raise FileNotFoundError("example-robot-data: python3 -m pip install example-robot-data==5.0.0")
    return os.path.join(ROBOTS_DIR, file)


def build(file, floating):
    path = robot_path(file)
    if floating:
        return pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    return pin.buildModelFromUrdf(path)


def random_q(model, rng):
    q = np.zeros(model.nq)
    lo, hi = model.lowerPositionLimit, model.upperPositionLimit
    for j in model.joints[1:]:
        iq, kind = j.idx_q, j.shortname()
        if kind == "JointModelFreeFlyer":
            q[iq:iq + 3] = rng.uniform(-1, 1, 3)
            quat = rng.normal(size=4)
            quat /= np.linalg.norm(quat)
            q[iq + 3:iq + 7] = quat if quat[3] >= 0 else -quat
        elif kind.startswith("JointModelRUB"):
            th = rng.uniform(-np.pi, np.pi)
            q[iq:iq + 2] = [np.cos(th), np.sin(th)]
        elif j.nq == 1:
            a, b = lo[iq], hi[iq]
            if not (np.isfinite(a) and np.isfinite(b)) or b - a > 1e6:
                a, b = -np.pi, np.pi
            q[iq] = rng.uniform(a, b)
        else:
            raise NotImplementedError(kind)
    return q


def bodies(model):
    out = []
    for i in range(1, model.njoints):
        placement, inertia = model.jointPlacements[i], model.inertias[i]
        out.append(dict(
            joint=model.names[i], type=model.joints[i].shortname(),
            parent=model.names[model.parents[i]] if model.parents[i] > 0 else None,
            idx_q=int(model.joints[i].idx_q), idx_v=int(model.joints[i].idx_v),
            rotation=placement.rotation.tolist(), translation=placement.translation.tolist(),
            mass=float(inertia.mass), com=inertia.lever.tolist(), inertia=inertia.inertia.tolist()))
    return out


def reference():
    out = {"pinocchio": pin.__version__, "seed": SEED, "robots": []}
    for k, (name, file, floating) in enumerate(ROBOTS):
        model = build(file, floating)
        data = model.createData()
        rng = np.random.default_rng(SEED + k)
        states = []
        for _ in range(N_STATES):
            q = random_q(model, rng)
            v = rng.normal(size=model.nv)
            tau = rng.normal(size=model.nv)
            ddq = pin.aba(model, data, q, v, tau).copy()
            m = pin.crba(model, data, q).copy()
            m = np.triu(m) + np.triu(m, 1).T
            nle = pin.nonLinearEffects(model, data, q, v).copy()
            # The origin of every link the file welds to a moving one.
            pin.framesForwardKinematics(model, data, q)
            frames = {f.name: data.oMf[i].translation.tolist() for i, f in enumerate(model.frames)
                      if f.type == pin.FrameType.BODY and f.parentFrame != 0
                      and model.frames[f.parentFrame].type == pin.FrameType.FIXED_JOINT}
            states.append(dict(q=q.tolist(), v=v.tolist(), tau=tau.tolist(), ddq=ddq.tolist(),
                               M=m.tolist(), nle=nle.tolist(), welded_links=frames))
        out["robots"].append(dict(name=name, urdf=file, floating_base=floating, nq=model.nq,
                                  nv=model.nv, gravity=model.gravity.linear.tolist(),
                                  bodies=bodies(model), states=states))
    path = os.path.join(ROBOTS_DIR, "pinocchio.json")
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print("wrote", os.path.normpath(path))


def per_call_us(fn, number=2000, repeat=15):
    return 1e6 * statistics.median(timeit.repeat(fn, number=number, repeat=repeat)) / number


def timing():
    rows = {}
    for k, (name, file, floating) in enumerate(ROBOTS):
        model = build(file, floating)
        data = model.createData()
        rng = np.random.default_rng(SEED + k)
        q, v, tau = random_q(model, rng), rng.normal(size=model.nv), rng.normal(size=model.nv)
        rows[name] = dict(nv=model.nv, aba=per_call_us(lambda: pin.aba(model, data, q, v, tau)),
                          crba=per_call_us(lambda: pin.crba(model, data, q)))
    empty = pin.Model()
    empty_data = empty.createData()
    z = np.zeros(0)
    overhead = per_call_us(lambda: pin.aba(empty, empty_data, z, z, z))
    print(json.dumps(dict(pinocchio=pin.__version__, robots=rows, aba_empty_model=overhead)))


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--reference", action="store_true")
    parser.add_argument("--timing", action="store_true")
    args = parser.parse_args()
    if args.reference:
        reference()
    if args.timing:
        timing()
