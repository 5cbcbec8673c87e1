"""The package's layout: families as subpackages, old flat paths kept, a cheap ``import filterwnn``."""

import importlib
import subprocess
import sys
import warnings

import pytest

import filterwnn

FAMILIES = ("kalman", "monte_carlo", "wnn", "navigation", "studies")


SINGLE_HOME = sorted((old, new) for old, new in filterwnn.MOVED_MODULES.items() if isinstance(new, str))


@pytest.mark.parametrize("old,new", SINGLE_HOME)
def test_old_flat_paths_are_the_new_modules_and_warn_with_the_new_path(old, new):
    real = importlib.import_module(f"filterwnn.{new}")
    sys.modules.pop(f"filterwnn.{old}", None)
    with pytest.warns(DeprecationWarning, match=f"filterwnn.{new}"):
        alias = importlib.import_module(f"filterwnn.{old}")
    assert alias is real
    assert real.__spec__.name == f"filterwnn.{new}"


def test_every_top_level_name_resolves_and_lives_in_a_family_or_the_root():
    for name in filterwnn.__all__:
        obj = getattr(filterwnn, name)
        home = getattr(obj, "__module__", getattr(obj, "__name__", "filterwnn"))
        assert home.startswith("filterwnn"), (name, home)


@pytest.mark.parametrize("family", FAMILIES[:-1])
def test_each_family_exports_its_public_names(family):
    pkg = importlib.import_module(f"filterwnn.{family}")
    assert pkg.__all__
    for name in pkg.__all__:
        assert getattr(pkg, name) is not None
    assert set(pkg.__all__) <= set(dir(pkg))


def test_filterpy_style_imports():
    from filterwnn.kalman import MinimalSkewSigmaPoints, UnscentedKalmanFilter
    from filterwnn.monte_carlo import BootstrapParticleFilter
    from filterwnn.navigation import GPSDRFilter
    from filterwnn.wnn import WNNRegressor

    assert MinimalSkewSigmaPoints is filterwnn.MinimalSkewSigmaPoints
    assert UnscentedKalmanFilter.__module__ == "filterwnn.kalman.unscented"
    assert BootstrapParticleFilter.__module__ == "filterwnn.monte_carlo.particle_filter"
    assert GPSDRFilter.__module__ == "filterwnn.navigation.gpsdr"
    assert WNNRegressor.__module__ == "filterwnn.wnn.regressor"


def test_the_network_functions_stay_on_filterwnn_wnn():
    from filterwnn import wnn
    from filterwnn.wnn import network

    assert wnn.forward is network.forward and wnn.init_scaled is network.init_scaled


def test_the_old_scenarios_module_reads_through_scenarios_and_drives():
    from filterwnn.navigation import drives, scenarios

    sys.modules.pop("filterwnn.scenarios", None)
    with pytest.warns(DeprecationWarning, match="filterwnn.navigation.drives"):
        from filterwnn.scenarios import DRRun, read_drive_csv
    assert read_drive_csv is drives.read_drive_csv and DRRun is scenarios.DRRun
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        importlib.import_module("filterwnn.scenarios").nothing


def test_import_filterwnn_loads_no_heavy_dependency():
    code = ("import sys, filterwnn; heavy = [m for m in ('sklearn', 'pandas', 'matplotlib', 'filterwnn.studies', "
            "'filterwnn.wnn', 'joblib', 'tqdm') if m in sys.modules]; print(heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_no_module_below_the_studies_imports_them():
    code = ("import sys, filterwnn.kalman.unscented, filterwnn.monte_carlo.particle_filter, "
            "filterwnn.monte_carlo.gaussian_sum, filterwnn.navigation.gpsdr, filterwnn.navigation.drives, "
            "filterwnn.wnn.regressor, filterwnn.monte_carlo.smc; "
            "print([m for m in sys.modules if m.startswith('filterwnn.studies') or m == 'filterwnn.cli'])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_navigation_does_not_need_monte_carlo_or_wnn():
    code = ("import sys, filterwnn.navigation.gpsdr, filterwnn.navigation.drives, filterwnn.navigation.neural_filter; "
            "print([m for m in sys.modules if m.startswith(('filterwnn.monte_carlo', 'filterwnn.wnn'))])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
