"""Bounded reading of YAML input files: size, encoding, nesting, alias expansion, strings.

:func:`read_text` reads at most the file-size limit (so ``/dev/zero`` or a 50 MB
file costs a bounded read) and decodes UTF-8 (with or without BOM) or BOM-marked
UTF-16. :func:`check_events` walks the YAML *event* stream (ruamel's parser is
iterative, unlike its composer, and stops at the first limit crossed, so a deeply
nested or alias-bomb file is refused after a bounded amount of work; :func:`load` walks
each event as its composer takes it, so a file is parsed once) and raises a
:class:`~betvdesign.errors.SpecError` at ``file:line:col`` naming the field and the
limit; a number of more digits than the limit is refused there too, before Python's
``int()`` would raise on it (:func:`number_digits`). The limits live in
:mod:`betvdesign.spec.limits`.
"""

from __future__ import annotations

import codecs
import os
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.error import YAMLWarning
from ruamel.yaml.events import (
    AliasEvent,
    CollectionEndEvent,
    CollectionStartEvent,
    MappingStartEvent,
    ScalarEvent,
)
from ruamel.yaml.nodes import Node, ScalarNode
from ruamel.yaml.parser import RoundTripParser
from ruamel.yaml.resolver import VersionedResolver

from betvdesign.errors import Location, SpecError, SpecIssue
from betvdesign.output import answers
from betvdesign.spec import limits

#: Resolvers of plain scalars under YAML 1.2 (the default) and 1.1 (a ``%YAML 1.1``
#: directive): a scalar either reads as a number is counted as one.
_RESOLVERS = (VersionedResolver(version=(1, 2)), VersionedResolver(version=(1, 1)))
_NUMBER_TAGS = ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")


def number_digits(value: str, tag: str | None = None, plain: bool = True) -> int:
    """How many digits a YAML scalar has when it reads as a number (0 otherwise).

    Parameters
    ----------
    value : str
        The scalar's text.
    tag : str or None
        Its explicit tag (``!!int``), if any.
    plain : bool
        True for an unquoted scalar (its type then follows from its text).

    Returns
    -------
    int
        The count of its digits (letters of a hexadecimal, ``nan`` or ``inf`` included)
        when the YAML 1.2 or 1.1 rules make it an integer or a float, else 0.
    """
    if tag in _NUMBER_TAGS:
        numeric = True
    elif tag is None and plain:
        numeric = any(
            r.resolve(ScalarNode, value, (True, False)) in _NUMBER_TAGS for r in _RESOLVERS
        )
    else:
        numeric = False
    return sum(ch.isalnum() for ch in value) if numeric else 0


def _one(filename: str, message: str, line: int | None = None, col: int | None = None):
    return SpecError([SpecIssue(Location(filename, line, col), "", message)])


def read_text(path: str | os.PathLike[str]) -> str:
    """Text of a YAML input file, read within the size limit.

    Parameters
    ----------
    path : str or PathLike
        The file.

    Returns
    -------
    str
        The decoded text (:func:`decode`).

    Raises
    ------
    SpecError
        Not found, a directory, unreadable, larger than
        :func:`~betvdesign.spec.limits.max_file_bytes` or not decodable.
    """
    p = Path(path)
    fname = str(p)
    cap = limits.max_file_bytes()
    try:
        with open(p, "rb") as fh:
            raw = fh.read(cap + 1)
    except FileNotFoundError:
        raise _one(fname, "file not found") from None
    except IsADirectoryError:
        raise _one(fname, "is a directory, expected a YAML file") from None
    except OSError as exc:
        raise _one(fname, f"cannot read file: {exc.strerror or exc}") from None
    answers.note_read(p)  # a cached answer depends on this file (betv check)
    if len(raw) > cap:
        size = _size(p)
        got = f"{size:,} bytes" if size and size > cap else f"more than {cap:,} bytes"
        raise _one(
            fname,
            f"file is {got}; the limit is {cap:,} bytes (set {limits.FILE_BYTES_ENV} to raise it)",
        )
    return decode(raw, fname)


def _size(p: Path) -> int | None:
    try:
        return p.stat().st_size
    except OSError:
        return None


def decode(raw: bytes, fname: str) -> str:
    """Decode the bytes of a YAML file.

    Decode the bytes of a YAML file: UTF-8 (BOM optional) or UTF-16 with a BOM, as YAML
    1.2 allows.

    Parameters
    ----------
    raw : bytes
        The file's bytes.
    fname : str
        The file, for messages.

    Returns
    -------
    str
        The text, without a BOM.

    Raises
    ------
    SpecError
        Naming the line and column of the first undecodable byte.
    """
    if raw.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        try:
            return raw.decode("utf-16")
        except UnicodeDecodeError as exc:
            raise _one(fname, f"not valid UTF-16 text ({exc.reason} at byte {exc.start})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        col = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        raise _one(
            fname,
            f"not UTF-8 text ({exc.reason}, byte 0x{raw[exc.start]:02x}); save the file as UTF-8",
            line,
            col,
        ) from None
    return text.removeprefix("\ufeff")


@dataclass
class _Frame:
    """One open mapping or sequence during the event walk."""

    path: str
    is_map: bool
    anchor: str | None
    nodes: int = 1
    depth: int = 1  # levels below and including this one
    index: int = 0  # items seen (sequence) or keys+values seen (mapping)
    key: Any = None
    children: list[Any] = field(default_factory=list)


class _Walk:
    """The state of :func:`check_events`'s walk and what each kind of event does to it.

    ``sizes``: nodes and depth of each anchor, for the aliases that name it; ``stack``:
    the open collections; ``total``: nodes of the closed top-level ones.

    Parameters
    ----------
    filename : str
        The file, for messages.
    """

    def __init__(self, filename: str) -> None:
        self.filename = filename
        self.sizes: dict[str, tuple[int, int]] = {}  # anchor -> (nodes, depth)
        self.stack: list[_Frame] = []
        self.total = 0

    def fail(self, event: Any, path: str, message: str) -> None:
        """Raise the limit crossed at ``event``, at field ``path``.

        Raises
        ------
        SpecError
            At the event's ``file:line:col``.
        """
        m = event.start_mark
        if len(path) > 120:
            path = path[:60] + "…" + path[-59:]
        raise SpecError(
            [SpecIssue(Location(self.filename, m.line + 1, m.column + 1), path, message)]
        )

    def child_path(self) -> str:
        """The field path of the next node (its mapping's path for a key)."""
        stack = self.stack
        if not stack:
            return ""
        top = stack[-1]
        if top.is_map:
            if top.index % 2 == 0:  # a key
                return top.path
            key = top.key
            return f"{top.path}.{key}" if top.path else str(key)
        return f"{top.path}[{top.index}]"

    def add(self, nodes: int, depth: int, event: Any, path: str) -> None:
        """Count a node of ``nodes`` nodes and ``depth`` levels; fail past a limit."""
        stack = self.stack
        if stack:
            top = stack[-1]
            top.nodes += nodes
            top.depth = max(top.depth, depth + 1)
            top.index += 1
        else:
            self.total += nodes
        running = self.total + sum(f.nodes for f in stack)
        if running > limits.MAX_YAML_NODES:
            self.fail(
                event,
                path,
                f"more than {limits.MAX_YAML_NODES:,} YAML nodes"
                + (" once aliases are expanded" if self.sizes else "")
                + "; a device file has a few hundred",
            )
        if len(stack) + depth > limits.MAX_YAML_DEPTH:
            self.fail(event, path, f"YAML nested deeper than {limits.MAX_YAML_DEPTH} levels")

    def feed(self, event: Any) -> None:
        """Take the next event of the stream (those that are no node are passed over)."""
        if isinstance(event, ScalarEvent):
            self.scalar(event)
        elif isinstance(event, AliasEvent):
            self.alias(event)
        elif isinstance(event, CollectionStartEvent):
            self.start(event)
        elif isinstance(event, CollectionEndEvent):
            self.end(event)

    def scalar(self, event: ScalarEvent) -> None:
        """A scalar: its length and digits, then count it."""
        stack = self.stack
        path = self.child_path()
        value = event.value
        if len(value) > limits.MAX_STRING_CHARS:
            self.fail(
                event,
                path,
                f"string of {len(value):,} characters; the limit is {limits.MAX_STRING_CHARS:,}",
            )
        plain = bool(event.implicit and event.implicit[0])
        digits = (
            number_digits(value, event.tag, plain) if len(value) > limits.MAX_NUMBER_DIGITS else 0
        )
        if digits > limits.MAX_NUMBER_DIGITS:
            self.fail(
                event,
                path,
                f"number of {digits:,} digits; the limit is {limits.MAX_NUMBER_DIGITS} digits",
            )
        if stack and stack[-1].is_map and stack[-1].index % 2 == 0:
            stack[-1].key = value
        if event.anchor:
            self.sizes[event.anchor] = (1, 0)
        self.add(1, 0, event, path)

    def alias(self, event: AliasEvent) -> None:
        """An alias: refuse a recursive one, count what it names."""
        stack = self.stack
        path = self.child_path()
        if any(f.anchor == event.anchor for f in stack):
            self.fail(
                event,
                path,
                f"alias *{event.anchor} refers to a mapping or list that contains it "
                "(a recursive structure)",
            )
        nodes, depth = self.sizes.get(event.anchor, (1, 0))
        if stack and stack[-1].is_map and stack[-1].index % 2 == 0:
            stack[-1].key = f"*{event.anchor}"
        self.add(nodes, depth, event, path)

    def start(self, event: CollectionStartEvent) -> None:
        """A mapping or sequence opens."""
        path = self.child_path()
        if len(self.stack) + 1 > limits.MAX_YAML_DEPTH:
            self.fail(event, path, f"YAML nested deeper than {limits.MAX_YAML_DEPTH} levels")
        self.stack.append(_Frame(path, isinstance(event, MappingStartEvent), event.anchor))

    def end(self, event: CollectionEndEvent) -> None:
        """A mapping or sequence closes: remember its size if anchored, count it."""
        frame = self.stack.pop()
        if frame.anchor:
            self.sizes[frame.anchor] = (frame.nodes, frame.depth)
        self.add(frame.nodes, frame.depth, event, frame.path)


class _CheckedParser(RoundTripParser):
    """ruamel's round-trip parser; every event it hands out is first walked by ``walk``."""

    walk: _Walk | None = None

    def get_event(self) -> Any:
        """The next event, checked against the limits (:meth:`_Walk.feed`)."""
        event = super().get_event()
        if self.walk is not None:
            self.walk.feed(event)
        return event


def load(
    text: str, filename: str, *, allow_duplicate_keys: bool = False
) -> tuple[Node | None, Any]:
    """Compose and construct YAML text in one parse, within the limits.

    The composer takes each event from a parser that walks it first, as
    :func:`check_events` does, so a limit crossed stops the parse at that event (the
    composer has then built at most the nodes and depth the limits allow); the data is
    constructed from the composed tree, not from a second parse. A re-defined anchor is
    legal YAML (the last wins).

    Parameters
    ----------
    text : str
        The YAML text.
    filename : str
        The file, for messages.
    allow_duplicate_keys : bool
        True: a repeated key is no error here (the caller finds them all on the tree;
        the last wins in the data); False: ruamel's ``DuplicateKeyError`` at the first.

    Returns
    -------
    node : Node or None
        The composed tree (None for an empty text).
    data : Any
        The round-trip data (``CommentedMap`` ... with positions), as ``YAML(typ="rt")
        .load`` gives it; None for an empty text.

    Raises
    ------
    SpecError
        At the first limit crossed (:func:`check_events`).
    ruamel.yaml.YAMLError
        Malformed YAML (the loader reports it at its position).
    """
    yaml = YAML(typ="rt")
    yaml.allow_duplicate_keys = allow_duplicate_keys
    yaml.Parser = _CheckedParser
    yaml.parser.walk = _Walk(filename)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", YAMLWarning)
        node = yaml.compose(text)
        data = None if node is None else yaml.constructor.construct_document(node)
    return node, data


def check_events(text: str, filename: str) -> None:
    """Walk the YAML events of a text; raise at the first limit crossed.

    Alias expansion is counted as the composer and the validation will see it: an
    alias (or a ``<<`` merge) costs the nodes and depth of what it names. Malformed
    YAML raises ruamel's own ``MarkedYAMLError`` (the loader reports it).

    Parameters
    ----------
    text : str
        The YAML text.
    filename : str
        The file, for messages.

    Raises
    ------
    SpecError
        At ``file:line:col`` with the field path: more nodes than
        :data:`~betvdesign.spec.limits.MAX_YAML_NODES`, nesting deeper than
        :data:`~betvdesign.spec.limits.MAX_YAML_DEPTH`, a recursive alias, a string
        longer than :data:`~betvdesign.spec.limits.MAX_STRING_CHARS` or a number of
        more than :data:`~betvdesign.spec.limits.MAX_NUMBER_DIGITS` digits.
    """
    walk = _Walk(filename)
    for event in YAML(typ="rt").parse(text):
        walk.feed(event)
