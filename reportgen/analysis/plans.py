"""Vector polygons of the graphic-analytic method (план скоростей и план ускорений).

For a position of the mechanism, built from the analytic solution so that every vector of the
plan is exact; the scenes draw them to scale and "measure" them.

* Velocities: V_Q = V_R + V_QR for every point Q of a link with reference point R
  (V_QR ⊥ RQ, |V_QR| = ω·l_RQ); for a slider on a moving guide V_P(slider) = V_P(guide) + V_rel
  (V_rel ∥ guide).
* Accelerations: a_Q = a_R + aⁿ_QR + a^τ_QR (aⁿ = ω²·l toward R, a^τ = ε·l ⊥ RQ); for a slider on
  a moving guide a_P(slider) = a_P(guide) + a^k + a^r, a^k = 2·ω_guide × V_rel (Coriolis),
  a^r ∥ guide.  (Артоболевский, гл. 3; Попов–Тимофеев, «Кинематический анализ».)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..mechanism.model import FRAME, Mechanism


@dataclass
class Segment:
    """One vector of a plan: from the tip ``start`` to the tip ``end`` («p» is the pole), its kind
    and name (V_BA, aⁿ_BA …), its link and its physical length (m/s or m/s²)."""
    start: str           # plan point label at the start ("p" is the pole)
    end: str
    kind: str            # "abs", "rel", "normal", "tangential", "coriolis", "slide"
    name: str            # e.g. "V_BA", "a^n_BA"
    link: str = ""
    length: float = 0.0  # physical length of the vector (m/s or m/s²)


@dataclass
class Plan:
    """A velocity or acceleration plan: the tips as vectors from the pole, the segments, and for
    each tip the mechanism point and the link it belongs to."""
    kind: str                                  # "velocity" or "acceleration"
    tips: dict[str, np.ndarray] = field(default_factory=dict)    # label → vector from the pole
    segments: list[Segment] = field(default_factory=list)
    point_of_tip: dict[str, str] = field(default_factory=dict)   # tip label → mechanism point
    owner: dict[str, str] = field(default_factory=dict)          # tip label → its link, kept for the labels
                                                                 # when the link's segment is dropped


def _vec(row, pre: str, p: str) -> np.ndarray:
    return np.array([row[f"{pre}x_{p}"], row[f"{pre}y_{p}"]], dtype=float)


def _rot90(v: np.ndarray) -> np.ndarray:
    return np.array([-v[1], v[0]])


def _reference(mech: Mechanism, link) -> str:
    """The point of a link through which it is attached to the links solved before it: of its
    joint points, the one joined to the link listed first (the frame first, then the links in
    the case's order), so that the plans write V_HD = ω·l_DH of a coupler DH attached at D as
    the vector equations do (not V_DH because the case lists H first)."""
    rank = {l.name: i for i, l in enumerate(mech.links)}
    best: dict[str, int] = {}
    for j in mech.joints:
        if link.name in j.links:
            other = j.links[0] if j.links[1] == link.name else j.links[1]
            best[j.point] = min(best.get(j.point, len(rank)), rank.get(other, len(rank)))
    pts = [p for p in link.points if p in best]
    if pts:
        return min(pts, key=lambda p: best[p])          # ties: the first listed
    return next(iter(link.points))


def _coincident(row, mech: Mechanism, guide: str, p: str):
    """Velocity and acceleration of the guide's material point under point p."""
    if guide == FRAME:
        return np.zeros(2), np.zeros(2)
    link = mech.link(guide)
    ref = _reference(mech, link)
    r = _vec(row, "", p) - _vec(row, "", ref)
    w, e = row["w_" + guide], row["e_" + guide]
    v = _vec(row, "v", ref) + w * _rot90(r)
    a = _vec(row, "a", ref) + e * _rot90(r) - w * w * r
    return v, a


def _relative_points(mech: Mechanism):
    """(link, its reference point R, another point Q of it) for every moving link: the relative
    vectors V_QR, aⁿ_QR, a^τ_QR of the plans."""
    for link in mech.moving:
        ref = _reference(mech, link)
        for p in link.points:
            if p != ref:
                yield link, ref, p


def _guide_points(plan: Plan, row, mech: Mechanism, accel: bool = False):
    """For every prismatic joint on a moving guide: the joint, the guide, the slider, the label of
    the tip of the guide's point under the slider (set on the plan to that point's velocity, or
    acceleration when ``accel``) and the velocity of that point; the actuator's driving pair
    (the rod on the swinging cylinder) among them."""
    drive = mech.driving_pair()
    for j in mech.prismatic + ([drive] if drive is not None else []):
        guide, slider = j.links
        if guide == FRAME:
            continue
        v, a = _coincident(row, mech, guide, j.point)
        lab = f"{j.point}{guide}"
        plan.tips[lab] = a if accel else v
        plan.point_of_tip[lab] = j.point
        yield j, guide, slider, lab, v


def _start(kind: str, row, mech: Mechanism) -> tuple[Plan, set]:
    """A plan with the absolute vectors of all points (fixed points at the pole)."""
    plan = Plan(kind)
    pre = "v" if kind == "velocity" else "a"
    fixed = set(mech.link(FRAME).points)
    for link in mech.links:
        for p in link.points:
            if p not in plan.tips:
                plan.tips[p] = np.zeros(2) if p in fixed else _vec(row, pre, p)
                plan.point_of_tip[p] = p
    return plan, fixed


def _seg(plan: Plan, start: str, end: str, kind: str, name: str, link: str = "") -> None:
    """Add the segment start→end of the plan ("p" is the pole); its length is read off the tips."""
    a = np.zeros(2) if start == "p" else plan.tips[start]
    plan.segments.append(Segment(start, end, kind, name, link, float(np.hypot(*(plan.tips[end] - a)))))


def _finish(plan: Plan, fixed: set, prefix: str) -> Plan:
    """Absolute vectors from the pole to every moving point."""
    for p, v in list(plan.tips.items()):
        if plan.point_of_tip.get(p) == p and p not in fixed:
            _seg(plan, "p", p, "abs", f"{prefix}_{p}")
    return plan


def velocity_plan(row: pd.Series, mech: Mechanism) -> Plan:
    """The velocity plan of a row: V_Q = V_R + V_QR for every point Q of a link with reference point
    R (V_QR ⊥ RQ), V_P(slider) = V_P(guide) + V_rel for a slider on a moving guide
    (Артоболевский, гл. 3)."""
    plan, fixed = _start("velocity", row, mech)
    for link, ref, p in _relative_points(mech):
        _seg(plan, ref, p, "rel", f"V_{p}{ref}", link.name)
    for j, guide, slider, lab, _ in _guide_points(plan, row, mech):
        _seg(plan, lab, j.point, "slide", f"V_{j.point}{slider}{j.point}{guide}", slider)
    return _finish(plan, fixed, "V")


def acceleration_plan(row: pd.Series, mech: Mechanism, normal=None) -> Plan:
    """The acceleration plan of a row: a^n = −ω²·r and a^τ of every point about its link's
    reference point, Coriolis and relative terms of every slider on a moving guide. ``normal(link,
    r)`` gives the input link's normal component as :func:`construct_acceleration` laid it off
    (ω₁²·l_OA to 0,5 mm): the crank pin's acceleration is drawn from its two known components, so
    its tangential component is the one laid off — none for a uniformly turning crank (ε₁ = 0),
    not a stub left by rounding aⁿ_AO. The other links' normal components are drawn at their
    computed length (an enlarged view shows a short one as it is); their tangential components
    close on the points the construction found."""
    plan, fixed = _start("acceleration", row, mech)
    for link, ref, p in _relative_points(mech):
        w = row["w_" + link.name]
        r = _vec(row, "", p) - _vec(row, "", ref)
        given = normal is not None and mech.driver.rotary and link.name == mech.driver.link
        an = normal(link.name, r) if given else -w * w * r
        lab = f"n{p}{ref}"
        plan.tips[lab] = plan.tips[ref] + an
        _seg(plan, ref, lab, "normal", f"a^n_{p}{ref}", link.name)
        _seg(plan, lab, p, "tangential", f"a^τ_{p}{ref}", link.name)
    for j, guide, slider, lab, v_g in _guide_points(plan, row, mech, accel=True):
        v_rel = _vec(row, "v", j.point) - v_g
        ak = 2.0 * row["w_" + guide] * _rot90(v_rel)
        klab = f"k{j.point}"
        plan.tips[klab] = plan.tips[lab] + ak
        _seg(plan, lab, klab, "coriolis", f"a^k_{j.point}{slider}{j.point}{guide}", slider)
        _seg(plan, klab, j.point, "slide", f"a^r_{j.point}{slider}{j.point}{guide}", slider)
    return _finish(plan, fixed, "a")


def output_quantity(study) -> tuple[str, str, str, str]:
    """The output link's displacement column and its analog columns, with a Russian name:
    a slider on the frame (s_J), otherwise the last rocker pivoted on the frame (phi_k)."""
    mech = study.mechanism
    node = study.root.table("report")
    chosen = node.string("output")
    if chosen:
        pre, _, name = chosen.partition("_")
        title = node.text("output_title", chosen)
        if chosen not in study.kinematics.columns:
            raise node.error("output", f"нет столбца «{chosen}»",
                             expected="столбец кинематики: s_<пара>, phi_<звено>, x_<точка> или y_<точка>")
        if pre == "s":
            return chosen, f"vqs_{name}", f"aqs_{name}", title
        if pre == "phi":
            return chosen, f"wq_{name}", f"eq_{name}", title
        if pre in ("x", "y"):
            return chosen, f"vq{pre}_{name}", f"aq{pre}_{name}", title
        raise node.error("output", f"столбец «{chosen}» не является перемещением",
                         expected="s_<пара>, phi_<звено>, x_<точка> или y_<точка>")
    for j in reversed(mech.prismatic):
        if j.links[0] == FRAME:
            return f"s_{j.name}", f"vqs_{j.name}", f"aqs_{j.name}", _link_named(mech, j.links[1], "ползун")
    groups = study.structure.groups
    for g in reversed(groups):
        for l in g.links:
            if any(FRAME in jt.links and l in jt.links for jt in mech.joints):
                return f"phi_{l}", f"wq_{l}", f"eq_{l}", _link_named(mech, l, "звено")
    l = groups[-1].links[-1]
    return f"phi_{l}", f"wq_{l}", f"eq_{l}", _link_named(mech, l, "звено")


def parallel_outputs(study) -> list[tuple[str, str, str, str]]:
    """The outputs of a mechanism whose last groups hang in parallel (a V-compressor: two ВВП
    groups on one crank pin, each with its piston): one :func:`output_quantity` tuple per terminal
    group (a group no other group is attached to) that has a slider on the frame or a rocker
    pivoted on it, and per group with a slider on the frame that carries a working load though a
    later group hangs on it (the master rod's piston of an articulated-rod compressor), in the
    order of the groups. A single output (a chain of groups, or the output
    the case names in ``[report] output``) gives ``[output_quantity(study)]``."""
    main = output_quantity(study)
    if study.root.table("report").string("output"):
        return [main]
    mech = study.mechanism
    groups = [g for g in study.structure.groups if FRAME not in g.links and len(g.links) > 1]
    group_of = {l: i for i, g in enumerate(groups) for l in g.links}
    fed = set()            # groups another group is attached to
    for j in mech.joints:
        a, b = j.links
        if a in group_of and b in group_of and group_of[a] != group_of[b]:
            fed.add(min(group_of[a], group_of[b]))
    # a piston of a group another group hangs on (a compressor's master rod carrying the
    # articulated rod) is an output too when a working load acts on it
    worked = {ld.link for ld in study.loads.loads if ld.kind != "weight"} if study.root.has("loads") else set()
    outs = []
    for i, g in enumerate(groups):
        slider = next((j for j in mech.prismatic if j.links[0] == FRAME and j.links[1] in g.links), None)
        if i in fed and (slider is None or slider.links[1] not in worked):
            continue
        if slider is not None:
            outs.append((f"s_{slider.name}", f"vqs_{slider.name}", f"aqs_{slider.name}",
                         _link_named(mech, slider.links[1], "ползун")))
            continue
        rocker = next((l for l in g.links for jt in mech.joints
                       if jt.kind == "R" and FRAME in jt.links and l in jt.links), None)
        if rocker is not None:
            outs.append((f"phi_{rocker}", f"wq_{rocker}", f"eq_{rocker}", _link_named(mech, rocker, "звено")))
    if len(outs) < 2 or main[0] not in [o[0] for o in outs]:
        return [main]
    return outs


def _link_named(mech, link: str, noun: str):
    """The output link as the note names it: by the case's title where it has one («поршень C
    (звено 5)», «коромысло 3», «ползун 5 (долбяк)»), else by its kind and number («ползун 5»)."""
    from markupsafe import Markup, escape
    title = escape(mech.link(link).title or "")  # the case's text as read (``inline_html``): escaped
    plain = title.striptags()
    if not plain or plain == noun:
        return f"{noun} {link}"
    if " " not in plain and "(" not in plain:
        return Markup("{} {}").format(title, link)
    head, _, rest = title.partition(" ")   # halves of escaped markup stay escaped markup
    if rest.startswith("("):        # «ползун (долбяк)» → «ползун 5 (долбяк)»
        return head + Markup(" {} ").format(link) + rest
    return Markup("{} (звено {})").format(title, link)


# ----------------------------------------------------------------------------------------------
# The graphical construction (графическое построение планов)

READ_MM = 0.5        # a length is drawn and read on the plan to 0,5 mm


def drawn(value: float, mu: float) -> float:
    """A magnitude as it is laid off on the drawing: value/μ rounded to READ_MM, times μ."""
    return round(value / mu / READ_MM) * READ_MM * mu


def _guide_dir(row, mech: Mechanism, j) -> np.ndarray:
    """Current unit direction of a guide: the joint's angle turned with the guide link (its
    rotation read off two of its points, or off the slider's, which turns with it)."""
    guide, slider = j.links
    if guide == FRAME:
        return np.array([np.cos(j.angle), np.sin(j.angle)])
    if j.driving:       # the actuator's axis: from the cylinder's base pivot to the rod's end
        axis = _vec(row, "", j.point) - _vec(row, "", mech.driver.center)
        return axis / np.hypot(*axis)
    for name in (guide, slider):
        pts = list(mech.link(name).points.items())
        if len(pts) >= 2:
            (p, a), (q, b) = pts[0], pts[1]
            d0 = np.arctan2(b[1] - a[1], b[0] - a[0])
            now = _vec(row, "", q) - _vec(row, "", p)
            th = np.arctan2(now[1], now[0]) - d0 + j.angle
            return np.array([np.cos(th), np.sin(th)])
    v = _vec(row, "v", j.point) - _coincident(row, mech, guide, j.point)[0]
    n = float(np.hypot(*v)) or 1.0
    return v / n


@dataclass
class Construction:
    """The state of every link found by the construction: (V or a of its reference point, ω or ε)."""
    ref: dict[str, str]
    lin: dict[str, np.ndarray]
    ang: dict[str, float]

    def point(self, row, link: str, p: str, normal=None) -> np.ndarray:
        """The vector of point p of ``link`` found by the construction: the link's translation plus
        its angular term ω × r (plus the normal term when ``normal`` is given)."""
        r = _vec(row, "", p) - _vec(row, "", self.ref[link])
        out = self.lin[link] + self.ang[link] * _rot90(r)
        return out if normal is None else out + normal(link, r)


def _solve_groups(study, row, known_ang, rhs_terms) -> Construction:
    """Group by group (Assur's order), the unknown (vector, scalar) of each link of the group from
    the linear conditions of its pairs — for a dyad exactly the intersection of the two lines of
    its vector equations. ``rhs_terms(kind, joint, …)`` supplies the drawn (known) vectors."""
    mech = study.mechanism
    ref = {l.name: _reference(mech, l) for l in mech.moving}
    con = Construction(ref, {FRAME: np.zeros(2)}, {FRAME: 0.0})
    ref[FRAME] = next(iter(mech.link(FRAME).points), "")
    d = mech.driver
    drive = mech.driving_pair()
    joints = mech.joints + ([drive] if drive is not None else [])
    for g in study.structure.groups:
        links = list(g.links)
        if drive is not None and set(drive.links) & set(links):
            # the initial mechanism of an actuator: the cylinder's and the rod's groups together
            # (the rod's drives the link it is pinned to), the driving pair between them
            links = list(dict.fromkeys(links + [l for h in study.structure.groups
                                                if set(drive.links) & set(h.links) for l in h.links]))
        links = [l for l in links if l not in con.lin]
        if not links:
            continue
        idx = {l: 3 * i for i, l in enumerate(links)}
        rows_, rhs = [], []

        def coef(link, p, sign, A, b_off, comp):
            """Add sign·(field of link at p) component ``comp`` to row A; known links go to rhs."""
            r = _vec(row, "", p) - _vec(row, "", ref[link]) if link != FRAME else np.zeros(2)
            rot = _rot90(r)
            extra = rhs_terms("normal", link, r)
            if link in idx:
                i = idx[link]
                A[i + comp] += sign
                A[i + 2] += sign * rot[comp]
                return -sign * extra[comp]
            val = con.lin[link] + con.ang[link] * rot + extra
            return -sign * val[comp]

        for j in joints:
            a, b = j.links
            if not ({a, b} & set(links)) or not ({a, b} <= set(links) | set(con.lin)):
                continue
            if j.kind == "R":
                for comp in (0, 1):
                    A = np.zeros(3 * len(links))
                    c = coef(a, j.point, 1.0, A, 0, comp) + coef(b, j.point, -1.0, A, 0, comp)
                    rows_.append(A)
                    rhs.append(c)
            else:
                u = _guide_dir(row, mech, j)
                n = _rot90(u)
                A = np.zeros(3 * len(links))
                c = 0.0
                for sgn, lk in ((1.0, b), (-1.0, a)):
                    if lk in idx:
                        A[idx[lk] + 2] += sgn
                    else:
                        c -= sgn * con.ang[lk]
                rows_.append(A)
                rhs.append(c)
                rel = rhs_terms("relative", j, u)          # Coriolis (and driven relative) part
                for dirv, known in ((n, float(n @ rel)),) + (((u, float(u @ rel)),) if j.driving else ()):
                    A = np.zeros(3 * len(links))
                    c = known
                    for comp in (0, 1):
                        B = np.zeros(3 * len(links))
                        c += dirv[comp] * (coef(b, j.point, 1.0, B, 0, comp) + coef(a, j.point, -1.0, B, 0, comp))
                        A += dirv[comp] * B
                    rows_.append(A)
                    rhs.append(c)
        if d.rotary and d.link in links:
            A = np.zeros(3 * len(links))
            A[idx[d.link] + 2] = 1.0
            rows_.append(A)
            rhs.append(known_ang(d.link))
        sol, *_ = np.linalg.lstsq(np.array(rows_), np.array(rhs), rcond=None)
        for l, i in idx.items():
            con.lin[l] = sol[i:i + 2].copy()
            con.ang[l] = float(sol[i + 2])
    return con


def _constructed_row(row, mech: Mechanism, con: Construction, pre: str, ang: str, normal=None) -> pd.Series:
    out = row.copy()
    owner = mech.point_owner()
    for p, link in owner.items():
        v = np.zeros(2) if link == FRAME else con.point(row, link, p, normal)
        out[f"{pre}x_{p}"], out[f"{pre}y_{p}"] = v
    for l in mech.moving:
        out[f"{ang}_{l.name}"] = con.ang[l.name]
    return out


def _longest_rel(plan: Plan, link: str):
    rel = [s for s in plan.segments if s.kind == "rel" and s.link == link]
    return max(rel, key=lambda s: s.length) if rel else None


def group_rank(study) -> dict[str, int]:
    """Each link's group index in the order of attachment (the frame −1)."""
    rank = {FRAME: -1}
    for k, g in enumerate(study.structure.groups):
        rank.update({l: k for l in g.links})
    return rank


def omega_segment(plan: Plan, mech: Mechanism, link: str, rank: dict[str, int] | None = None):
    """The relative segment of the velocity plan a student reads the link's ω = V/l from: one
    to a pair of the link's own group (its own equations gave it: ω₃ = V_BC/l_CB of the rocker of
    group (2,3), not V_DC of the pair by which a later group hangs on it; ``rank`` —
    :func:`group_rank`, without it every pair counts as own), then one to a pair point rather than
    a centre of mass, then the longest (the most accurate reading)."""
    rank = rank or {}
    joints = {j.point for j in mech.joints}
    own = {j.point for j in mech.joints if link in j.links
           and all(rank.get(l, -1) <= rank.get(link, -1) for l in j.links)}
    rel = [s for s in plan.segments if s.kind == "rel" and s.link == link]
    return min(rel, key=lambda s: (s.end not in own, s.end not in joints, -s.length)) if rel else None


def _drawn_input_rate(row: pd.Series, mech: Mechanism, kind: str, mu: float) -> float:
    """ω₁ (``kind`` "w") or ε₁ ("e") of the input link as the plan gives it: the crank pin's
    velocity ω₁·l_OA (or tangential acceleration ε₁·l_OA) laid off to 0,5 mm at the scale ``mu``
    and divided back by l_OA; a sliding input keeps its value."""
    d = mech.driver
    rate = float(row[f"{kind}_" + d.link])
    if d.rotary:
        l = float(np.hypot(*(_vec(row, "", mech.crank_pin()) - _vec(row, "", d.center))))
        rate = np.sign(rate) * drawn(abs(rate) * l, mu) / l
    return rate


def construct_velocity(row: pd.Series, study, mu: float) -> tuple[pd.Series, Plan]:
    """The velocity plan as it is constructed: pa = ω₁·l_OA/μ_v drawn to 0,5 mm (for an
    actuator the rod's relative velocity), then each group's points at the intersection of the
    lines of its equations V̄_B = V̄_A + V̄_BA (⊥ AB), V̄_B = V̄_C + V̄_BC (⊥ CB) or, for a slider,
    ∥ the guide. Returns the row of constructed velocities and the plan."""
    mech = study.mechanism
    w1 = _drawn_input_rate(row, mech, "w", mu)

    def terms(kind, obj, vec):
        if kind == "normal":
            return np.zeros(2)
        if obj.driving:
            return vec * drawn(float(row.get(f"vs_{obj.name}", 0.0)), mu)
        return np.zeros(2)
    con = _solve_groups(study, row, lambda _l: w1, terms)
    vrow = _constructed_row(row, mech, con, "v", "w")
    return vrow, velocity_plan(vrow, mech)


def measured_omegas(vrow, vplan: Plan, mech: Mechanism, mu_v: float,
                    rank: dict[str, int] | None = None) -> dict[str, float]:
    """ω of each link as the student gets it: the relative segment of its velocity plan that
    :func:`omega_segment` picks (the one the note's ω = V/l prints) read to 0,5 mm over the
    distance of its points (a slider turns with its guide)."""
    out = {}
    for l in mech.moving:
        s = omega_segment(vplan, mech, l.name, rank)
        w = float(vrow["w_" + l.name])
        if s is not None and s.length > 1e-12:
            r = float(np.hypot(*(_vec(vrow, "", s.end) - _vec(vrow, "", s.start))))
            out[l.name] = np.sign(w) * drawn(s.length, mu_v) / r
        else:
            out[l.name] = w
    for j in mech.prismatic:
        # a slider turns with its moving guide: ω_slider = ω_guide exactly (a stone has no segment
        # of its own; a piston rod's own reading would give a second, different ω of one rotation)
        if j.links[0] != FRAME and (_longest_rel(vplan, j.links[1]) is None
                                    or _longest_rel(vplan, j.links[0]) is not None):
            out[j.links[1]] = out[j.links[0]]
    return out


def read_velocities(row: pd.Series, study, mu_v: float) -> pd.Series:
    """The position's row with what the student reads off the constructed velocity plan (scale
    ``mu_v``) before the acceleration plan: each link's ω of :func:`measured_omegas` (the input
    link's given ω₁ kept) and each stone's velocity relative to its moving guide read to 0,5 mm —
    the numbers :func:`construct_acceleration` draws the normal terms aⁿ = ω²·l and the Coriolis
    terms a^k = 2·ω·V_r from, so that the equations printed with them agree with the plan."""
    mech = study.mechanism
    vrow, vplan = construct_velocity(row, study, mu_v)
    out = row.copy()
    for name, w in measured_omegas(vrow, vplan, mech, mu_v, group_rank(study)).items():
        if not (mech.driver.rotary and name == mech.driver.link):
            out[f"w_{name}"] = w
    for j in mech.prismatic:
        guide = j.links[0]
        if guide == FRAME or f"vs_{j.name}" not in out:
            continue
        v_rel = _vec(vrow, "v", j.point) - _coincident(vrow, mech, guide, j.point)[0]
        out[f"vs_{j.name}"] = math.copysign(drawn(float(np.hypot(*v_rel)), mu_v), float(row[f"vs_{j.name}"]))
    return out


def construct_acceleration(row: pd.Series, vrow: pd.Series, omegas: dict[str, float], study, mu: float,
                           mu_v: float) -> tuple[pd.Series, Plan]:
    """The acceleration plan as it is constructed: normal components aⁿ = ω²·l with ω measured on
    the velocity plan, Coriolis a^k = 2·ω·V_r with V_r read off the velocity plan, both drawn to
    0,5 mm; the tangential (⊥ link) and relative (∥ guide) directions intersected group by
    group."""
    mech = study.mechanism
    e1 = _drawn_input_rate(row, mech, "e", mu)

    def terms(kind, obj, vec):
        if kind == "normal":
            if obj == FRAME:
                return np.zeros(2)
            r = float(np.hypot(*vec))
            if r < 1e-15:
                return np.zeros(2)
            return -vec / r * drawn(omegas[obj] ** 2 * r, mu)
        guide, slider = obj.links
        out = np.zeros(2)
        if guide != FRAME:
            vg = _coincident(vrow, mech, guide, obj.point)[0]
            v_rel = _vec(vrow, "v", obj.point) - vg
            vr = float(np.hypot(*v_rel))
            if vr > 1e-15:
                mag = drawn(2 * abs(omegas[guide]) * drawn(vr, mu_v), mu)
                out = out + np.sign(omegas[guide]) * _rot90(v_rel / vr) * mag
        if obj.driving:
            out = out + vec * drawn(float(row.get(f"as_{obj.name}", 0.0)), mu)
        return out
    con = _solve_groups(study, row, lambda _l: e1, terms)
    arow = _constructed_row(row, mech, con, "a", "e",
                            normal=lambda link, r: terms("normal", link, r))
    for l, w in omegas.items():
        arow["w_" + l] = w
    for c in vrow.index:
        if c.startswith(("vx_", "vy_")):
            arow[c] = vrow[c]
    return arow, acceleration_plan(arow, mech, normal=lambda link, r: terms("normal", link, r))
