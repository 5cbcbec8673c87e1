"""Vehicle GPS/DR navigation.

The dead-reckoning and GPS/DR models with filterpy-compatible ``fx``/``hx``/Jacobians and
sensor grades (:mod:`.dead_reckoning`), the filter side: motion logic, per-fix accuracy and
outages (:mod:`.gpsdr`), the second paper's neural filter (:mod:`.neural_filter`), simulated
scenarios and the run object (:mod:`.scenarios`) and the readers of recorded drives: CSV,
onavdata, the shipped sample (:mod:`.drives`).
"""

from .._lazy import lazy_exports

_EXPORTS = {
    "dead_reckoning": "dead_reckoning",
    "gpsdr": "gpsdr",
    "neural_filter": "neural_filter",
    "scenarios": "scenarios",
    "drives": "drives",
    "DRModel": "dead_reckoning:DRModel",
    "GPSDRModel": "dead_reckoning:GPSDRModel",
    "SENSOR_GRADES": "dead_reckoning:SENSOR_GRADES",
    "dr_residual": "dead_reckoning:dr_residual",
    "dr_z_mean": "dead_reckoning:dr_z_mean",
    "wrap_angle": "dead_reckoning:wrap_angle",
    "GPSDRFilter": "gpsdr:GPSDRFilter",
    "NeuralFilter": "neural_filter:NeuralFilter",
    "Scenario": "scenarios:Scenario",
    "SCENARIOS": "scenarios:SCENARIOS",
    "DRRun": "scenarios:DRRun",
    "simulate_scenario": "scenarios:simulate_scenario",
    "read_drive_csv": "drives:read_drive_csv",
    "DRIVE_CSV_COLUMNS": "drives:DRIVE_CSV_COLUMNS",
    "sample_drive_path": "drives:sample_drive_path",
    "load_car_drive": "drives:load_car_drive",
    "outage_starts": "scenarios:outage_starts",
    "with_outage": "scenarios:with_outage",
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
__all__ = [k for k in _EXPORTS if k not in ("dead_reckoning", "gpsdr", "neural_filter", "scenarios", "drives")]
