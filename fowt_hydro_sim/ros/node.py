"""The ``fowt_hydro_sim`` ROS 2 node: steps the platform model in real or accelerated time and
publishes its motion and loads (contract: docs/ros_interface.md).

The node stays thin: parameters become a ``PlatformModel``; messages go in and out through
``msg_adapters``; input checks live in ``inputs.py``. The simulator owns time: ``/clock`` and
every stamp are simulation time. A stepping thread advances the model one publish period
at a time, paced against the wall clock (``real_time_factor``), or as fast as possible in
batches of publish periods (one compiled call each, published by a second thread while
the next batch is computed), while the executor serves the subscriptions.

Wave samples on the topic (wave_source topic): paced, wave_timeout_s wall seconds without a
sample (counted from the first step) mean still water. As fast as possible the node waits
for its first sample, and then as long as a publisher of the topic is on the graph (its
samples may be held back by flow control while the node is busy); with none left, still
water after wave_timeout_s. Silence counts only while the executor runs: samples a
publisher has sent and gone, queued in the node while a loaded machine keeps its executor
from taking them, are not silence.

Exit codes of ``fowt-sim node``: 0 the run is complete (duration_s stepped) or was stopped by
the user (Ctrl-C, SIGTERM); 1 the run was cut short or is incomplete because of an error (the
controller lost with controller_lost stop, a diverging state, the wave bag ending before
duration_s, the wave topic going silent after it had delivered samples, the recording
failing), said in one line at the end, the bag closed readable; 2 bad input (parameters,
parameter file, platform), one line.
"""
from __future__ import annotations

import contextlib
import gc
import logging
import math
import re
import threading
import time
from collections import deque
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import asdict, dataclass

import numpy as np
import rclpy
from geometry_msgs.msg import AccelStamped, PointStamped, PoseStamped, TwistStamped, Vector3Stamped, WrenchStamped
from nav_msgs.msg import Odometry
from rcl_interfaces.msg import SetParametersResult
from rclpy.duration import Duration
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.serialization import deserialize_message
from rosgraph_msgs.msg import Clock

import msg_adapters as adapt
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import (
    ConfigError,
    HydroOptions,
    RunConfig,
    SampleError,
    SeaState,
    load_case,
    load_platform,
    platform_path,
)
from fowt_hydro_sim.physics.loads import PUBLISHED, ROW, SUMMED
from fowt_hydro_sim.physics.loads.external import check_wrench
from fowt_hydro_sim.physics.model import WAVE_BLOCK_S, PlatformModel
from fowt_hydro_sim.physics.wave_feed import WaveFeed
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.ros import parameters
from fowt_hydro_sim.ros.run_config import run_config
from fowt_hydro_sim.ros.startup import ignore_stop_signals, init_ros
from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.rosbag.writer import BagError, BagWriter, RecordingStopped
from fowt_hydro_sim.settings import like, setting
from fowt_hydro_sim.turbine.system import with_system
from msg_adapters import cdr, topics
from msg_adapters.sim_time import nanoseconds, nanoseconds_array

MESSAGE_CLASSES = {topics.type_name(c): c for c in (AccelStamped, Clock, Odometry, PointStamped, PoseStamped,
                                                    TwistStamped, Vector3Stamped, WrenchStamped)}

OUTPUTS = topics.outputs(PUBLISHED)  # every published load component has its topic
WAVE_SOURCES = ("internal", "topic", "bag", "none")
CONTROLLER_LOST = ("stop", "open_loop")  # lockstep: what the node does when its controller is gone
BATCH_S = 5.0  # simulated seconds stepped per compiled call when running as fast as possible
MAX_LATENESS_S = 0.5  # further behind the wall-clock schedule, pacing restarts from now
MOTION_LIMITS = np.array([2000.0, 2000.0, 200.0, 1.2, 1.2, 50.0])  # beyond: the state has diverged
DELIVERY_TIMEOUT_S = 5.0  # at the end of a run: wall seconds at most for subscribers to acknowledge every output
WARNING_INTERVAL_S = 5.0  # refused inputs of one kind: at most one warning line per this many wall seconds
WAITING_INTERVAL_S = 10.0  # waiting for wave samples: one line per this many wall seconds
QUIET_TICK_S = 0.1  # the wave topic's executor check: a timer of this period
QUIET_TICKS = 3  # that many ticks in a row without an elevation sample: nothing is left in the node's queue


class WarningLimiter:
    """Warnings about refused inputs, rate-limited per kind (the text without its numbers):
    the first of a kind at once, then at most one line per ``interval_s`` with a count of
    those not shown; ``flush`` reports what is still counted."""

    def __init__(self, warn, interval_s: float = WARNING_INTERVAL_S):
        self._warn, self.interval_s = warn, interval_s
        self._kinds: dict[str, list] = {}  # kind: [wall time of the last line, not shown, last text]

    @staticmethod
    def kind(text: str) -> str:
        return re.sub(r"[-+]?\d[\d.e+-]*", "#", text)

    def __call__(self, text: str) -> None:
        now = time.monotonic()
        entry = self._kinds.setdefault(self.kind(text), [-math.inf, 0, text])
        if now - entry[0] < self.interval_s:
            entry[1], entry[2] = entry[1] + 1, text
            return
        self._warn(text + (f" (and {entry[1]} more like it not shown)" if entry[1] else ""))
        entry[:] = [now, 0, text]

    def flush(self) -> None:
        for entry in self._kinds.values():
            if entry[1]:
                self._warn(f"{entry[1]} more refused like: {entry[2]}")
                entry[1] = 0


@dataclass(frozen=True)
class NodeSettings:
    """The node's parameters: run and sea-state settings (their defaults, meanings and ranges
    from ``physics.config``), and the node's own."""

    system: str = setting("", "named system (packaged name or system YAML: platform, turbine and mooring that "
                              "belong together, e.g. iea15_volturnus_s); fills platform and mooring")
    platform: str = like(RunConfig, "platform")
    drag_model: str = like(RunConfig, "drag_model", default="filtered")
    wetted_length: str = like(RunConfig, "wetted_length")
    load_directions: str = like(RunConfig, "load_directions")
    hydrostatics: str = like(RunConfig, "hydrostatics")
    slow_drift: str = like(RunConfig, "slow_drift")
    mooring: str = like(RunConfig, "mooring")
    load_case: str = setting("lc5.3", "load case giving the sea state (lc5.0 .. lc6.5); hs_m/tp_s > 0 override it")
    hs_m: float = like(SeaState, "hs_m", default=0.0, unset=0.0, note="; 0 = the load case's")
    tp_s: float = like(SeaState, "tp_s", default=0.0, unset=0.0, note="; 0 = the load case's")
    gamma: float = like(SeaState, "gamma", default=0.0, unset=0.0, note="; 0 = the load case's")
    heading_deg: float = like(SeaState, "heading_deg")
    seed: int = like(SeaState, "seed", note=" of the internal waves")
    wave_source: str = setting("internal", "internal: synthesised from the sea state; topic: /waves/elevation; "
                                           "bag: /waves/elevation of wave_bag; none: still water",
                               choices=WAVE_SOURCES)
    wave_bag: str = setting("", "bag whose /waves/elevation drives the model (wave_source bag)")
    wave_point_xy: tuple[float, float] = setting((0.0, 0.0), "where the /waves/elevation samples are measured "
                                                             "(world x, y) [m]")
    wave_sample_dt_s: float = setting(0.1, "step of the streamed elevation series [s] (samples are resampled "
                                           "onto it)", gt=0.0)
    preview_s: float = setting(60.0, "delay of the streamed wave kinematics behind the elevation samples [s]",
                               gt=0.0)
    wave_timeout_s: float = setting(2.0, "wall seconds without elevation samples (counted from the first step) "
                                         "before still water is assumed (as fast as possible: only after a first "
                                         "sample and once the topic has no publisher left)", gt=0.0)
    wave_block_s: float = setting(WAVE_BLOCK_S, "the internal waves' kinematics are synthesised in blocks of this "
                                                "many simulated seconds, two held, the next made ahead in a worker "
                                                "thread [s]", gt=0.0)
    dt_s: float = like(RunConfig, "dt_s")
    initial_state: tuple[float, ...] = like(RunConfig, "initial_state")
    real_time_factor: float = setting(1.0, "1 = real time, N = N times faster, 0 = as fast as possible", ge=0.0)
    publish_rate_hz: float = setting(20.0, "output rate in simulation time [Hz]; a multiple of it must be 1/dt_s",
                                     gt=0.0)
    duration_s: float = like(RunConfig, "duration_s", default=0.0, gt=None, ge=0.0,
                             description="simulated seconds, then stop stepping; 0 = until stopped")
    world_frame_id: str = setting("world", "frame id of the world frame")
    platform_frame_id: str = setting("platform", "frame id of the platform (body) frame")
    lockstep: bool = setting(False, "wait for an external wrench stamped for each publish time before stepping")
    lockstep_timeout_s: float = setting(5.0, "wall seconds to wait for the wrench in lockstep, then step anyway",
                                        gt=0.0)
    controller_lost: str = setting("stop", "lockstep: when the controller is gone (no publisher of the wrench, "
                                           "or controller_timeouts timeouts in a row): stop stepping, or go on "
                                           "open loop with the last wrench", choices=CONTROLLER_LOST)
    controller_timeouts: int = setting(3, "lockstep: timeouts in a row that mean the controller is gone", ge=1)
    record: str = setting("", "bag directory recording every input and output of the run; empty = no recording")
    record_overwrite: bool = setting(False, "replace an existing bag at the record path")
    record_failure: str = setting("stop", "when the recording cannot be written (disk full): the bag is closed "
                                          "readable, then stepping stops, or continues unrecorded",
                                  choices=("stop", "continue"))
    wait_for_subscribers: int = setting(0, "before stepping, wait (at most 60 wall seconds) until this many "
                                           "subscribers are connected to /platform/pose (a run as fast as "
                                           "possible is over before a late subscriber is discovered)", ge=0)

    def __post_init__(self) -> None:
        """The rules between parameters (each one's own range is checked as it is read)."""
        ratio = 1.0 / (self.publish_rate_hz * self.dt_s)
        if abs(ratio - round(ratio)) > 1e-6 or round(ratio) < 1:
            raise ConfigError(f"parameter publish_rate_hz: 1/(publish_rate_hz dt_s) must be a whole number, "
                              f"got {ratio:g}")
        if self.wave_source == "bag" and not self.wave_bag:
            raise ConfigError("parameter wave_bag: wave_source bag needs the path of a bag with /waves/elevation")
        if not (self.world_frame_id and self.platform_frame_id):
            raise ConfigError("parameters world_frame_id, platform_frame_id: must not be empty")
        if self.hydrostatics == "free_surface":
            raise ConfigError("parameter hydrostatics: 'free_surface' is implemented for a prescribed motion only "
                              "(fowt-sim loads), not for the node")
        load_case(self.load_case)  # an unknown load case fails here

    @property
    def sea_state(self) -> SeaState:
        case = load_case(self.load_case).sea_state
        return SeaState(self.hs_m or case.hs_m, self.tp_s or case.tp_s, self.gamma or case.gamma,
                        heading_deg=self.heading_deg, seed=self.seed)

    @property
    def steps_per_publish(self) -> int:
        return int(round(1.0 / (self.publish_rate_hz * self.dt_s)))


class SimulatorNode(Node):
    """The simulator node; its settings come from the ROS parameters (``PARAMETERS``)."""

    def __init__(self, **node_kwargs):
        super().__init__("fowt_hydro_sim", **node_kwargs)
        parameters.declare(self, NodeSettings)
        parameters.refuse_unknown(self)
        self.settings = with_system(parameters.read(self, NodeSettings))
        s = self.settings
        platform = load_platform(s.platform)
        waves = None
        if s.wave_source == "internal":
            waves = synthesize(s.sea_state, repeat_period(s.sea_state, s.duration_s))
        options = HydroOptions(wetted_length=s.wetted_length, load_directions=s.load_directions,
                               hydrostatics=s.hydrostatics, slow_drift=s.slow_drift)
        self.model = PlatformModel(platform, waves, dt_s=s.dt_s, drag_model=s.drag_model, options=options,
                                   wave_block_s=s.wave_block_s, mooring_model=s.mooring)
        self.model.reset(motion=np.array(s.initial_state))
        # the node's outputs: the contract's, then each mooring line's tensions
        self._n_lines = self.model.n_mooring_lines
        self._outputs_map = {**OUTPUTS, **{f"tension{i}": (topics.tension_topic(i), topics.VECTOR3_STAMPED)
                                           for i in range(1, self._n_lines + 1)}}
        self._feed: WaveFeed | None = None
        self._wave_bag = None  # (topic, log time, bytes) of the wave bag, read as needed
        if s.wave_source in ("topic", "bag"):
            self._feed = WaveFeed(self.model, s.wave_point_xy, s.world_frame_id, s.wave_sample_dt_s, s.preview_s,
                                  s.sea_state.heading_deg)
            self._last_sample_wall = time.monotonic()
            self._said_waiting = time.monotonic()
            self._still_water = False
            self._samples_received = False
            self._quiet_ticks = 0
        if s.wave_source == "bag":
            bag = Bag(s.wave_bag)
            bag.check_type(topics.ELEVATION)
            self._wave_bag = bag.messages([topics.ELEVATION])
        self._recorder = self._open_recorder() if s.record else None
        self._lock = threading.Condition()
        self._wrench = (np.zeros(6), "world", -math.inf)  # wrench, frame, stamp
        self._timeouts = 0  # lockstep: timeouts in a row
        self._open_loop = False  # lockstep given up: the controller is gone
        self._rtf = s.real_time_factor
        self._stop = threading.Event()
        self.incomplete: str | None = None  # why the run is cut short or incomplete (an error): exit code 1
        self.lateness_s: deque[float] = deque(maxlen=100_000)  # wall lateness of each paced publish
        self.dropped = 0  # messages DDS refused (a subscriber too slow for the pace)
        self.published = 0  # messages published (each also recorded when recording)
        self._refused = WarningLimiter(self.get_logger().warning)
        self._publisher = ThreadPoolExecutor(max_workers=1, thread_name_prefix="fowt_publish")
        self._published: Future | None = None  # the batch being published
        self._make_interface()
        self.add_on_set_parameters_callback(self._on_set_parameters)
        self.get_logger().info(
            f"{platform.name}, drag {s.drag_model}, mooring {self.model.platform.mooring.model}, waves {s.wave_source}"
            + (f" (Hs {s.sea_state.hs_m:g} m, Tp {s.sea_state.tp_s:g} s, seed {s.sea_state.seed})"
               if s.wave_source == "internal" else " (still water)" if s.wave_source == "none" else
               f" ({topics.ELEVATION} {'of ' + s.wave_bag if s.wave_bag else ''} at {s.wave_point_xy}, "
               f"kinematics {self._feed.delay_s:g} s behind the samples)")
            + f", dt {s.dt_s:g} s, real-time factor {s.real_time_factor:g}"
            + (", lockstep" if s.lockstep else "") + (f", recording to {s.record}" if s.record else ""))
        self._thread = threading.Thread(target=self._run, name="fowt_stepping", daemon=True)

    # ------------------------------------------------------------------ set-up
    def _open_recorder(self) -> BagWriter:
        """The run's bag, holding its full configuration (reproducible from the bag alone)."""
        s = self.settings
        config = run_config(parameters.values(s), platform_path(s.platform).read_text(), asdict(s.sea_state))
        try:
            recorder = BagWriter(s.record, config=config, overwrite=s.record_overwrite)
        except BagError as exc:
            raise ConfigError(f"parameter record: {exc}") from None
        except OSError as exc:
            raise ConfigError(f"parameter record: cannot create the bag directory {s.record}: "
                              f"{exc.strerror or exc}") from None
        self._output_channels = [recorder.add_topic(topic, kind) for topic, kind in self._outputs_map.values()]
        self._input_channel = {topic: recorder.add_topic(topic, kind) for topic, kind in topics.INPUTS.items()}
        return recorder

    def _make_interface(self) -> None:
        out = QoSProfile(depth=1000)  # accelerated runs: room for a slower subscriber
        self._pub = {name: self.create_publisher(MESSAGE_CLASSES[kind], topic, out)
                     for name, (topic, kind) in self._outputs_map.items()}
        self._output_names = list(self._outputs_map)  # the order of cdr.outputs, then the tensions
        self._total_rows = [ROW[c] for c in SUMMED]
        self._load_rows = [ROW[c] for c in PUBLISHED]  # one topic each
        inputs = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE)
        # raw: the bytes as sent are recorded (rclpy's serialisation leaves padding bytes unset)
        self.create_subscription(WrenchStamped, topics.EXTERNAL_WRENCH, self._on_wrench, inputs, raw=True)
        if self.settings.wave_source == "topic":  # room for a record replayed faster than it is read
            samples = QoSProfile(depth=100_000, reliability=ReliabilityPolicy.RELIABLE)
            self.create_subscription(PointStamped, topics.ELEVATION, self._on_elevation, samples, raw=True)
            self.create_timer(QUIET_TICK_S, self._quiet_tick)

    def _quiet_tick(self) -> None:
        """A tick of the executor that serves the wave topic: counted until the next sample.
        Ticks come only while the executor runs, so samples queued in the node while it is too
        busy to take them (a loaded machine) never count as silence (``_topic_silent``)."""
        with self._lock:
            self._quiet_ticks += 1

    def _on_set_parameters(self, changes) -> SetParametersResult:
        for p in changes:
            if p.name == "real_time_factor" and isinstance(p.value, (int, float)) and p.value >= 0:
                self._rtf = float(p.value)
                continue
            return SetParametersResult(successful=False, reason=f"{p.name}: only real_time_factor (>= 0) can "
                                                                f"change while running; restart the node")
        return SetParametersResult(successful=True)

    # ------------------------------------------------------------------ inputs
    def _record_input(self, topic: str, data: bytes) -> None:
        if self._recorder is not None:
            try:
                self._recorder.write(self._input_channel[topic], nanoseconds(self.model.time_s), data)
            except RecordingStopped as exc:
                self._recording_stopped(exc)

    def _recording_stopped(self, exc: RecordingStopped) -> None:
        """The bag could not be written (disk full): it is closed and readable; said in one
        line; stepping stops or goes on as record_failure says."""
        stop = self.settings.record_failure == "stop"
        self.get_logger().error(f"{exc}; {'stepping stopped' if stop else 'stepping goes on unrecorded'} "
                                f"(record_failure {self.settings.record_failure})")
        if stop:
            self._stop.set()

    def _on_wrench(self, data: bytes) -> None:
        self._record_input(topics.EXTERNAL_WRENCH, data)
        t, wrench, frame = adapt.wrench_from_msg(deserialize_message(data, WrenchStamped))
        try:
            wrench = check_wrench(wrench, frame)
        except SampleError as exc:
            self._refused(f"{exc}; keeping the last good wrench")
            return
        with self._lock:
            self._wrench = (wrench, frame, t)
            self._lock.notify_all()

    def _on_elevation(self, data: bytes) -> None:
        self._record_input(topics.ELEVATION, data)
        with self._lock:
            self._accept_elevation(*adapt.elevation_from_msg(deserialize_message(data, PointStamped)))
            self._lock.notify_all()

    def _accept_elevation(self, t: float, x: float, y: float, eta: float, frame: str) -> None:
        """One elevation sample into the wave feed; a refused one is logged and ignored."""
        feed = self._feed
        try:
            made = feed.accept(t, x, y, eta, frame)
        except SampleError as exc:
            self._refused(f"{exc}; sample ignored")
            return
        if feed.resampler.gap_s > 2.5 * feed.resampler.sample_dt_s and not self._still_water:
            self.get_logger().warning(f"wave elevation: {feed.resampler.gap_s:.2f} s gap before t = {t:.3f} s, "
                                      f"interpolated")
        self._last_sample_wall = time.monotonic()
        self._samples_received = True
        self._quiet_ticks = 0
        if self._still_water and made:
            self.get_logger().info("wave elevation samples again: leaving still water")
            self._still_water = False

    def _next_bag_sample(self) -> bool:
        """Feed the wave bag's next elevation sample; False at the end of the bag."""
        message = next(self._wave_bag, None)
        if message is None:
            return False
        _, _, data = message
        self._record_input(topics.ELEVATION, data)
        (t,), ((x, y, eta),) = cdr.decode_stamped(topics.POINT_STAMPED, [data])
        self._accept_elevation(float(t), float(x), float(y), float(eta), cdr.frame_id(data))
        return True

    def _wait_for_waves(self, until_s: float) -> bool:
        """Stream kinematics up to ``until_s``: from the wave bag (False at its end), or from
        the topic, going on in still water once it is silent (``_topic_silent``). False if the
        node is stopping."""
        with self._lock:
            while not self._stop.is_set():
                if self._feed.feed(until_s):
                    return True
                if self._wave_bag is not None:
                    if not self._next_bag_sample():
                        self._wave_bag_ended()
                        return False
                    continue
                if self._topic_silent():
                    self._feed.fill_still_water()
                    continue
                self._lock.wait(timeout=0.05)
        return False

    def _wave_bag_ended(self) -> None:
        """Said; before duration_s the run is cut short."""
        s, t = self.settings, self.model.time_s
        if s.duration_s and t < s.duration_s - 1e-9:
            self.incomplete = f"the wave bag {s.wave_bag} ended at t = {t:.2f} s, before duration_s {s.duration_s:g} s"
            self.get_logger().error(f"{self.incomplete} (its waves are known up to t = {self._feed.until_s:.2f} s): "
                                    f"stepping stopped")
        else:
            self.get_logger().info(f"wave bag {s.wave_bag} ends: waves known up to t = {self._feed.until_s:.2f} s, "
                                   f"stepping stopped")

    def _topic_silent(self) -> bool:
        """Whether the wave topic counts as silent (the caller goes on in still water): no sample
        for wave_timeout_s wall seconds while the executor kept running (QUIET_TICKS ticks
        without a sample, ``_quiet_tick``), and, as fast as possible, a first sample received
        and no publisher left. Said once; silent after samples before the waves of duration_s
        are known, the run is incomplete."""
        s, now = self.settings, time.monotonic()
        silent = now - self._last_sample_wall
        if self._still_water:
            return True
        if silent <= s.wave_timeout_s or self._quiet_ticks < QUIET_TICKS:
            return False
        publishers = self.count_publishers(topics.ELEVATION)
        if self._rtf == 0 and (publishers or not self._samples_received):
            if now - self._said_waiting > WAITING_INTERVAL_S:
                self.get_logger().info(f"waiting for wave elevation samples on {topics.ELEVATION} ({publishers} "
                                       f"publisher(s)) to step past t = {self.model.time_s:.2f} s")
                self._said_waiting = now
            return False
        self._still_water = True
        if not self._samples_received:
            self.get_logger().warning(f"no wave elevation on {topics.ELEVATION} for {silent:.1f} s: going on in "
                                      f"still water")
            return True
        last = self._feed.resampler.last[0]
        if s.duration_s and self._feed.until_s >= s.duration_s - 1e-9:  # the run's waves are all known
            self.get_logger().info(f"no wave elevation on {topics.ELEVATION} for {silent:.1f} s after samples up "
                                   f"to t = {last:.2f} s: waves known up to t = {self._feed.until_s:.2f} s, "
                                   f"duration_s {s.duration_s:g} s")
            return True
        self.incomplete = (f"the wave topic {topics.ELEVATION} went silent after samples up to t = {last:.2f} s: "
                           f"still water from t = {self._feed.until_s:.2f} s on")
        self.get_logger().error(f"no wave elevation on {topics.ELEVATION} for {silent:.1f} s ({publishers} "
                                f"publisher(s)) after samples up to t = {last:.2f} s: going on in still water from "
                                f"t = {self._feed.until_s:.2f} s (the kinematics lag the samples by "
                                f"{self._feed.delay_s:g} s); the run is incomplete")
        return True

    def _wait_for_controller(self) -> None:
        """Lockstep: before the first step, wait until a controller is connected both ways."""
        said = time.monotonic()
        while not self._stop.is_set() and (self._pub["odom"].get_subscription_count() == 0
                                           or self.count_publishers("/platform/external_wrench") == 0):
            if time.monotonic() - said > 5.0:
                self.get_logger().info("lockstep: waiting for a controller on /platform/odom and "
                                       "/platform/external_wrench")
                said = time.monotonic()
            time.sleep(0.05)
        time.sleep(0.5)  # let discovery finish on the controller's side too

    def _wait_for_lockstep(self, time_s: float) -> bool:
        """Wait for a wrench stamped ``time_s``; a controller that subscribes to the odometry
        meanwhile (after it was sent: a controller started or restarted) is sent it again
        (only the odometry, not recorded: a slow controller has it already, and the run's
        outputs stay one sample per stamp). A controller gone (its wrench publisher left the
        graph, or controller_timeouts timeouts in a row) is said once; then False (stop) or
        open loop, as controller_lost says."""
        s = self.settings
        if self._open_loop:
            return True
        deadline = time.monotonic() + s.lockstep_timeout_s
        subscribers = self._pub["odom"].get_subscription_count()  # those that have the odometry of time_s
        with self._lock:
            while self._wrench[2] < time_s - 1e-9 and not self._stop.is_set():
                if self.count_publishers(topics.EXTERNAL_WRENCH) == 0:
                    return self._controller_lost(time_s, f"no publisher on {topics.EXTERNAL_WRENCH} any more")
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    self._timeouts += 1
                    if self._timeouts >= s.controller_timeouts:
                        return self._controller_lost(time_s, f"{self._timeouts} lockstep timeouts in a row")
                    self.get_logger().warning(f"lockstep: no external wrench stamped {time_s:.3f} s within "
                                              f"{s.lockstep_timeout_s:g} s; stepping with the last one")
                    return True
                if not self._lock.wait(timeout=min(remaining, 0.5)):
                    now = self._pub["odom"].get_subscription_count()
                    if now > subscribers:
                        self._resend_odometry()
                    subscribers = min(subscribers, now)
        self._timeouts = 0
        return True

    def _resend_odometry(self) -> None:
        """The odometry of the current state once more, unrecorded."""
        _, blocks = self._outputs_now()
        publisher = self._pub["odom"]
        data = next(iter(cdr.messages(blocks[self._output_names.index("odom")])))
        with publisher.handle:
            try:
                publisher.handle.publish_raw(data)
            except _rclpy.RCLError as exc:
                self._dropped(publisher.topic_name, exc)

    def _controller_lost(self, time_s: float, why: str) -> bool:
        """Say once that the controller is gone; False if the stepping stops."""
        stop = self.settings.controller_lost == "stop"
        if stop:
            self.incomplete = f"the controller was lost at t = {time_s:.3f} s ({why})"
        self.get_logger().error(f"lockstep: the controller is gone at t = {time_s:.3f} s ({why}): "
                                + ("stepping stopped (controller_lost stop)" if stop else
                                   "going on open loop with the last wrench (controller_lost open_loop)"))
        self._open_loop = True
        return not stop

    # ------------------------------------------------------------------ stepping
    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        """Stop stepping, finish publishing and close the recording (complete and indexed)."""
        self._stop.set()
        with self._lock:
            self._lock.notify_all()
        if self._thread.is_alive():
            self._thread.join(timeout=10)
        self._publisher.shutdown(wait=True)
        self._refused.flush()
        if self._recorder is not None:
            self._recorder.close()

    def wait_for_delivery(self, timeout_s: float = DELIVERY_TIMEOUT_S) -> None:
        """At the end of a run: wait until reliable subscribers have acknowledged every output
        (DDS repairs lost samples at its heartbeats), at most ``timeout_s`` in all; said if not."""
        deadline = time.monotonic() + timeout_s
        late = [publisher.topic_name for publisher in self._pub.values()
                if not publisher.wait_for_all_acked(Duration(seconds=max(0.0, deadline - time.monotonic())))]
        if late:
            self.get_logger().warning(f"{len(late)} output topic(s) not acknowledged by every subscriber within "
                                      f"{timeout_s:g} s (e.g. {late[0]}): a subscriber may have missed the last "
                                      f"messages")

    @property
    def recording_failed(self) -> bool:
        """Whether the recording stopped early (its bag is closed, with what was written)."""
        return self._recorder is not None and self._recorder.failure is not None

    @property
    def finished(self) -> bool:
        return not self._thread.is_alive()

    def _run(self) -> None:
        start_wall, start_cpu, start_sim = time.monotonic(), time.process_time(), self.model.time_s
        start_blocks, start_taken = self.model.wave_block_wait_s, self.model.wave_blocks_taken
        try:
            self._step_until_done()
        except InputError as exc:  # a model that cannot go on (MoorDyn failing, a line out of its table)
            self.incomplete = str(exc)
            self.get_logger().error(f"{exc}: stepping stopped, nothing more is published")
            self._stop.set()
        finally:
            wall, cpu = time.monotonic() - start_wall, time.process_time() - start_cpu
            taken, ahead = np.subtract(self.model.wave_blocks_taken, start_taken)
            report = f"stepping ended at t = {self.model.time_s:.2f} s: {self.model.time_s - start_sim:.1f} s " \
                     f"simulated in {wall:.2f} s of wall time ({cpu:.2f} s of CPU), {self.published} messages " \
                     f"published, {self.model.wave_block_wait_s - start_blocks:.3f} s waiting for wave blocks " \
                     f"({ahead} of {taken} made ahead)"
            if self.lateness_s:
                late = np.array(self.lateness_s) * 1e3
                report += (f"; pacing lateness p50 {np.percentile(late, 50):.3f} ms, p99 "
                           f"{np.percentile(late, 99):.3f} ms over {late.size} steps")
            self.get_logger().info(report)

    def _wait_for_subscribers(self, count: int, timeout_s: float = 60.0) -> None:
        """Before the first step: until ``count`` subscribers are connected to the pose topic."""
        deadline = time.monotonic() + timeout_s
        while (count and self._pub["pose"].get_subscription_count() < count and not self._stop.is_set()
               and time.monotonic() < deadline):
            time.sleep(0.05)
        if count and self._pub["pose"].get_subscription_count() < count:
            self.get_logger().warning(f"wait_for_subscribers: {self._pub['pose'].get_subscription_count()} of "
                                      f"{count} subscribers after {timeout_s:g} s; stepping anyway")

    def _step_until_done(self) -> None:
        s, model = self.settings, self.model
        period = s.steps_per_publish * s.dt_s
        if s.lockstep:
            self._wait_for_controller()
        self._wait_for_subscribers(s.wait_for_subscribers)
        gc.collect()
        gc.freeze()  # the set-up's objects out of the collector's way: shorter pauses while stepping
        self._publish_now()
        self._anchor = (time.monotonic(), model.time_s, self._rtf)  # pacing: wall, sim, factor
        if self._feed is not None:
            with self._lock:  # the set-up and the waits above are no silence of the wave topic
                self._last_sample_wall = self._anchor[0]  # later than any sample taken so far
        try:
            while not self._stop.is_set():
                if s.duration_s and model.time_s >= s.duration_s - 1e-9:
                    self.get_logger().info(f"duration {s.duration_s:g} s reached: stepping stopped")
                    return
                if s.lockstep and not self._wait_for_lockstep(model.time_s):
                    return
                # as fast as possible: a batch of publish periods per compiled call
                waits = s.lockstep and not self._open_loop
                periods = 1 if self._rtf > 0 or waits else max(1, int(round(BATCH_S / period)))
                if s.duration_s:
                    periods = max(1, min(periods, int(round((s.duration_s - model.time_s) / period))))
                if self._feed is not None and not self._wait_for_waves(
                        model.time_s + periods * period + 3 * s.wave_sample_dt_s):
                    return
                with self._lock:
                    wrench, frame, _ = self._wrench
                model.set_external_wrench(wrench, frame)
                if periods > 1:
                    if not self._step_batch(periods * period, period):
                        return
                    continue
                self._finish_publishing()
                model.step(s.steps_per_publish)
                if not self._healthy(np.array([model.time_s]), model.motion[None], model.velocity[None]):
                    return
                outputs = self._outputs_now()  # built before the deadline, sent at it
                self._pace(period)
                self._publish(*outputs)
        finally:
            self._finish_publishing()
            gc.unfreeze()

    def _step_batch(self, duration_s: float, period_s: float) -> bool:
        """Step a batch, computed (without the GIL) while the previous batch is published;
        False if it diverged."""
        result = self.model.run(duration_s, output_interval_s=period_s)
        rows = slice(1, None)  # the first row is where the batch started, already published
        healthy = self._healthy(result.time_s[rows], result.motion[rows], result.velocity[rows])
        self._finish_publishing()
        outputs = self._outputs(result.time_s[rows][:healthy], result.motion[rows][:healthy],
                                result.velocity[rows][:healthy], result.acceleration[rows][:healthy],
                                result.loads[rows][:healthy], result.wave_elevation_m[rows][:healthy])
        self._published = self._publisher.submit(self._publish, *outputs)
        return healthy == len(result.time_s) - 1

    def _finish_publishing(self) -> None:
        if self._published is not None:
            self._published.result()
            self._published = None

    def _pace(self, period_s: float) -> None:
        """Sleep until the wall-clock time of the current simulated time: an absolute deadline
        on the monotonic clock, from the anchor (so lateness does not accumulate)."""
        wall0, sim0, rtf = self._anchor
        if self._rtf != rtf:  # re-anchor after a change of speed
            wall0, sim0, rtf = time.monotonic(), self.model.time_s - period_s, self._rtf
        if rtf > 0:
            target = wall0 + (self.model.time_s - sim0) / rtf
            delay = target - time.monotonic()
            if delay < -MAX_LATENESS_S:  # after a stall (waiting for input): no catching up
                wall0, sim0 = time.monotonic(), self.model.time_s
            else:
                if delay > 0:
                    time.sleep(delay)
                self.lateness_s.append(time.monotonic() - target)
        self._anchor = (wall0, sim0, rtf)

    def _healthy(self, time_s: np.ndarray, motion: np.ndarray, velocity: np.ndarray) -> int:
        """How many rows of states (n, 6) are healthy: all, or those before the first that is
        not (logged, and the stepping stops)."""
        bad = ~(np.isfinite(motion).all(axis=1) & np.isfinite(velocity).all(axis=1)
                & (np.abs(motion) < MOTION_LIMITS).all(axis=1))
        if not bad.any():
            return len(time_s)
        first = int(np.argmax(bad))
        self.incomplete = f"the state diverged at t = {time_s[first]:.3f} s"
        self.get_logger().error(f"the state diverged at t = {time_s[first]:.3f} s (motion {motion[first].tolist()}): "
                                f"stepping stopped, nothing more is published")
        self._stop.set()
        return first

    def _outputs_now(self) -> tuple[np.ndarray, list[np.ndarray]]:
        m = self.model
        return self._outputs(np.array([m.time_s]), m.motion[None], m.velocity[None], m.acceleration[None],
                             m.loads[None], np.array([float(m.wave_elevation(m.time_s)[0])]))

    def _publish_now(self) -> None:
        self._publish(*self._outputs_now())

    def _outputs(self, time_s: np.ndarray, motion: np.ndarray, velocity: np.ndarray, acceleration: np.ndarray,
                 loads: np.ndarray, elevation_m: np.ndarray) -> tuple[np.ndarray, list[np.ndarray]]:
        """Every output of each sample (row): the times and one block of CDR messages per topic."""
        total = loads[:, self._total_rows].sum(axis=1)
        blocks = cdr.output_blocks(time_s, motion, velocity, acceleration, loads[:, self._load_rows], total,
                                   elevation_m, self.settings.world_frame_id, self.settings.platform_frame_id)
        tensions = self.model.mooring_tensions(time_s, motion)
        return time_s, blocks + cdr.tension_blocks(time_s, tensions, self.settings.world_frame_id)

    def _publish(self, time_s: np.ndarray, blocks: list[np.ndarray]) -> None:
        """Publish each sample's messages (row by row, topics in contract order), then record them."""
        if not len(time_s):
            return
        self._send(blocks)
        self.published += len(time_s) * len(blocks)
        if self._recorder is not None:
            try:
                self._recorder.write_blocks(nanoseconds_array(time_s), self._output_channels, blocks)
            except RecordingStopped as exc:
                self._recording_stopped(exc)

    def _send(self, blocks: list[np.ndarray]) -> None:
        """Publish the CDR bytes straight through rclpy's publisher handles (held for the
        batch, as ``Publisher.publish`` holds its own for each message). A reliable subscriber
        too slow for an accelerated run makes DDS refuse the write after blocking: the
        message is dropped and counted, the node goes on."""
        publishers = [self._pub[name] for name in self._output_names]
        with contextlib.ExitStack() as held:
            for publisher in publishers:
                held.enter_context(publisher.handle)
            sends = [publisher.handle.publish_raw for publisher in publishers]
            for row in zip(*map(cdr.messages, blocks)):
                for send, data, publisher in zip(sends, row, publishers):
                    try:
                        send(data)
                    except _rclpy.RCLError as exc:
                        self._dropped(publisher.topic_name, exc)

    def _dropped(self, topic: str, exc: Exception) -> None:
        self.dropped += 1
        if self.dropped == 1 or self.dropped % 1000 == 0:
            self.get_logger().warning(f"{self.dropped} message(s) dropped, e.g. on {topic} "
                                      f"({str(exc).split(',')[0]}): a subscriber cannot keep up; lower "
                                      f"real_time_factor or publish_rate_hz")


def main(args: list[str] | None = None) -> int:
    """``fowt-sim node [--ros-args ...]``: run the node until stopped or its duration is done;
    the exit code as the module says (0 complete or stopped, 1 cut short or incomplete, 2 bad input)."""
    logging.basicConfig(level=logging.INFO, format="[%(levelname)s] [%(name)s]: %(message)s")
    log = logging.getLogger("fowt_hydro_sim")
    try:
        init_ros(args)
        node = SimulatorNode()
    except KeyboardInterrupt:  # stopped while starting: nothing was stepped
        log.error("fowt-sim node: interrupted while starting")
        rclpy.try_shutdown()
        return 130
    except Exception as exc:  # bad parameters, parameter file or platform: one line, no traceback
        log.error(f"fowt-sim node: {exc}".splitlines()[0])
        rclpy.try_shutdown()
        return 2
    executor = SingleThreadedExecutor()  # one executor: no wait set rebuilt at every spin
    executor.add_node(node)
    node.start()
    try:
        while rclpy.ok() and not node.finished:
            executor.spin_once(timeout_sec=0.1)
        node.wait_for_delivery()
        for _ in range(5):  # let the last messages go out
            executor.spin_once(timeout_sec=0.1)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        ignore_stop_signals()
        node.stop()
        executor.shutdown(timeout_sec=1.0)
        node.destroy_node()
        rclpy.try_shutdown()
    if node.incomplete:
        log.error(f"fowt-sim node: the run is incomplete: {node.incomplete} (exit code 1)")
    return 1 if node.recording_failed or node.incomplete else 0
