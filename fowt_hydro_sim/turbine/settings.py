"""The turbine's settings, as the turbine node's parameters and the coupled runs' options
name them (no ROS here: ``fowt-sim simulate --turbine rosco`` reads them too)."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError, RunConfig
from fowt_hydro_sim.settings import like, setting
from fowt_hydro_sim.turbine.description import TurbineDescription
from fowt_hydro_sim.turbine.wind import DEFAULT_WIND_M_S, WIND_KINDS, Wind, check_series, read_series, series_wind

WIND_TOPIC = "/turbine/wind_speed"  # the turbine's free wind topic (msg_adapters.topics.TURBINE; test_coupled)
BagSeries = Callable[[str, str], tuple[np.ndarray, np.ndarray]]  # (bag, topic) -> (times [s], values)


@dataclass(frozen=True)
class TurbineSettings:
    """The turbine node's parameters."""

    system: str = setting("", "named system (packaged name or system YAML: platform, turbine and mooring that "
                              "belong together, e.g. iea15_volturnus_s); fills platform and turbine")
    turbine: str = setting("iea15_umaine", "packaged turbine name or turbine YAML file")
    discon_changes: str = like(TurbineDescription, "discon_changes", note=" (over the turbine file's own)")
    platform: str = like(RunConfig, "platform", note="; its hub point is where the wrench is applied")
    hub_height_m: float = setting(0.0, "height of the thrust point above the platform's reference point [m]; "
                                       "0 = the platform's hub point", ge=0.0)
    wind: str = setting("steady", "wind input: steady, step, ramp (from wind_speed_m_s to wind_end_m_s at "
                                  "wind_start_s, ramp over wind_ramp_s), file (wind_file), bag (wind_topic of "
                                  "wind_bag)", choices=(*WIND_KINDS, "bag"))
    wind_speed_m_s: float = setting(DEFAULT_WIND_M_S, "hub-height wind speed (before the step or ramp) [m/s]",
                                    ge=0.0, le=80.0)
    wind_end_m_s: float = setting(DEFAULT_WIND_M_S, "wind speed after the step or ramp [m/s]", ge=0.0, le=80.0)
    wind_start_s: float = setting(0.0, "time of the step or start of the ramp [s]", ge=0.0)
    wind_ramp_s: float = setting(60.0, "duration of the ramp [s]", gt=0.0)
    wind_file: str = setting("", "CSV of time [s] and hub-height wind speed [m/s] (wind file)")
    wind_bag: str = setting("", "bag holding a hub-height wind speed series (wind bag)")
    wind_topic: str = setting(WIND_TOPIC,
                              "topic of wind_bag with the wind speed (a turbine quantity topic: Vector3Stamped, x)")
    rotor_start: str = setting("steady", "steady: the turbine starts at its steady operating point in the "
                                           "initial wind; given: at rotor_speed_rad_s and pitch_rad",
                                 choices=("steady", "given"))
    rotor_speed_rad_s: float = setting(0.5, "initial rotor speed (rotor_start given) [rad/s]", ge=0.0)
    pitch_rad: float = setting(0.0, "initial blade pitch (rotor_start given) [rad]", ge=-0.5, le=1.6)
    fixed_platform: bool = setting(False, "ignore the platform's motion (a turbine on a fixed foundation)")
    rosco_logging: int = setting(0, "ROSCO's LoggingLevel: 0 none, 1 its debug channels (rosco.RO.dbg), 2 and its "
                                    "local variables (.dbg2), 3 and the swap array (.dbg3)", ge=0, le=3)
    rosco_debug_dir: str = setting("", "folder where ROSCO's debug files are copied when the node ends "
                                       "(rosco_logging > 0); empty: not kept")
    wait_for_subscribers: int = setting(0, "before answering the first odometry, wait (at most 60 wall seconds) "
                                           "until this many subscribers are connected to each /turbine/ topic (a "
                                           "recorder started alongside, so that its bag misses no sample) and one "
                                           "to the wrench", ge=0)

    def __post_init__(self) -> None:
        if self.wind == "file" and not self.wind_file:
            raise ConfigError("parameter wind_file: wind file needs the path of a CSV of time and speed")
        if self.wind == "bag" and not self.wind_bag:
            raise ConfigError("parameter wind_bag: wind bag needs the path of a bag with a wind speed topic")
        if self.rosco_debug_dir and not self.rosco_logging:
            raise ConfigError("parameter rosco_debug_dir: ROSCO writes debug files only with rosco_logging > 0")

    def make_wind(self, bag_series: BagSeries | None = None) -> Wind:
        """The wind input; a bag's wind series is read with ``bag_series`` (path, topic) ->
        (times, speeds), the bag reader's (``rosbag``: the turbine package reads no bag)."""
        if self.wind == "file":
            return series_wind(*read_series(self.wind_file))
        if self.wind == "bag":
            if bag_series is None:
                raise ConfigError("parameter wind: bag needs a bag reader here; use the turbine node or simulate")
            time_s, speed = bag_series(self.wind_bag, self.wind_topic)
            check_series(time_s, speed, f"wind bag {self.wind_bag} {self.wind_topic}")
            return series_wind(time_s, speed)
        return Wind(self.wind, self.wind_speed_m_s, self.wind_end_m_s, self.wind_start_s, self.wind_ramp_s)


