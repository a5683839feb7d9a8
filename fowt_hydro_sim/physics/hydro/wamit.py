"""WAMIT's dimensionless numeric output, read and redimensionalised as OpenFAST HydroDyn reads it.

HydroDyn's potential-flow model (PotMod 1) takes four WAMIT files by a common root name
(``PotFile``): ``.hst`` (hydrostatic restoring), ``.1`` (added mass and damping), ``.3``
(first-order excitation) and, for second-order loads, ``.12d`` (difference-frequency QTF). The
readers here follow HydroDyn's ``WAMIT.f90`` (``WAMIT_Init``) and ``WAMIT2.f90``:

- ``.1`` rows are ``PER I J Abar Bbar``; a period ``PER < 0`` is the zero-frequency limit and
  ``PER = 0`` the infinite-frequency limit, both with the added mass only (``PER I J Abar``; the
  damping is zero there). Entries WAMIT leaves out are zero. Frequencies are sorted ascending
  (``omega = 2 pi / PER``).
- ``.3`` rows are ``PER BETA I |Xbar| phase(deg) Re(Xbar) Im(Xbar)``, one block of headings per
  period, the same headings for every period; the complex value is taken from Re and Im (as
  HydroDyn does). Headings are sorted ascending.
- ``.hst`` rows are ``I J Cbar``.
- ``.12d`` rows are ``PER1 PER2 BETA1 BETA2 I |Fbar| phase(deg) Re(Fbar) Im(Fbar)``. WAMIT may
  write one triangle of the frequency pairs only; the other is filled from the difference-frequency
  QTF's symmetry ``F(w2, w1) = conj F(w1, w2)``.
- ``.ss`` (HydroDyn's ``SS_Radiation``, RdtnMod 2; written by WAMIT's SS_Fitting) is a state-space
  form of the radiation memory: a title line; the enabled-DOF flags (six 0/1 numbers); the number
  of states n; the states per DOF (six numbers summing to n); then A (n rows of n numbers), B
  (n rows of 6) and C (6 rows of n), dimensional (SI: no WAMITULEN, rho or g scaling, as HydroDyn
  reads them). Text after the numbers on the flag and count lines is a comment. The memory load
  is ``F = C x`` with ``dx/dt = A x + B v`` (v the body velocity), so ``C exp(A t) B`` stands for
  minus the retardation kernel.

Redimensionalisation (``L`` = HydroDyn's ``WAMITULEN``, ``rho`` = water density, ``g`` = gravity;
for 6N x 6N matrices the factor of element (i, j) is that of the 6 x 6 block position
(i mod 6, j mod 6); "trans" = DOF 1-3, "rot" = DOF 4-6)::

    quantity                 file   trans-trans      trans-rot / rot-trans   rot-rot
    restoring C              .hst   rho g L^2        rho g L^3               rho g L^4
    added mass A             .1     rho L^3          rho L^4                 rho L^5
    damping B                .1     rho w L^3        rho w L^4               rho w L^5

    quantity                          file   force (DOF 1-3)   moment (DOF 4-6)
    excitation X per unit amplitude   .3     rho g L^2         rho g L^3
    QTF per unit amplitude squared    .12d   rho g L           rho g L^2

Units of the results: C in N/m, N/rad, N m/m, N m/rad; A in kg, kg m, kg m^2; B in N s/m,
N s/rad, N m s/m, N m s/rad; X in N/m and N m/m (per metre of wave amplitude); the QTF in
N/m^2 and N m/m^2. Frames and signs are WAMIT's: the body frame at the WAMIT origin (``XBODY``),
x along heading 0 deg, z up; the excitation phase is that of ``Re(X e^{i w t})`` against the
incident wave elevation at the origin, ``Re(A e^{i w t})`` (WAMIT's time convention).

A malformed file raises :class:`WamitFormatError` whose one-line message names the file and the
line.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass
from pathlib import Path

import numpy as np

log = logging.getLogger(__name__)


class WamitFormatError(ValueError):
    """A WAMIT file that cannot be read; the message (one line) names the file and the line."""


@dataclass(frozen=True)
class Hydrostatics:
    """Hydrostatic restoring from a ``.hst`` file, redimensionalised.

    ``stiffness_si``: (6N, 6N) in N/m, N/rad, N m/m, N m/rad (see the module's table)."""

    stiffness_si: np.ndarray


@dataclass(frozen=True)
class Radiation:
    """Added mass and damping from a ``.1`` file, redimensionalised.

    ``omega_rad_s``: (n,) the finite, positive frequencies, ascending; ``added_mass_si`` and
    ``damping_si``: (n, 6N, 6N) at those frequencies; ``added_mass_zero_si`` and
    ``added_mass_inf_si``: (6N, 6N) the zero- and infinite-frequency limits (None when the file
    has no such rows; HydroDyn requires both)."""

    omega_rad_s: np.ndarray
    added_mass_si: np.ndarray
    damping_si: np.ndarray
    added_mass_zero_si: np.ndarray | None
    added_mass_inf_si: np.ndarray | None


@dataclass(frozen=True)
class Excitation:
    """First-order wave excitation from a ``.3`` file, redimensionalised.

    ``omega_rad_s``: (n,) ascending; ``heading_deg``: (m,) ascending; ``force_per_amplitude_si``:
    complex (n, m, 6N) in N/m (DOF 1-3) and N m/m (DOF 4-6)."""

    omega_rad_s: np.ndarray
    heading_deg: np.ndarray
    force_per_amplitude_si: np.ndarray


@dataclass(frozen=True)
class DifferenceQtf:
    """Difference-frequency quadratic transfer function from a ``.12d`` file, redimensionalised.

    ``omega_rad_s``: (n,) ascending; ``heading_pairs_deg``: (p, 2) the (BETA1, BETA2) pairs in the
    file; ``qtf_per_amplitude_squared_si``: complex (p, n, n, 6N) in N/m^2 (DOF 1-3) and N m/m^2
    (DOF 4-6), NaN where the file gives neither a pair nor its mirror."""

    omega_rad_s: np.ndarray
    heading_pairs_deg: np.ndarray
    qtf_per_amplitude_squared_si: np.ndarray

    def mean_drift(self) -> np.ndarray:
        """The mean-drift force per unit amplitude squared, (p, n, 6N): the real diagonal
        ``F(w, w)`` of each heading pair."""
        diagonal = np.diagonal(self.qtf_per_amplitude_squared_si, axis1=1, axis2=2)  # (p, 6N, n)
        return np.moveaxis(diagonal, -1, 1).real


@dataclass(frozen=True)
class StateSpaceRadiation:
    """The radiation memory in state-space form from a ``.ss`` file (one body, six DOFs):
    ``dx/dt = a x + b v``, ``F = c x``.

    ``a``: (n, n) in 1/s; ``b``: (n, 6); ``c``: (6, n), such that ``c exp(a t) b`` is in N/m,
    N/rad, N m/m, N m/rad per second (minus the retardation kernel); ``states_per_dof``: (6,)
    the file's count of states for each DOF."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    states_per_dof: np.ndarray


@dataclass(frozen=True)
class PotentialFlowData:
    """One body's WAMIT data set as HydroDyn reads it from ``PotFile`` (``.hst``, ``.1``, ``.3``;
    ``.12d`` when present)."""

    hydrostatics: Hydrostatics
    radiation: Radiation
    excitation: Excitation
    difference_qtf: DifferenceQtf | None


# --------------------------------------------------------------------------- scaling
def _block_power(index: np.ndarray) -> np.ndarray:
    """0 for a translation DOF (1-3 of each body), 1 for a rotation DOF (4-6), from 1-based
    indices."""
    return ((index - 1) % 6 >= 3).astype(int)


def _matrix_scale(n_dof: int, base: float, length_m: float, first_power: int) -> np.ndarray:
    """The (n_dof, n_dof) factors ``base * L^(first_power + rot_i + rot_j)``."""
    rot = _block_power(np.arange(1, n_dof + 1))
    return base * length_m ** (first_power + rot[:, None] + rot[None, :])


def _vector_scale(n_dof: int, base: float, length_m: float, first_power: int) -> np.ndarray:
    """The (n_dof,) factors ``base * L^(first_power + rot_i)``."""
    return base * length_m ** (first_power + _block_power(np.arange(1, n_dof + 1)))


def _check_constants(rho_kg_m3: float, g_m_s2: float, length_m: float) -> None:
    for name, value in (("water density", rho_kg_m3), ("gravity", g_m_s2), ("WAMITULEN", length_m)):
        if not np.isfinite(value) or value <= 0:
            raise ValueError(f"{name} must be a positive number, not {value!r}")


# --------------------------------------------------------------------------- parsing
def _rows(path: Path, widths: tuple[int, ...], index_columns: tuple[int, ...]) -> list[tuple[int, list[float]]]:
    """The numeric rows of ``path`` as (line number, values), each with one of ``widths``
    numbers (extra columns are refused); ``index_columns`` must hold positive integers."""
    try:
        text = path.read_text()
    except OSError as exc:
        raise WamitFormatError(f"{path}: cannot read ({exc.strerror or exc})") from None
    fast = _rows_fast(text, widths, index_columns)
    if fast is not None:
        return fast
    rows = []
    for number, line in enumerate(text.splitlines(), start=1):
        fields = line.split()
        if not fields:
            continue
        if len(fields) not in widths:
            expected = " or ".join(str(w) for w in widths)
            raise WamitFormatError(f"{path}:{number}: expected {expected} numbers, found {len(fields)}")
        try:
            values = [float(f.replace("D", "E").replace("d", "e")) for f in fields]
        except ValueError:
            bad = next(f for f in fields if not _is_number(f))
            raise WamitFormatError(f"{path}:{number}: {bad!r} is not a number") from None
        if not all(np.isfinite(values)):
            raise WamitFormatError(f"{path}:{number}: a value is not finite")
        for c in index_columns:
            if values[c] != int(values[c]) or values[c] < 1:
                raise WamitFormatError(f"{path}:{number}: DOF index {fields[c]!r} is not a positive integer")
        rows.append((number, values))
    if not rows:
        raise WamitFormatError(f"{path}: no data")
    return rows


def _rows_fast(text: str, widths: tuple[int, ...],
               index_columns: tuple[int, ...]) -> list[tuple[int, list[float]]] | None:
    """:func:`_rows` for a well-formed file in one numpy conversion; None when any line needs
    the line-by-line checks (which then name it)."""
    numbered = [(number, line.split()) for number, line in enumerate(text.splitlines(), start=1)]
    numbered = [(number, fields) for number, fields in numbered if fields]
    if not numbered or any(len(fields) not in widths for _, fields in numbered):
        return None
    try:
        flat = np.array([f for _, fields in numbered for f in fields], dtype=float)
    except ValueError:
        return None
    if not np.all(np.isfinite(flat)):
        return None
    values = flat.tolist()
    rows, start = [], 0
    for number, fields in numbered:
        row = values[start:start + len(fields)]
        start += len(fields)
        if any(row[c] != int(row[c]) or row[c] < 1 for c in index_columns):
            return None
        rows.append((number, row))
    return rows


def _is_number(field: str) -> bool:
    try:
        float(field.replace("D", "E").replace("d", "e"))
    except ValueError:
        return False
    return True


def _n_dof(path: Path, rows: list[tuple[int, list[float]]], index_columns: tuple[int, ...]) -> int:
    n = int(max(values[c] for _, values in rows for c in index_columns))
    n_dof = 6 * -(-n // 6)
    log.debug("%s: %d DOF", path, n_dof)
    return n_dof


# --------------------------------------------------------------------------- readers
def read_hst(path: Path | str, rho_kg_m3: float, g_m_s2: float, length_m: float = 1.0) -> Hydrostatics:
    """The hydrostatic restoring matrix of a WAMIT ``.hst`` file, in SI units (``length_m`` is
    HydroDyn's WAMITULEN)."""
    path = Path(path)
    _check_constants(rho_kg_m3, g_m_s2, length_m)
    rows = _rows(path, (3,), (0, 1))
    n_dof = _n_dof(path, rows, (0, 1))
    c = np.zeros((n_dof, n_dof))
    for _, (i, j, value) in rows:
        c[int(i) - 1, int(j) - 1] = value
    return Hydrostatics(stiffness_si=c * _matrix_scale(n_dof, rho_kg_m3 * g_m_s2, length_m, 2))


def read_1(path: Path | str, rho_kg_m3: float, length_m: float = 1.0) -> Radiation:
    """Added mass and damping of a WAMIT ``.1`` file, in SI units, sorted by frequency."""
    path = Path(path)
    _check_constants(rho_kg_m3, 1.0, length_m)
    rows = _rows(path, (4, 5), (1, 2))
    n_dof = _n_dof(path, rows, (1, 2))
    finite: dict[float, tuple[np.ndarray, np.ndarray]] = {}
    limits: dict[str, np.ndarray] = {}
    for number, values in rows:
        period, i, j = values[0], int(values[1]) - 1, int(values[2]) - 1
        if period <= 0:
            if len(values) != 4:
                raise WamitFormatError(f"{path}:{number}: a zero- or infinite-frequency row holds "
                                       "PER I J A (4 numbers)")
            limits.setdefault("zero" if period < 0 else "inf", np.zeros((n_dof, n_dof)))[i, j] = values[3]
            continue
        if len(values) != 5:
            raise WamitFormatError(f"{path}:{number}: a finite-frequency row holds PER I J A B (5 numbers)")
        a, b = finite.setdefault(period, (np.zeros((n_dof, n_dof)), np.zeros((n_dof, n_dof))))
        a[i, j], b[i, j] = values[3], values[4]
    if not finite:
        raise WamitFormatError(f"{path}: no finite-frequency rows")
    periods = np.array(sorted(finite, reverse=True))  # ascending frequency
    omega = 2 * np.pi / periods
    scale = _matrix_scale(n_dof, rho_kg_m3, length_m, 3)
    added_mass = np.stack([finite[p][0] for p in periods]) * scale
    damping = np.stack([finite[p][1] for p in periods]) * scale * omega[:, None, None]
    zero, inf = limits.get("zero"), limits.get("inf")
    return Radiation(omega_rad_s=omega, added_mass_si=added_mass, damping_si=damping,
                     added_mass_zero_si=None if zero is None else zero * scale,
                     added_mass_inf_si=None if inf is None else inf * scale)


def read_3(path: Path | str, rho_kg_m3: float, g_m_s2: float, length_m: float = 1.0) -> Excitation:
    """First-order excitation per unit wave amplitude of a WAMIT ``.3`` file, in SI units,
    sorted by frequency and heading."""
    path = Path(path)
    _check_constants(rho_kg_m3, g_m_s2, length_m)
    rows = _rows(path, (7,), (2,))
    n_dof = _n_dof(path, rows, (2,))
    table: dict[float, dict[float, np.ndarray]] = {}
    first_line: dict[float, int] = {}
    for number, (period, heading, i, _mod, _phase, re, im) in rows:
        if period <= 0:
            raise WamitFormatError(f"{path}:{number}: period {period:g} s: excitation needs a finite frequency")
        first_line.setdefault(period, number)
        table.setdefault(period, {}).setdefault(heading, np.zeros(n_dof, complex))[int(i) - 1] = complex(re, im)
    headings = sorted(next(iter(table.values())))
    for period, by_heading in table.items():
        if sorted(by_heading) != headings:
            raise WamitFormatError(f"{path}:{first_line[period]}: period {period:g} s has headings "
                                   f"{sorted(by_heading)}, not those of the first period {headings}")
    periods = sorted(table, reverse=True)
    force = np.array([[table[p][h] for h in headings] for p in periods])
    return Excitation(omega_rad_s=2 * np.pi / np.array(periods), heading_deg=np.array(headings),
                      force_per_amplitude_si=force * _vector_scale(n_dof, rho_kg_m3 * g_m_s2, length_m, 2))


def read_12d(path: Path | str, rho_kg_m3: float, g_m_s2: float, length_m: float = 1.0) -> DifferenceQtf:
    """The difference-frequency QTF of a WAMIT ``.12d`` file, in SI units; the missing triangle
    of frequency pairs is filled by conjugate symmetry."""
    path = Path(path)
    _check_constants(rho_kg_m3, g_m_s2, length_m)
    rows = _rows(path, (9,), (4,))
    n_dof = _n_dof(path, rows, (4,))
    for number, values in rows:
        if values[0] <= 0 or values[1] <= 0:
            raise WamitFormatError(f"{path}:{number}: periods must be positive")
    periods = sorted({v[0] for _, v in rows} | {v[1] for _, v in rows}, reverse=True)
    where = {p: k for k, p in enumerate(periods)}
    pairs = sorted({(v[2], v[3]) for _, v in rows})
    pair_at = {p: k for k, p in enumerate(pairs)}
    qtf = np.full((len(pairs), len(periods), len(periods), n_dof), np.nan + 0j)
    for _, (p1, p2, b1, b2, i, _mod, _phase, re, im) in rows:
        qtf[pair_at[(b1, b2)], where[p1], where[p2], int(i) - 1] = complex(re, im)
    mirror = np.conj(np.swapaxes(qtf, 1, 2))
    qtf = np.where(np.isnan(qtf), mirror, qtf)
    scale = _vector_scale(n_dof, rho_kg_m3 * g_m_s2, length_m, 1)
    return DifferenceQtf(omega_rad_s=2 * np.pi / np.array(periods), heading_pairs_deg=np.array(pairs),
                         qtf_per_amplitude_squared_si=qtf * scale)


def _leading_integers(path: Path, number: int, line: str, count: int, what: str) -> list[int]:
    """The first ``count`` fields of ``line`` as integers (the rest is a comment)."""
    fields = line.split()[:count]
    try:
        values = [float(f.replace("D", "E").replace("d", "e")) for f in fields]
    except ValueError:
        values = []
    if len(values) != count or any(v != int(v) or v < 0 for v in values):
        raise WamitFormatError(f"{path}:{number}: expected {what} ({count} non-negative integers)")
    return [int(v) for v in values]


def read_ss(path: Path | str) -> StateSpaceRadiation:
    """The state-space radiation matrices of a ``.ss`` file (module docstring), checked as
    HydroDyn's ``SS_Rad_Init`` checks them: the states per DOF sum to the number of states and
    the matrices have that many rows. The model moves all six DOFs, so each must be enabled in
    the file (HydroDyn refuses a file lacking a DOF its run enables)."""
    path = Path(path)
    try:
        lines = path.read_text().splitlines()
    except OSError as exc:
        raise WamitFormatError(f"{path}: cannot read ({exc.strerror or exc})") from None
    numbered = [(k, line) for k, line in enumerate(lines, start=1)]
    body = [(k, line) for k, line in numbered[1:] if line.split()]
    if len(body) < 3:
        raise WamitFormatError(f"{path}: expected a title, the DOF flags, the number of states and the states "
                               "per DOF before the matrices")
    (k_flags, flags_line), (k_n, n_line), (k_per, per_line) = body[:3]
    flags = _leading_integers(path, k_flags, flags_line, 6, "the enabled-DOF flags")
    if flags != [1] * 6:
        raise WamitFormatError(f"{path}:{k_flags}: DOF flags {flags}: the model moves all six DOFs, the file must "
                               "enable them all (1 1 1 1 1 1)")
    (n,) = _leading_integers(path, k_n, n_line, 1, "the number of states")
    per_dof = _leading_integers(path, k_per, per_line, 6, "the states per DOF")
    if n < 1 or sum(per_dof) != n:
        raise WamitFormatError(f"{path}:{k_per}: the states per DOF {per_dof} do not sum to the number of states {n}")
    rows = body[3:]
    if len(rows) != 2 * n + 6:
        raise WamitFormatError(f"{path}: {len(rows)} matrix rows; {n} states need {2 * n + 6} (A {n}, B {n}, C 6)")
    matrices = []
    for start, count, width, name in ((0, n, n, "A"), (n, n, 6, "B"), (2 * n, 6, n, "C")):
        block = np.zeros((count, width))
        for r, (number, line) in enumerate(rows[start:start + count]):
            fields = line.split()
            if len(fields) != width:
                raise WamitFormatError(f"{path}:{number}: a row of {name} holds {width} numbers, found {len(fields)}")
            try:
                block[r] = [float(f.replace("D", "E").replace("d", "e")) for f in fields]
            except ValueError:
                bad = next(f for f in fields if not _is_number(f))
                raise WamitFormatError(f"{path}:{number}: {bad!r} is not a number") from None
            if not np.all(np.isfinite(block[r])):
                raise WamitFormatError(f"{path}:{number}: a value is not finite")
        matrices.append(block)
    a, b, c = matrices
    return StateSpaceRadiation(a=a, b=b, c=c, states_per_dof=np.array(per_dof))


def read_potential_flow(root: Path | str, rho_kg_m3: float, g_m_s2: float,
                        length_m: float = 1.0) -> PotentialFlowData:
    """HydroDyn's ``PotFile`` set: ``root`` + ``.hst``, ``.1``, ``.3`` (and ``.12d`` when it exists),
    checked as HydroDyn checks them: the ``.1`` file has both the zero- and infinite-frequency
    limits, and the ``.3`` file has the ``.1`` file's finite frequencies."""
    root = Path(root)
    one = root.with_name(root.name + ".1")
    radiation = read_1(one, rho_kg_m3, length_m)
    if radiation.added_mass_zero_si is None or radiation.added_mass_inf_si is None:
        raise WamitFormatError(f"{one}: needs both the zero-frequency (period < 0) and the infinite-frequency "
                               "(period 0) added mass")
    three = root.with_name(root.name + ".3")
    excitation = read_3(three, rho_kg_m3, g_m_s2, length_m)
    if (excitation.omega_rad_s.shape != radiation.omega_rad_s.shape
            or not np.allclose(excitation.omega_rad_s, radiation.omega_rad_s, rtol=1e-9)):
        raise WamitFormatError(f"{three}: its frequencies differ from those of {one.name} (not the same WAMIT run)")
    twelve = root.with_name(root.name + ".12d")
    return PotentialFlowData(
        hydrostatics=read_hst(root.with_name(root.name + ".hst"), rho_kg_m3, g_m_s2, length_m),
        radiation=radiation, excitation=excitation,
        difference_qtf=read_12d(twelve, rho_kg_m3, g_m_s2, length_m) if twelve.exists() else None)


# --------------------------------------------------------------------------- writer
def write_1(path: Path | str, radiation: Radiation, rho_kg_m3: float, length_m: float = 1.0) -> None:
    """Write ``radiation`` (SI units) as a WAMIT ``.1`` file, nondimensionalised by the module's
    table: the zero-frequency limit as period -1, the infinite-frequency limit as period 0 (when
    given), then the finite frequencies in ascending order; every matrix element is written."""
    _check_constants(rho_kg_m3, 1.0, length_m)
    n_dof = radiation.added_mass_si.shape[-1]
    scale = _matrix_scale(n_dof, rho_kg_m3, length_m, 3)
    lines = []
    for period, limit in ((-1.0, radiation.added_mass_zero_si), (0.0, radiation.added_mass_inf_si)):
        if limit is not None:
            lines += [f"{period:16.8E} {i + 1:5d} {j + 1:5d} {limit[i, j] / scale[i, j]:16.8E}"
                      for i in range(n_dof) for j in range(n_dof)]
    for k, omega in enumerate(radiation.omega_rad_s):
        a = radiation.added_mass_si[k] / scale
        b = radiation.damping_si[k] / (scale * omega)
        lines += [f"{2 * np.pi / omega:16.8E} {i + 1:5d} {j + 1:5d} {a[i, j]:16.8E} {b[i, j]:16.8E}"
                  for i in range(n_dof) for j in range(n_dof)]
    Path(path).write_text("\n".join(lines) + "\n")


def write_hst(path: Path | str, hydrostatics: Hydrostatics, rho_kg_m3: float, g_m_s2: float,
              length_m: float = 1.0) -> None:
    """Write ``hydrostatics`` (SI units) as a WAMIT ``.hst`` file: ``I J C/(rho g L^k)``, every
    element."""
    _check_constants(rho_kg_m3, g_m_s2, length_m)
    c = hydrostatics.stiffness_si
    n_dof = c.shape[0]
    c = c / _matrix_scale(n_dof, rho_kg_m3 * g_m_s2, length_m, 2)
    Path(path).write_text("".join(f"{i + 1:6d}{j + 1:6d} {c[i, j]:16.8E}\n" for i in range(n_dof)
                                  for j in range(n_dof)))


def write_3(path: Path | str, excitation: Excitation, rho_kg_m3: float, g_m_s2: float, length_m: float = 1.0) -> None:
    """Write ``excitation`` (SI units, WAMIT's time convention) as a WAMIT ``.3`` file: ``PER BETA I
    |X| phase(deg) Re(X) Im(X)`` nondimensionalised, the frequencies ascending, every heading for
    every frequency."""
    _check_constants(rho_kg_m3, g_m_s2, length_m)
    force = excitation.force_per_amplitude_si
    n_dof = force.shape[-1]
    scale = _vector_scale(n_dof, rho_kg_m3 * g_m_s2, length_m, 2)
    lines = []
    for k, omega in enumerate(excitation.omega_rad_s):
        for b, heading in enumerate(excitation.heading_deg):
            x = force[k, b] / scale
            lines += [f"{2 * np.pi / omega:16.8E} {heading:16.8E} {i + 1:5d} {abs(x[i]):16.8E} "
                      f"{np.degrees(np.angle(x[i])):16.8E} {x[i].real:16.8E} {x[i].imag:16.8E}" for i in range(n_dof)]
    Path(path).write_text("\n".join(lines) + "\n")
