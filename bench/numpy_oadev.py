#!/usr/bin/python3
"""Octave overlapping Allan deviation of a raw float64 rate record, in numpy.

The comparison for bench/whole-process. allantools is not a Debian package (and the machine
that ran the benchmark had no PyPI), so this is a re-implementation of what allantools.oadev
does for frequency data with taus="octave", written for the benchmark, not allantools itself:
  phase = [0, cumsum(y) * tau0]                       (allantools frequency2phase)
  m = 1, 2, 4, ... 2^floor(log2(N)), kept when m < N   (allantools tau_generator "octave")
  for each m: v = phase[2m:] - 2 phase[m:-m] + phase[:-2m]
              adev = sqrt(sum(v^2) / (2 n)) / (m tau0), error adev / sqrt(n)  (calc_adev_phase)
with numpy's vectorised slices as allantools uses them (docs/theory.md §3: the overlapping
estimator). Prints one line per tau: tau_s, adev, adev_error, n.

Usage: numpy_oadev.py FILE.f64 RATE_HZ
"""
import sys

import numpy as np


def oadev_octave(y, rate):
    tau0 = 1.0 / rate
    phase = np.concatenate(([0.0], np.cumsum(y) * tau0))
    n_max = int(np.floor(np.log2(len(y))))
    rows = []
    for m in (2 ** np.arange(n_max + 1)).astype(np.int64):
        if m >= len(y):
            continue
        n = len(phase) - 2 * m
        if n <= 0:
            continue
        v = phase[2 * m:] - 2.0 * phase[m:m + n] + phase[:n]
        adev = np.sqrt(np.sum(v * v) / (2.0 * n)) / (m * tau0)
        rows.append((m * tau0, adev, adev / np.sqrt(n), n))
    return rows


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: numpy_oadev.py FILE.f64 RATE_HZ")
    y = np.fromfile(sys.argv[1], dtype="<f8")
    for tau, adev, err, n in oadev_octave(y, float(sys.argv[2])):
        print(f"{tau:.6g} {adev:.10g} {err:.4g} {n}")


if __name__ == "__main__":
    main()
