"""The DR study figures: coinciding series share a labelled line, outliers get their own panel."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from filterwnn.studies import plotting  # noqa: E402


def test_coincide_groups_within_rtol_only():
    t = np.linspace(1.0, 10.0, 50)
    g = plotting.coincide_groups({"EKF": t, "UKF": t * 1.01, "SUKF": t * 0.995, "NN": t * 1.05})
    assert g == [["EKF", "UKF", "SUKF"], ["NN"]]
    assert plotting.coincide_groups({"a": t, "b": t * 1.01}, rtol=0.001) == [["a"], ["b"]]
    with pytest.raises(ValueError, match="rtol"):
        plotting.coincide_groups({"a": t}, rtol=-1)


def test_split_outliers():
    c = {"EKF": np.ones(4), "UKF": 2 * np.ones(4), "NN": 3 * np.ones(4), "NN-faithful": 1e3 * np.ones(4)}
    assert plotting.split_outliers(c) == ["NN-faithful"]
    assert plotting.split_outliers({k: c[k] for k in ("EKF", "UKF", "NN")}) == []


def _errors(rng, scales, n_runs=3, n=60):
    base = rng.normal(size=(n_runs, n, 2)).cumsum(axis=1)
    return {k: base * s if s != "own" else rng.normal(size=(n_runs, n, 2)) * 1e3 for k, s in scales.items()}


def test_position_errors_figure_groups_and_outlier_panel():
    rng = np.random.default_rng(0)
    t = np.arange(1, 61) * 0.1
    err = _errors(rng, {"EKF": 1.0, "EKF-oracle": 0.5, "UKF": 1.0, "SUKF": 1.0, "NN": 2.0, "NN-faithful": "own"})
    fig = plotting.dr_position_errors(t, err, t_switch=3.0, title="test road")
    axes = np.array(fig.axes).reshape(-1, 2) if len(fig.axes) % 2 == 0 else None
    assert axes is not None and axes.shape[0] == 3          # one run, main range, outliers
    labels = [ln.get_label() for ln in axes[1, 0].get_lines()]
    assert "EKF, UKF, SUKF (coincide)" in labels and "NN-faithful" not in labels
    assert [ln.get_label() for ln in axes[2, 0].get_lines() if not ln.get_label().startswith("_")] == ["NN-faithful"]
    assert len(axes[1, 0].collections) == 2                  # bands for two filters only
    plt.close(fig)


def test_outage_errors_figure_groups_coinciding_filters():
    rng = np.random.default_rng(1)
    t = np.arange(1, 61) * 0.1
    err = _errors(rng, {"EKF": 2.0, "EKF-8": 1.0, "UKF-8": 1.0, "SUKF-8": 1.0, "DR-only": 10.0})
    fig = plotting.dr_outage_errors(t, err, outages=[(2.0, 3.0)], title="GPS/DR")
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert labels == ["EKF", "EKF-8, UKF-8, SUKF-8 (coincide)", "DR-only"]
    plt.close(fig)
