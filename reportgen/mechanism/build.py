"""Build a :class:`Mechanism` from the case file's tables (all values evaluated to SI)."""
from __future__ import annotations

import math
from typing import Mapping

from ..case import units as U
from ..case.expr import Q
from ..case.reader import Node
from ..case.text import check_name
from ..errors import CaseError, did_you_mean
from .model import FRAME, Driver, Joint, Link, Mechanism

LINK_KEYS = ["name", "title", "points", "mass", "weight", "J_S", "com"]
JOINT_KEYS = ["type", "links", "point", "guide", "slider", "line", "offset", "name", "symbol"]
DRIVER_KEYS = ["type", "link", "center", "phi0", "direction", "omega", "epsilon",
               "cylinder", "rod", "base", "end", "range", "speed", "acceleration"]
Holders = dict[str, list[tuple[str, str]]]   # point name -> [(link, where it is defined)]


def build_mechanism(root: Node, names: Mapping[str, Q], g: float) -> Mechanism:
    """Read [frame], [[links]], [[joints]], [driver] and [sketch] of a case."""
    frame, holders = _read_frame(root, names)
    qdim = U.LENGTH if root.table("driver").raw("type") == "actuator" else U.ANGLE
    links, deferred = _read_links(root, names, g, qdim, holders)
    index = _LinkIndex([frame] + links)
    joints = [_read_joint(jn, names, index) for jn in root.tables("joints")]
    _check_shared_points(root, holders, joints)
    driver = _read_driver(root, names, index, joints)
    mech = Mechanism([frame] + links, joints, driver, deferred=deferred)
    _read_sketch(root, names, mech)
    return mech


def _read_frame(root: Node, names: Mapping[str, Q]) -> tuple[Link, Holders]:
    """The frame (link "0") with its points from ``[frame] points``."""
    frame_node = root.table("frame")
    frame_node.check_keys(["points"])
    frame = Link(FRAME, "стойка")
    pts = frame_node.table("points")
    holders: Holders = {}
    for pname, v in pts.data.items():
        pname = check_name(pname, file=pts.file, key=pts.key(str(pname)), what="имя точки")
        frame.points[pname] = pts.vector(pname, v, U.LENGTH, names)
        holders[pname] = [(FRAME, f"[frame] points.{pname} (стойка)")]
    return frame, holders


def _read_links(root: Node, names: Mapping[str, Q], g: float, qdim, holders: Holders) -> tuple[list[Link], list]:
    """The moving links of ``[[links]]`` (their points, mass, weight G = m·g, J_S, centre of mass)
    and the points deferred to assembly (``{offset, from, at}``: placed at a position of q)."""
    links: list[Link] = []
    deferred = []
    seen = {FRAME}
    for ln in root.tables("links"):
        ln.check_keys(LINK_KEYS, required=["name", "points"])
        name = ln.name("name", required=True, what="имя звена")
        if name in seen:
            raise ln.error("name", f"звено «{name}» описано дважды", expected="уникальное имя звена")
        seen.add(name)
        link = Link(name, ln.text("title", "") or "")
        pn = ln.table("points", required=True)
        if not pn.data:
            raise pn.error(None, "у звена нет ни одной точки", expected="points = { A = [0, 0], B = [\"0.3 m\", 0] }")
        for pname, v in pn.data.items():
            pname = check_name(pname, file=pn.file, key=pn.key(str(pname)), what="имя точки")
            holders.setdefault(pname, []).append((name, f"{pn.key(pname)} (звено «{name}»)"))
            if isinstance(v, Mapping):
                sub = Node(v, pn.key(pname), pn.file)
                if "offset" in v:
                    sub.check_keys(["offset", "from", "at"], required=["offset", "from", "at"])
                    off = sub.vector("offset", v["offset"], U.LENGTH, names)
                    frm = sub.string("from", required=True)
                    at = sub.eval_value(v["at"], "at", qdim, names)
                    deferred.append((name, pname, frm, off, at))
                    continue
                sub.check_keys(["r", "angle"], required=["r", "angle"])
                r = sub.quantity("r", U.LENGTH, names, required=True)
                a = sub.quantity("angle", U.ANGLE, names, required=True)
                link.points[pname] = (r * math.cos(a), r * math.sin(a))
            else:
                link.points[pname] = pn.vector(pname, v, U.LENGTH, names)
        link.mass = ln.quantity("mass", U.MASS, names, nonnegative=True)
        link.weight = ln.quantity("weight", U.FORCE, names, nonnegative=True)
        if link.weight is None and link.mass is not None:
            link.weight = link.mass * g
        link.J_S = ln.quantity("J_S", U.INERTIA, names, nonnegative=True)
        link.com = ln.string("com")
        if link.com is not None and link.com not in link.points and link.com not in [d[1] for d in deferred if d[0] == name]:
            raise ln.error("com", f"точка «{link.com}» не принадлежит звену «{name}»",
                           expected="имя одной из точек звена: " + ", ".join(link.points),
                           hint=did_you_mean(link.com, list(link.points)))
        links.append(link)
    if not links:
        raise root.error("links", "не описано ни одного подвижного звена", expected="[[links]] …")
    return links, deferred


class _LinkIndex:
    """The links by name (the frame "0" first), for the pairs and the driver that name them."""

    def __init__(self, links: list[Link]):
        self.by_name = {l.name: l for l in links}

    def link(self, node: Node, key: str, name: str) -> Link:
        if name not in self.by_name:
            raise node.error(key, f"нет звена «{name}»", expected="имя звена из [[links]] или \"0\" (стойка)",
                             hint=did_you_mean(name, list(self.by_name)))
        return self.by_name[name]

    @staticmethod
    def point(node: Node, key: str, link: Link, p: str) -> None:
        if p not in link.points:
            where = "стойки" if link.is_frame else f"звена «{link.name}»"
            raise node.error(key, f"точка «{p}» не задана у {where}",
                             expected="одна из точек: " + ", ".join(link.points),
                             hint=did_you_mean(p, list(link.points)))


def _read_joint(jn: Node, names: Mapping[str, Q], index: _LinkIndex) -> Joint:
    """One pair of ``[[joints]]``: a revolute (R) joining two links at a point, or a prismatic
    (P): the slider's point on a guide line (through two points of the guide, or through a point
    at an angle), with its offset and its ГОСТ 2.770 symbol."""
    jn.check_keys(JOINT_KEYS, required=["type", "point"])
    kind = jn.string("type", required=True, choices=["R", "P"])
    point = jn.string("point", required=True)
    if kind == "R":
        pair = jn.raw("links")
        if not (isinstance(pair, list) and len(pair) == 2):
            raise jn.error("links", "для вращательной пары нужны два звена",
                           expected="links = [\"1\", \"2\"]", got=repr(pair))
        a, b = (str(x) for x in pair)
        la, lb = index.link(jn, "links", a), index.link(jn, "links", b)
        if a == b:
            raise jn.error("links", "пара соединяет звено само с собой", expected="два разных звена")
        index.point(jn, "point", la, point)
        index.point(jn, "point", lb, point)
        if jn.has("symbol"):
            raise jn.error("symbol", "условное обозначение задаётся только для поступательной пары",
                           expected="symbol в [[joints]] с type = \"P\"")
        name = jn.name("name", point, what="имя пары")
        return Joint("R", (a, b), point, name)
    for k in ("guide", "slider", "line"):
        if not jn.has(k):
            raise jn.error(k, f"для поступательной пары нужен ключ «{k}»",
                           expected="guide = \"0\", slider = \"5\", line = { through = [0, \"Y_H\"], angle = \"0 deg\" }")
    guide = index.link(jn, "guide", jn.string("guide"))
    slider = index.link(jn, "slider", jn.string("slider"))
    index.point(jn, "point", slider, point)
    lp, ang = _guide_line(jn.table("line"), names, guide, index)
    offset = jn.quantity("offset", U.LENGTH, names, default=0.0)
    name = jn.name("name", f"{slider.name}{guide.name}", what="имя пары")
    # ГОСТ 2.770 symbol of the pair: a slider (block) on its guide, or a cylinder with its
    # piston and rod (the guide the cylinder, the slider the rod: a rocking cylinder)
    symbol = jn.string("symbol", "slider", choices=["slider", "cylinder"])
    if symbol == "cylinder" and guide.is_frame:
        raise jn.error("symbol", "цилиндром изображается пара двух подвижных звеньев (качающийся цилиндр)",
                       expected="symbol = \"slider\" для ползуна на стойке")
    return Joint("P", (guide.name, slider.name), point, name, lp, ang, offset, cylinder=symbol == "cylinder")


def _guide_line(line: Node, names: Mapping[str, Q], guide: Link, index: _LinkIndex) -> tuple[tuple, float]:
    """A prismatic pair's guide line in the guide's frame: a point of it and its angle, from
    ``{from, to}`` (two points of the guide) or ``{through, angle}``."""
    if line.has("from"):
        line.check_keys(["from", "to"], required=["from", "to"])
        p1, p2 = line.string("from"), line.string("to")
        index.point(line, "from", guide, p1)
        index.point(line, "to", guide, p2)
        (x1, y1), (x2, y2) = guide.points[p1], guide.points[p2]
        if math.hypot(x2 - x1, y2 - y1) == 0:
            raise line.error(None, "точки направляющей совпадают", expected="две разные точки")
        return (x1, y1), math.atan2(y2 - y1, x2 - x1)
    line.check_keys(["through", "angle"], required=["through"])
    thr = line.raw("through")
    if isinstance(thr, str) and thr in guide.points:
        lp = guide.points[thr]
    elif isinstance(thr, str):
        raise line.error("through", f"точка «{thr}» не задана у звена «{guide.name}»",
                         expected="имя точки направляющего звена или координаты [x, y]",
                         hint=did_you_mean(thr, list(guide.points)))
    else:
        lp = line.vector("through", thr, U.LENGTH, names)
    return lp, line.quantity("angle", U.ANGLE, names, default=0.0)


def _check_shared_points(root: Node, holders: Holders, joints: list[Joint]) -> None:
    """A point name held by several links (the frame included) is one point of the mechanism
    only where those links are joined at it: every holder must be connected to the others by
    pairs ([[joints]]) at that very point. Otherwise two different points share a name — e.g. a
    frame point ``H`` beside the slider's moving ``H`` — and one of them would silently replace
    the other; that is an error naming both places. (Where no pair at all is at that point, a
    pair is missing: the structural analysis reports it with Chebyshev's count.)"""
    for p, owners in holders.items():
        if len(owners) < 2:
            continue
        parent = {ln: ln for ln, _ in owners}

        def find(x: str) -> str:
            while parent[x] != x:
                x = parent[x]
            return x

        for j in joints:
            if j.kind == "R" and j.point == p and all(ln in parent for ln in j.links):
                parent[find(j.links[0])] = find(j.links[1])
        if not any(j.point == p for j in joints):
            continue  # no pair at this point at all: the structural analysis reports the missing pair
        roots: dict[str, tuple[str, str]] = {}
        for ln, place in owners:
            roots.setdefault(find(ln), (ln, place))
        if len(roots) > 1:
            (_, first), (_, second) = list(roots.values())[:2]
            raise CaseError(f"точка «{p}» задана в двух местах, не соединённых парой в этой точке: "
                            f"{first} и {second}", file=root.file, key=second.split(" ")[0],
                            expected="разные имена для разных точек; общая точка двух звеньев "
                                     "соединяется парой [[joints]] с point = \"" + p + "\"")


def _read_driver(root: Node, names: Mapping[str, Q], index: _LinkIndex, joints: list[Joint]) -> Driver:
    """The input link of ``[driver]``: a crank or a rocker turning about its centre, or an actuator
    (cylinder and rod) whose length is the generalised coordinate."""
    dn = root.table("driver", required=True)
    dn.check_keys(DRIVER_KEYS, required=["type"])
    kind = dn.string("type", required=True, choices=["crank", "rocker", "actuator"])
    if kind in ("crank", "rocker"):
        link = index.link(dn, "link", dn.string("link", required=True))
        center = dn.string("center")
        if center is None:
            cands = [j.point for j in joints if j.kind == "R" and link.name in j.links and FRAME in j.links]
            if len(cands) != 1:
                raise dn.error("center", "не удалось определить ось кривошипа",
                               expected="center = \"O\": точка вращательной пары кривошипа со стойкой")
            center = cands[0]
        index.point(dn, "center", link, center)
        direction = dn.string("direction", "ccw", choices=["ccw", "cw"])
        q_range = _swing_range(dn, names) if kind == "rocker" else None
        if kind == "rocker" and dn.has("epsilon"):
            raise dn.error("epsilon", "качающееся входное звено движется с постоянной по модулю угловой скоростью "
                                      "(прямой ход +ω, обратный −ω)", expected="omega без epsilon")
        if kind == "crank" and dn.has("range"):
            raise dn.error("range", "диапазон задаётся качающемуся входному звену, кривошип делает полные обороты",
                           expected="type = \"rocker\" с range = [\"-30 deg\", \"30 deg\"] или кривошип без range")
        return Driver(kind, link.name, center=center, q_range=q_range,
                      phi0=dn.quantity("phi0", U.ANGLE, names, default=0.0),
                      direction=1 if direction == "ccw" else -1,
                      omega=dn.quantity("omega", U.ANGULAR_VELOCITY, names, positive=True),
                      epsilon=dn.quantity("epsilon", U.ANGULAR_ACCELERATION, names, default=0.0))
    for k in ("cylinder", "rod", "base", "end", "range"):
        if not dn.has(k):
            raise dn.error(k, f"для гидроцилиндра нужен ключ «{k}»",
                           expected="cylinder, rod, base, end, range = [\"S_min\", \"S_max\"]")
    cyl = index.link(dn, "cylinder", dn.string("cylinder"))
    rod = index.link(dn, "rod", dn.string("rod"))
    base = dn.string("base")
    end = dn.string("end")
    index.point(dn, "base", cyl, base)
    index.point(dn, "end", rod, end)
    if cyl.points[base] != (0.0, 0.0) or rod.points[end] != (0.0, 0.0):
        raise dn.error("base", "оси гидроцилиндра: начало локальной системы цилиндра должно быть в точке base, штока — в точке end",
                       expected=f"{base} = [0, 0] у звена «{cyl.name}» и {end} = [0, 0] у звена «{rod.name}»")
    rng = dn.raw("range")
    if not (isinstance(rng, list) and len(rng) == 2):
        raise dn.error("range", "ожидался диапазон длины гидроцилиндра", expected="range = [\"0.42 m\", \"0.67 m\"]")
    lo = dn.eval_value(rng[0], "range[0]", U.LENGTH, names, positive=True)
    hi = dn.eval_value(rng[1], "range[1]", U.LENGTH, names, positive=True)
    if not hi > lo:
        raise dn.error("range", "верхняя граница диапазона не больше нижней", expected="range = [S_min, S_max], S_max > S_min")
    return Driver("actuator", cyl.name, center=base, rod=rod.name, end=end, q_range=(lo, hi),
                  omega=dn.quantity("speed", U.VELOCITY, names, positive=True),
                  epsilon=dn.quantity("acceleration", U.ACCELERATION, names, default=0.0))


def _swing_range(dn, names) -> tuple[float, float]:
    """``range = [q_min, q_max]`` of an input rocker: angles of the generalised coordinate q, the
    swing 0 < q_max − q_min < 360°."""
    rng = dn.raw("range")
    example = "range = [\"-30 deg\", \"30 deg\"]"
    if not (isinstance(rng, list) and len(rng) == 2):
        raise dn.error("range", "для качающегося входного звена нужен диапазон угла качания",
                       expected=example + " (углы обобщённой координаты q: крайние положения звена)")
    lo = dn.eval_value(rng[0], "range[0]", U.ANGLE, names)
    hi = dn.eval_value(rng[1], "range[1]", U.ANGLE, names)
    if not hi > lo:
        raise dn.error("range", "верхняя граница угла качания не больше нижней", expected=example + ", q_max > q_min")
    if hi - lo >= 2 * math.pi:
        raise dn.error("range", "размах качания не меньше полного оборота",
                       expected="размах q_max − q_min < 360°; полные обороты — type = \"crank\"")
    return lo, hi


def _read_sketch(root: Node, names, mech: Mechanism) -> None:
    sk = root.table("sketch")
    sk.check_keys(["at", "points"])
    mech.sketch_q = sk.quantity("at", U.ANGLE if mech.driver.rotary else U.LENGTH, names,
                                default=None) if sk.has("at") else None
    pts = sk.table("points")
    owner = mech.point_owner()
    for p, v in pts.data.items():
        p = str(p)
        if p not in owner:
            raise pts.error(p, f"в эскизе указана неизвестная точка «{p}»", expected="имя точки механизма",
                            hint=did_you_mean(p, list(owner)))
        mech.sketch[p] = pts.vector(p, v, U.LENGTH, names)
