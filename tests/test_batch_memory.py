"""A kept batch worker over several variants: what it keeps stays bounded, the collector leaves
nothing behind, and a variant built after others is byte for byte the variant built alone.

Each build runs in a fresh interpreter set up as a worker (``batch._init_worker``: warm-up,
shared caches, the warm state frozen), as ``reportgen batch`` runs it; counts, never times."""
from __future__ import annotations

import json
import subprocess
import sys

import pytest
from conftest import CASES, ROOT

SECTIONS = "structure,kinematics"  # a part of the note with figures and tables: quick enough

CHILD = r"""
import gc, json, sys
from pathlib import Path
from reportgen import batch
from reportgen.report import render
from weasyprint.layout import LayoutContext

out, names, sections = Path(sys.argv[1]), sys.argv[2].split(","), sys.argv[3].split(",")
variants = {v.name: v for v in batch.read_variants(Path(sys.argv[4]), Path(sys.argv[5]))}
batch._init_worker()
for i, name in enumerate(names):
    o = batch.run_variant(variants[name], str(out / str(i)), ("pdf", "html"), sections)
    live = gc.get_objects()
    contexts = sum(isinstance(x, LayoutContext) for x in live)
    images = list(render._IMAGE_CACHE.values())
    print(json.dumps({
        "ok": o.ok, "error": o.error, "files": [Path(f).name for f in o.files],
        "images": len(images),
        "attached": sum(isinstance(getattr(im, "_context", None), LayoutContext) for im in images),
        "contexts": contexts, "live": len(live), "frozen": gc.get_freeze_count(),
        "left": gc.collect(),
    }), flush=True)
"""


def _worker(out, names: list[str]) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", CHILD, str(out), ",".join(names), SECTIONS,
         str(CASES / "class_six_bar.csv"), str(CASES / "ws000_six_bar.toml")],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _rows(proc: subprocess.Popen) -> list[dict]:
    stdout, stderr = proc.communicate(timeout=600)
    assert proc.returncode == 0, stderr[-3000:]
    return [json.loads(line) for line in stdout.splitlines() if line.startswith("{")]


@pytest.fixture(scope="module")
def builds(tmp_path_factory):
    """One worker builds variant 03, then 02 twice (the second 02 draws the kept, detached
    images of the first); another builds 02 alone. The two run at the same time."""
    kept, alone = tmp_path_factory.mktemp("kept"), tmp_path_factory.mktemp("alone")
    procs = _worker(kept, ["03", "02", "02"]), _worker(alone, ["02"])
    return kept, _rows(procs[0]), alone, _rows(procs[1])


def test_worker_keeps_bounded_state(builds):
    _kept, rows, _alone, _ = builds
    assert [r["ok"] for r in rows] == [True] * 3, [r["error"] for r in rows]
    for r in rows:
        assert r["contexts"] == 0      # no WeasyPrint document outlives its variant
        assert r["attached"] == 0      # kept images are cut loose from their document
        assert r["left"] == 0          # the collection after the variant left no cyclic garbage
    # the image cache holds what the last variant used, not what every variant used
    assert rows[0]["images"] == rows[1]["images"] == rows[2]["images"] > 0
    # the warm state is frozen once; what stays visible to the collector does not grow with variants
    assert rows[0]["frozen"] == rows[1]["frozen"] == rows[2]["frozen"] > 100_000
    assert rows[2]["live"] - rows[1]["live"] < 2_000
    assert max(r["live"] for r in rows) < rows[0]["frozen"] // 2


def test_variant_after_others_is_the_variant_alone(builds):
    kept, rows, alone, rows_alone = builds
    assert rows_alone[0]["ok"], rows_alone[0]["error"]
    names = rows_alone[0]["files"]
    assert sorted(n.rsplit(".", 1)[1] for n in names) == ["html", "pdf"]
    for name in names:
        ref = (alone / "0" / name).read_bytes()
        assert (kept / "1" / name).read_bytes() == ref, name   # after another variant
        assert (kept / "2" / name).read_bytes() == ref, name   # after itself: kept images redrawn


def test_detached_image_keeps_what_drawing_reads():
    """What an SVG image reads of its context when drawn (hyphenation dictionaries, nested
    images) is still there after it is cut loose, and nothing of the document is."""
    import functools

    from reportgen import batch

    class Context:
        font_config = "fonts"
        dictionaries = {"ru": 1}
        style_for = "every computed style of a document"

        def __init__(self):
            self.get_image_from_uri = functools.partial(lambda **kw: kw, cache={}, url_fetcher="f", context=self)

    class Svg:
        stream, context = "page stream", "context"

    class Image:
        def __init__(self):
            self._context, self._svg = Context(), Svg()

    image = Image()
    cache = {"data:a": image, "data:b": object()}
    assert batch._detach_images(cache) == 1
    ctx = image._context
    assert isinstance(ctx, batch._DetachedContext) and not hasattr(ctx, "style_for")
    assert ctx.font_config == "fonts" and ctx.dictionaries == {}
    got = ctx.get_image_from_uri(url="u")
    assert got["context"] is ctx and got["url_fetcher"] == "f" and got["url"] == "u"
    assert image._svg.stream is None and image._svg.context is None
    assert batch._detach_images(cache) == 0   # idempotent
