"""The Python module's import time and per-call overhead (scripts/benchmark).

Usage: python_axis_call.py LOG.csv  (PYTHONPATH at the build's python/)
Prints: import_ms call_ms library_ms overhead_ms, for driveid.axis on the
log's first 1000 samples (trace off, its default), medians of 101 calls,
each followed by the command's computation (ComputeAxisCommand on the log
already read) timed inside the module without Python: the overhead is the
median of the differences, and holds the keyword arguments' translation,
the arrays' copy and checks, the command line's parsing and the reading
through the log reader.
"""
import sys
import time

start = time.perf_counter()
import driveid  # noqa: E402

import_ms = (time.perf_counter() - start) * 1e3

import numpy  # noqa: E402

lines = [line for line in open(sys.argv[1], encoding="utf-8") if not line.startswith("#")]
header = lines[0].strip().split(",")
table = numpy.loadtxt(lines[1:1001], delimiter=",", ndmin=2)
arrays = {name: numpy.ascontiguousarray(table[:, k]) for k, name in enumerate(header)}
driveid.axis(**arrays)
given = [("arrays", arrays)]
calls, library, differences = [], [], []
for _ in range(101):
    # Alternated, so that a busy machine slows both alike.
    s = time.perf_counter()
    driveid.axis(**arrays)
    calls.append(time.perf_counter() - s)
    library.append(driveid._driveid.axis_library_seconds(["axis", "--", "arrays"], given, 1))
    differences.append(calls[-1] - library[-1])


def median(values):
    return sorted(values)[len(values) // 2] * 1e3


print("%.1f %.3f %.3f %.3f" % (import_ms, median(calls), median(library), median(differences)))
