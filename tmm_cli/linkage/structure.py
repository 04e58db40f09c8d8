"""Structural analysis of a planar linkage (docs/methods.md §1).

* Chebyshev's formula W = 3n - 2 p5 - p4 (n moving links, p5 lower pairs: one per
  :class:`~tmm_cli.linkage.mechanism.Joint`, p4 = 0 higher pairs).
* Assur decomposition. The class-I mechanism I(0, crank) is the ground and the
  crank; the remaining links are split into Assur groups (structural groups with
  zero mobility, 3k = 2p, no smaller group inside) by a search from the crank
  outward: at every step the smallest set of not-yet-attached links that forms a
  group with the ground, the crank and the groups found so far is taken (ties: the
  lexicographically smallest link indices). The groups are therefore listed in the
  order of attachment; the textbook order of *separation* (Artobolevsky, Popov &
  Timofeev: from the group farthest from the input link) is this list reversed.
* Class of a group (Artobolevsky): 2 for a dyad; otherwise the number of sides of
  the most complex closed contour formed by its internal pairs, or, when the
  internal pairs form no contour, the largest number of internal pairs on one link
  (a triad: a ternary base link with three internal pairs, class III). Order = the
  number of external pairs. Class of the mechanism = highest class of its groups.
* Type of a group, reading convention used throughout tmm:
  - a dyad (two links A, B) is read from the side of the most recently attached
    body: A is the link whose external pair joins the body attached latest (crank
    before ground, a later group before an earlier one; ties: the lower link
    index). The type is ``kind(external pair of A) + kind(pair A-B) +
    kind(external pair of B)``: the slider-crank rod+slider is ``RRP``, the
    slotted lever of a shaper ``RPR``, the Scotch yoke ``RPP``, a tangent
    mechanism ``PRP``; reading a dyad from its other end gives ``PRR``/``PPR``,
    which are Artobolevsky's second/fifth kind read backwards;
  - a triad (class III, order 3): its three legs (binary links) in the same
    reading order, each as ``external pair + pair with the base link``, joined
    by ``-``: ``RR-RR-RR``;
  - any other group: the external pair kinds, ``/``, the internal pair kinds.
* Passive (redundant) constraints and idle (local) degrees of freedom are flagged
  in ``warnings`` when found: a link or a pair of links joined to already attached
  links by more pairs than they have freedoms (2p > 3k), a link with a single pair.

:func:`analyze` raises :class:`~tmm_cli.errors.StageError` ``('structure', ...)``
when the linkage cannot be driven by the crank (W != 1, links left over from the
decomposition); with ``task=`` given, the same message is raised as a
:class:`~tmm_cli.errors.TaskError` pointing at the task's ``mechanism`` section.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from itertools import combinations

from ..errors import StageError
from ..messages import Message
from .mechanism import Joint, Mechanism

_ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI", 7: "VII", 8: "VIII"}


def roman(k: int) -> str:
    """A class number in Roman numerals.

    Parameters
    ----------
    k : int
        The class (Assur's classification).

    Returns
    -------
    str
        ``"I"``, ``"II"``...; the number itself beyond the table.
    """
    return _ROMAN.get(k, str(k))


@dataclass
class Group:
    """One Assur group, in the reading order described in the module docstring.

    ``links``: link indices (dyad: [A, B]; triad: the three legs, then the base);
    ``joints``: dyad: [external of A, A-B, external of B]; otherwise the external
    pairs (in leg order) followed by the internal pairs.
    """
    links: list[int]
    joints: list[Joint]
    klass: int
    order: int
    type: str
    names: list[str] = field(default_factory=list)
    external: list[Joint] = field(default_factory=list)
    internal: list[Joint] = field(default_factory=list)
    attached_to: list[int] = field(default_factory=list)   # bodies outside the group it joins

    @property
    def label(self) -> str:
        return f"{roman(self.klass)}({','.join(str(i) for i in self.links_sorted)})"

    @property
    def links_sorted(self) -> list[int]:
        return sorted(self.links)

    def describe(self) -> str:
        """e.g. ``group II(2,3) (links rod, rocker)``."""
        return f"group {self.label} (links {', '.join(self.names)})"

    def message_params(self) -> dict:
        """The group as warning parameters (tmm_cli.messages): its label and its links' names."""
        return {"group": self.label, "links": list(self.names)}

    def to_dict(self) -> dict:
        return {"links": list(self.names), "indices": list(self.links), "class": self.klass,
                "order": self.order, "type": self.type,
                "joints": [j.name for j in self.joints]}


@dataclass
class StructureResult:
    """The structural analysis: the mobility W = 3n - 2p5 - p4, the Assur groups, the formula."""

    n: int
    p5: int
    p4: int
    W: int
    groups: list[Group]
    class_: int
    formula: str
    drive: int
    warnings: list[str] = field(default_factory=list)
    passive: int = 0            # number of passive (redundant) constraints found
    idle: list[str] = field(default_factory=list)   # links with an idle degree of freedom

    def to_dict(self) -> dict:
        return {"n": self.n, "p5": self.p5, "p4": self.p4, "W": self.W, "class": self.class_,
                "groups": [g.to_dict() for g in self.groups], "formula": self.formula,
                "passive_constraints": self.passive, "idle_links": list(self.idle)}


# ---------------------------------------------------------------------------------
def _fail(task, msg: str):
    if task is not None:
        return task.error(("mechanism",), msg)
    return StageError("structure", msg)


def _pair_points(lk) -> list[str]:
    """The points of a link that are meant as pairs: a bar's two ``points``, a slider's pin
    (a link's ``local`` lists them first, then its ``extra`` points)."""
    return list(lk.local)[:2 if lk.kind == "bar" else 1]


def _lonely_pair_points(mech: Mechanism) -> list[tuple[str, str]]:
    """(link name, message) for every pair point that only one link uses -- a typo such as
    ``[E, D]`` for ``[C, D]``: 'point E is used by link4 only: a pair needs two links --
    did you mean C?' (C: a point of another link that no second link uses either)."""
    import difflib

    from ..limits import lookalike, script_note

    def lonely_of(lk, points):
        return [p for p in points if mech.owner.get(p, []) == [lk.index]]

    out = []
    for lk in mech.links:
        for p in lonely_of(lk, _pair_points(lk)):
            others = [q for o in mech.links if o.index != lk.index for q in lonely_of(o, o.local)]
            alike = [q for q in others if lookalike(p, q)]        # one typed with Cyrillic letters
            guess = alike or difflib.get_close_matches(p, others, n=1, cutoff=0.5) or (others if len(others) == 1 else [])
            hint = (Message("structure.fail.point_hint_script", point=alike[0], note=script_note(p, alike[0])) if alike
                    else Message("structure.fail.point_hint", point=guess[0]) if guess else Message("text", text=""))
            out.append((lk.name, Message("structure.fail.lonely_point", point=p, link=lk.name, hint=hint)))
    return out


def _connected(nodes: set[int], edges: list[Joint]) -> bool:
    nodes = set(nodes)
    if not nodes:
        return True
    start = next(iter(nodes))
    seen = {start}
    stack = [start]
    while stack:
        x = stack.pop()
        for j in edges:
            for u, v in ((j.a, j.b), (j.b, j.a)):
                if u == x and v in nodes and v not in seen:
                    seen.add(v)
                    stack.append(v)
    return seen == nodes


def _longest_cycle(nodes: list[int], edges: list[Joint]) -> int:
    """Length of the longest simple cycle of a small multigraph (0 if acyclic)."""
    adj: dict[int, list[tuple[int, int]]] = {v: [] for v in nodes}
    for k, j in enumerate(edges):
        adj[j.a].append((j.b, k))
        adj[j.b].append((j.a, k))
    return max((_cycle_through(adj, s, s, {s}, frozenset(), 0) for s in nodes), default=0)


def _cycle_through(adj: dict, start: int, v: int, used_nodes: set, used_edges: frozenset, length: int) -> int:
    """The longest simple cycle back to ``start`` that goes on from ``v`` (reached by ``length``
    edges ``used_edges`` through ``used_nodes``) over nodes above ``start`` (each cycle found
    once, from its least node); 0 if none.  (A function of the module, not one nested in
    :func:`_longest_cycle`: a nested one that calls itself is a reference cycle.)"""
    best = 0
    for w, k in adj[v]:
        if k in used_edges:
            continue
        if w == start and length >= 1:
            best = max(best, length + 1)
        elif w not in used_nodes and w > start:
            best = max(best, _cycle_through(adj, start, w, used_nodes | {w}, used_edges | {k}, length + 1))
    return best


def _classify(S: list[int], ext: list[Joint], inner: list[Joint]) -> int:
    if len(S) == 2:
        return 2
    cyc = _longest_cycle(S, inner)
    deg = {v: 0 for v in S}
    for j in inner:
        deg[j.a] += 1
        deg[j.b] += 1
    return max(2, cyc, max(deg.values()))


def analyze(mech: Mechanism, task=None) -> StructureResult:
    """Structural analysis of ``mech`` (see the module docstring for conventions).

    Parameters
    ----------
    mech : Mechanism
        The linkage (links, lower pairs, the crank).
    task : Task or None
        Given: a linkage the crank cannot drive is an invalid task (TaskError naming
        ``mechanism`` and its line); None: a StageError('structure', ...).

    Returns
    -------
    StructureResult
        n (moving links), p5 (lower pairs), p4, the degree of freedom W = 3n - 2p5 - p4
        (Chebyshev), the Assur groups in the order of attachment, their class and order,
        the structural formula, passive constraints and idle links.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: Chebyshev's formula, Assur's
    classification of structural groups.
    """
    n = mech.n
    joints = list(mech.joints)
    p5 = len(joints)
    p4 = 0
    W = 3 * n - 2 * p5 - p4
    names = {lk.index: lk.name for lk in mech.links}
    names[0] = "ground"
    warnings: list[str] = []

    # idle degrees of freedom: a link with a single pair (it turns freely about it)
    npairs = {i: 0 for i in range(1, n + 1)}
    for j in joints:
        for b in (j.a, j.b):
            if b:
                npairs[b] += 1
    idle = [names[i] for i in range(1, n + 1) if npairs[i] == 1 and i != mech.drive]
    for nm in idle:
        warnings.append(Message("structure.idle_link", link=nm))

    drive = mech.drive
    crank_ground = [j for j in joints if {j.a, j.b} == {0, drive}]
    passive = 0
    if len(crank_ground) != 1 or crank_ground[0].kind != "R":
        msg = (f"the crank '{names[drive]}' must be joined to the ground by exactly one revolute pair "
               f"(found {len(crank_ground)} pair(s) between them)")
        raise _fail(task, msg)

    known = {0: 0, drive: 1}          # body -> attachment rank
    remaining = [i for i in range(1, n + 1) if i != drive]
    groups: list[Group] = []
    rank = 2

    def pairs_of(S: set[int]) -> list[Joint]:
        return [j for j in joints if (j.a in S or j.b in S)
                and (j.a in S or j.a in known) and (j.b in S or j.b in known)]

    while remaining:
        # passive constraints: one or two links over-constrained by the known bodies
        for k in (1, 2):
            for S in combinations(remaining, k):
                P = pairs_of(set(S))
                inner = [j for j in P if j.a in S and j.b in S]
                if 2 * len(P) > 3 * k and _connected(set(S), inner):
                    extra = 2 * len(P) - 3 * k
                    passive = max(passive, extra)
                    msg = Message("structure.passive", links=[names[i] for i in S], pairs=len(P),
                                  freedoms=3 * k, extra=extra)
                    if msg not in warnings:
                        warnings.append(msg)
        found = None
        for k in range(2, len(remaining) + 1, 2):
            for S in combinations(remaining, k):
                Sset = set(S)
                P = pairs_of(Sset)
                if 2 * len(P) != 3 * k:
                    continue
                inner = [j for j in P if j.a in Sset and j.b in Sset]
                if not _connected(Sset, inner):
                    continue
                deg = {v: 0 for v in S}
                for j in P:
                    for b in (j.a, j.b):
                        if b in Sset:
                            deg[b] += 1
                if min(deg.values()) < 2:
                    continue
                ext = [j for j in P if not (j.a in Sset and j.b in Sset)]
                if not ext:
                    continue
                found = (list(S), P, inner, ext)
                break
            if found:
                break
        if not found:
            break
        S, P, inner, ext = found
        groups.append(_make_group(S, P, inner, ext, known, names))
        for i in S:
            known[i] = rank
            remaining.remove(i)
        rank += 1

    if W != 1 or remaining:
        why = []
        if W < 1:
            why.append(Message("structure.fail.rigid" if W == 0 else "structure.fail.over_constrained",
                               W=W, n=n, p5=p5, p4=p4))
            if passive:
                why.append(Message("structure.fail.special_dimensions"))
        elif W > 1:
            why.append(Message("structure.fail.inputs", W=W, n=n, p5=p5, p4=p4))
            if idle:
                why.append(Message("structure.fail.idle", links=list(idle)))
        if remaining and W == 1:
            why.append(Message("structure.fail.no_groups", links=[names[i] for i in remaining], crank=names[drive]))
        why.extend(w for w in warnings if "passive" in w and w not in why)
        lonely = _lonely_pair_points(mech)
        if lonely:      # a typo in a point name: say that first, the count follows from it
            (first_link, _), *_ = lonely
            msg = Message("structure.fail.reasons", reasons=[m for _, m in lonely] + why)
            if task is not None:
                raise task.error(("mechanism", "links", first_link), msg)
            raise StageError("structure", msg)
        raise _fail(task, Message("structure.fail.reasons", reasons=why))

    klass = max([1] + [g.klass for g in groups])
    formula = " -> ".join([f"I(0,{drive})"] + [g.label for g in groups])
    return StructureResult(n=n, p5=p5, p4=p4, W=W, groups=groups, class_=klass, formula=formula,
                           drive=drive, warnings=warnings, passive=passive, idle=idle)


def _make_group(S, P, inner, ext, known, names) -> Group:
    Sset = set(S)

    def outside(j: Joint) -> int:
        return j.a if j.a not in Sset else j.b

    def inside(j: Joint) -> int:
        return j.b if j.a not in Sset else j.a

    klass = _classify(S, ext, inner)
    order = len(ext)
    attached = sorted({outside(j) for j in ext})
    # reading order: by the attachment rank of the outside body, latest first; ties by index
    ext_sorted = sorted(ext, key=lambda j: (-known[outside(j)], inside(j), outside(j)))
    if len(S) == 2 and len(ext) == 2 and len(inner) == 1:
        A = inside(ext_sorted[0])
        B = inside(ext_sorted[1])
        if A == B:                        # both external pairs on one link (not a proper dyad)
            links = sorted(S)
            typ = "".join(j.kind for j in ext_sorted) + "/" + "".join(j.kind for j in inner)
            joints = ext_sorted + inner
        else:
            links = [A, B]
            joints = [ext_sorted[0], inner[0], ext_sorted[1]]
            typ = "".join(j.kind for j in joints)
    else:
        deg = {v: 0 for v in S}
        for j in inner:
            deg[j.a] += 1
            deg[j.b] += 1
        legs_ok = (len(S) == 4 and len(ext) == 3 and len(inner) == 3
                   and sorted(deg.values()) == [1, 1, 1, 3])
        if legs_ok:
            base = next(v for v in S if deg[v] == 3)
            legs = [inside(j) for j in ext_sorted]
            links = legs + [base]
            joints = []
            parts = []
            for j in ext_sorted:
                leg = inside(j)
                ji = next(q for q in inner if leg in (q.a, q.b))
                joints += [j, ji]
                parts.append(j.kind + ji.kind)
            typ = "-".join(parts)
        else:
            seen: list[int] = []
            for j in ext_sorted:
                if inside(j) not in seen:
                    seen.append(inside(j))
            links = seen + [v for v in sorted(S) if v not in seen]
            joints = ext_sorted + inner
            typ = "".join(j.kind for j in ext_sorted) + "/" + "".join(j.kind for j in inner)
    return Group(links=links, joints=joints, klass=klass, order=order, type=typ,
                 names=[names[i] for i in links], external=ext_sorted, internal=list(inner),
                 attached_to=attached)
