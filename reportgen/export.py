"""Export of a Study: every table as CSV and every scalar into scalars.json (written atomically)."""
from __future__ import annotations

import csv
import io
import json
import math
import os
import tempfile
from pathlib import Path
from typing import Iterable

import numpy as np
import pandas as pd

from .analysis.link_motion import link_motion
from .analysis.study import Study
from .errors import CaseError


def atomic_write(path: Path, data: bytes | str) -> None:
    """Write to a temporary file in the same folder, then rename (never a half-written file)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix="." + path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode("utf-8") if isinstance(data, str) else data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _csv(df: pd.DataFrame) -> str:
    """The table as CSV text, numbers with 17 significant digits (``%.17g``: every float64 read
    back exactly). A table of finite float64 columns only (the cycle tables: about 10⁶ cells) is
    formatted row by row with one format string, byte for byte what ``DataFrame.to_csv`` writes
    but without its per-cell Python calls (about 8× faster); any other table goes to pandas."""
    if len(df) and all(dt == np.float64 for dt in df.dtypes):
        values = df.to_numpy()
        if np.isfinite(values).all():
            head = io.StringIO()
            csv.writer(head, lineterminator="\n").writerow([str(c) for c in df.columns])
            fmt = ",".join(["%.17g"] * values.shape[1])
            return head.getvalue() + "\n".join(map(fmt.__mod__, map(tuple, values.tolist()))) + "\n"
    return df.to_csv(index=False, float_format="%.17g", lineterminator="\n")


def _jsonable(v):
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.bool_,)):
        return bool(v)
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    return v


def tables(study: Study, at: Iterable[float] | None = None) -> dict[str, pd.DataFrame]:
    """All tables of the study (computing what they need): the linkage's, then each task's.

    With ``at`` (``export --at``) only the tables of single positions: ``at`` itself, the
    structure tables and the tasks that need no linkage; the report positions and the cycle are
    not solved (a mechanism that assembles at the requested positions but not over the whole
    cycle is analysed there; a task column of ``at`` that needs the cycle, dynamics, solves it)."""
    out: dict[str, pd.DataFrame] = {}
    if at is not None and study.has_linkage:
        out.update(_structure_tables(study, solved=False))
        out.update(study.extra_tables(positions_only=True))
        out["at"] = _at_table(study, list(at))
        return out
    if study.has_linkage:
        out.update(_linkage_tables(study))
    out.update(study.extra_tables())
    return out


def _at_table(study: Study, q: list[float]) -> pd.DataFrame:
    """Kinematics at the requested positions, with the columns of every task analysis that
    can evaluate itself at arbitrary positions (an ``at(q)`` method: dynamics, …)."""
    df = study.at(q)
    for name in study.tasks():
        fn = getattr(study.analysis(name), "at", None)
        if fn is None:
            continue
        extra = fn(np.asarray(q, dtype=float))
        df = pd.concat([df.reset_index(drop=True),
                        extra.drop(columns=[c for c in extra.columns if c in df.columns]).reset_index(drop=True)],
                       axis=1)
    return df


def _linkage_tables(study: Study) -> dict[str, pd.DataFrame]:
    if not study.has_cycle:          # [grid] cycle = false: the report positions only
        return {"kinematics": study.kinematics, **_structure_tables(study)}
    out = {"kinematics": study.kinematics, "cycle": study.cycle, **_structure_tables(study)}
    if study.strokes is not None:          # an input rocker: its return stroke separately
        out["strokes"] = study.strokes
        if study.kinematics_return is not None:
            out["kinematics_return"] = study.kinematics_return
    return out


def _structure_tables(study: Study, solved: bool = True) -> dict[str, pd.DataFrame]:
    """Links, pairs and Assur groups; a link's motion as the note's table of links states it
    (a frame-hinged link that turns fully is a crank, :mod:`reportgen.analysis.link_motion`).
    ``solved=False`` (``export --at``): the report positions are not solved, so a link's motion
    is the structure's (a mechanism analysed at single positions may not assemble over the cycle)."""
    st = study.structure

    def motion(name: str) -> str:
        return link_motion(study, name) if solved else st.link_motion[name]
    return {
        "links": pd.DataFrame([{"link": l.name, "title": l.title, "motion": motion(l.name),
                                "mass": l.mass, "weight": l.weight, "J_S": l.J_S, "com": l.com}
                               for l in study.mechanism.moving]),
        "pairs": pd.DataFrame(st.pairs),
        "groups": pd.DataFrame([{"order_of_solution": i, "links": g.label, "class": g.klass,
                                 "order": g.order, "kind": g.kind_ru, "title": g.title}
                                for i, g in enumerate(st.groups)]),
    }


# columns that may stay blank: values the case does not give (a link without a mass)
OPTIONAL_COLUMNS = {"links": {"mass", "weight", "J_S", "com"}}


def nonfinite(tabs: dict[str, pd.DataFrame], scalars: dict | None = None) -> list[str]:
    """Where a table or a scalar holds NaN, ±inf or a missing value: ``["cycle.omega_3", …]``
    (empty when everything is finite; :data:`OPTIONAL_COLUMNS` may be blank)."""
    bad: list[str] = []
    for name, df in tabs.items():
        skip = OPTIONAL_COLUMNS.get(name, set())
        for col in df.columns:
            if col in skip:
                continue
            v = df[col]
            if v.dtype.kind in "fc":
                if not np.isfinite(v.to_numpy()).all():
                    bad.append(f"{name}.{col}")
            elif v.dtype.kind == "O" and v.map(_bad_cell).any():
                bad.append(f"{name}.{col}")

    def walk(v, path: str) -> None:
        if isinstance(v, dict):
            for k, x in v.items():
                walk(x, f"{path}.{k}" if path else str(k))
        elif isinstance(v, (list, tuple)):
            for i, x in enumerate(v):
                walk(x, f"{path}[{i}]")
        elif _bad_cell(v):
            bad.append(f"scalars.{path}")

    walk(scalars or {}, "")
    return bad


def _bad_cell(v) -> bool:
    if v is None:
        return True
    if isinstance(v, (float, np.floating, complex)):
        return not np.isfinite(v)
    return False


def check_finite(tabs: dict[str, pd.DataFrame], scalars: dict | None, file: str | None = None) -> None:
    """A :class:`CaseError` when a result is not a finite number (overflow of a value far out of
    the usual range): never an ``inf`` or a blank in a CSV, a null in scalars.json, a «nan» in the note."""
    bad = nonfinite(tabs, scalars)
    if bad:
        shown = ", ".join(bad[:5]) + (" …" if len(bad) > 5 else "")
        raise CaseError(f"расчёт дал бесконечные или неопределённые значения ({shown})", file=file,
                        expected="величины варианта в обычном для курсового проекта диапазоне",
                        hint="проверьте размеры, массы, скорости и нагрузки: вероятно, одна из них "
                             "на много порядков больше или меньше обычной")


def export(study: Study, out_dir: Path, at: Iterable[float] | None = None) -> list[Path]:
    """Compute everything first (checking that every number is finite), then write the files
    (each atomically)."""
    with np.errstate(all="ignore"):
        tabs = tables(study, at)
        raw = study.all_scalars(positions_only=at is not None)
    check_finite(tabs, raw, str(study.spec.path))
    scalars = _jsonable(raw)
    from .report.safety import clean_stale_temps
    clean_stale_temps(Path(out_dir), names=(*(f"{n}.csv" for n in tabs), "scalars.json"))
    written = []
    for name, df in tabs.items():
        p = Path(out_dir) / f"{name}.csv"
        atomic_write(p, _csv(df))
        written.append(p)
    p = Path(out_dir) / "scalars.json"
    atomic_write(p, json.dumps(scalars, ensure_ascii=False, indent=2, sort_keys=True) + "\n")
    written.append(p)
    return written
