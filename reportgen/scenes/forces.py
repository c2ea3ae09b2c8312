"""Drawings of the force analysis: each Assur group taken apart with its loads and its force
polygon to scale, Жуковский's lever (the velocity plan turned by 90°), reaction diagrams over
the cycle, and the capacity, actuator and axle-load curves of an actuator-driven linkage.

Scenes only draw what ``study.forces`` computed (``Forces.details`` at a report position,
``Forces.cycle`` over the cycle)."""
from __future__ import annotations

import itertools
import math
import re
import unicodedata
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import NamedTuple

import matplotlib
import numpy as np
import pandas as pd
from matplotlib.patches import Arc

from ..analysis.forces import crank_pin, lever_points
from ..analysis.plans import READ_MM, Plan, drawn, velocity_plan
from ..core import kinetostatics as KS
from ..style import mplstyle
from ..style.numbers import fmt, shared_decimals
from .draw import GREY, INK, SUBSCRIPT, Canvas, arrow, draw_mechanism, gost_scale, legend_rows, nice_scale
from .mechanism import LANDSCAPE_GAIN, LANDSCAPE_H, LANDSCAPE_W, Drawing
from .plans import INSET_MARKS, SAME_MM, PlanScene, coincident, find_insets, joint_label

BLUE = "#1f4e9c"
RED = "#b2182b"
ARROW_MM = 22.0          # the largest load arrow on a scheme (arrows on schemes are not to scale)
MIN_ARROW_MM = 6.0


def is_initial(f, g) -> bool:
    """Whether the force group ``g`` of ``f.model`` is the initial mechanism (the driving link with
    the frame: it holds the balancing moment of a crank or the actuator's cylinder–rod pair)."""
    return any(f.model.pairs[k].kind in (KS.K_MOM, KS.K_ACT) for k in g.pairs)


def group_name(f, g, case: str = "nom") -> str:
    """«Начальный механизм (0,1)» / «Группа (2,3)»; ``case="gen"``: «начального механизма (0,1)» /
    «группы (2,3)» (the crank with the frame is the initial mechanism, not an Assur group)."""
    first = is_initial(f, g)
    word = {("nom", True): "Начальный механизм", ("nom", False): "Группа",
            ("gen", True): "начального механизма", ("gen", False): "группы"}[case, first]
    return f"{word} {g.label}"


def sub(text: str) -> str:
    """Digits as Unicode subscripts after the first character: R12 → R₁₂, Φ2 → Φ₂."""
    return text[0] + text[1:].translate(SUBSCRIPT)


def load_label(ld: dict) -> str:
    """Label of a load on a drawing: G₂, Φ₂, M_Φ₂ (as MΦ₂), or the load's own name."""
    if ld["kind"] in ("G", "Phi", "MPhi", "Mfly"):
        return sub(ld["name"]) if ld["kind"] != "MPhi" and ld["kind"] != "Mfly" else "M" + sub(ld["name"][1:])
    return ld["name"]


UNSUB = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")


def split_label(label: str) -> tuple[str, str, str] | None:
    """A force label of the tables (R₁₂, Φ₂, MΦ₂′, Fур) split into the letter, its index and the
    primes: ("R", "12", ""), ("M", "Φ2", "′"), ("F", "ур", ""); None for an empty letter."""
    text = label.translate(UNSUB)
    primes = ""
    while text and text[-1] in "′″'":
        primes = ("′" if text[-1] == "'" else text[-1]) + primes
        text = text[:-1]
    if not text:
        return None
    return text[0], text[1:], primes


GREEK_TEX = {"Φ": r"\Phi", "ω": r"\omega", "ε": r"\varepsilon"}


def math_label(label: str) -> str:
    """A force label of the tables (R₁₂, Φ₂, MΦ₂, Fур, G₂′) in mathtext for a drawing:
    $R_{12}$, $\\Phi_{2}$, $M_{\\Phi 2}$, $F_{ур}$, $G′_{2}$."""
    parts = split_label(label)
    if parts is None:
        return label
    head, rest, primes = parts
    head = GREEK_TEX.get(head, head)
    rest = "".join(GREEK_TEX.get(c, c) + (" " if c in GREEK_TEX else "") for c in rest).strip()
    # a Russian abbreviation in the index (пс, ур) upright, as in the text: italic «пс» reads «nc»
    rest = re.sub(r"[А-Яа-яЁё]+", lambda m: rf"\mathrm{{{m.group(0)}}}", rest)
    return "$" + head + primes + (f"_{{{rest}}}" if rest else "") + "$"


def html_label(label: str) -> str:
    """The same label in the note's HTML (textbook notation, as ``math_label`` draws it): the
    Latin letter in italics, Greek upright, the index as a subscript, primes after the letter:
    <i>P</i><sub>пс</sub>, <i>M</i>′<sub>Φ2</sub>, Φ<sub>2</sub>. Labels are built by the
    program from validated names (letters and digits only)."""
    from markupsafe import escape
    parts = split_label(label)
    if parts is None:
        return str(escape(label))
    head, rest, primes = (str(escape(x)) for x in parts)
    letter = head if "GREEK" in unicodedata.name(parts[0], "") else f"<i>{head}</i>"
    return letter + primes + (f"<sub>{rest}</sub>" if rest else "")


def pair_label(a: str, b: str) -> str:
    return "R" + (a + b).translate(SUBSCRIPT)


@dataclass
class Vector:
    """A force of the group's polygon: label, (Fx, Fy), point of application, role."""

    label: str
    F: np.ndarray
    at: tuple[float, float]
    role: str              # "load", "known", "unknown", "internal"
    link: str = ""         # the link the force acts on
    other: str = ""        # internal reaction: the link that exerts it
    kind: int = -1         # reaction: the pair kind (kinetostatics K_REV, K_PRI, …)
    tex: str = ""          # mathtext label when it is not math_label(label) (components R^n, R^τ)
    back: str = ""         # internal reaction: the label of the opposite force when it is not
                           # pair_label(link, other) (links merged into one body)
    base: tuple | None = None   # a sliding pair's point when the reaction acts off it (at h = M/N)


@dataclass
class Constructed:
    """A reaction found on the force polygon: its magnitude read off the drawing (to READ_MM)
    against the analytic one."""

    label: str
    graphic: float
    exact: float

    @property
    def dev_pct(self) -> float:
        return (self.graphic - self.exact) / self.exact * 100.0 if self.exact else 0.0


@dataclass
class GroupDrawing(Drawing):
    mu_F: float = 0.0
    vectors: list[Vector] = field(default_factory=list)
    constructed: list[Constructed] = field(default_factory=list)   # reactions found by construction
    method: str = ""              # Construction.method ("" where the polygon is drawn, not constructed)


def _over_group(study, links: set, cols: dict, pt) -> bool:
    """Whether point ``pt`` lies within the box of the points of the group's links."""
    mech = study.mechanism
    pts = [p for l in links for p in mech.link(l).points]
    xs = [cols["x_" + p] for p in pts if "x_" + p in cols]
    ys = [cols["y_" + p] for p in pts if "y_" + p in cols]
    if not xs:
        return False
    tol = 1e-9 * mech.size()
    return min(xs) - tol <= pt[0] <= max(xs) + tol and min(ys) - tol <= pt[1] <= max(ys) + tol


def group_vectors(study, label: str, gi: int) -> tuple[list[Vector], list[dict], list[Vector]]:
    """Forces on group ``gi`` at position ``label``: the external forces (loads and known
    reactions of the groups solved before, then this group's unknown reactions), the moments
    on its links, and its internal reactions (force on the second link of the pair)."""
    f = study.forces
    det = f.details(label)
    g = f.model.groups[gi]
    links = set(g.links)
    cols = det["cols"]
    ext, moments, internal = [], [], []
    for ld in det["loads"]:
        if ld["link"] not in links:
            continue
        if ld["M"] is None:
            ext.append(Vector(load_label(ld), np.array([ld["Fx"], ld["Fy"]]),
                              (cols["x_" + ld["point"]], cols["y_" + ld["point"]]), "load", ld["link"]))
        else:
            moments.append(dict(label=load_label(ld), M=ld["M"], link=ld["link"]))
    unknown = set(g.pairs)
    for k, pv in enumerate(det["pairs"]):
        p = pv["pair"]
        if p.kind == KS.K_MOM:
            if p.b in links:
                moments.append(dict(label="Mур", M=pv["M"], link=p.b))
            continue
        F = np.array([pv["Rx"], pv["Ry"]])
        at, base = (pv["x"], pv["y"]), None
        if p.kind == KS.K_PRI and pv["N"] and abs(pv["Mp"] / pv["N"]) > 1e-9 * study.mechanism.size():
            # a sliding pair's reaction acts h = M/N from the slider's point along the guide (the
            # arm the note's table gives: analysis.forces xN, yN), not at the slider's point —
            # drawn there when that point lies over the group (a yoke's arm of three mechanism
            # sizes would shrink the scheme to nothing: drawn at the slider, the table gives h)
            h = pv["Mp"] / pv["N"]
            off = (pv["x"] + h * pv["ux"], pv["y"] + h * pv["uy"])
            if _over_group(study, links, cols, off):
                at, base = off, at
        if p.a in links and p.b in links:
            internal.append(Vector(pair_label(p.a, p.b), F, at, "internal", p.b, p.a, kind=p.kind, base=base))
        elif p.b in links:
            ext.append(Vector(pair_label(p.a, p.b), F, at, "unknown" if k in unknown else "known", p.b,
                              kind=p.kind, base=base))
        elif p.a in links:
            ext.append(Vector(pair_label(p.b, p.a), -F, at, "unknown" if k in unknown else "known", p.a,
                              kind=p.kind, base=base))
    order = {"load": 0, "known": 1, "unknown": 2}
    ext.sort(key=lambda v: order[v.role])
    return ext, moments, internal


def _arrow_mm(F: float, Fmax: float) -> float:
    return max(MIN_ARROW_MM, ARROW_MM * F / Fmax) if Fmax > 0 else MIN_ARROW_MM


FAN_DEG = 30.0        # arrows from one point closer in direction than this are staggered in length
FAN_STEP_MM = 8.0     # … so that each one's free end (and label) lies this much beyond the previous


def _scheme_arrows(ext, Fmax: float, mu_l: float) -> dict[int, float]:
    """Length in mm of every drawn arrow of a group's scheme (index in ``ext``): by magnitude
    (not to scale), but arrows drawn from one point in nearly one direction (a stone and a slider
    at one pair: G₄ and G₅, Φ₄ and Φ₅) are staggered, the shorter first, so that their free ends
    and labels do not pile up at one spot."""
    out: dict[int, float] = {}
    free: dict[int, tuple] = {}
    for i, v in enumerate(ext):
        n = float(np.hypot(*v.F))
        if n < 1e-9 * Fmax:
            continue
        out[i] = _arrow_mm(n, Fmax)
        free[i] = (v.at, v.F / n * (1 if v.role == "load" else -1))    # from the point to the free end
    return _staggered(out, free, 2.0 * mu_l)


def _staggered(lengths: dict, free: dict, near: float) -> dict:
    """The arrows' lengths (mm, by key) with the arrows drawn from one point (``free[key]`` =
    (point, unit vector from it to the free end); points closer than ``near``, data units) in
    nearly one direction (within FAN_DEG) staggered, the shorter first, each one's free end
    FAN_STEP_MM beyond the previous: their heads and labels do not pile up at one spot."""
    out = dict(lengths)
    fans: list[tuple[tuple[float, float], np.ndarray, list]] = []
    for i, (at, u) in free.items():
        for p, d, members in fans:
            if math.hypot(p[0] - at[0], p[1] - at[1]) < near and float(np.dot(d, u)) > math.cos(math.radians(FAN_DEG)):
                members.append(i)
                break
        else:
            fans.append(((at[0], at[1]), u, [i]))
    for _, _, members in fans:
        last = -math.inf
        for i in sorted(members, key=lambda j: out[j]):
            out[i] = max(out[i], last + FAN_STEP_MM)
            last = out[i]
    return out


HEAD_CLEAR_MM = 1.0         # an arrow's head kept this far from every other arrow's shaft
HEAD_LEN_MM = 2.7           # the printed length of an arrowhead of draw.arrow (head_mm = 2,2)


def _seg_gap(p0, p1, q0, q1) -> float:
    """The least distance between the segments p0–p1 and q0–q1 (0 where they cross)."""
    def d(p, a, b):
        v = b - a
        t = min(max(float(np.dot(p - a, v) / max(float(np.dot(v, v)), 1e-300)), 0.0), 1.0)
        return float(np.hypot(*(p - a - t * v)))
    r, s_ = p1 - p0, q1 - q0
    den = float(r[0] * s_[1] - r[1] * s_[0])
    if abs(den) > 1e-300:
        t = float((q0 - p0)[0] * s_[1] - (q0 - p0)[1] * s_[0]) / den
        u = float((q0 - p0)[0] * r[1] - (q0 - p0)[1] * r[0]) / den
        if 0.0 <= t <= 1.0 and 0.0 <= u <= 1.0:
            return 0.0
    return min(d(p0, q0, q1), d(p1, q0, q1), d(q0, p0, p1), d(q1, p0, p1))


def _clear_heads(lengths: dict, free: dict, mm: float) -> dict:
    """The arrows' lengths (mm, by key; ``free`` as for :func:`_staggered`, ``mm`` — data units
    per printed mm) with each head that lies on another arrow's shaft (closer than HEAD_CLEAR_MM:
    ws000's G₄ on the Жуковский lever, its head on P_пс's shaft) moved off it: the arrow made
    longer, 0,5 mm at a time up to 4 mm, else shorter down to MIN_ARROW_MM, at the first length
    whose head clears every shaft and whose own shaft passes no other head, the steps of a fan
    (:func:`_staggered`) kept (the lever's arrows are not to scale: their points and directions
    give the moments). Unchanged where none does."""
    out = dict(lengths)

    def parts(i: int, L: float):
        at, u = np.asarray(free[i][0], float), np.asarray(free[i][1], float)
        tip = at + u * L * mm
        return at, tip - u * min(HEAD_LEN_MM, L) * mm, tip       # start, base of the head, tip

    def clear(i: int, L: float) -> bool:
        a, base, tip = parts(i, L)
        u = np.asarray(free[i][1], float)
        for j, Lj in out.items():
            if j == i:
                continue
            b, base_j, tip_j = parts(j, Lj)
            # a fan of :func:`_staggered` (one point, nearly one direction) keeps its steps
            if (np.hypot(*(a - b)) < 2.0 * mm and float(np.dot(u, free[j][1])) > math.cos(math.radians(FAN_DEG))
                    and abs(L - Lj) < FAN_STEP_MM - 1e-9):
                return False
            if (np.hypot(*(a - b)) > 1e-9 * mm and _seg_gap(base, tip, b, base_j) < HEAD_CLEAR_MM * mm
                    or np.hypot(*(a - b)) > 1e-9 * mm and _seg_gap(a, base, base_j, tip_j) < HEAD_CLEAR_MM * mm):
                return False
        return True

    for i in sorted(out):
        if clear(i, out[i]):
            continue
        tries = [out[i] + 0.5 * k for k in range(1, 9)] + [out[i] - 0.5 * k for k in range(1, int(2 * (out[i] - MIN_ARROW_MM)) + 1)]
        out[i] = next((L for L in tries if clear(i, L)), out[i])
    return out


MOMENT_LABEL_GAP_MM = 1.5   # clearance of a moment's label from every other label


def _moment_arc(cv: Canvas, x, y, M, label, color=INK, r_mm=5.0, k: int = 0):
    """A moment as an arc with an arrowhead (counter-clockwise for M > 0); ``k``: how many arcs
    are drawn round the point before it (each a ring further out). Its label is set by the
    k-th arc's own stretch (45°, 135°, 225°, … round the point), clear of the other labels, so
    that the labels of two moments at one joint (M_ур and M_Φ1 of a crank) are not stacked."""
    ax = cv.ax
    r = cv.mm(r_mm)
    ax.add_patch(Arc((x, y), 2 * r, 2 * r, theta1=20, theta2=290, color=color, lw=1.0, zorder=6))
    end = math.radians(290 if M > 0 else 20)
    tip = (x + r * math.cos(end), y + r * math.sin(end))
    d = 1 if M > 0 else -1
    tang = (-math.sin(end) * d, math.cos(end) * d)
    arrow(ax, tip[0] - tang[0] * cv.mm(1.5), tip[1] - tang[1] * cv.mm(1.5), tip[0], tip[1], color=color,
          lw=1.0, head_mm=2.0, zorder=7)
    a = math.radians(45.0 + 90.0 * (k % 3))     # on the arc (20°…290°), a quarter turn apart
    u = (math.cos(a), math.sin(a))
    cv.labels.add(x + r * u[0], y + r * u[1], math_label(label), prefer=u, fontsize=10, color=color,
                  gap_mm=MOMENT_LABEL_GAP_MM)


def _moment_arcs(cv: Canvas, moments, mech, ref, cols):
    """The non-zero moments of a drawing, each at its link's centre of mass (else its reference
    point); a second moment at one point drawn on a ring further out (M_ур in red)."""
    placed: dict[str, int] = {}
    for m in moments:
        if abs(m["M"]) < 1e-12:
            continue
        S = mech.link(m["link"]).com or ref[m["link"]]
        k = placed.get(S, 0)
        placed[S] = k + 1
        _moment_arc(cv, cols["x_" + S], cols["y_" + S], m["M"], m["label"],
                    RED if m["label"] == "Mур" else INK, r_mm=5.0 + 3.5 * k, k=k)


class GroupForces:
    """One Assur group taken apart at a report position: the links to scale μ_l with the loads
    and reactions as arrows (arrows not to scale), and beside it the force polygon of the group
    to scale μ_F (external forces head to tail; the internal reaction closes the polygon of one
    link, dashed)."""

    needs = ("forces",)

    def __init__(self, label: str, gi: int, mu_l: float | None = None, mu_F: float | None = None,
                 landscape: bool = False):
        """``mu_l``, ``mu_F``: the scales asked by the caller (a drawing sheet), else those that fit
        the note's page; ``landscape``: a landscape page may be taken where it pays (the note)."""
        self.label, self.gi = label, gi
        self.mu_l, self.mu_F = mu_l, mu_F
        self.landscape = landscape

    def _layout(self, xs, ys, ext, internal, g, Fmax, gain: float, floor: float = 0.0,
                scheme: float = 1.0, stack: bool = False) -> SimpleNamespace:
        """The scales and the places of the scheme and the force polygon when the scheme is given
        70·gain·scheme mm and the polygon 62·gain mm (gain 1 on the note's portrait page); the
        polygon beside the scheme, or under it (``stack``)."""
        span = max(np.ptp(xs), np.ptp(ys), floor, 1e-6)
        mu_l = self.mu_l or gost_scale(span, 70.0 * gain * scheme)
        # arrow tips on the scheme (mm converted with μ_l)
        tips = []
        lengths = _scheme_arrows(ext, Fmax, mu_l)
        for i, v in enumerate(ext):
            n = float(np.hypot(*v.F))
            if i not in lengths:
                continue
            # drawn from its point as a load (a reaction opposite to a load at its point too), else
            # ending at its pair or point (a load along a link's line), as draw does
            along = _along_bar(v, lengths[i] * mu_l, self._bars, NEAR_MM * mu_l)
            L = (lengths[i] + 4.0) * mu_l * (1 if (v.role == "load" and not along) or _opposes_load(v, ext) else -1)
            tips.append((v.at[0] + v.F[0] / n * L, v.at[1] + v.F[1] / n * L))
            tips.append(v.at)            # a sliding pair's reaction off the slider (at h = M/N)
        allx = np.concatenate([xs, [t[0] for t in tips]])
        ally = np.concatenate([ys, [t[1] for t in tips]])
        # force polygon: the external forces link by link (the link with most forces first), so
        # that an internal reaction closes the polygon of the links before it
        seq = [v for v in ext if float(np.hypot(*v.F)) > 1e-9 * Fmax]
        count = {l: sum(1 for v in seq if v.link == l) for l in g.links}
        order = sorted(g.links, key=lambda l: (-count[l], g.links.index(l)))
        seq = [v for l in order for v in seq if v.link == l]
        cum = np.cumsum([np.zeros(2)] + [v.F for v in seq], axis=0)
        pext = max(np.ptp(cum[:, 0]), np.ptp(cum[:, 1]), 1e-9)
        mu_F = self.mu_F or nice_scale(pext, 62.0 * gain)
        built = construct_polygon(seq, internal, mu_F)
        if built is not None:
            seq, constructed, internal = built.chain, built.found, built.internal
            count = {l: sum(1 for v in seq if v.link == l) for l in g.links}
            order = list(dict.fromkeys(v.link for v in seq))
            cum = np.cumsum([np.zeros(2)] + [v.F for v in seq], axis=0)
        else:
            constructed = []
        k = mu_l / mu_F                                   # force → data units of the canvas
        if stack:
            x0 = (allx.max() + allx.min()) / 2 - (cum[:, 0].max() + cum[:, 0].min()) / 2 * k
            y0 = ally.min() - cv_gap(mu_l) - cum[:, 1].max() * k
        else:
            x0 = allx.max() + cv_gap(mu_l) - cum[:, 0].min() * k
            y0 = (ally.max() + ally.min()) / 2 - (cum[:, 1].max() + cum[:, 1].min()) / 2 * k
        poly = np.column_stack([x0 + cum[:, 0] * k, y0 + cum[:, 1] * k])
        inset = _inset(seq, cum, mu_F, k, poly, mu_l)
        ext_pts = np.vstack([poly] + ([inset["box"]] if inset else []))
        x_lo, x_hi = min(allx.min(), ext_pts[:, 0].min()), max(allx.max(), ext_pts[:, 0].max())
        y_lo, y_hi = min(ally.min(), ext_pts[:, 1].min()), max(ally.max(), ext_pts[:, 1].max())
        return SimpleNamespace(mu_l=mu_l, mu_F=mu_F, allx=allx, ally=ally, seq=seq, constructed=constructed,
                               internal=internal, count=count, order=order, cum=cum, poly=poly, inset=inset,
                               ext_pts=ext_pts, built=built, w_mm=(x_hi - x_lo) / mu_l + 20.0,
                               h_mm=(y_hi - y_lo) / mu_l + 20.0)

    def _grown(self, lay: SimpleNamespace, args: tuple) -> SimpleNamespace:
        """A small scheme drawn at the next finer ГОСТ 2.302 scales while the drawing stays within
        the text width and :data:`GROUP_MAX_H` (a group whose links span a few centimetres at the
        first scale, beside a large force polygon): the polygon beside the scheme, or under it
        when only that fits, the polygon at its first scale or one step smaller (its room × 0.8);
        the finest such scale (beside, and the larger polygon, preferred at a tie)."""
        best = lay
        *head, gain, floor = args
        for stack in (False, True):
            for pg, k in itertools.product((1.0, 0.8), SCHEME_GROWTH):
                cand = self._layout(*head, gain * pg, floor, scheme=k / pg, stack=stack)
                if cand.mu_l < best.mu_l * (1 - 1e-9) and cand.w_mm <= PORTRAIT_W and cand.h_mm <= GROUP_MAX_H:
                    best = cand
        return best

    def draw(self, study) -> GroupDrawing:
        f = study.forces
        mech = study.mechanism
        det = f.details(self.label)
        cols = det["cols"]
        g = f.model.groups[self.gi]
        ext, moments, internal = group_vectors(study, self.label, self.gi)
        pts = {p for l in g.links for p in mech.link(l).points}
        # the links' lines (every pair of a link's points): a load drawn along one is turned to end
        # at its point (a slider's resistance pushing up the rod's line)
        self._bars = bars = [(np.array([cols["x_" + a], cols["y_" + a]]), np.array([cols["x_" + b], cols["y_" + b]]))
                             for l in g.links for k, a in enumerate(list(mech.link(l).points))
                             for b in list(mech.link(l).points)[k + 1:]]
        xs = np.array([cols["x_" + p] for p in pts])
        ys = np.array([cols["y_" + p] for p in pts])
        Fmax = max([float(np.hypot(*v.F)) for v in ext + internal] + [1e-12])
        # a group whose joints nearly coincide (a stone and a slider at one point) is drawn at a
        # scale fitting a sixth of the whole mechanism, not enlarged until its symbols pile up
        allp = {p for l in mech.moving for p in l.points}
        floor = max(np.ptp([cols["x_" + p] for p in allp]), np.ptp([cols["y_" + p] for p in allp])) / 6.0
        gain = 1.0
        lay = self._layout(xs, ys, ext, internal, g, Fmax, gain, floor)
        for _ in range(3):                # wider than the page at the first guess: smaller scales
            if self.mu_l is not None or self.mu_F is not None or lay.w_mm <= PORTRAIT_W:
                break
            gain = PORTRAIT_W / lay.w_mm * 0.98
            lay = self._layout(xs, ys, ext, internal, g, Fmax, gain, floor)
        landscape = False
        if self.landscape and self.mu_l is None and self.mu_F is None:
            # on a landscape page when that enlarges both the scheme and the polygon LANDSCAPE_GAIN
            # times and the drawing fits the page; a drawing that large still within the portrait
            # text width stays on the portrait page (no landscape page for a small figure)
            wide = self._layout(xs, ys, ext, internal, g, Fmax, LANDSCAPE_GAIN * 1.05, floor)
            larger = lay.mu_l >= LANDSCAPE_GAIN * wide.mu_l and lay.mu_F >= LANDSCAPE_GAIN * wide.mu_F
            if larger and wide.w_mm <= PORTRAIT_W and wide.h_mm <= GROUP_MAX_H:
                lay, gain = wide, LANDSCAPE_GAIN * 1.05
            else:
                landscape = larger and wide.w_mm <= LANDSCAPE_W and wide.h_mm <= LANDSCAPE_H
            if landscape:
                lay = wide
        if (not landscape and self.mu_l is None and self.mu_F is None
                and max(np.ptp(xs), np.ptp(ys)) / lay.mu_l < SMALL_SCHEME_MM):
            lay = self._grown(lay, (xs, ys, ext, internal, g, Fmax, gain, floor))
        mu_l, mu_F, allx, ally, seq, constructed, internal, count, order, poly, inset, ext_pts, built = (
            lay.mu_l, lay.mu_F, lay.allx, lay.ally, lay.seq, lay.constructed, lay.internal, lay.count, lay.order,
            lay.poly, lay.inset, lay.ext_pts, lay.built)
        cv = Canvas(min(allx.min(), ext_pts[:, 0].min()), max(allx.max(), ext_pts[:, 0].max()),
                    min(ally.min(), ext_pts[:, 1].min()), max(ally.max(), ext_pts[:, 1].max()), mu_l,
                    margin_mm=10, max_w=1e4 if self.mu_l is not None else LANDSCAPE_W if landscape else PORTRAIT_W)
        ax = cv.ax
        draw_mechanism(cv, mech, cols, only=set(g.links), supports=False, lw=1.4, com=True)
        lengths = _scheme_arrows(ext, Fmax, mu_l)
        scheme: list[tuple[np.ndarray, np.ndarray]] = []     # arrows drawn on the scheme
        for i, v in enumerate(ext):
            n = float(np.hypot(*v.F))
            if i not in lengths:
                continue
            L = lengths[i] * mu_l
            color = {"load": INK, "known": INK, "unknown": BLUE}[v.role]
            ex, ey = v.F[0] / n, v.F[1] / n
            if v.base is not None:       # the guide's line from the slider to where the reaction acts
                ax.plot([v.base[0], v.at[0]], [v.base[1], v.at[1]], color=color, lw=0.5, ls=(0, (6, 2, 1, 2)),
                        zorder=2)
                cv.labels.add(0.5 * (v.base[0] + v.at[0]), 0.5 * (v.base[1] + v.at[1]), "$h$",
                              prefer=(-ey, ex), fontsize=10, color=color)
            along = _along_bar(v, L, bars, cv.mm(NEAR_MM))
            # loads start at their point, reactions end at the pair; a reaction opposite to a load
            # at its point (R₀₅ against G₅) starts there too, so that the two do not cover each other
            if (v.role == "load" and not along) or _opposes_load(v, ext):
                a0, a1 = v.at, (v.at[0] + ex * L, v.at[1] + ey * L)
                lx, ly, pref = a1[0], a1[1], (ex, ey)
            else:
                a0, a1 = (v.at[0] - ex * L, v.at[1] - ey * L), v.at
                lx, ly, pref = a0[0], a0[1], (-ex, -ey)
            a0, a1, lx, ly = _beside(np.asarray(a0, float), np.asarray(a1, float), lx, ly, scheme,
                                     cv.mm(SCHEME_SHIFT_MM), cv.mm(NEAR_MM))
            scheme.append((a0, a1))
            arrow(ax, a0[0], a0[1], a1[0], a1[1], color=color, lw=1.2, zorder=6)
            cv.labels.add(lx, ly, math_label(v.label), prefer=pref, fontsize=10, color=color)
        _moment_arcs(cv, moments, mech, f.model.ref, cols)
        # polygon: a side lying back along an earlier one (R₀₁ = −R₂₁ of a crank loaded by one
        # force) drawn beside it, joined by thin lines
        sides = _inset_sides(poly, cv.mm(OFFSET_MM), cv.mm(NEAR_MM))
        for i, v in enumerate(seq):
            a, b, moved = sides[i]
            color = BLUE if v.role == "unknown" else INK
            if moved:
                for p0, p1 in ((poly[i], a), (poly[i + 1], b)):
                    ax.plot([p0[0], p1[0]], [p0[1], p1[1]], lw=0.4, color=GREY, zorder=4)
            if inset and i in inset["tiny"]:
                # drawn with its head in the enlarged inset: here a line, so that no heads pile up
                ax.plot([a[0], b[0]], [a[1], b[1]], color=color, lw=0.8, zorder=6)
            else:
                arrow(ax, a[0], a[1], b[0], b[1], color=color, lw=1.3, zorder=6)
            mid = (a + b) / 2
            d = b - a
            nrm = np.array([-d[1], d[0]]) / (np.hypot(*d) or 1.0)
            if not inset or i not in inset["tiny"]:
                cv.labels.add(mid[0], mid[1], v.tex or math_label(v.label), prefer=nrm, fontsize=10, color=color)
        if built is not None and built.lines:
            _direction_lines(ax, built.lines, poly)
        if inset:
            _draw_inset(cv, seq, inset)
        # internal reactions: a cut between the first links of the order and the rest crossed by
        # one internal pair; its force on the first links closes their polygon (dashed)
        n = 0
        closing = []
        for kk in range(1, len(order)):
            n += count[order[kk - 1]]
            side = set(order[:kk])
            cross = [v for v in internal if (v.link in side) != (v.other in side)]
            if len(cross) != 1 or n == 0:
                continue
            v = cross[0]
            F, lab = (v.F, v.label) if v.link in side else (-v.F, v.back or pair_label(v.link, v.other))
            start, end, moved = _clear_of_sides(poly[n], poly[0], poly, cv.mm(OFFSET_MM), cv.mm(NEAR_MM))
            # not onto a side already moved aside (R₀₁ drawn beside R₄₃): the other side, or further
            shifted = [(a, b) for a, b, m in sides if m]
            if moved and any(covered(start, end, a, b, cv.mm(NEAR_MM)) > 0.2 for a, b in shifted):
                step = start - poly[n]
                for cand in (-step, 2.0 * step):
                    s2, e2 = poly[n] + cand, poly[0] + cand
                    if not any(covered(s2, e2, a, b, cv.mm(NEAR_MM)) > 0.2 for a, b in shifted):
                        start, end = s2, e2
                        break
            if moved:                     # shifted off a side it would cover: joined by thin lines
                for p0, p1 in ((poly[n], start), (poly[0], end)):
                    ax.plot([p0[0], p1[0]], [p0[1], p1[1]], lw=0.4, color=GREY, zorder=4)
            arrow(ax, start[0], start[1], end[0], end[1], color=BLUE, lw=1.0, ls="--", zorder=5)
            closing.append(Vector(lab, F, v.at, "internal", v.link if v.link in side else v.other))
            mid = (start + end) / 2
            d = end - start
            nrm = np.array([-d[1], d[0]]) / (np.hypot(*d) or 1.0)
            cv.labels.add(mid[0], mid[1], math_label(lab), prefer=nrm, fontsize=10, color=BLUE)
        ax.plot([poly[0, 0]], [poly[0, 1]], "o", ms=2.5, color=INK)
        return GroupDrawing(cv.svg(), cv.width_mm, mu_l, landscape=landscape, mu_F=mu_F, vectors=seq + closing,
                            constructed=constructed,
                            method=built.method if built is not None else "")


def _unit(v) -> np.ndarray:
    n = float(np.hypot(*v))
    return np.asarray(v, dtype=float) / n if n > 0 else np.zeros(2)


def _component_tex(label: str, sup: str) -> str:
    """R₁₂ with a superscript n or τ in mathtext: $R^{n}_{12}$."""
    text = label.translate(UNSUB)
    return "$" + text[0] + "^{" + sup + "}_{" + text[1:] + "}$"


class Construction(NamedTuple):
    """A force polygon as constructed: its sides in the order drawn (head to tail, the last
    ending at the first's start), the reactions read off it, the sides whose lines of known
    direction were drawn to intersect (pairs of vertex indices of the polygon: side i runs from
    vertex i to i + 1, the closing side of the first link's polygon from vertex k to vertex 0)
    and the method: "closing" (one link, the closing side), "intersection" (two lines through
    the ends of the group's chain; "actuated": the same with the cylinder and the rod as one
    body), "links" (an inner prismatic pair: each link's polygon
    closed by its outer reaction), "link_intersection" (an inner prismatic pair and an outer
    one on the same link: the two lines intersect on that link's polygon)."""

    chain: list[Vector]
    found: list[Constructed]
    lines: list[tuple[int, int]]
    method: str
    internal: list[Vector]        # the inner reactions of the construction (the actuator's pair
                                  # is inside one body: its cylinder and rod bear one link's name)


def construct_polygon(seq: list[Vector], internal: list[Vector], mu_F: float) -> Construction | None:
    """The force polygon of a group constructed as the graphical method does it (Артоболевский [1],
    гл. «Кинетостатика»; Попов–Тимофеев [2]), for every kind of class II group and the initial
    link. Every known force is laid off head to tail, rounded to READ_MM on the drawing, and the
    unknown reactions are read off the drawing to READ_MM:

    - one link (the crank): the closing side of its polygon;
    - inner revolute pair (ВВВ, ВВП, ПВП): each unknown reaction of an outer pair has a known
      line — a revolute pair splits into R^τ ⊥ the link (from the moments of the link about the
      inner pair, analytic) and R^n along the link; a prismatic pair gives R ⊥ the guide; the two
      lines through the ends of the group's chain intersect in the polygon's vertex;
    - inner prismatic pair, both outer pairs revolute (ВПВ): the inner reaction is ⊥ the guide
      and its magnitude comes from the moments of a link about its outer pair (analytic, as R^τ);
      the polygon of each link is then closed by its outer reaction;
    - inner prismatic pair and an outer prismatic pair on one link (ВПП): both reactions on that
      link are ⊥ their guides, so its polygon is closed by intersecting the two lines; the
      other link's polygon is closed by its outer reaction;
    - the initial mechanism of an actuator-driven linkage: the cylinder and the rod are one
      body of variable length (structure.decomposition), joined to the output link by a
      revolute pair, which is then an inner revolute pair as above (R^n along the cylinder).

    Returns the ``Construction`` or None where the group has none of these forms (class III
    groups, the actuator's pair, lines closer than 3° to parallel)."""
    unknown = [v for v in seq if v.role == "unknown"]

    def drawn_vec(F) -> np.ndarray:
        # a side shorter than TINY_MM is laid off on the enlarged inset, where its rounding error
        # is m times smaller: it is kept at its length
        n = float(np.hypot(*F))
        return np.asarray(F, dtype=float) if n / mu_F < TINY_MM else _unit(F) * drawn(n, mu_F)

    def laid(v: Vector) -> Vector:
        return Vector(v.label, drawn_vec(v.F), v.at, v.role, v.link, v.other, v.kind, v.tex)

    def read(label: str, R, exact) -> Constructed:
        return Constructed(label, drawn(float(np.hypot(*R)), mu_F), float(np.hypot(*exact)))

    if len(unknown) == 1 and not internal:      # one link (the crank): the closing side of the polygon
        u = unknown[0]
        chain = [laid(v) for v in seq if v.role != "unknown"]
        if not chain:
            return None
        C = np.sum([v.F for v in chain], axis=0)
        return Construction(chain + [Vector(u.label, -C, u.at, "unknown", u.link, kind=u.kind)],
                            [read(u.label, C, u.F)], [], "closing", [])
    act = [w for w in internal if w.kind == KS.K_ACT]
    if len(act) == 1 and len(internal) == 2:
        return _construct_actuated(seq, internal, act[0], mu_F)
    if len(unknown) != 2 or unknown[0].link == unknown[1].link or len(internal) != 1:
        return None
    if internal[0].kind == KS.K_PRI:
        return _construct_inner_prismatic(seq, unknown, internal[0], laid, read)
    if internal[0].kind != KS.K_REV:
        return None
    dirs = []
    for v in unknown:
        if v.kind == KS.K_PRI:
            d = _unit(v.F)                       # the normal of the guide (no friction)
        elif v.kind == KS.K_REV:
            d = _unit(np.subtract(internal[0].at, v.at))
        else:
            return None
        if not d.any():
            return None
        dirs.append(d)
    if _parallel(*dirs):
        return None

    (u1, u2), (d1, d2) = unknown, dirs
    t1, t2 = u1.F - (u1.F @ d1) * d1, u2.F - (u2.F @ d2) * d2
    known = [v for v in seq if v.role != "unknown"]
    middle = sorted(known, key=lambda v: (v.link != u1.link, v.link == u2.link))
    chain = []
    if float(np.hypot(*t1)) > 1e-9 * float(np.hypot(*u1.F)):
        chain.append(Vector(u1.label, drawn_vec(t1), u1.at, "known", u1.link, kind=u1.kind,
                            tex=_component_tex(u1.label, r"\tau")))
    chain += [laid(v) for v in middle]
    if float(np.hypot(*t2)) > 1e-9 * float(np.hypot(*u2.F)):
        chain.append(Vector(u2.label, drawn_vec(t2), u2.at, "known", u2.link, kind=u2.kind,
                            tex=_component_tex(u2.label, r"\tau")))
    C = np.sum([v.F for v in chain], axis=0) if chain else np.zeros(2)
    lam = np.linalg.solve(np.column_stack([d1, d2]), -C)     # λ₁d₁ + C + λ₂d₂ = 0
    n1, n2 = lam[0] * d1, lam[1] * d2
    sup = ["n" if v.kind == KS.K_REV else None for v in unknown]
    first = Vector(u1.label, n1, u1.at, "unknown", u1.link, kind=u1.kind,
                   tex=_component_tex(u1.label, "n") if sup[0] and chain and chain[0].label == u1.label else "")
    last = Vector(u2.label, n2, u2.at, "unknown", u2.link, kind=u2.kind,
                  tex=_component_tex(u2.label, "n") if sup[1] and chain and chain[-1].label == u2.label else "")
    R1 = n1 + (chain[0].F if chain and chain[0].label == u1.label else 0.0)
    R2 = n2 + (chain[-1].F if chain and chain[-1].label == u2.label else 0.0)
    n = len(chain) + 1
    return Construction([first] + chain + [last], [read(u1.label, R1, u1.F), read(u2.label, R2, u2.F)],
                        [(0, 1), (n, n + 1)], "intersection", internal)


def _construct_actuated(seq, internal, act: Vector, mu_F: float) -> Construction | None:
    """The initial mechanism of an actuator-driven linkage with the cylinder and the rod taken
    as one body (the actuator's force, normal force and moment are inner forces of the body)."""
    body = {act.link: act.other, act.other: act.other}

    def merged(v: Vector) -> Vector:
        return Vector(v.label, v.F, v.at, v.role, body.get(v.link, v.link), body.get(v.other, v.other),
                      v.kind, v.tex, pair_label(v.link, v.other) if v.other else "")

    rest = [merged(w) for w in internal if w is not act]
    if rest[0].link == rest[0].other:
        return None
    built = construct_polygon([merged(v) for v in seq], rest, mu_F)
    return built._replace(method="actuated") if built is not None and built.method == "intersection" else None


def _parallel(d1, d2) -> bool:
    """Lines closer than 3° to parallel do not give a readable intersection."""
    return abs(d1[0] * d2[1] - d1[1] * d2[0]) < 0.05


def _construct_inner_prismatic(seq, unknown, inner: Vector, laid, read) -> Construction | None:
    """The polygons of a group whose inner pair is prismatic (ВПВ, ВПП), link by link: the chain
    is [outer reaction of link a, loads of a, loads of b, outer reaction of b]; the inner
    reaction closes the polygon of link a (vertex k back to vertex 0), drawn dashed by the
    caller. Link b is the one with the outer prismatic pair when there is one."""
    d_in = _unit(inner.F)                               # ⊥ the inner guide (no friction)
    by_link = {v.link: v for v in unknown}
    if not d_in.any() or set(by_link) != {inner.link, inner.other}:
        return None
    pri = [v for v in unknown if v.kind == KS.K_PRI]
    if any(v.kind not in (KS.K_REV, KS.K_PRI) for v in unknown) or len(pri) == 2:
        return None
    ub = pri[0] if pri else next(v for v in unknown if v.link == inner.link)
    ua = next(v for v in unknown if v is not ub)
    la = [laid(v) for v in seq if v.role != "unknown" and v.link == ua.link]
    lb = [laid(v) for v in seq if v.role != "unknown" and v.link == ub.link]
    La = np.sum([v.F for v in la], axis=0) if la else np.zeros(2)
    Lb = np.sum([v.F for v in lb], axis=0) if lb else np.zeros(2)
    sign = 1.0 if inner.link == ub.link else -1.0     # inner.F acts on inner.link
    found = []
    if pri:       # ВПП: on link b, R_ab ⊥ the inner guide and R_0b ⊥ the outer guide intersect
        d_out = _unit(ub.F)
        if not d_out.any() or _parallel(d_in, d_out):
            return None
        lam = np.linalg.solve(np.column_stack([d_in, d_out]), -Lb)
        R_ab, Rb = lam[0] * d_in, lam[1] * d_out
        found.append(read(ub.label, Rb, ub.F))
        found.append(read(inner.label if sign > 0 else pair_label(inner.link, inner.other), R_ab, sign * inner.F))
        method = "link_intersection"
    else:         # ВПВ: R_ab from the moments (analytic), laid off to the drawing's accuracy
        R_ab = laid(Vector(inner.label, sign * inner.F, inner.at, "known")).F
        Rb = -(Lb + R_ab)
        found.append(read(ub.label, Rb, ub.F))
        method = "links"
    Ra = R_ab - La                                      # link a: R_a + L_a − R_ab = 0
    found.insert(0, read(ua.label, Ra, ua.F))
    chain = ([Vector(ua.label, Ra, ua.at, "unknown", ua.link, kind=ua.kind)] + la + lb
             + [Vector(ub.label, Rb, ub.at, "unknown", ub.link, kind=ub.kind)])
    k = 1 + len(la)                                     # the vertex where link a's polygon is closed
    n = len(chain)
    lines = [(n - 1, n), (k, 0)] if pri else []
    return Construction(chain, found, lines, method, [inner])


def _direction_lines(ax, lines: list[tuple[int, int]], poly: np.ndarray) -> None:
    """The lines of known direction (sides between the given vertices of the polygon), thin
    dash-dot beyond the vertex where they intersect (the construction left visible on the
    drawing)."""
    for i, j in lines:
        a, b = poly[i], poly[j]
        d = b - a
        n = float(np.hypot(*d))
        if n == 0:
            continue
        ext = d / n * max(n * 0.25, float(np.ptp(poly[:, 0])) * 0.08)
        ax.plot([a[0] - ext[0], b[0] + ext[0]], [a[1] - ext[1], b[1] + ext[1]], color=GREY, lw=0.5,
                ls=(0, (8, 2, 1, 2)), zorder=3)


class LoadedScheme:
    """The whole mechanism at a report position to a ГОСТ 2.302 scale with every applied load:
    the weights G, the inertia forces Φ at the centres of mass, the useful (technological)
    resistance, the inertia moments M_Φ and the balancing moment M_ур (or the actuator's force)
    as arcs, in textbook notation; the arrows are not to scale (their lengths grow with the
    force, the largest ``ARROW_MM``), with the pivots' centre lines and the guides' axes."""

    needs = ("forces",)

    def __init__(self, label: str, mu: float | None = None):
        self.label, self.mu = label, mu

    def draw(self, study) -> Drawing:
        from .draw import mechanism_centre_lines
        from .mechanism import fit_canvas
        f = study.forces
        mech = study.mechanism
        det = f.details(self.label)
        cols = det["cols"]
        forces = [ld for ld in det["loads"] if ld["M"] is None and np.hypot(ld["Fx"], ld["Fy"]) > 0]
        moments = [dict(label=load_label(ld), M=ld["M"], link=ld["link"]) for ld in det["loads"]
                   if ld["M"] is not None]
        for pv in det["pairs"]:
            p = pv["pair"]
            if p.kind == KS.K_MOM:
                moments.append(dict(label="Mур", M=pv["M"], link=p.b))
        Fmax = max([float(np.hypot(ld["Fx"], ld["Fy"])) for ld in forces] + [1e-12])
        pts = _points(mech)
        xs = [cols["x_" + p] for p in pts]
        ys = [cols["y_" + p] for p in pts]
        span = max(np.ptp(xs), np.ptp(ys), 1e-9)
        reach = 0.2 * span                               # room for the arrows (a fifth of the mechanism)
        cv = fit_canvas([min(xs) - reach, max(xs) + reach], [min(ys) - reach, max(ys) + reach], self.mu,
                        avail_w=150, avail_h=150, margin_mm=6)
        draw_mechanism(cv, mech, cols, lw=1.4)
        mechanism_centre_lines(cv, mech, cols)
        big = max(1.0, 0.2 * span / cv.mu / ARROW_MM)     # on a large drawing the arrows grow with it
        for ld in forces:
            F = np.array([ld["Fx"], ld["Fy"]])
            n = float(np.hypot(*F))
            at = (cols["x_" + ld["point"]], cols["y_" + ld["point"]])
            L = cv.mm(max(2 * MIN_ARROW_MM, _arrow_mm(n, Fmax) * big))   # longer than the moments' arcs
            tip = (at[0] + F[0] / n * L, at[1] + F[1] / n * L)
            color = INK if ld["kind"] in ("G", "Phi") else RED
            arrow(cv.ax, at[0], at[1], tip[0], tip[1], color=color, lw=1.2, zorder=6)
            cv.labels.add(tip[0], tip[1], math_label(load_label(ld)), prefer=tuple(F), fontsize=10, color=color)
        _moment_arcs(cv, moments, mech, f.model.ref, cols)
        return Drawing(cv.svg(), cv.width_mm, cv.mu)


TINY_MM = 5.0          # a polygon side shorter than this is repeated enlarged in an inset
INSET_MM = (6.0, 40.0)  # the smallest enlarged side at least, the whole enlarged chain at most


def _runs(idx: list[int]) -> list[list[int]]:
    out: list[list[int]] = []
    for i in idx:
        if out and out[-1][-1] == i - 1:
            out[-1].append(i)
        else:
            out.append([i])
    return out


INSET_RATIO = 4.0     # tiny sides differing more than this in size go to separate insets


def _size_runs(runs: list[list[int]], seq) -> list[list[int]]:
    """Runs of tiny polygon sides cut where one side is more than INSET_RATIO times the next (or
    the previous): a chain Φ₅, Φ₄, G₄ of 60, 3 and 2 Н enlarged as one piece leaves Φ₄ and G₄ a
    blob of arrowheads beside Φ₅; cut, each piece gets its own magnification."""
    out: list[list[int]] = []
    for run in runs:
        cur = [run[0]]
        for i in run[1:]:
            a, b = float(np.hypot(*seq[cur[-1]].F)), float(np.hypot(*seq[i].F))
            if max(a, b) > INSET_RATIO * max(min(a, b), 1e-300):
                out.append(cur)
                cur = [i]
            else:
                cur.append(i)
        out.append(cur)
    return out


def _magnification(small: float, span: float, mu_F: float) -> float:
    """m of the series 2, 5, 10, 20, 50, … : the smallest with the smallest side ≥ 6 mm, not
    making the chain longer than 45 mm."""
    best = 1.0
    for e in range(0, 8):
        for base in (2.0, 5.0, 10.0):
            m = base * 10 ** e
            if span * m / mu_F > INSET_MM[1]:
                return best
            best = m
            if small * m / mu_F >= INSET_MM[0]:
                return m
    return best


def _inset(seq, cum, mu_F, k, poly, mu_l):
    """Each run of the polygon's tiny sides enlarged m times, drawn under the polygon side by
    side; None when every side is long enough to be read."""
    tiny = [i for i, v in enumerate(seq) if float(np.hypot(*v.F)) / mu_F < TINY_MM]
    parts, shown = [], set()
    ox = poly[:, 0].min()
    top = poly[:, 1].min() - 16.0 * mu_l
    pad = 5.0 * mu_l
    for run in _size_runs(_runs(tiny), seq):
        sub = cum[run[0]:run[-1] + 2]
        span = max(np.ptp(sub[:, 0]), np.ptp(sub[:, 1]), 1e-12)
        small = max(min(float(np.hypot(*seq[i].F)) for i in run), 1e-12)
        m = _magnification(small, span, mu_F)
        if m <= 1.0:
            continue
        pts = (sub - sub.min(axis=0)) * k * m
        pts = pts + np.array([ox + pad, top - pad - pts[:, 1].max()])
        segs = _inset_sides(pts, OFFSET_MM * mu_l, NEAR_MM * mu_l)
        ends = np.vstack([pts] + [np.vstack(sg[:2]) for sg in segs])
        lo, hi = ends.min(axis=0), ends.max(axis=0)
        box = np.array([[lo[0] - pad, lo[1] - pad], [hi[0] + pad, max(top, hi[1] + pad)]])
        parts.append(dict(run=run, pts=pts, segs=segs, box=box, m=m))
        shown |= set(run)
        ox = box[1, 0] + 6.0 * mu_l
    if not parts:
        return None
    return dict(tiny=shown, parts=parts, box=np.vstack([p["box"] for p in parts]))


def _inset_sides(pts: np.ndarray, offset: float, near: float) -> list[tuple[np.ndarray, np.ndarray, bool]]:
    """The sides of an enlarged chain as drawn: (start, end, moved). A side that would cover more
    than a fifth of an earlier side (the chain folds back on itself: G₃ and Φ₃ nearly opposite) is
    moved ``offset`` beside itself, away from that side, as the main polygon's closing side is
    (``_clear_of_sides``), or twice as far or to the other side when that place covers a side
    too; it is joined to its vertices by thin lines. Sides shorter than 2·``near`` (drawn in an
    enlarged inset) neither cover nor are covered, and a side meeting the previous one at their
    common vertex is not covered by it there (1,5·``near`` of both left out)."""
    out: list[tuple[np.ndarray, np.ndarray, bool]] = []
    trim = 1.5 * near

    def cut(p, q, ends):
        """The segment pq without ``trim`` at each of its ends touching ``ends`` (a common vertex)."""
        L = float(np.hypot(*(q - p)))
        u = (q - p) / (L or 1.0) * trim
        at_p = any(float(np.hypot(*(p - e))) < 2.0 * near for e in ends)
        at_q = any(float(np.hypot(*(q - e))) < 2.0 * near for e in ends)
        if L <= trim * (at_p + at_q):
            return None
        return (p + u if at_p else p, q - u if at_q else q)

    def hit(a, b):
        for s0, s1, _ in out:
            if float(np.hypot(*(s1 - s0))) < 2.0 * near:
                continue
            mine, theirs = cut(a, b, (s0, s1)), cut(s0, s1, (a, b))
            if mine is None or theirs is None or _crossing(*mine, *theirs):
                continue
            if covered(*mine, *theirs, near) > 0.2 or covered(*theirs, *mine, near) > 0.2:
                return s0, s1
        return None

    for n in range(len(pts) - 1):
        a, b = pts[n], pts[n + 1]
        first = hit(a, b) if float(np.hypot(*(b - a))) >= 2.0 * near else None
        if first is None:
            out.append((a, b, False))
            continue
        d = b - a
        nrm = np.array([-d[1], d[0]]) / (np.hypot(*d) or 1.0)
        if ((first[0] + first[1]) / 2 - (a + b) / 2) @ nrm > 0:
            nrm = -nrm
        off = next((nrm * offset * k for k in (1.0, -1.0, 2.0, -2.0)
                    if hit(a + nrm * offset * k, b + nrm * offset * k) is None), nrm * offset)
        out.append((a + off, b + off, True))
    return out


def _crossing(a0, a1, b0, b1, min_sin: float = 0.25) -> bool:
    """Whether the segments cross inside both at an angle over ≈ 15° (sin > ``min_sin``): such
    sides are read apart however near they run around the crossing."""
    d, e = a1 - a0, b1 - b0
    den = float(d[0] * e[1] - d[1] * e[0])
    if abs(den) <= min_sin * float(np.hypot(*d) * np.hypot(*e)):
        return False
    w = b0 - a0
    t, u = (w[0] * e[1] - w[1] * e[0]) / den, (w[0] * d[1] - w[1] * d[0]) / den
    return 0.0 < t < 1.0 and 0.0 < u < 1.0


def _draw_inset(cv, seq, inset) -> None:
    """The enlarged chains in dashed frames, each with its magnification."""
    from matplotlib.patches import Rectangle
    for part in inset["parts"]:
        (x0, y0), (x1, y1) = part["box"]
        cv.ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, lw=0.5, ls=(0, (4, 2)), color=GREY))
        pts = part["pts"]
        for n, i in enumerate(part["run"]):
            v = seq[i]
            a, b, moved = part["segs"][n]
            color = BLUE if v.role == "unknown" else INK
            if moved:                     # shifted off a side it would cover: joined by thin lines
                for p0, p1 in ((pts[n], a), (pts[n + 1], b)):
                    cv.ax.plot([p0[0], p1[0]], [p0[1], p1[1]], lw=0.4, color=GREY, zorder=4)
            arrow(cv.ax, a[0], a[1], b[0], b[1], color=color, lw=1.1, zorder=6)
            d = b - a
            nrm = np.array([-d[1], d[0]]) / (np.hypot(*d) or 1.0)
            cv.labels.add((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, v.tex or math_label(v.label), prefer=nrm, fontsize=10,
                          color=color)
        cv.labels.add((x0 + x1) / 2, y0, f"×{part['m']:.0f}", prefer=(0, -1), fontsize=8)


PORTRAIT_W = 170.0    # width of a group's drawing on a portrait page, mm
GROUP_MAX_H = 200.0   # height of a group's drawing enlarged to a finer scale (GroupForces._grown), mm
SCHEME_GROWTH = (1.25, 1.5, 2.0, 2.5, 3.0)   # room of a small scheme tried, × its first room
SMALL_SCHEME_MM = PORTRAIT_W / 3   # a group's links spanning less than this on paper are drawn larger
OFFSET_MM = 3.5       # an inner reaction covering a side of the polygon is drawn this far beside it
NEAR_MM = 1.2         # two sides closer than this along a stretch cover each other at print scale


def covered(a0, a1, b0, b1, near: float, samples: int = 41) -> float:
    """The share of the segment a0a1 lying within ``near`` of the segment b0b1."""
    a0, a1, b0, b1 = (np.asarray(x, dtype=float) for x in (a0, a1, b0, b1))
    t = np.linspace(0.0, 1.0, samples)[:, None]
    pts = a0 + t * (a1 - a0)
    d = b1 - b0
    dd = float(d @ d)
    u = np.clip((pts - b0) @ d / dd, 0.0, 1.0) if dd > 0 else np.zeros(samples)
    dist = np.hypot(*(pts - (b0 + u[:, None] * d)).T)
    return float(np.mean(dist < near))


def _along_bar(v, L: float, bars, near: float) -> bool:
    """Whether the load ``v``, drawn from its point ``L`` long (data units), would lie along one of
    the ``bars`` (a link's line) and drawn the other way would not: it is then drawn ending at its
    point (a slider's resistance pushing up the rod's line)."""
    if v.role != "load":
        return False
    n = float(np.hypot(*v.F))
    ex, ey = v.F[0] / n, v.F[1] / n

    def on_bar(sign):
        tip = np.array([v.at[0] + sign * ex * L, v.at[1] + sign * ey * L])
        return any(covered(np.asarray(v.at, float), tip, b0, b1, near) > 0.2
                   for b0, b1 in bars if float(np.hypot(*(b1 - b0))) > 0)
    return on_bar(1.0) and not on_bar(-1.0)


def _opposes_load(v, ext) -> bool:
    """Whether the reaction ``v`` is nearly opposite (within 25°) to a load applied at its point."""
    u = _unit(v.F)
    scale = max(float(np.hypot(*w.at)) for w in ext) or 1.0
    return v.role != "load" and any(
        w.role == "load" and float(np.hypot(*(np.asarray(w.at) - np.asarray(v.at)))) < 1e-9 * scale
        and float(_unit(w.F) @ u) < -0.9 for w in ext)


def _clear_of_sides(start, end, poly, offset: float, near: float):
    """The closing side start→end of a link's polygon, moved ``offset`` beside itself (away from
    the polygon's middle; twice as far, or to the other side, when that place still covers a side)
    when it would cover more than a fifth of a side of the polygon (an inner reaction nearly
    collinear with an outer one: a link loaded almost by two forces): (start, end, moved)."""
    def hits(s, e):
        return any(covered(s, e, poly[i], poly[i + 1], near) > 0.2 or covered(poly[i], poly[i + 1], s, e, near) > 0.2
                   for i in range(len(poly) - 1))
    if not hits(start, end):
        return start, end, False
    d = end - start
    nrm = np.array([-d[1], d[0]]) / (np.hypot(*d) or 1.0)
    if (poly.mean(axis=0) - (start + end) / 2) @ nrm > 0:
        nrm = -nrm
    off = next((nrm * offset * k for k in (1.0, 2.0, -1.0, -2.0)
                if not hits(start + nrm * offset * k, end + nrm * offset * k)), nrm * offset)
    return start + off, end + off, True


SCHEME_SHIFT_MM = 2.5   # a scheme's arrow along another one at the same point is drawn this far beside it


def _beside(a0, a1, lx, ly, drawn, shift: float, near: float):
    """A scheme's force arrow a0→a1 covering more than a fifth of an arrow already drawn (Φ₅ and
    P_пс both applied at the slider along its guide) moved ``shift`` beside itself, to the side
    where it covers none; the label's anchor moves with it: (a0, a1, lx, ly)."""
    def hits(p0, p1):
        return any(covered(p0, p1, s0, s1, near) > 0.2 or covered(s0, s1, p0, p1, near) > 0.2 for s0, s1 in drawn)
    if not hits(a0, a1):
        return a0, a1, lx, ly
    d = a1 - a0
    nrm = np.array([-d[1], d[0]]) / (np.hypot(*d) or 1.0)
    for k in (1.0, -1.0, 2.0, -2.0):
        off = nrm * shift * k
        if not hits(a0 + off, a1 + off):
            return a0 + off, a1 + off, lx + off[0], ly + off[1]
    return a0, a1, lx, ly


def cv_gap(mu_l: float) -> float:
    """Gap between the scheme and the force polygon: 22 mm in canvas units."""
    return 22.0 * mu_l


@dataclass
class LeverDrawing(Drawing):
    moments: pd.DataFrame = None        # label, F [N], h [mm], Fh = ±F·h [N·mm], balancing
    analog: bool = True                 # a plan of velocity analogs (static mode)
    arm_mm: float = 0.0                 # signed moment of the unit balancing load about the pole [mm],
                                        # as measured on the drawing (to 0,5 mm)
    graphic: float = 0.0                # the balancing force found on the drawing: −Σ F·h / h_ур
    arm_exact_mm: float = 0.0
    forces_turned: bool = False         # the plan unturned, the forces turned by 90° clockwise
    insets: list = field(default_factory=list)   # enlarged views of crowded images (scenes.plans.Inset)
    in_views: int = 0                   # forces drawn in the enlarged views (not on the lever itself)


class ZhukovskyLever:
    """Жуковский's lever: the plan of velocities (analogs when the motion is static) turned by
    90° counter-clockwise, with every load applied at the image of its point (moments as
    couples on two points of their link) and the balancing force at the image of the crank pin
    (or the actuator's force on the rod and the cylinder)."""

    needs = ("forces", "kinematics")

    def __init__(self, label: str, mu: float | None = None, landscape: bool = False):
        """``mu``: the scale of the turned plan asked by the caller (a drawing sheet);
        ``landscape``: a landscape page may be taken where it pays (the note)."""
        self.label = label
        self.mu = mu
        self.landscape = landscape

    def draw(self, study) -> LeverDrawing:
        f = study.forces
        mech = study.mechanism
        det = f.details(self.label)
        cols = det["cols"]
        w = float(f.solution.omega[det["index"]])
        analog = abs(w) < 1e-300
        scale = 1.0 if analog else w
        row = pd.Series({**cols, **{f"vx_{p}": scale * cols[f"vqx_{p}"] for p in _points(mech)},
                         **{f"vy_{p}": scale * cols[f"vqy_{p}"] for p in _points(mech)}})
        plan = velocity_plan(row, mech)
        rot = {k: np.array([-v[1], v[0]]) for k, v in plan.tips.items()}
        # applied loads (forces at images, moments as couples)
        items = []
        for ld in det["loads"]:
            if ld["M"] is None:
                p = ld["point"]
                items.append((load_label(ld), rot[p], np.array([ld["Fx"], ld["Fy"]]), False))
            else:
                cc = {k: np.array([v]) for k, v in cols.items()}
                (xa, ya, va), (xb, yb, vb) = lever_points(cc, mech, ld["link"])
                dx, dy = float(xb[0] - xa[0]), float(yb[0] - ya[0])
                l2 = dx * dx + dy * dy
                fc = ld["M"] / l2 * np.array([-dy, dx])
                pa = scale * np.array([-float(va[1][0]), float(va[0][0])])
                pb = scale * np.array([-float(vb[1][0]), float(vb[0][0])])
                lab = load_label(ld)
                items.append((lab + "′", pb, fc, False))
                items.append((lab + "″", pa, -fc, False))
        row_f = f.row(self.label)
        d = mech.driver
        if d.rotary:
            pin = crank_pin(mech)
            o = np.array([cols["x_" + d.center], cols["y_" + d.center]])
            a = np.array([cols["x_" + pin], cols["y_" + pin]])
            t = np.array([-(a - o)[1], (a - o)[0]]) / np.hypot(*(a - o))
            bal = [("Fур", rot[pin], float(row_f["F_bal_zhukovsky"]) * t, True)]
            arm = float(rot[pin][0] * t[1] - rot[pin][1] * t[0])
        else:
            e = np.array([cols["x_" + d.end], cols["y_" + d.end]])
            b = np.array([cols["x_" + d.center], cols["y_" + d.center]])
            u = (e - b) / np.hypot(*(e - b))
            wc = cols["wq_" + d.link]
            vc = np.array([cols["vqx_" + d.center] - wc * (e - b)[1], cols["vqy_" + d.center] + wc * (e - b)[0]])
            pc = scale * np.array([-vc[1], vc[0]])
            F = float(row_f["F_act_zhukovsky"])
            dp = rot[d.end] - pc
            arm = float(dp[0] * u[1] - dp[1] * u[0])
            bal = [("F" + d.rod.translate(SUBSCRIPT), rot[d.end], F * u, True),
                   ("F" + d.link.translate(SUBSCRIPT), pc, -F * u, True)]
        tips = np.array([[0.0, 0.0]] + [list(v) for v in rot.values()] + [list(it[1]) for it in items + bal])
        # a plan turned into a tall, narrow lever is turned back: the plan as drawn with every force
        # turned by 90° clockwise instead — the same moments about the pole (Артоболевский [1])
        turned = bool(np.ptp(tips[:, 1]) > 1.3 * np.ptp(tips[:, 0]))
        if turned:
            back = lambda v: np.array([v[1], -v[0]])  # noqa: E731 - rotation by −90°
            rot = {k: back(v) for k, v in rot.items()}
            items = [(lab, back(pt), back(F), b) for lab, pt, F, b in items]
            bal = [(lab, back(pt), back(F), b) for lab, pt, F, b in bal]
            tips = np.array([[t[1], -t[0]] for t in tips])
        landscape = False
        insets = []
        if self.mu is None:
            # on a landscape page when that enlarges the lever at least LANDSCAPE_GAIN times
            wide = dict(avail_w=LANDSCAPE_W, avail_h=LANDSCAPE_H - 32, margin_mm=16, page_w=LANDSCAPE_W)
            landscape = self.landscape and (Canvas.scale(tips[:, 0], tips[:, 1], avail_w=160, avail_h=170, margin_mm=16)
                         >= LANDSCAPE_GAIN * Canvas.scale(tips[:, 0], tips[:, 1], **wide))
            page = wide if landscape else dict(avail_w=160, avail_h=170, margin_mm=16)
            mu = Canvas.scale(tips[:, 0], tips[:, 1], **page)
            # crowded images (a long thin lever: points a millimetre apart near the pole) shown
            # enlarged as on the plans, ГОСТ 2.305 выносные элементы
            lever_plan = Plan(plan.kind, {k: v for k, v in rot.items() if k in plan.tips}, plan.segments,
                              plan.point_of_tip)
            max_w = LANDSCAPE_W if landscape else 165.0
            insets = find_insets(lever_plan, mu, max_w - 32)
            box = np.vstack([tips] + [[i.at - i.radius * i.k - i.pad, i.at + i.radius * i.k + i.pad] for i in insets])
            cv = Canvas(box[:, 0].min(), box[:, 0].max(), box[:, 1].min(), box[:, 1].max(), mu, 16, max_w=max_w)
        else:
            cv = Canvas(tips[:, 0].min(), tips[:, 0].max(), tips[:, 1].min(), tips[:, 1].max(), self.mu, 16, max_w=1e4)
        ax = cv.ax
        for seg in plan.segments:
            p0 = np.zeros(2) if seg.start == "p" else rot[seg.start]
            p1 = rot[seg.end]
            ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color=GREY if seg.kind == "abs" else INK,
                    lw=0.8 if seg.kind == "abs" else 1.2, ls="--" if seg.kind == "abs" else "-", zorder=2)
        ax.plot([0], [0], "o", ms=3, color=INK)
        hidden = {lab for i in insets for lab in i.tips}
        if "p" not in hidden:
            cv.labels.add(0.0, 0.0, "$p$", prefer=(-1, -1), fontsize=10)
        shown = [lab for lab, v in rot.items() if lab in plan.point_of_tip and np.hypot(*v) >= 1e-12 and lab not in hidden]
        for lab, group in coincident(rot, shown, cv.mm(SAME_MM)).items():
            v = rot[lab]
            cv.labels.add(v[0], v[1], joint_label(group, plan, "velocity"), prefer=v, fontsize=10, color=GREY)
        for n, ins in enumerate(insets):
            ins.mark = INSET_MARKS[n % len(INSET_MARKS)]
            PlanScene(self.label, "velocity")._draw_inset(cv, lever_plan, ins, "$p$")
        Fmax = max([float(np.hypot(*it[2])) for it in items + bal] + [1e-12])
        # a load that the moments' table prints as 0 Н (the couple of a crank's inertia moment of
        # 0,001 Н·м among forces of kilonewtons) is neither drawn nor listed
        dec = shared_decimals([float(np.hypot(*it[2])) for it in items + bal])
        rows = []
        in_views = 0
        # the balancing force placed first: its label and leader at the crank pin are settled before
        # the loads sharing its line there (the crank's own inertia couple M′_Φ1 ⊥ pa at a) look for room
        order = bal + items
        # a force at an image inside an enlarged view is drawn there only (the region of the
        # lever is marked by its circle), not crowded on the lever itself
        drawn, free = {}, {}
        for j, (_, p, F, is_bal) in enumerate(order):
            n = float(np.hypot(*F))
            if n >= 1e-9 * Fmax and (is_bal or round(n, dec) != 0):
                drawn[j] = max(MIN_ARROW_MM, 0.8 * _arrow_mm(n, Fmax))
                free[j] = (next((ins.at + (p - ins.centre) * ins.k for ins in insets
                                 if np.hypot(*(p - ins.centre)) <= ins.radius), p), F / n)
        # by magnitude (at least MIN_ARROW_MM: a shorter one is all head), staggered where several
        # leave one image in nearly one direction (ws000's G₃ and M′Φ₂ at b, M″Φ₄ and G₅ at h)
        drawn = _clear_heads(_staggered(drawn, free, cv.mm(2.0)), free, cv.mm(1.0))
        for j, (lab, p, F, is_bal) in enumerate(order):
            if j not in drawn:
                continue
            n = float(np.hypot(*F))
            L = cv.mm(drawn[j])
            color = RED if is_bal else INK
            at = free[j][0]
            in_views += at is not p
            tip = at + F / n * L
            arrow(ax, at[0], at[1], tip[0], tip[1], color=color, lw=1.1, zorder=6)
            cv.labels.add(tip[0], tip[1], math_label(lab), prefer=F, fontsize=10, color=color)
            mom = float(p[0] * F[1] - p[1] * F[0]) / cv.mu
            h = round(abs(mom) / n / READ_MM) * READ_MM          # the arm as measured on the drawing
            rows.append(dict(label=lab, F=n, h=h, Fh=math.copysign(n * h, mom) if h > 0 else 0.0,
                             balancing=is_bal, h_exact=abs(mom) / n))
        rows = [r for r in rows if not r["balancing"]] + [r for r in rows if r["balancing"]]   # F_ур last
        table = pd.DataFrame(rows, columns=["label", "F", "h", "Fh", "balancing", "h_exact"])
        arm_mm = arm / cv.mu
        arm_read = math.copysign(round(abs(arm_mm) / READ_MM) * READ_MM, arm_mm)
        loads_ = table[~table["balancing"].astype(bool)]
        total = float(loads_["Fh"].sum())
        graph = -total / arm_read if abs(arm_read) > 0 else 0.0
        return LeverDrawing(cv.svg(), cv.width_mm, cv.mu, landscape=landscape, moments=table, analog=analog,
                            arm_mm=arm_read,
                            graphic=graph, arm_exact_mm=arm_mm, forces_turned=turned, insets=insets,
                            in_views=in_views)


def _points(mech) -> list[str]:
    out = []
    for l in mech.links:
        for p in l.points:
            if p not in out:
                out.append(p)
    return out


# --------------------------------------------------------------------------------------------
# Curves over the cycle
# --------------------------------------------------------------------------------------------
def _x(study, df):
    if study.mechanism.driver.swing:
        return np.degrees(df["q"].to_numpy()), "φ, град", 10
    if study.mechanism.driver.rotary:
        return np.degrees(df["q"].to_numpy() - study.grid.start), "φ, град", 30
    return df["q"].to_numpy(), "S, м", None


def _mark_positions(ax, study, x_of, y_col, tab):
    x = x_of(tab)
    ax.plot(x, tab[y_col].to_numpy(), "o", ms=3, color=INK)


class ReactionCurves:
    """Magnitudes of the reactions of every pair over the cycle (kN) and the balancing moment
    (or the actuator force)."""

    needs = ("forces",)

    def draw(self, study) -> Drawing:
        f = study.forces
        cyc, tab = f.cycle, f.table
        x, xlabel, step = _x(study, cyc)
        fig = mplstyle.figure(160, 150)
        ax1, ax2 = fig.subplots(2, 1, sharex=True, height_ratios=[3, 2])
        # more pairs than colours in the cycle: the next round of colours dashed, then dotted, so
        # that no two curves look alike (R₀₁ and R₀₅ both black in the slotting machine's seven)
        colours = len(matplotlib.rcParams["axes.prop_cycle"])
        n = 0
        for p in f.model.pairs:
            if p.kind == KS.K_MOM:
                continue
            key = shown_key(f, p)
            ax1.plot(x, cyc["R_" + key] / 1e3, lw=1.2, ls=("-", "--", ":", "-.")[(n // colours) % 4],
                     label=pair_label(*key.split("_")[:2]))
            n += 1
        ax1.set_ylabel("$R$, кН")
        legend_rows(ax1, 7, fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), frameon=False)
        m_bal = math_label("Mур")            # $M_{\mathrm{ур}}$: the symbol of the text, not a plain «Mур»
        main, lab = ("M_bal", f"{m_bal}, Н·м") if f.rotary else ("F_act", "$F$, кН")
        k = 1.0 if f.rotary else 1e-3
        xt = _x(study, tab)[0]
        ax2.plot(x, cyc[main] * k, lw=1.3, label=m_bal if f.rotary else None)
        ax2.plot(xt, tab[main] * k, "o", ms=3)
        if "M_bal_linkage" in cyc:
            ax2.plot(x, cyc["M_bal_linkage"], lw=1.1, ls="--", label=f"{m_bal} без маховика")
            ax2.legend(fontsize=8, loc="best")
        ax2.axhline(0, color="0.3", lw=0.6)
        ax2.set_ylabel(lab)
        ax2.set_xlabel(xlabel)
        if step:
            from .diagrams import angle_ticks
            angle_ticks(ax2, x, step)
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


def shown_key(f, p) -> str:
    """The orientation of a pair as chosen in ``[forces] pairs`` (else as declared)."""
    rev = f"{p.b}_{p.a}"
    if rev in f.settings.pairs and p.name not in f.settings.pairs:
        return rev
    return p.name


class CapacityCurves:
    """Worksheet 002, figures 4.1–4.3: the capacity at the points and at the load (with the
    load), the actuator force with the cylinders' force, the pressure with the system pressure."""

    needs = ("forces",)

    def draw(self, study) -> Drawing:
        f = study.forces
        s = f.settings
        cyc, tab = f.cycle, f.table
        S = cyc["q"].to_numpy()
        fig = mplstyle.figure(160, 190)
        ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
        c = s.capacity
        for pt in list(c.points) + [c.point]:
            ax1.plot(S, cyc["Gcap_" + pt] / 1e3, lw=1.3, label=math_label("G" + pt))
            ax1.plot(tab["q"], tab["Gcap_" + pt] / 1e3, "o", ms=3)
        P = float(-[ld for ld in f.solution.loads if ld.name == c.load][0].Fy[0])
        ax1.axhline(P / 1e3, color=RED, lw=1.0, ls="--", label=f"{math_label(c.load)} = {fmt(P / 1e3, sig=4)} кН")
        ax1.set_ylabel("G, кН")
        ax1.legend(fontsize=8, loc="best")
        ax2.plot(S, cyc["F_act"] / 1e3, lw=1.3)
        ax2.plot(tab["q"], tab["F_act"] / 1e3, "o", ms=3)
        ax2.axhline(s.actuator.F_max / 1e3, color=RED, lw=1.0, ls="--", label=r"$k \cdot p \cdot \eta \cdot A$")
        ax2.set_ylabel("F, кН")
        ax2.legend(fontsize=8, loc="best")
        ax3.plot(S, cyc["p_act"] / 1e6, lw=1.3)
        ax3.plot(tab["q"], tab["p_act"] / 1e6, "o", ms=3)
        ax3.axhline(s.actuator.pressure / 1e6, color=RED, lw=1.0, ls="--", label="давление в гидросистеме")
        ax3.set_ylabel("p, МПа")
        ax3.set_xlabel("S, м")
        ax3.legend(fontsize=8, loc="best")
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


class AxleCurves:
    """Worksheet 002, figure 6.2: the share of the weight on the steered axle and the maximum
    capacity G_max (R_A,min of the nominal load) and G*_max (R_A ≥ k_A·ΣG with the load itself),
    as the note's formulas name them. The worksheet's own (wrong) G_max is the answer key's, not
    the student's figure."""

    needs = ("forces",)

    def draw(self, study) -> Drawing:
        f = study.forces
        c = f.settings.carrier
        cyc, tab = f.cycle, f.table
        S = cyc["q"].to_numpy()
        fig = mplstyle.figure(160, 130)
        ax1, ax2 = fig.subplots(2, 1, sharex=True)
        ax1.plot(S, cyc["front_share_pct"], lw=1.3, label="управляемый мост $R_A$")
        ax1.plot(tab["q"], tab["front_share_pct"], "o", ms=3)
        ax1.axhline(100 * c.min_share, color=RED, lw=1.0, ls="--", label="наименьшая допустимая доля")
        ax1.set_ylabel(r"$R_A/\Sigma G$, %")
        ax1.legend(fontsize=8, loc="best")
        ax2.plot(S, cyc["Gmax_carrier"] / 1e3, lw=1.3, label=r"$G_{\mathrm{max}}$")
        ax2.plot(S, cyc["Gmax_carrier_consistent"] / 1e3, lw=1.1, ls="-.", label=r"$G^{*}_{\mathrm{max}}$")
        ax2.set_ylabel("G, кН")
        ax2.set_xlabel("S, м")
        ax2.legend(fontsize=8, loc="best")
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


__all__ = ["LoadedScheme", "GroupForces", "GroupDrawing", "ZhukovskyLever", "LeverDrawing", "ReactionCurves", "CapacityCurves",
           "AxleCurves", "group_vectors", "html_label", "load_label", "pair_label", "shown_key", "sub", "Vector"]
