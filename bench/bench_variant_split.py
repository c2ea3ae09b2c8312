"""Where a batch variant's CPU before the PDF layout goes: a batch worker (``batch._init_worker``) builds
variants 02… of ``cases/class_six_bar.csv`` (after 01 as a warm-up) and adds up ``time.process_time`` per
stage — the analysis, ``build_report``, each section, each scene's ``draw``, ``to_svg``/``savefig``, the
constrained layout, the label placer, matplotlib's tick/text/line drawing, the garbage collections, the HTML.
The stages nest (a section holds its scenes, a scene its ``savefig``): each line is a total of its own.

Usage: ``python bench/bench_variant_split.py [N]`` (N variants, default 3). Prints seconds per variant and the
load; writes only into a temporary folder.
"""
import sys, time, os, collections, tempfile
from pathlib import Path
ROOT = Path(__file__).resolve().parents[1]; sys.path.insert(0, str(ROOT))
TMP = Path(tempfile.mkdtemp())
from reportgen import batch as B
B._init_worker()
vs = B.read_variants(ROOT / "cases/class_six_bar.csv", ROOT / "cases/ws000_six_bar.toml")
from reportgen.analysis.study import Study
from reportgen.case.load import load_spec
from reportgen.report import assemble
from reportgen.report.render import write_html, _build_scope
from reportgen.style import mplstyle, svgslim
import matplotlib.figure as mf
acc = collections.Counter()
def timed(name, fn):
    def w(*a, **k):
        c = time.process_time()
        try: return fn(*a, **k)
        finally: acc[name] += time.process_time() - c
    return w
import matplotlib.layout_engine as le
import matplotlib.axis as ma, matplotlib.text as mt, matplotlib.lines as ml, matplotlib.legend as mleg
import matplotlib.axes as maxes
import matplotlib.backends.backend_svg as bsvg
from reportgen.scenes import labels
# (stage name, owner, attribute): every stage timed the same way
STAGES = [
    ("to_svg", mplstyle, "to_svg"), ("savefig", mf.Figure, "savefig"), ("slim", svgslim, "slim"),
    ("constrained", le.ConstrainedLayoutEngine, "execute"), ("label_place", labels.LabelPlacer, "place"),
    ("update_ticks", ma.Axis, "_update_ticks"), ("axis_tightbbox", ma.Axis, "get_tightbbox"),
    ("axis_draw", ma.Axis, "draw"), ("get_major_ticks", ma.Axis, "get_major_ticks"),
    ("text_layout", mt.Text, "_get_layout"), ("text_draw", mt.Text, "draw"), ("line_draw", ml.Line2D, "draw"),
    ("legend_draw", mleg.Legend, "draw"), ("axes_init", maxes.Axes, "__init__"),
    ("svg_draw_path", bsvg.RendererSVG, "draw_path"), ("svg_draw_text", bsvg.RendererSVG, "draw_text"),
]
for label, owner, attr in STAGES:
    setattr(owner, attr, timed(label, getattr(owner, attr)))
import reportgen.report.render as RR
for nm in ("_typography", "_fill_refs", "_fix_text"):
    if hasattr(RR, nm): setattr(RR, nm, timed(nm, getattr(RR, nm)))
from reportgen.report import sections as SS
import reportgen.scenes as SC, pkgutil, importlib
for mi in pkgutil.iter_modules(SC.__path__):
    m = importlib.import_module("reportgen.scenes." + mi.name)
    for nm, c in list(vars(m).items()):
        if isinstance(c, type) and c.__module__ == m.__name__ and "draw" in vars(c):
            c.draw = timed("scenes_draw_total", c.draw)
            c.draw = timed("scene_" + nm, c.draw)
import importlib, pkgutil
for mi in pkgutil.iter_modules(SS.__path__):
    m = importlib.import_module("reportgen.report.sections." + mi.name)
    if hasattr(m, "build") and callable(m.build): setattr(m, "build", timed("sec_" + mi.name, m.build))
def run(v, i):
    spec = load_spec(v.base, v.params); spec.meta_overrides = dict(v.meta)
    st = Study(spec)
    c = time.process_time()
    for n in sorted(assemble.needs(st)): getattr(st, n)
    acc["analysis"] += time.process_time() - c
    c = time.process_time(); rep = assemble.build_report(st); acc["build_report"] += time.process_time() - c
    c = time.process_time()
    with _build_scope(): write_html(rep, TMP / f"o{i}.html")
    acc["write_html"] += time.process_time() - c
    B._after_variant()
import gc
_g = {}
def cb(phase, info):
    if phase == "start": _g["t"] = time.process_time()
    else: acc[f"gc{info['generation']}"] += time.process_time() - _g["t"]; acc[f"gc{info['generation']}_n"] += 1
gc.callbacks.append(cb)
run(vs[0], 0); acc.clear()
n = int(sys.argv[1]) if len(sys.argv) > 1 else 3
for i, v in enumerate(vs[1:1+n], 1): run(v, i)
for k, t in acc.most_common(): print(f"{k:14s} {t/n:.3f}")
print("load", os.getloadavg()[0])
