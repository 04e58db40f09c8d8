"""Exceptions of tmm.

* :class:`TaskError` -- the task file is invalid (CLI exit code 2). Carries the file,
  line, column and the field path so the message can point at the exact spot.
* :class:`StageError` -- a valid task cannot be computed (CLI exit code 3): a group
  does not assemble, a position is singular... Carries the stage and the position.
"""
from __future__ import annotations


def _where(file: str, line: int | None, col: int | None) -> str:
    """FILE, FILE:LINE or FILE:LINE:COL."""
    if line is None:
        return file
    return f"{file}:{line}" if col is None else f"{file}:{line}:{col}"


class TaskError(Exception):
    """Invalid task input. ``issues`` is a list of (field, line, column, message). ``kind``: what
    the invalid file is, for the message's head (`error: invalid <kind>`): the task, or the
    answers file or tolerance file given with it (exit code 2 all the same)."""

    def __init__(self, message: str, *, file: str | None = None,
                 issues: list[tuple[str, int | None, int | None, str]] | None = None, kind: str = "task"):
        self.kind = kind
        self.file = file
        self.issues = issues or []
        self.message = message
        super().__init__(self.render())

    def render(self) -> str:
        where = self.file or "<task>"
        if not self.issues:
            return f"{where}: {self.message}"
        lines = []
        for field, line, col, msg in self.issues:
            loc = _where(where, line, col)
            lines.append(f"{loc}: field '{field}': {msg}" if field else f"{loc}: {msg}")
        return "\n".join(lines)

    def coded(self):
        """:meth:`render` as one coded message (``tmm_cli.messages.Message``, code
        ``input.issues``: one ``input.at`` / ``input.at_field`` a line, each holding its
        issue's message -- coded where the check that found it codes it, else as written),
        so a page in another language can show it; its English text is :meth:`render`'s.
        None when the two would differ."""
        from .messages import Message
        from .messages import as_message as part

        where = self.file or "<task>"
        if not self.issues:
            out = Message("input.issues", issues=[Message("input.at", where=where, message=part(self.message))])
        else:
            items = []
            for field, line, col, msg in self.issues:
                loc = _where(where, line, col)
                items.append(Message("input.at_field", where=loc, field=field, message=part(msg)) if field
                             else Message("input.at", where=loc, message=part(msg)))
            out = Message("input.issues", issues=items)
        return out if str(out) == self.render() else None


class StageError(Exception):
    """A stage failed on valid input (e.g. the mechanism does not assemble).  ``message``
    is the English text; a coded one (a :class:`tmm_cli.messages.Message`) is shown in
    the report's language too (:meth:`to_dict` gives its code and parameters).
    ``never_assembles``: the links of a group that assembles at no crank angle at all
    (the kinematics), which makes the task invalid (:func:`tmm_cli.validation.impossible_dimensions`)."""

    def __init__(self, stage: str, message: str, position: str | float | None = None, *,
                 never_assembles: list[str] | None = None):
        self.stage = stage
        self.message = message
        self.position = position
        self.never_assembles = never_assembles
        text = f"stage '{stage}' failed"
        if position is not None:
            text += f" at {position}" if isinstance(position, str) else f" at crank angle {position:.6g} deg"
        super().__init__(f"{text}: {message}")

    def to_dict(self) -> dict:
        """The results.json entry: stage, English message, position, and for a coded
        message its ``code`` and ``params``."""
        from .messages import Message

        out = {"stage": self.stage, "message": str(self.message), "position": self.position}
        code = self.message.code if isinstance(self.message, Message) else None
        if code is not None:
            out.update(code=code, params=dict(self.message.params))
        return out


def dotted(path) -> str:
    """A field path as a task file's reader names it: ``('links', 'crank', 'extra', 0)`` ->
    ``links.crank.extra[0]``."""
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else ("." if out else "") + str(p)
    return out


def field_error(field: str, message: str) -> TaskError:
    """A TaskError naming its field (dotted path, e.g. 'loads.forces[0].at') without the
    file and line: the pipeline adds them (``Task.locate``)."""
    return TaskError(message, issues=[(field, None, None, message)])


def guarded(stage: str):
    """Decorator: run a stage function, turning an unexpected numerical failure
    (ArithmeticError, ValueError, IndexError, KeyError, RuntimeError, LinAlgError) into a
    StageError of ``stage``."""
    def deco(fn):
        def wrapper(*a, **kw):
            try:
                return fn(*a, **kw)
            except StageError:
                raise
            except (ArithmeticError, ValueError, IndexError, KeyError, RuntimeError,
                    __import__("numpy").linalg.LinAlgError) as exc:
                raise StageError(stage, f"{type(exc).__name__}: {exc}") from exc
        return wrapper
    return deco
