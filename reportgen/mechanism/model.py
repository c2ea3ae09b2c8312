"""The mechanism as plain data: links with local points, joints, the driver.

Conventions (see docs/case-format.md):

* link "0" is the frame; its points are global coordinates;
* every other link has its own local frame in which its points are given; the link angle
  φ_k is the angle of that frame's x axis;
* a link that slides on a guide (the slider of a prismatic joint) has its local x axis along the
  guide direction;
* a linear actuator (hydraulic cylinder) consists of the cylinder, whose local frame has its
  origin at the base pivot and its x axis toward the rod end, and the rod, whose local frame has
  its origin at the rod-end pivot and the same direction; the distance between the two pivots is
  the generalised coordinate.
"""
from __future__ import annotations

from dataclasses import dataclass, field

FRAME = "0"


@dataclass
class Link:
    name: str
    title: str = ""
    points: dict[str, tuple[float, float]] = field(default_factory=dict)
    mass: float | None = None
    weight: float | None = None
    J_S: float | None = None
    com: str | None = None

    @property
    def is_frame(self) -> bool:
        return self.name == FRAME


@dataclass
class Joint:
    """A lower pair.  ``kind`` is "R" (вращательная) or "P" (поступательная).

    For "R": ``links = (a, b)`` and ``point`` is a point name carried by both links.
    For "P": ``links = (guide, slider)``, ``point`` is the slider's point that moves along the
    guide line, ``line_point``/``angle`` give the line in the guide's local frame (for the frame:
    global), ``offset`` is the signed distance of the slider point from the line (left of the
    direction positive).  ``driving`` marks the actuator's own pair (cylinder–rod); ``cylinder``
    a pair of two moving links drawn as a cylinder (the guide) with its piston and rod (the
    slider), ГОСТ 2.770, instead of a block on a slotted link (case key ``symbol = "cylinder"``)."""

    kind: str
    links: tuple[str, str]
    point: str
    name: str
    line_point: tuple[float, float] = (0.0, 0.0)
    angle: float = 0.0
    offset: float = 0.0
    driving: bool = False
    cylinder: bool = False


@dataclass
class Driver:
    kind: str                       # "crank", "rocker" (an input link swung over q_range) or "actuator"
    link: str                       # crank (or input rocker) link, or the cylinder
    center: str = ""                # crank: pivot point on the frame side; actuator: base pivot
    phi0: float = 0.0               # crank angle at q = 0
    direction: int = 1              # +1 counter-clockwise, −1 clockwise
    omega: float | None = None      # |dq/dt|: rad/s for a crank, m/s for an actuator
    epsilon: float = 0.0            # d²q/dt²
    rod: str = ""                   # actuator rod link
    end: str = ""                   # actuator rod-end pivot point (on the rod)
    q_range: tuple[float, float] | None = None

    @property
    def rotary(self) -> bool:
        """The input link turns about a frame pivot (q an angle): a crank or a swinging rocker."""
        return self.kind in ("crank", "rocker")

    @property
    def periodic(self) -> bool:
        """Full revolutions (the motion repeats after 2π of q): only a crank.  A swinging input
        (rocker) and an actuator move over their range q_range forth and back."""
        return self.kind == "crank"

    @property
    def swing(self) -> bool:
        """An input rocker driven over the range q_range (качающееся входное звено)."""
        return self.kind == "rocker"


@dataclass
class Mechanism:
    links: list[Link]               # frame first
    joints: list[Joint]
    driver: Driver
    sketch: dict[str, tuple[float, float]] = field(default_factory=dict)
    sketch_q: float = 0.0
    # points given by a global offset from another point of the same link at a position q:
    # (link, point, from_point, (dx, dy), q); their local coordinates need the kinematics
    deferred: list[tuple[str, str, str, tuple[float, float], float]] = field(default_factory=list)

    def link(self, name: str) -> Link:
        for l in self.links:
            if l.name == name:
                return l
        raise KeyError(name)

    @property
    def moving(self) -> list[Link]:
        return [l for l in self.links if not l.is_frame]

    def point_owner(self) -> dict[str, str]:
        """Point name → the first link carrying it (the frame wins for fixed points)."""
        owner: dict[str, str] = {}
        for l in self.links:
            for p in l.points:
                owner.setdefault(p, l.name)
        return owner

    def crank_pin(self) -> str:
        """The rotating input link's point joined to the next link (the crank pin A); a point
        of the input link other than its pivot (a centre of mass) is never taken for it when a
        joint is there."""
        d = self.driver
        crank = self.link(d.link)
        joined = {j.point for j in self.joints if d.link in j.links and FRAME not in j.links}
        for p in crank.points:
            if p != d.center and p in joined:
                return p
        return [p for p in crank.points if p != d.center][0]

    @property
    def prismatic(self) -> list[Joint]:
        return [j for j in self.joints if j.kind == "P"]

    def driving_pair(self) -> Joint | None:
        """The actuator's own prismatic pair cylinder–rod (not among ``joints``: the kinematics
        drives it through q = S): the rod slides along the cylinder's x axis, its end ``end`` on
        that line, relative rate vs_<rod><cylinder>. None for a crank or a rocker."""
        d = self.driver
        if d.kind != "actuator":
            return None
        return Joint("P", (d.link, d.rod), d.end, f"{d.rod}{d.link}", driving=True)

    def size(self) -> float:
        """A length scale of the mechanism (for tolerances and drawing)."""
        import math
        s = 0.0
        for l in self.links:
            for x, y in l.points.values():
                s = max(s, math.hypot(x, y))
        return s or 1.0
