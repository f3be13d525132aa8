"""Validates an FMU with FMPy and simulates it in both interfaces.

Called by the Rust tests with one JSON argument:
{"fmu": path, "stop": t1, "interval": dt, "rtol": r, "outputs": [names],
 "start": {name: value}, "cs_start": {name: value},
 "input": {"name": input, "points": [[t, value], ...]}}
Prints JSON: {"problems": [...], "ModelExchange": {"time": [...], name: [...]},
"CoSimulation": {...}}. Model Exchange runs FMPy's own CVODE at rtol r
(its absolute tolerance is r times each state's nominal, 1);
Co-Simulation runs the FMU's own method.
"""
import json
import sys

import numpy as np

from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

config = json.loads(sys.argv[1])
signal = None
if "input" in config:
    points = config["input"]["points"]
    kinds = [("time", np.double), (config["input"]["name"], np.double)]
    signal = np.array([tuple(p) for p in points], dtype=kinds)
result = {"problems": [str(p) for p in validate_fmu(config["fmu"])]}
for kind in ["ModelExchange", "CoSimulation"]:
    start = dict(config.get("start", {}))
    if kind == "CoSimulation":
        start.update(config.get("cs_start", {}))
    run = simulate_fmu(
        config["fmu"],
        fmi_type=kind,
        stop_time=config["stop"],
        relative_tolerance=config["rtol"],
        output_interval=config["interval"],
        output=config["outputs"],
        start_values=start,
        record_events=False,
        input=signal,
    )
    result[kind] = {"time": run["time"].tolist()}
    for name in config["outputs"]:
        result[kind][name] = run[name].tolist()
print(json.dumps(result))
