"""The falling chain of n rigid rods, from the Rust core.

A chain hangs in a "U" between two anchors; at t = 0 one end is released.
Load a scene (``Scene.load("scenes/span-d3.toml")``), change it
(``scene.set("chain.links", 100)``), run it (``simulate(scene)`` returns a
``Run`` whose arrays are numpy), sweep a key
(``sweep(scene, {"start.p1.0": [1, 2, 3]})``) or solve the hanging chain
(``catenary``); ``view(runs, path)`` writes runs as one HTML page that
plays them (a ``Run`` shows as that page in Jupyter). Errors are ValueErrors with the CLI's one-line message
naming the field. Runs and sweeps release the GIL, and Ctrl-C stops them:
they raise KeyboardInterrupt within a fraction of a second.
"""

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str
__all__: List[str]

_Float = npt.NDArray[np.float64]
_Value = Union[str, bool, int, float, Sequence[Any], Mapping[str, Any], np.generic]

class Scene:
    """A scene: a chain, how it starts and how to run it (the TOML files of
    ``scenes/``, described in ``scenes/README.md``).

    Loading and ``set`` check keys and types as the CLI does; ranges are
    checked when the scene runs, or by ``check()``. Errors are ValueErrors
    whose message is the CLI's one line, starting with the field.
    """

    @staticmethod
    def load(path: Union[str, os.PathLike[str]]) -> Scene:
        """Reads a scene file. A scene without ``name`` is named after the file."""
    @staticmethod
    def from_toml(text: str) -> Scene:
        """Parses a scene from TOML text (at most 1 MiB, as a scene file). A
        scene without ``name`` is named "scene"."""
    @overload
    def set(self, key: str, value: _Value) -> Scene: ...
    @overload
    def set(self, key: Mapping[str, _Value]) -> Scene: ...
    def set(self, key: Union[str, Mapping[str, _Value]], value: Optional[_Value] = None) -> Scene:
        """A new scene with the value at the dotted ``key`` replaced, as
        ``--set KEY=VALUE`` does; or, given one dict, several values at once,
        applied in order and checked together
        (``scene.set({"start.kind": "angles", "start.angles": phi})``).
        A ``str`` value is read as the text after ``=`` in ``--set``;
        numbers, bools, sequences (iterators too) and dicts are taken as they
        are. Setting ``start.kind`` removes the ``[start]`` keys the new kind
        does not take, so a start changes kind with its own keys in one call.
        A dict holds at most 1000 keys.

        The value is bounded before it is read whole: a list, iterator or
        dict holds at most 1000000 items (``start.angles`` at
        ``chain.links``' cap), the whole value at most 2001000, it nests at
        most 8 deep, and a ``str`` is at most 32 MiB. Past a bound (an
        endless iterator such as ``itertools.count()``, a list that contains
        itself) it raises ValueError naming the key."""
    def unset(self, key: str) -> Scene:
        """A new scene without the value at the dotted ``key``, which takes
        its default again; ValueError naming the key for an unknown key, an
        element or a key that must be given (``chain.links``)."""
    def refine(self, n: int) -> Scene:
        """The same continuous chain cut into ``n`` rods (1..=1000000), as
        ``converge`` and ``--refine N`` refine: total mass, length, the
        bending viscosity ``eta = r l``, EA, EI and the tip mass kept, so the
        per-rod ``chain.mass`` and ``chain.damping`` change (``set("chain.links",
        n)`` keeps them, which is not a refinement). A folded start's
        ``start.down`` scales with n; an ``angles`` start raises ValueError."""
    def to_toml(self) -> str:
        """The scene as TOML text (with every ``set`` applied; defaults left out)."""
    def to_dict(self) -> Dict[str, Any]:
        """The scene's TOML tree as a dict (defaults left out)."""
    def check(self) -> None:
        """Checks everything a run needs; raises ValueError naming the field."""
    @property
    def name(self) -> str:
        """The scene's name."""
    @property
    def description(self) -> str:
        """What the scene is (free text)."""
    def __eq__(self, other: object) -> bool: ...

class Run:
    """A finished run: its summary and its samples as read-only float64 arrays.

    A run that failed holds what it computed up to ``summary["t_reached"]``;
    its ``status`` says how it failed.
    """

    @property
    def summary(self) -> Dict[str, Any]:
        """The ``simulate --json`` object as a dict. Among its work counters,
        ``error_test_failures``, ``newton_failures`` (the rejected attempts
        by cause) and ``newton_iterations`` are the implicit methods' (bdf,
        bdf-dense; 0 for the explicit ones)."""
    @property
    def t(self) -> _Float:
        """Sample times, shape (samples,)."""
    @property
    def phi(self) -> _Float:
        """Angles phi_1..phi_n from the horizontal (rad), shape (samples, n)."""
    @property
    def w(self) -> _Float:
        """Angular rates w_1..w_n, shape (samples, n)."""
    @property
    def tip(self) -> _Float:
        """Position of the free end, shape (samples, 2)."""
    @property
    def tip_velocity(self) -> _Float:
        """Velocity of the free end, shape (samples, 2)."""
    @property
    def energy(self) -> _Float:
        """Energy T + V (+ U_bend, + U_elastic), shape (samples,)."""
    @property
    def forces(self) -> _Float:
        """Joint forces, shape (samples, n + 1, 2): joint 0 is the pivot,
        joint n the free tip (zero); each [tension, shear] in the frame of
        the rod after the joint (tension > 0 pulls it back toward the
        pivot; shear along its normal). Force units."""
    @property
    def floor_forces(self) -> Optional[_Float]:
        """The floor's force at each joint, shape (samples, n + 1, 2), each
        [fx, fy] in the scene's axes (fy > 0 pushes up; force units): joint
        j gathers the contacts at rod j's start and rod j - 1's end; summed
        over the joints, what a scale under the chain reads (``simulate
        --forces``'s columns floor_x_k, floor_y_k). None without a floor."""
    @property
    def floor_force(self) -> Optional[_Float]:
        """The floor's total force on the chain, shape (samples, 2), [fx, fy]
        in the scene's axes (fy > 0 pushes up): what a scale under the chain
        reads (``simulate --out``'s floor_x, floor_y), read at the samples
        (a stiff floor's contacts are impulses far shorter than
        ``output_dt``). None without a floor."""
    @property
    def landed_weight(self) -> Optional[_Float]:
        """The weight of what the floor pushes, shape (samples,): g m_i / 2
        per contact point with a force (``simulate --out``'s
        landed_weight). None without a floor."""
    @property
    def landed_length(self) -> Optional[_Float]:
        """The length of chain that has landed, shape (samples,): l_i / 2 per
        end of rod i at most one rod length above the floor line (or in it),
        read off the rods' ends, not the contact forces; on Cayley's chain it
        follows the free fall's g t^2 / 2 to two rods up to half the chain
        landed; rods thrown higher than a rod are not counted. None without a
        floor."""
    @property
    def pivot_force(self) -> _Float:
        """The support's force on the first rod, shape (samples, 2), [fx, fy]
        in the scene's axes ([0, M g] for a chain hanging at rest); zero once
        the pivot is let go. ``forces[:, 0, :]`` is the same force in the
        rod's frame."""
    @property
    def dissipated(self) -> _Float:
        """``W`` of the energy balance ``E + W = E(0)`` since t = 0, shape
        (samples,) (the summary's ``dissipated``): with a fixed pivot, the
        work dissipated by joint friction (and elastic links' dashpots);
        with a moving pivot, that work less the support's,
        ``friction_work - support_work`` (it may be negative)."""
    @property
    def support_work(self) -> _Float:
        """The work the support has done on the chain since t = 0, shape
        (samples,): ``F_0 . P0'`` (the pivot's force on rod 1 times its
        velocity) by the trapezoid rule over the samples. Zero for a fixed
        pivot and once it is let go."""
    @property
    def friction_work(self) -> _Float:
        """The work dissipated by joint friction alone since t = 0 (and
        elastic links' dashpots), shape (samples,): ``dissipated +
        support_work``; exactly ``dissipated`` with a fixed pivot."""
    @property
    def links(self) -> int:
        """The number of rods n."""
    @property
    def status(self) -> str:
        """``ok``, or how the run failed (the same as ``summary["status"]``):
        ``diverged``, ``step_size_too_small``, ``max_steps``,
        ``linear_solve_failed``, ``inaccurate`` (it reached ``t_end``, but
        its energy balance error exceeds the chain's energy scale: the
        numbers are not a solution) or ``interrupted``."""
    @property
    def scene(self) -> Scene:
        """The scene that ran (with the keyword flags of ``simulate`` applied)."""
    def joints(self, k: int) -> _Float:
        """The joints r_0 = P0 .. r_n (the tip) at sample ``k``, shape (n + 1, 2)."""
    @property
    def rod_lengths(self) -> _Float:
        """Each rod's length l_1..l_n (length unit), pivot to tip, shape
        (n,): ``chain.length / n`` each for equal rods, else as the profile
        (``chain.taper``, ``chain.rod_masses``, ``chain.rod_lengths``)
        shares the length; they sum to ``chain.length``."""
    @property
    def rod_masses(self) -> _Float:
        """Each rod's mass m_1..m_n (mass unit), pivot to tip, shape (n,):
        ``chain.mass`` each for equal rods, else as the profile shares the
        chain's mass ``n chain.mass``."""
    def __len__(self) -> int: ...
    def _repr_html_(self) -> str:
        """The run as ``falling-chain view``'s page (play, scrub, the tip
        speed and energy balance, the summary) in an ``<iframe srcdoc>``:
        what Jupyter shows for a ``Run``, its data within the page's 1.8 MB.
        A chain of more rods than ``view`` draws (10^4; 5000 unequal rods)
        shows as a short text saying why."""

def simulate(
    scene: Scene,
    *,
    method: Optional[str] = None,
    dt: Optional[float] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    t_end: Optional[float] = None,
    output_dt: Optional[float] = None,
) -> Run:
    """Runs ``scene`` (as ``falling-chain simulate SCENE --json``) and returns
    its ``Run``. The keywords override ``run.method``, ``run.dt``,
    ``run.rtol``, ``run.atol``, ``run.t_end`` and ``run.output_dt``. Bad
    input raises ValueError; a failed run does not raise. Releases the GIL;
    Ctrl-C stops the run within a fraction of a second and raises
    KeyboardInterrupt (no run is returned)."""

def sweep(
    scene: Scene,
    vary: Dict[str, Union[str, Sequence[Any], npt.ArrayLike]],
    *,
    method: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    shard: Optional[Union[str, Tuple[int, int]]] = None,
    jobs: Optional[int] = None,
) -> Dict[str, np.ndarray]:
    """Runs ``scene`` once per value of the keys in ``vary`` (several keys: the
    product), in parallel, and returns the rows of ``falling-chain sweep
    --out`` as numpy columns named as its CSV header. A ``str`` value is
    ``--vary`` syntax (``"0.3:5.97:120"``); a sequence or iterator holds at
    most 1000000 values, and the product at most 1000000 runs. ``jobs`` is
    1 to 256 (default: the machine's cores). Bad input raises ValueError
    naming the field, before any run. Releases the GIL; Ctrl-C stops the
    sweep (no run starts, runs in progress stop) within a fraction of a
    second and raises KeyboardInterrupt (no rows are returned)."""

def catenary(
    p0: Sequence[float],
    p1: Sequence[float],
    length: float,
    links: Optional[int] = None,
) -> Dict[str, Any]:
    """The hanging chain between ``p0`` and ``p1`` (``catenary --json``): ``a``,
    ``x0``, ``c``, ``vertex``, ``lowest_point`` and, with ``links`` (at most
    1000000, as ``chain.links``), ``angles`` (numpy), ``joints`` (numpy),
    ``end_error``, ``alpha``, ``beta``. Raises ValueError naming the input."""

def precision(
    scene: Scene,
    *,
    methods: Optional[Union[str, Sequence[str]]] = None,
    check_dt: Optional[float] = None,
    richardson: bool = False,
    budget: Optional[float] = None,
    shard: Optional[Union[str, Tuple[int, int]]] = None,
    jobs: Optional[int] = None,
    measure: Union[str, Sequence[str], None] = None,
) -> Dict[str, np.ndarray]:
    """The work-precision table of ``scene`` (the columns of ``falling-chain
    precision --out``): the DOPRI5 reference (rtol 1e-13) and its RK4 and BDF
    checks first (``run`` NaN), then every method (or ``methods``) across
    tolerances, RK4 across steps: ``status``, the work (``steps``,
    ``rhs_evals``, ``rhs_equiv``, ...), ``err_tip`` (over L) and ``err_vmax``
    (relative), ``wall_seconds``. ``check_dt`` (default 1e-4, at most 1e7
    RK4 steps: in [t_end / 1e7, t_end], 3 t_end / 1e7 with Richardson) and
    ``richardson`` set the RK4 check; ``budget`` (seconds) holds in every
    phase, the reference and its checks too: it skips or stops what is past
    it, each row's ``note`` saying so; ``methods`` names at least one
    method; ``shard`` runs only its points (join with ``merge``); ``jobs``
    is 1 to 256. Releases the GIL; Ctrl-C raises KeyboardInterrupt in every
    phase; bad input raises ValueError naming the argument."""

def stability(
    scene: Scene,
    *,
    methods: Optional[Union[str, Sequence[str]]] = None,
    vary: Optional[Dict[str, Union[str, Sequence[Any], npt.ArrayLike]]] = None,
    budget: Optional[float] = None,
    shard: Optional[Union[str, Tuple[int, int]]] = None,
    jobs: Optional[int] = None,
    measure: Union[str, Sequence[str], None] = None,
) -> Dict[str, np.ndarray]:
    """Where each method fails on ``scene`` (the columns of ``falling-chain
    stability --out``): every method (or ``methods``) at every step or
    tolerance, run to the end with at most 2e5 steps: ``outcome``,
    ``status``, ``t_reached``, ``energy_error_rel``, ``wall_seconds``.
    ``vary`` (one key: at most 1000 values) makes a row per value.
    ``budget``, ``shard`` and ``jobs`` as in ``precision``."""

def needs(
    scene: Scene,
    tol: float,
    *,
    links: Optional[Union[str, Sequence[int]]] = None,
    methods: Optional[Union[str, Sequence[str]]] = None,
    budget: Optional[float] = None,
    jobs: Optional[int] = None,
    measure: Union[str, Sequence[str], None] = None,
) -> Dict[str, Any]:
    """What ``scene`` needs at ``tol`` (``falling-chain needs --json``):
    ``links`` (the smallest n whose tip path, tip end and maximum tip speed
    agree with the finest of the ``links`` ladder, default 25 to 400, or
    None), ``fastest`` and ``least_work`` (method, ``param_name``, ``param``,
    ``error``, ``rhs_equiv``, ``wall_seconds``), ``methods``, ``terms`` (per
    optional term: ``on``, ``needed``, ``tip_path``, ``tip_speed_max``) and
    ``ladder`` (converge's report), ``skipped`` (what ``budget``, which
    holds in every phase, stopped), ``reference_status``,
    ``method_runs`` (per method: ``points``, ``ran``, ``budget``) and
    ``one_method`` (on a constraint floor its one method, moreau-jean at
    ``run.dt``, with no method study; else None). Releases
    the GIL; Ctrl-C raises KeyboardInterrupt."""

def ensemble(
    scene: Scene,
    *,
    members: int = 16,
    spread: float = 1e-3,
    seed: int = 0,
    budget: Optional[float] = None,
    jobs: Optional[int] = None,
    measure: Union[str, Sequence[str], None] = None,
) -> Dict[str, Any]:
    """``scene`` run from ``members`` starts whose rod angles are each moved
    by a number drawn uniformly from ``[-spread, spread]`` rad (``seed``
    chooses the draws, the same on every machine): ``falling-chain ensemble
    --json`` as a dict: ``members``, ``spread``, ``seed``, ``ok`` (members
    that ended ok), ``stats`` (per quantity: ``mean``, ``sd``, ``sem``,
    ``min``, ``max``, ``count``, over the members that ended ok; the
    quantities ``tip_speed_max``, ``t_tip_speed_max``, ``tip_end_x``,
    ``tip_end_y``, ``energy_end``, ``dissipated``, ``floor_force_max`` with a
    floor, ``steps``) and ``failures``. ``members`` in 2..=4096, ``spread``
    in [0, 0.1] (ValueError naming it otherwise). Releases the GIL; Ctrl-C
    raises KeyboardInterrupt."""

def ensemble_series(
    scene: Scene,
    *,
    members: int = 16,
    spread: float = 1e-3,
    seed: int = 0,
    budget: Optional[float] = None,
    jobs: Optional[int] = None,
) -> Dict[str, Any]:
    """``scene`` run as ``ensemble`` runs it, and the statistics over the
    members that ended ok of every output at each output time (the members
    share them): ``falling-chain ensemble --out-series`` as a dict. ``t``
    (times,); ``members`` (how many are in the statistics); ``series``, by
    output (``tip_x``, ``tip_y``, ``tip_vx``, ``tip_vy``, ``tip_speed``,
    ``energy``, ``dissipated``, ``pivot_x``, ``pivot_y``, and with a floor
    ``floor_x``, ``floor_y``, ``landed_weight``, ``landed_length``), a dict
    of arrays ``mean``, ``sem``, ``sd``, ``min``, ``max``, each (times,); and
    ``ensemble``, what ``ensemble`` returns for the same arguments. The same
    on any number of ``jobs``, bit for bit. ValueError as ``ensemble``, and
    naming ``members`` when the series would take more than 1 GiB. Releases
    the GIL; Ctrl-C raises KeyboardInterrupt."""

def merge(paths: Sequence[Union[str, "os.PathLike[str]"]]) -> Dict[str, np.ndarray]:
    """Joins the ``--out`` tables of a sharded sweep, precision or stability
    into the whole table, as numpy columns; ValueError (``merge: ...``) for
    a missing or repeated run, a row not run within its shard's budget, or
    shards of another scene or options. ``paths`` is a list: one path alone
    raises TypeError naming ``paths``."""

def methods() -> List[str]:
    """The names of the integration methods ``run.method`` accepts."""

def view(runs: Union[Run, Sequence[Run]], path: Union[str, os.PathLike[str]]) -> os.PathLike[str]:
    """Writes ``runs`` (one ``Run`` or 1 to 8) as one self-contained HTML page
    at ``path`` (``FILE.html``, ending in ``.html`` exactly), as ``falling-chain view`` does: the chains to
    scale and overlaid, play, pause and scrub, the tip speed and the energy
    balance, each run's summary. Long runs are thinned (the page says so).
    Returns ``path`` as a ``pathlib.Path``. Bad input raises ValueError naming
    ``runs`` or ``path``, and nothing is written."""
