"""A closed-form branch re-posed on the robot by pinocchio, the independent check of every answer, in the fewest
calls a check can take: pinocchio's q made from a template list, the joints' forward kinematics, the one frame's
placement, and a pose error on plain floats.

The error is e = sqrt(|p - p*|^2 + |R - R*|_F^2 / 2) against the goal (p*, R*): |R - R*|_F^2 / 2 = (2 sin(a/2))^2, a
the angle of R*^T R, so e is the norm of pinocchio's log6 of the relative pose (what the search measures, in m and
rad) to within a part in 10^9 where both are below 1e-9 (a solution's), and neither is small where the other is not.
A branch left further than CLOSE is measured again by log6 and polished (:meth:`.inverse_solver.IkSolver._checked`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..reader.kinematic_model import KinematicModel

CLOSE = 1e-10  # m and rad: a branch re-posed this near is a solution without being measured again


@dataclass(frozen=True)
class Reposer:
    """The model and data, the frame, pinocchio's q at the rest values as a list (the template a branch's values
    are written into), where each chain joint's value goes in it (its index, and whether it is continuous: a
    cosine and a sine), and whether q is the chain's values as they are."""

    model: Any
    data: Any
    frame: int
    template: list[float]
    slots: tuple[tuple[int, bool], ...]
    direct: bool = False
    pinocchio: Any = None  # (the module, imported once: an import statement costs a branch's check a tenth)

    @classmethod
    def of(cls, model: KinematicModel, frame: int, chain: Sequence[int], rest: np.ndarray) -> Reposer | None:
        """The reposer of the chain joints ``chain`` (indices into the joints one sets), the others at ``rest``; None
        for a robot with mimic joints, whose q :meth:`KinematicModel.configuration` makes (and checks)."""
        import pinocchio as pin  # (heavy: pinocchio)

        if model.followers:
            return None
        template = model.configuration({j.name: float(v) for j, v in zip(model.joints, rest, strict=True)})
        slots = tuple((model.joints[k].q_index, model.joints[k].kind == "continuous") for k in chain)
        direct = slots == tuple((k, False) for k in range(len(template)))
        return cls(model.model, model.data, frame, template.tolist(), slots, direct, pin)

    def error(self, values: Sequence[float], goal: Sequence[Sequence[float]]) -> float:
        """The pose error (the module's e) of the chain at ``values`` against ``goal`` (4x4 rows as lists)."""
        pin = self.pinocchio
        if self.direct:  # (q is the chain's values: six revolute joints, nothing else)
            q = values
        else:
            q = self.template.copy()
            for (index, turns), value in zip(self.slots, values, strict=True):
                if turns:
                    q[index], q[index + 1] = math.cos(value), math.sin(value)
                else:
                    q[index] = value
        pin.forwardKinematics(self.model, self.data, np.array(q))
        (a0, a1, a2, a3), (b0, b1, b2, b3), (c0, c1, c2, c3), _ = pin.updateFramePlacement(
            self.model, self.data, self.frame
        ).homogeneous.tolist()
        (x0, x1, x2, x3), (y0, y1, y2, y3), (z0, z1, z2, z3), _ = goal
        a0, a1, a2, a3, b0, b1, b2, b3 = a0 - x0, a1 - x1, a2 - x2, a3 - x3, b0 - y0, b1 - y1, b2 - y2, b3 - y3
        c0, c1, c2, c3 = c0 - z0, c1 - z1, c2 - z2, c3 - z3  # (the differences, squared by products: no pow)
        moved = a3 * a3 + b3 * b3 + c3 * c3
        turned = a0 * a0 + a1 * a1 + a2 * a2 + b0 * b0 + b1 * b1
        turned += b2 * b2 + c0 * c0 + c1 * c1 + c2 * c2
        return math.sqrt(moved + 0.5 * turned)
