"""allanlab in Python: simulate gyro records, Allan-family curves with intervals, IEEE 952
coefficient fits and the sim-to-real diagnosis, on numpy arrays.

Each function runs the steps of the `allanlab` command of the same name (the compiled
``_allanlab`` extension calls them), so its numbers are the command line's on the same record.
Values are in the units you name (``units="deg/s"``, ``"deg/h"``, ``"rad/s"``; with
``type="angle"``: ``"deg"``, ``"rad"``, ``"arcsec"``) at ``rate_hz`` samples per second; tau in
seconds. A bad argument raises ValueError, a record the work cannot use RuntimeError, each with
the command's one-line message. See docs/python.md.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from . import _allanlab

__version__ = _allanlab.version
__all__ = ["Record", "simulate", "AvarResult", "avar", "Coefficient", "FitResult", "fit",
           "Diagnosis", "diagnose"]

_RATE_UNITS = ("deg/h", "deg/s", "rad/s")


def _columns(values) -> List[np.ndarray]:
    """A 1-D record, or the columns of a 2-D one (samples along axis 0)."""
    a = np.asarray(values, dtype=np.float64)
    if a.ndim == 1:
        return [a]
    if a.ndim == 2:
        return [np.ascontiguousarray(a[:, k]) for k in range(a.shape[1])]
    raise ValueError(f"values: a 1-D record or a 2-D array of columns is needed, got {a.ndim} dimensions")


def _per_column(values, one):
    columns = _columns(values)
    results = [one(c) for c in columns]
    return results[0] if np.asarray(values).ndim == 1 else results


def _out_units(units: str, out_units: Optional[str]) -> str:
    """The deviation's unit: as asked, else the input's rate unit, else rad/s."""
    if out_units is not None:
        return out_units
    return units if units in _RATE_UNITS else "rad/s"


@dataclass(frozen=True)
class Record:
    """A simulated gyro record: ``rate`` in rad/s at ``sample_rate_hz``."""
    rate: np.ndarray
    sample_rate_hz: float
    sensor_name: str
    seed: int
    trial: int
    expected_is_exact: bool
    preset: str = ""
    sensor: str = ""
    units: str = "rad/s"

    @property
    def time_s(self) -> np.ndarray:
        return np.arange(self.rate.size) / self.sample_rate_hz

    def expected_avar(self, m, estimator: str = "overlapping") -> np.ndarray:
        """Exact E[AVAR(m)] in (rad/s)^2 of records like this one (same model and length), for
        the overlapping or nonoverlapping estimator at averaging factors m."""
        if estimator not in ("overlapping", "nonoverlapping"):
            raise ValueError(f"estimator: expected overlapping or nonoverlapping, got '{estimator}'")
        ms = [int(v) for v in np.atleast_1d(m)]
        return _allanlab.expected_avar(self.preset, self.sensor, self.sample_rate_hz, ms, self.rate.size,
                                       estimator == "overlapping")


def simulate(preset: Optional[str] = None, *, sensor: Optional[str] = None, duration_s: float,
             seed: int = 0, trial: int = 0, rate_hz: Optional[float] = None) -> Record:
    """One record of a preset (``"mg25_mems"``, ...) or a YAML sensor spec, as
    ``allanlab simulate``: the same seed and trial give the same samples."""
    rate, info = _allanlab.simulate(preset or "", sensor or "", duration_s, seed, trial, rate_hz)
    return Record(rate=rate, sample_rate_hz=info["sample_rate_hz"], sensor_name=info["sensor_name"], seed=seed,
                  trial=trial, expected_is_exact=info["expected_is_exact"], preset=preset or "", sensor=sensor or "")


def _points(points: List[Dict[str, Any]], key: str, dtype=np.float64) -> np.ndarray:
    return np.array([np.nan if p[key] is None else p[key] for p in points], dtype=dtype)


@dataclass(frozen=True)
class AvarResult:
    """An Allan-family curve, as ``allanlab avar --json`` writes it: one entry per tau. ``var``
    in ``units`` squared, ``dev`` and its interval ``dev_low``..``dev_high`` (NaN without one) in
    ``units``; ``alpha`` the power-law noise type used for the EDF."""
    statistic: str
    units: str
    confidence: float
    m: np.ndarray
    tau_s: np.ndarray
    var: np.ndarray
    dev: np.ndarray
    dev_low: np.ndarray
    dev_high: np.ndarray
    edf: np.ndarray
    terms: np.ndarray
    alpha: np.ndarray
    notes: List[str]
    json: Dict[str, Any] = field(repr=False)

    @classmethod
    def from_json(cls, j: Dict[str, Any]) -> "AvarResult":
        p = j["points"]
        return cls(statistic=j["estimator"]["statistic"], units=j["units"]["dev"],
                   confidence=j["estimator"]["confidence"], m=_points(p, "m", np.int64), tau_s=_points(p, "tau_s"),
                   var=_points(p, "var"), dev=_points(p, "dev"), dev_low=_points(p, "dev_low"),
                   dev_high=_points(p, "dev_high"), edf=_points(p, "edf"), terms=_points(p, "terms", np.int64),
                   alpha=_points(p, "alpha", np.int64), notes=list(j["notes"]), json=j)


def avar(values, rate_hz: float, units: str, *, type: str = "rate", estimator: str = "overlapping",
         taus: str = "octave", ci: str = "auto", confidence: float = 0.683,
         out_units: Optional[str] = None):
    """The curve ``allanlab avar`` gives: estimator overlapping, nonoverlapping, modified,
    hadamard, hadamard_nonoverlapping, total or time; taus octave, decade, dense:K, all or a comma
    list of seconds; ci auto, gr, simple or none. A 2-D array gives one result per column."""
    out = _out_units(units, out_units)
    return _per_column(values, lambda c: AvarResult.from_json(json.loads(_allanlab.avar(
        c, rate_hz, units, type=type, estimator=estimator, taus=taus, ci=ci, confidence=confidence,
        out_units=out))))


@dataclass(frozen=True)
class Coefficient:
    """One fitted coefficient in its datasheet unit: ``value`` +- ``sigma``, or, when the data do
    not determine it, ``value`` None and its 95 % ``upper_limit``."""
    name: str
    value: Optional[float]
    sigma: Optional[float]
    unit: str
    fitted: bool
    upper_limit: Optional[float] = None
    interval_95: Optional[tuple] = None
    slope_method: Optional[float] = None


@dataclass(frozen=True)
class FitResult:
    """What ``allanlab fit --json`` writes: the IEEE 952 coefficients (Q, N, B, K, R, and any
    band-limit or extra term), the fit's chi2 on its degrees of freedom, and the curve fitted."""
    coefficients: Dict[str, Coefficient]
    chi2: float
    dof: int
    poor_fit: bool
    curve: AvarResult
    json: Dict[str, Any] = field(repr=False)


def _coefficient(name: str, e: Dict[str, Any]) -> Coefficient:
    interval = e.get("interval_95")
    return Coefficient(name=name, value=e.get("value"), sigma=e.get("sigma"), unit=e.get("unit", ""),
                       fitted=e.get("fitted", False), upper_limit=e.get("upper_limit"),
                       interval_95=tuple(interval) if interval else None, slope_method=e.get("slope_method"))


def fit(values, rate_hz: float, units: str, *, type: str = "rate", taus: Optional[str] = None,
        method: Optional[str] = None, terms: Optional[str] = None, select_terms: Optional[bool] = None,
        band_limit: Optional[str] = None, uncertainty: Optional[str] = None,
        bootstrap_trials: Optional[int] = None, seed: Optional[int] = None, min_tau_s: float = 0.0,
        max_tau_s: float = 0.0, out_units: Optional[str] = None):
    """The fit ``allanlab fit`` makes (defaults as its options: GLS on the dense:10 overlapping
    curve, terms Q,N,B,K,R with selection, band-limit auto). A 2-D array: one fit per column."""
    kw = {k: v for k, v in dict(taus=taus, method=method, terms=terms, select_terms=select_terms,
                                band_limit=band_limit, uncertainty=uncertainty, bootstrap_trials=bootstrap_trials,
                                seed=seed).items() if v is not None}
    out = _out_units(units, out_units)

    def one(c):
        j = json.loads(_allanlab.fit(c, rate_hz, units, type=type, min_tau_s=min_tau_s, max_tau_s=max_tau_s,
                                     out_units=out, **kw))
        coefficients = {k: _coefficient(k, e) for k, e in j["coefficients"].items() if "unit" in e}
        f = j["fit"]
        return FitResult(coefficients=coefficients, chi2=f["chi2"], dof=f["dof"], poor_fit=f["poor_fit"],
                         curve=AvarResult.from_json(j["curve"]), json=j)
    return _per_column(values, one)


@dataclass(frozen=True)
class Diagnosis:
    """What ``allanlab diagnose --json`` writes: whether the record departs significantly from
    its baseline model, the verdict (an effect id, ``"unexplained"`` or ``"none"``) and every
    candidate tried."""
    significant: bool
    verdict: str
    json: Dict[str, Any] = field(repr=False)


def diagnose(values, rate_hz: float, units: str, *, type: str = "rate", model: Optional[str] = None,
             preset: Optional[str] = None, sensor: Optional[str] = None, float_terms: Optional[str] = None,
             trials: Optional[int] = None, seed: Optional[int] = None, false_alarm: Optional[float] = None):
    """The diagnosis ``allanlab diagnose`` makes (defaults as its options: the baseline ``fit``
    reports, 30 trials per envelope, seed 1, false alarm 0.05; ``model`` a comma list of IEEE
    terms, or ``preset``/``sensor`` with ``float_terms`` refitted). ``units`` a gyro's (rad/s,
    deg/s, deg/h; deg, rad, arcsec with type="angle") or an accelerometer's (m/s^2, g, mg: the
    values are then an accelerometer axis, reported as the command reports an Accel_X column).
    A 2-D array: one diagnosis per column."""
    kw = {k: v for k, v in dict(model=model, preset=preset, sensor=sensor, float_terms=float_terms, trials=trials,
                                seed=seed, false_alarm=false_alarm).items() if v is not None}

    def one(c):
        j = json.loads(_allanlab.diagnose(c, rate_hz, units, type=type, **kw))
        return Diagnosis(significant=j["gap"]["significant"], verdict=j["verdict"]["effect"], json=j)
    return _per_column(values, one)
