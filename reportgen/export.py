"""Export of a Study: every table as CSV and every scalar into scalars.json (written atomically)."""
from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path
from typing import Iterable

import numpy as np
import pandas as pd

from .analysis.study import Study


def atomic_write(path: Path, data: bytes | str) -> None:
    """Write to a temporary file in the same folder, then rename (never a half-written file)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix="." + path.name + ".", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode("utf-8") if isinstance(data, str) else data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _csv(df: pd.DataFrame) -> str:
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
    """All tables of the study (computing what they need): the linkage's, then each task's."""
    out: dict[str, pd.DataFrame] = {}
    if study.has_linkage:
        out.update(_linkage_tables(study))
    out.update(study.extra_tables())
    if at is not None and study.has_linkage:
        out["at"] = _at_table(study, list(at))
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
    st = study.structure
    return {
        "kinematics": study.kinematics,
        "cycle": study.cycle,
        "links": pd.DataFrame([{"link": l.name, "title": l.title, "motion": st.link_motion[l.name],
                                "mass": l.mass, "weight": l.weight, "J_S": l.J_S, "com": l.com}
                               for l in study.mechanism.moving]),
        "pairs": pd.DataFrame(st.pairs),
        "groups": pd.DataFrame([{"order_of_solution": i, "links": g.label, "class": g.klass,
                                 "order": g.order, "kind": g.kind_ru, "title": g.title}
                                for i, g in enumerate(st.groups)]),
    }


def export(study: Study, out_dir: Path, at: Iterable[float] | None = None) -> list[Path]:
    """Compute everything first, then write the files (each atomically)."""
    tabs = tables(study, at)
    scalars = _jsonable(study.all_scalars())
    written = []
    for name, df in tabs.items():
        p = Path(out_dir) / f"{name}.csv"
        atomic_write(p, _csv(df))
        written.append(p)
    p = Path(out_dir) / "scalars.json"
    atomic_write(p, json.dumps(scalars, ensure_ascii=False, indent=2, sort_keys=True) + "\n")
    written.append(p)
    return written
