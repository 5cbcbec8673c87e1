"""Vehicle GPS/DR navigation.

The dead-reckoning and GPS/DR models with filterpy-compatible ``fx``/``hx``/Jacobians and
sensor grades (:mod:`.dead_reckoning`), the filter side: motion logic, per-fix accuracy and
outages (:mod:`.gpsdr`), the second paper's neural filter (:mod:`.neural_filter`), simulated
scenarios and the run object (:mod:`.scenarios`) and the readers of recorded drives: CSV,
onavdata, the shipped sample (:mod:`.drives`).
"""

from .._lazy import lazy_exports, module_exports

_EXPORTS = module_exports({
    "dead_reckoning": ("DRModel", "GPSDRModel", "SENSOR_GRADES", "dr_residual", "dr_z_mean", "wrap_angle"),
    "gpsdr": ("GPSDRFilter",),
    "neural_filter": ("NeuralFilter",),
    "scenarios": ("Scenario", "SCENARIOS", "DRRun", "simulate_scenario", "outage_starts", "with_outage"),
    "drives": ("read_drive_csv", "DRIVE_CSV_COLUMNS", "sample_drive_path", "load_car_drive"),
})
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
__all__ = [name for name, target in _EXPORTS.items() if ":" in target]
