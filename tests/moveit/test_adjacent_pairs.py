"""The Adjacent pairs of an SRDF (issue 45: a fleet's, found at once): the same pairs as MoveIt's setup assistant's
connection graph gives (computeConnectionGraph in moveit_setup_assistant: every link without collision geometry joins
all its neighbours, over and over until nothing changes), written here as that loop, on random trees and graphs."""

from __future__ import annotations

import itertools

from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import budget
from xacrokit.moveit.collision_matrix import adjacent_pairs, pair


def connection_graph(joints, solid):
    """The setup assistant's loop, as it is written there: the oracle."""
    graph: dict[str, set[str]] = {}
    for parent, child in joints:
        if parent and child:
            graph.setdefault(parent, set()).add(child)
            graph.setdefault(child, set()).add(parent)
    changed = True
    while changed:
        changed = False
        for link, neighbours in list(graph.items()):
            if link in solid:
                continue
            for first, second in itertools.combinations(sorted(neighbours), 2):
                if second not in graph[first]:
                    graph[first].add(second)
                    graph[second].add(first)
                    changed = True
    return {pair(link, other) for link, others in graph.items() for other in others if {link, other} <= solid}


NAMES = [f"l{k}" for k in range(12)]


@settings(max_examples=budget(200))  # (small graphs judged in microseconds: many, of every shape a group takes)
@given(
    joints=st.lists(st.tuples(st.sampled_from([*NAMES, None]), st.sampled_from([*NAMES, None])), max_size=20),
    solid=st.sets(st.sampled_from(NAMES)),
)
def test_the_pairs_are_the_setup_assistants_on_random_graphs(joints, solid):
    assert adjacent_pairs(joints, solid) == connection_graph(joints, solid)


def test_a_fleets_bases_on_a_world_without_geometry_are_all_adjacent():
    joints = [("world", f"r{k}_base") for k in range(30)] + [(f"r{k}_base", f"r{k}_arm") for k in range(30)]
    joints += [(f"r{k}_arm", f"r{k}_mount") for k in range(30)] + [(f"r{k}_mount", f"r{k}_hand") for k in range(30)]
    solid = {f"r{k}_{part}" for k in range(30) for part in ("base", "arm", "hand")}
    found = adjacent_pairs(joints, solid)
    assert found == connection_graph(joints, solid)
    assert (
        len(found) == 30 * 29 // 2 + 30 * 2
    )  # (the bases pairwise; each arm with its base, and its hand past the mount)
