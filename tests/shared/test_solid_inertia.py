"""Principal moments without numpy for diagonal tensors: the same bits as LAPACK's eigvalsh, the same verdicts."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from xacrokit.shared.solid_inertia import entries_problem, principal_moments, tensor, tensor_problem

MOMENT = st.one_of(
    st.floats(min_value=-1e6, max_value=1e6, allow_nan=False),
    st.floats(min_value=-1e300, max_value=1e300, allow_nan=False),
    st.sampled_from([0.0, -0.0, 1e-300, 5e-324, 1e-200, 1e-146, 1e-140, 1e-9, 1.0, 1e140, 1e146, 1e200]),
)
OFF = st.one_of(st.just(0.0), st.just(-0.0), st.floats(min_value=-1e3, max_value=1e3, allow_nan=False))
ENTRIES = st.tuples(MOMENT, OFF, OFF, MOMENT, OFF, MOMENT)


def _lapack(entries: tuple[float, ...]) -> list[float]:
    found: list[float] = np.linalg.eigvalsh(tensor(*entries)).tolist()
    return found


# (the property is cheap: 300 examples a run cover diagonal, mixed and full tensors side by side)
@settings(max_examples=300, deadline=None)
@given(st.lists(ENTRIES, max_size=6))
def test_principal_moments_equal_lapacks_bits_in_order(batch: list[tuple[float, ...]]) -> None:
    # (repr: the sign of a zero is part of the bits, and a message prints it)
    assert repr(principal_moments(batch)) == repr([_lapack(entries) for entries in batch])


@settings(max_examples=300, deadline=None)
@given(ENTRIES)
def test_entries_problem_says_what_tensor_problem_says(entries: tuple[float, ...]) -> None:
    assert entries_problem(*entries) == tensor_problem(tensor(*entries))


def test_a_diagonal_tensor_is_judged_without_numpy_and_a_bad_one_still_said() -> None:
    # (the values are exact: a diagonal's moments are its entries, sorted; 3 > 1 + 1 breaks the triangle inequality)
    assert principal_moments([(3.0, 0.0, 0.0, 1.0, 0.0, 2.0)]) == [[1.0, 2.0, 3.0]]
    problem = entries_problem(3.0, 0.0, 0.0, 1.0, 0.0, 1.0)
    assert problem is not None and "triangle inequality" in problem and "1, 1, 3" in problem
    assert entries_problem(1.0, 0.0, 0.0, math.inf, 0.0, 1.0) == "the inertia tensor has entries that are not finite"
    assert entries_problem(1.0, 0.0, 0.0, 1.0, 0.0, 1.5) is None
