"""The kinematic tree walk, written once for the spec's validation and for ``gen-robot check``: who hangs from whom,
which links are roots, which a walk from the roots never reaches (they sit in a cycle), and the way up from a link."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from typing import Generic, TypeVar

Key = TypeVar("Key")  # what an edge is known by: a spec path, a joint name
Value = TypeVar("Value")  # what a walk carries down the tree (a depth, a transform)


class Tree(Generic[Key]):
    """Parent-child edges added one by one; the first parent of a link wins (a second one is reported by the caller)."""

    def __init__(self) -> None:
        self.parent_of: dict[str, tuple[str, Key]] = {}
        self.children: dict[str, list[str]] = {}

    def add(self, parent: str, child: str, key: Key) -> tuple[str, Key] | None:
        """Hang ``child`` from ``parent``; when the child has a parent already, add nothing and return that one."""
        if child in self.parent_of:
            return self.parent_of[child]
        self.parent_of[child] = (parent, key)
        self.children.setdefault(parent, []).append(child)
        return None

    def roots(self, links: Iterable[str]) -> list[str]:
        """The links without a parent, sorted."""
        return sorted(name for name in links if name not in self.parent_of)

    def reachable(self, starts: Iterable[str]) -> set[str]:
        """Every link at or below ``starts``."""
        seen: set[str] = set()
        stack = list(starts)
        while stack:
            current = stack.pop()
            if current not in seen:
                seen.add(current)
                stack += self.children.get(current, [])
        return seen

    def down(self, starts: Iterable[str], first: Value, step: Callable[[Value, Key], Value]) -> dict[str, Value]:
        """Every link at or below ``starts`` with a value carried down the edges: ``first`` at a start, then
        ``step(parent's value, edge)`` (summed weights, composed transforms). One walk, each link once: a loop is not
        followed."""
        found = dict.fromkeys(starts, first)
        stack = list(found)
        while stack:
            current = stack.pop()
            for child in self.children.get(current, []):
                if child not in found:
                    found[child] = step(found[current], self.parent_of[child][1])
                    stack.append(child)
        return found

    def depths(self, starts: Iterable[str], weight: Callable[[Key], int] = lambda key: 1) -> dict[str, int]:
        """Every link at or below ``starts``, with the summed ``weight`` of the edges down to it from its start (0 at
        a start; each edge 1 by default: the links above it)."""
        return self.down(starts, 0, lambda depth, key: depth + weight(key))

    def path_up(self, start: str, target: str) -> list[str]:
        """Links from ``start`` up through its ancestors to ``target`` (both included), or [] when target is not
        above it."""
        path, current, seen = [start], start, {start}
        while current != target:
            if current not in self.parent_of:
                return []
            current = self.parent_of[current][0]
            if current in seen:
                return []
            seen.add(current)
            path.append(current)
        return path


def cycles(next_of: Mapping[str, str]) -> list[list[str]]:
    """The cycles of a "follows" relation (a mimic joint and the joint it mimics): each once, as the names along it
    starting from the smallest, in a stable order. A chain that ends (at a name with no successor) is no cycle."""
    found: dict[tuple[str, ...], list[str]] = {}
    done: set[str] = set()
    for start in sorted(next_of):
        path: list[str] = []
        where: dict[str, int] = {}
        current: str | None = start
        while current is not None and current not in done and current not in where:
            where[current] = len(path)
            path.append(current)
            current = next_of.get(current)
        if current is not None and current in where:  # back to a name of this walk: the loop from there
            loop = path[where[current] :]
            first = loop.index(min(loop))
            loop = loop[first:] + loop[:first]
            found.setdefault(tuple(loop), loop)
        done.update(path)
    return list(found.values())
