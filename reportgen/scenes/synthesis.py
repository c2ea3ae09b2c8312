"""The synthesis construction at scale (Артоболевский § 25; Попов, Тимофеев, гл. 2): the extreme
positions of the output link, the chord seen from the crank centre under θ = 180°·(K − 1)/(K + 1),
the θ-circle(s), every variant's crank centre (numbered), and for the chosen variant the
extended and folded crank–coupler lines with the crank circle; for the shaper (slotted lever,
coupler, ram) the coupler and the ram at both extremes, the ram's guide, the sag f and the stroke H."""
from __future__ import annotations

import math

import numpy as np
from matplotlib.patches import Arc, Circle

from ..core import synthesis as S
from ..mechanism.model import FRAME
from .draw import GREY, INK, SUBSCRIPT, Canvas, _block, centre_line
from .mechanism import Drawing

_FS = 9


def _pt(cv: Canvas, p, name: str, dx=1.5, dy=1.5, filled=True, color=INK):
    cv.ax.add_patch(Circle(p, cv.mm(0.9), fc=color if filled else "white", ec=color, lw=0.9, zorder=5))
    cv.labels.add(*p, name, prefer=(dx, dy), point=True, fontsize=_FS, color=color)     # placed by cv.svg()


def _variant_centres(vs, chosen: int, taken: str) -> dict[int, str]:
    """The crank centres of the solution variants as the textbook marks them: O₁, O₂, … (the
    variant's number as a subscript, the numbering of the note's table of variants). Where that
    would repeat a name of the drawing (the six-bar's rocker pivot O₂), the chosen centre is O₁,
    as the crank centre beside the rocker's O₂, and the others O₁′, O₁″, O₁‴ in their order."""
    names = {w["variant"]: "O" + str(w["variant"]).translate(SUBSCRIPT) for w in vs}
    if taken not in names.values():
        return names
    others = [n for n in sorted(names) if n != chosen]
    return {chosen: "O₁", **{n: "O₁" + "′″‴"[i] for i, n in enumerate(others)}}


def _seg(cv: Canvas, p, q, lw=1.4, ls="-", color=INK, z=3):
    cv.ax.plot([p[0], q[0]], [p[1], q[1]], lw=lw, ls=ls, color=color, zorder=z)


def _dim(cv: Canvas, a, b, label: str, **text):
    """A dimension line a ↔ b with its label at the middle (``text``: offset and alignment)."""
    cv.ax.annotate("", xy=b, xytext=a, xycoords="data",
                   arrowprops=dict(arrowstyle="<->", lw=0.7, shrinkA=0, shrinkB=0))
    dx, dy = text.pop("dx", 0.0), text.pop("dy", 1.0)
    cv.labels.add((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, label, prefer=(dx, dy), fontsize=_FS, **text)


def _angle(cv: Canvas, o, p, q, label: str, r_mm=10.0):
    """An arc at o from the direction o→p to o→q (the smaller angle) labelled."""
    a1 = math.degrees(math.atan2(p[1] - o[1], p[0] - o[0]))
    a2 = math.degrees(math.atan2(q[1] - o[1], q[0] - o[0]))
    if (a2 - a1) % 360 > 180:
        a1, a2 = a2, a1
    r = cv.mm(r_mm)
    cv.ax.add_patch(Arc(o, 2 * r, 2 * r, theta1=a1, theta2=a2 if a2 > a1 else a2 + 360, lw=0.8, color=INK))
    mid = math.radians(a1 + ((a2 - a1) % 360) / 2)
    cv.labels.add(o[0] + r * math.cos(mid), o[1] + r * math.sin(mid), label, prefer=(math.cos(mid), math.sin(mid)),
                  fontsize=_FS)


class SynthesisConstruction:
    """The construction of the chosen synthesis variant, all variants' centres marked."""

    needs = ()

    def draw(self, study) -> Drawing:
        sy = study.synthesis
        kind, v, vs = sy.kind, sy.chosen, sy.variants
        ram = self._ram(study) if kind == "slotted_lever" else None
        pts = self._points(kind, v, vs)
        if ram:
            pts += [(r["x_" + ram["E"]], r["y_" + ram["E"]]) for r in ram["rows"]]
        xs, ys = zip(*pts)
        cv = Canvas.fit(xs, ys, avail_w=150, avail_h=170, margin_mm=14)
        getattr(self, "_" + kind)(cv, v, vs)
        if ram:
            self._shaper(cv, v, ram)
        return Drawing(cv.svg(), cv.width_mm, cv.mu)

    # ---------------------------------------------------------------- the shaper's ram
    @staticmethod
    def _ram(study) -> dict | None:
        """The shaper six-bar (slotted lever + coupler + ram): when the engine's output is a slider
        on the frame coupled to the lever's end, the linkage's positions at the two extremes
        found by the check (the roots of the ram's first analog), if the lever's end there is at
        the synthesised points D₁, D₂ (the case's frame is the synthesis frame)."""
        sy = study.synthesis
        chk = sy.check
        if not chk or chk.get("extremes") != 2 or not chk["column"].startswith("s_"):
            return None
        mech = study.mechanism
        j = next((p for p in mech.prismatic if p.name == chk["column"][2:] and p.links[0] == FRAME), None)
        if j is None:
            return None
        slider, e = j.links[1], j.point
        rod = next((r for r in mech.joints if r.kind == "R" and r.point == e and slider in r.links), None)
        if rod is None:
            return None
        coupler = next(l for l in rod.links if l != slider)
        d = next((r.point for r in mech.joints if r.kind == "R" and coupler in r.links and r.point != e), None)
        if d is None:
            return None
        rows = [row for _, row in study.at(np.array([chk["q1"], chk["q2"]])).iterrows()]
        v = sy.chosen
        h, l = v["theta"] / 2, v["l"]
        ends = {(-l * math.sin(h), l * math.cos(h)), (l * math.sin(h), l * math.cos(h))}
        got = [(r["x_" + d], r["y_" + d]) for r in rows]
        if not all(min(math.hypot(x - p[0], y - p[1]) for p in ends) < 1e-9 * l for x, y in got):
            return None
        rows.sort(key=lambda r: r["x_" + d])        # D₁ (left) first, as in the construction
        return dict(rows=rows, D=d, E=e, joint=j, mech=mech)

    @staticmethod
    def _shaper(cv, v, ram):
        """Both extreme positions of the lever's end D with the coupler DE and the ram E on its
        guide (the ram's axis dash-dot, ГОСТ 2.303 thin); the arc of D with its sag
        f = l·(1 − cos(θ/2)) and the ram's stroke H = E₁E₂ dimensioned."""
        h, l = v["theta"] / 2, v["l"]
        rows, d, e, j = ram["rows"], ram["D"], ram["E"], ram["joint"]
        cv.ax.add_patch(Arc((0.0, 0.0), 2 * l, 2 * l, theta1=90 - math.degrees(h), theta2=90 + math.degrees(h),
                            lw=0.8, ls="--", color=INK))
        ux, uy = math.cos(j.angle), math.sin(j.angle)
        es = [(r["x_" + e], r["y_" + e]) for r in rows]
        s = [(p[0] - es[0][0]) * ux + (p[1] - es[0][1]) * uy for p in es]
        lo, hi = min(s) - cv.mm(16), max(s) + cv.mm(16)
        centre_line(cv, es[0][0] + ux * lo, es[0][1] + uy * lo, es[0][0] + ux * hi, es[0][1] + uy * hi)
        for k, (r, p) in enumerate(zip(rows, es), 1):
            _seg(cv, (r["x_" + d], r["y_" + d]), p, lw=1.4)
            _block(cv, p[0], p[1], j.angle, INK, 1.4, 1.0, 4)
            _pt(cv, p, f"{e}{'₁₂'[k - 1]}", dx=5, dy=2)
        # the ram's stroke H between its extreme positions, above the guide
        nx, ny = -uy, ux
        off = cv.mm(12)
        a, b = [(p[0] + nx * off, p[1] + ny * off) for p in es]
        for p, q in zip(es, (a, b)):
            _seg(cv, (p[0] + nx * cv.mm(3.5), p[1] + ny * cv.mm(3.5)), (q[0] + nx * cv.mm(1.5), q[1] + ny * cv.mm(1.5)), lw=0.5)
        _dim(cv, a, b, "H")
        # the sag f of the arc of D (from its chord D₁D₂ to its top at the lever's mid position),
        # dimensioned left of D₁ on the chord's and the top's extension lines
        y0, y1 = l * math.cos(h), l
        x1 = -l * math.sin(h)
        _seg(cv, (-cv.mm(1.5), y1), (x1 - cv.mm(10), y1), lw=0.5)
        _seg(cv, (x1 - cv.mm(1.5), y0), (x1 - cv.mm(10), y0), lw=0.5)
        xd = x1 - cv.mm(8)
        _dim(cv, (xd, y0), (xd, y1), "f", dx=-1, dy=0, ha="right", va="center")

    # ---------------------------------------------------------------- extents
    @staticmethod
    def _points(kind, v, vs):
        if kind == "slider_crank":
            out = [(0.0, 0.0), (v["x_C2"], 0.0), (v["x_O"] - v["a"], v["y_O"] - v["a"]),
                   (v["x_O"] + v["a"], v["y_O"] + v["a"])]
            for xc, yc, R in S.theta_circles((v["x_C1"], 0.0), (v["x_C2"], 0.0), v["theta"]):
                if abs(math.hypot(v["x_O"] - xc, v["y_O"] - yc) - R) < 1e-9 * R:
                    out += [(xc - R, yc - R), (xc + R, yc + R)]
            return out
        if kind == "slotted_lever":
            h = v["theta"] / 2
            return [(0.0, 0.0), (0.0, v["d"] + v["a"]), (-v["l"] * math.sin(h), v["l"] * math.cos(h)),
                    (v["l"] * math.sin(h), v["l"] * math.cos(h)), (-v["a"], v["d"]), (v["a"], v["d"])]
        out = [(0.0, 0.0), (v["x_B1"], v["y_B1"]), (v["x_B2"], v["y_B2"])]
        out += [(w["x_O"] - w["a"], w["y_O"] - w["a"]) for w in vs] + [(w["x_O"] + w["a"], w["y_O"] + w["a"]) for w in vs]
        if v["theta"] > 1e-12:
            for xc, yc, R in S.theta_circles((v["x_B1"], v["y_B1"]), (v["x_B2"], v["y_B2"]), v["theta"]):
                if any(abs(math.hypot(w["x_O"] - xc, w["y_O"] - yc) - R) < 1e-9 * R for w in vs):
                    out += [(xc - R, yc - R), (xc + R, yc + R)]
        if kind == "six_bar":
            out += [(v["x_C1"], v["path_y"]), (v["x_C2"], v["path_y"])]
        return out

    # ---------------------------------------------------------------- common parts
    @staticmethod
    def _crank(cv, v, far, near, o, names=None):
        """Chosen variant: O–far (a + b), O–near (b − a), the crank circle, θ at O; with
        ``names`` (the A labels of the far and the near extreme) both extreme positions of the
        crank OA drawn bold: A on O→far (extended dyad) and on the far side of O from the
        near extreme (folded dyad, O between A and B)."""
        _seg(cv, o, far, lw=1.0)
        _seg(cv, o, near, lw=1.0)
        cv.ax.add_patch(Circle(o, v["a"], fill=False, ls="--", lw=0.8, ec=INK))
        _angle(cv, o, far, near, "θ", r_mm=14)
        if names is None:
            return
        for p, sg, name in ((far, 1.0, names[0]), (near, -1.0, names[1])):
            d = math.hypot(p[0] - o[0], p[1] - o[1])
            a = (o[0] + sg * v["a"] * (p[0] - o[0]) / d, o[1] + sg * v["a"] * (p[1] - o[1]) / d)
            _seg(cv, o, a, lw=2.0)
            _seg(cv, a, p, lw=1.0)
            _pt(cv, a, name, dx=-sg * 4, dy=-sg * 4)

    @staticmethod
    def _circles(cv, b1, b2, theta, centres):
        """The θ-circles that carry a variant's crank centre."""
        if theta <= 1e-12:
            return
        for xc, yc, R in S.theta_circles(b1, b2, theta):
            if any(abs(math.hypot(x - xc, y - yc) - R) < 1e-9 * R for x, y in centres):
                cv.ax.add_patch(Circle((xc, yc), R, fill=False, ls=":", lw=0.8, ec=GREY))

    @staticmethod
    def _locus(cv, vs):
        """The given locus of the crank centre: the circle about the rocker pivot (all
        centres equally far from it) or the horizontal lines through the centres."""
        ds = [math.hypot(w["x_O"], w["y_O"]) for w in vs]
        if max(ds) - min(ds) < 1e-9 * max(ds) and len({round(w["y_O"], 9) for w in vs}) > 1:
            cv.ax.add_patch(Circle((0.0, 0.0), ds[0], fill=False, ls="-.", lw=0.6, ec=GREY))
            return
        xs = [w["x_O"] for w in vs]
        for y in {round(w["y_O"], 12) for w in vs}:
            _seg(cv, (min(xs) - cv.mm(8), y), (max(xs) + cv.mm(8), y), lw=0.6, ls="-.", color=GREY)

    # ---------------------------------------------------------------- kinds
    def _crank_rocker(self, cv, v, vs, rocker="C", lab=("B₁", "B₂")):
        c0 = (0.0, 0.0)
        b1, b2 = (v["x_B1"], v["y_B1"]), (v["x_B2"], v["y_B2"])
        _seg(cv, c0, b1, lw=2.0)
        _seg(cv, c0, b2, lw=2.0)
        r = v["c"]
        a0 = math.degrees(math.atan2(b2[1], b2[0]))
        cv.ax.add_patch(Arc(c0, 2 * r, 2 * r, theta1=a0, theta2=a0 + math.degrees(v["psi"]), lw=0.8, ls="--", color=INK))
        _seg(cv, b1, b2, lw=0.8, ls="-.", color=GREY)
        _angle(cv, c0, b1, b2, "ψ", r_mm=8)
        self._circles(cv, b1, b2, v["theta"], [(w["x_O"], w["y_O"]) for w in vs])
        self._locus(cv, vs)
        names = _variant_centres(vs, v["variant"], rocker)
        for w in vs:
            if w["variant"] != v["variant"]:
                _pt(cv, (w["x_O"], w["y_O"]), names[w["variant"]], filled=False, color=GREY)
        o = (v["x_O"], v["y_O"])
        far = (v["x_far"], v["y_far"])
        i_far = 0 if math.hypot(far[0] - b1[0], far[1] - b1[1]) < math.hypot(far[0] - b2[0], far[1] - b2[1]) else 1
        sub = [lab[0][-1], lab[1][-1]]
        self._crank(cv, v, far, (v["x_near"], v["y_near"]), o, names=("A" + sub[i_far], "A" + sub[1 - i_far]))
        _pt(cv, c0, rocker, dx=1.5, dy=-4)
        _pt(cv, b1, lab[0], dx=-5, dy=1.5)
        _pt(cv, b2, lab[1])
        _pt(cv, o, names[v["variant"]], dx=1.5, dy=-4)

    def _six_bar(self, cv, v, vs):
        self._crank_rocker(cv, v, vs, rocker="O₂", lab=("B₀", "B₁"))
        y = v["path_y"]
        c1, c2 = (v["x_C1"], y), (v["x_C2"], y)
        lo, hi = min(c1[0], c2[0], 0.0), max(c1[0], c2[0])
        _seg(cv, (lo - cv.mm(5), y), (hi + cv.mm(5), y), lw=0.8, ls="-.", color=INK)
        _seg(cv, (v["x_B1"], v["y_B1"]), c1, lw=1.4)
        _seg(cv, (v["x_B2"], v["y_B2"]), c2, lw=1.4)
        _pt(cv, c1, "C₀", dx=-2, dy=2)
        _pt(cv, c2, "C₁", dx=1, dy=2)
        yd = y - cv.mm(9)
        for c in (c1, c2):
            _seg(cv, c, (c[0], yd - cv.mm(1.5)), lw=0.5)
        _dim(cv, (c1[0], yd), (c2[0], yd), "H")

    def _slider_crank(self, cv, v, vs):
        c1, c2 = (v["x_C1"], 0.0), (v["x_C2"], 0.0)
        o = (v["x_O"], v["y_O"])
        _seg(cv, (min(0.0, c1[0]) - cv.mm(6), 0.0), (c2[0] + cv.mm(6), 0.0), lw=0.8, ls="-.")
        self._circles(cv, c1, c2, v["theta"], [o])
        self._crank(cv, v, c2, c1, o, names=("A₂", "A₁"))
        _seg(cv, o, (o[0], 0.0), lw=0.6, ls="--", color=GREY)
        cv.labels.add(o[0], o[1] / 2, "e", prefer=(-1, 0), fontsize=_FS)
        _pt(cv, c1, "C₁", dx=-2, dy=2)
        _pt(cv, c2, "C₂", dx=1, dy=2)
        _pt(cv, o, "O", dx=-4, dy=-4)

    def _slotted_lever(self, cv, v, vs):
        h = v["theta"] / 2
        c0, o = (0.0, 0.0), (0.0, v["d"])
        d1 = (-v["l"] * math.sin(h), v["l"] * math.cos(h))
        d2 = (v["l"] * math.sin(h), v["l"] * math.cos(h))
        _seg(cv, c0, d1, lw=2.0)
        _seg(cv, c0, d2, lw=2.0)
        _seg(cv, c0, o, lw=0.6, ls="-.", color=GREY)
        cv.ax.add_patch(Circle(o, v["a"], fill=False, ls="--", lw=0.8, ec=INK))
        for s in (-1.0, 1.0):
            a = (s * v["d"] * math.cos(h) * math.sin(h), v["d"] * math.cos(h) ** 2)
            _seg(cv, o, a, lw=1.0)
            _pt(cv, a, "A₁" if s < 0 else "A₂", dx=(-5 if s < 0 else 1.5))
        _angle(cv, c0, d1, d2, "ψ = θ", r_mm=12)
        _pt(cv, c0, "C", dx=1.5, dy=-4)
        _pt(cv, o, "O", dx=1.5, dy=1.5)
        _pt(cv, d1, "D₁", dx=-5)
        _pt(cv, d2, "D₂")
        span = np.array([d1, d2])
        cv.ax.annotate("", xy=tuple(span[1]), xytext=tuple(span[0]),
                       arrowprops=dict(arrowstyle="<->", lw=0.7, shrinkA=0, shrinkB=0))
