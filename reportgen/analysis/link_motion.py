"""The kind of motion of a link as the solved positions show it: the structure (mechanism layer,
before any position is solved) calls every link hinged to the frame other than the input a
rocker; one that makes whole turns over the cycle is a crank (Артоболевский [1], гл. 1). The
note's table of links and the export's links table both read it from here, so they agree."""
from __future__ import annotations

import numpy as np

from ..mechanism.structure import MOTION

TURNING = "вращательное (кривошип, вращающаяся кулиса)"


def turns_fully(study, link: str) -> bool:
    """Whether ``link`` makes whole turns over the cycle: its angle, unwrapped, grows by a
    multiple of 2π: the driven crank of a double-crank linkage, Whitworth's rotating slotted
    lever. Read from the report positions (the kinematics the structure section needs anyway,
    never the cycle curves): a periodic input's positions cover one turn, so the steps of the
    link's angle between neighbouring positions, each taken in (−π, π] and closed from the last
    position back to the first, add up to a multiple of 2π."""
    kin = study.kinematics
    col = f"phi_{link}"
    if not study.mechanism.driver.periodic or col not in kin or len(kin) < 3:
        return False
    ang = kin.sort_values("q")[col].to_numpy(dtype=float)
    steps = np.angle(np.exp(1j * np.diff(np.append(ang, ang[0]))))
    return bool(abs(steps.sum()) > np.pi)


def link_motion(study, link: str) -> str:
    """The kind of motion of ``link``: the structure's, except a link hinged to the frame that
    turns fully (:func:`turns_fully`) rotates («вращательное»), it does not swing."""
    motion = study.structure.link_motion[link]
    if motion == MOTION["rocker"] and turns_fully(study, link):
        return TURNING
    return motion
