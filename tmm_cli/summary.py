"""Terminal output with rich: the run summary and the check table."""
from __future__ import annotations

import re
from pathlib import Path

from . import locales


def _console():
    from rich.console import Console
    return Console(stderr=False, highlight=False, emoji=False)


def _f(x, digits=5) -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, (int,)) and not isinstance(x, bool):
        return str(x)
    try:
        return f"{float(x):.{digits}g}"
    except (TypeError, ValueError):
        return str(x)


def _words(table: str, lang: str) -> dict:
    """The terminal's words of the catalogue's summary table ``table`` (``run``, ``check``,
    ``batch``) in ``lang``, English's where ``lang`` lacks one."""
    return {**locales.of("summary", table, "en"), **(locales.of("summary", table, lang) if lang != "en" else {})}


def run_words(lang: str = "en") -> dict[str, str]:
    """The terminal's words of `tmm run` in ``lang`` (the catalogue's summary ``run`` table)."""
    return _words("run", lang)


def _summary_rows(results: dict, lang: str = "en") -> list[tuple[str, str]]:
    """(quantity, value) of each row of the run summary, in ``lang``: its words from the
    catalogue, its numbers in the language's writing (ru, uk: the decimal comma, and lists
    separated by semicolons, as the report writes them)."""
    from .numfmt import list_sep, localize
    T = run_words(lang)
    sep = list_sep(lang)
    rows: list[tuple[str, str]] = []
    add = lambda *row: rows.append(row)  # noqa: E731

    def f(x, digits=5) -> str:
        if isinstance(x, bool):
            return T["is_yes"] if x else T["is_no"]
        return localize(_f(x, digits), lang)
    st = results.get("structure")
    if st:
        add(T["W"], f"{st['W']} (n={st['n']}, p5={st['p5']}, p4={st['p4']})")
        formula = str(st.get("formula"))
        add(T["formula"], formula if lang == "en" else formula.replace(" -> ", " → "))
    pos = results.get("positions")
    if pos:
        add(T["phi0"], f(pos.get("phi0")))
        if pos.get("K") is not None:
            add(T["K"], f(pos.get("K")))
    syn = results.get("synthesis")
    if syn and isinstance(syn.get("lengths"), dict):
        for name, value in syn["lengths"].items():         # the generated mechanism: the task's answer
            add(T["syn_length"].format(name=name), f(value))
    rows_t = [r for r in results.get("transmission") or () if isinstance(r, dict) and r.get("gamma_min") is not None]
    if rows_t:                                           # the least of every dyad's least
        least = min(rows_t, key=lambda r: r["gamma_min"])
        add(T["gamma"], f"{f(least['gamma_min'])} ({least.get('group', '')})")
    if syn and syn.get("type") == "function" and syn.get("gamma_min") is not None and syn.get("grashof") == "crank-rocker":
        # a crank-rocker generator: the row above is the full turn's, this its working range's
        # (any other generator's transmission stage runs over the range already)
        add(T["gamma_range"], f(syn["gamma_min"]))
    if results.get("singular"):
        add(T["singular"], sep.join(f(s, 7) for s in results["singular"]))
    fw = results.get("flywheel")
    if fw:
        add(T["J"], f(fw.get("J")))
        add(T["Db"], f"{f(fw.get('diameter'))} {T['times']} {f(fw.get('width'))}")
    cam = results.get("cam")
    if cam:
        add(T["r0"], f(cam.get("r0")))
        if cam.get("r0_given"):
            add(T["r0_min"], f(cam.get("r0_min")))
            add(T["pressure"], f(cam.get("max_pressure_angle")))
    g = results.get("gears")
    if g:
        add(T["aw"], f(g.get("aw")))
        # a wheel without an involute flank (its tip inside the base circle, its involute beginning
        # above the tip): eps_alpha is a formal value, the pair cannot mesh (the warnings say why)
        formal = any(str(m.get("code", "")).startswith("gears.no_involute") for m in results.get("messages") or ()
                     if isinstance(m, dict))
        why = ("" if not g.get("eps_alpha_formal") else T["formal_mesh"] if formal
               else T["formal_interfere"] if (g.get("checks") or {}).get("interference") else T["formal_pointed"])
        add(T["eps"], f(g.get("eps_alpha")) + why)
    pl = results.get("planetary")
    if pl:
        add(T["planetary_z"], sep.join(f"{k}={v}" for k, v in (pl.get("z") or {}).items()))
        add(T["planetary_ratio"], f(pl.get("ratio")))
    dt = results.get("drive_train")
    if dt:
        add(T["dt_z"], " | ".join("/".join(str(v) for v in s["z"]) for s in dt.get("stages", [])))
        add(T["dt_ratio"], f(dt.get("ratio")))
        if dt.get("motor_power_computed"):
            add(T["motor_power"], f(dt.get("motor_power")))
    bal = results.get("balancing")
    if bal and bal.get("max"):
        add(T["shaking"], f(bal["max"].get("F")))
        if "F_balanced" in bal["max"]:
            add(T["shaking_bal"], f(bal["max"]["F_balanced"]))
    if bal and bal.get("rotor"):
        add(T["rotor_m"], sep.join(f(c["m"]) for c in bal["rotor"]["corrections"]))
    d2 = results.get("dof2")
    if d2:
        hit, top = d2.get("impact") or {}, d2.get("max") or {}
        if hit:
            add(T["dof2_vM"], f((hit.get("M") or {}).get("v")))
            add(T["dof2_T2"], f(hit.get("striker_energy")))
        if "v_M" in top:
            add(T["dof2_vM_max"], f(top["v_M"].get("value")))
        if "R01" in top:
            add(T["dof2_R01"], f(top["R01"].get("value")))
        if "driving_moment_max" in top:
            add(T["dof2_Md"], f(top["driving_moment_max"].get("value")))
        if (d2.get("energy") or {}).get("relative_error") is not None:
            add(T["dof2_energy"], f(d2["energy"]["relative_error"], 2))
    df = results.get("differential")
    if df:
        add(T["diff_u"], f(df.get("u")))
        # the satellite named in the language (the wheels 1, 3 and the carrier H by their symbols)
        member = {"satellite": locales.words(lang).get("diff.satellite", "satellite")} if lang != "en" else {}
        add(T["diff_speeds"], sep.join(f"{member.get(k, k)}: {f(v)}" for k, v in (df.get("speeds_rpm") or {}).items()))
        if df.get("torques"):
            add(T["diff_torques"], sep.join(f"{k}: {f(v)}" for k, v in df["torques"].items()))
    return rows


def print_summary(results: dict, paths: list[Path], lang: str = "en") -> None:
    """The run summary on stdout: the table of the main quantities, the warnings, the
    files written, in ``lang`` (`tmm run --lang`: the words from the catalogue, the
    warnings rendered from results.json's ``messages``). Rich draws it; when the output is
    no terminal and nothing in it needs Rich (no wrapping, no markup, one-cell characters:
    :func:`_plain_summary`), the same text is written without importing Rich (~10 % of a
    JSON run)."""
    T = run_words(lang)
    title = f"tmm: {results.get('task', {}).get('title') or ''}"
    rows = _summary_rows(results, lang)
    from .messages import render_grouped
    warnings = render_grouped(results, lang)           # a change point's warnings one head with items
    words = (T["quantity"], T["value"], T["warning"], T["wrote"])
    plain = _plain_summary(title, rows, warnings, [str(p) for p in paths], words)
    if plain is not None:
        import sys
        sys.stdout.write(plain)
        sys.stdout.flush()
        return
    from rich.markup import escape
    from rich.table import Table

    con = _console()
    # the task's title, the warnings and the paths are printed as written (no markup read in them)
    t = Table(title=escape(title), show_header=True)
    t.add_column(escape(T["quantity"]))
    t.add_column(escape(T["value"]), justify="right")
    for row in rows:
        t.add_row(*(escape(c) for c in row))
    con.print(t)
    for w, items in _with_items(warnings):
        con.print(f"[yellow]{escape(T['warning'])}:[/yellow] {escape(w)}")
        for item in items:
            for line in _item_lines(item, con.width):
                con.print(escape(line))
    for p in paths:
        con.print(f"{escape(T['wrote'])} {escape(str(p))}")


# the characters rich.cells counts as one cell each without its width table (Latin, Greek, Cyrillic
# without its combining marks, the dashes, quotes and ellipsis of general punctuation, the arrows
# and the minus sign U+2212)
_ONE_CELL = re.compile("[\x20-\x7e\xa0-\xac\xae-\u02ff\u0370-\u0482\u048a-\u052f\u2010-\u2027\u2190-\u2199\u2212]*")
_MARKUP_OR_EMOJI = re.compile(r"[\[\]]|:\S*:")      # a Rich markup tag, an emoji code (:name:)


def _with_items(warnings: list) -> list[tuple[str, list[str]]]:
    """The warnings as ``(text, items)``: a plain string has no items."""
    return [(w, []) if isinstance(w, str) else (w[0], list(w[1])) for w in warnings]


def _item_lines(item: str, width: int) -> list[str]:
    """An item under a warning (a change point's: messages.grouped) as printed lines: "  – " and
    the words, wrapped at ``width`` with a hanging indent; a word longer than a line stays whole."""
    import textwrap
    lines = textwrap.wrap(item, width=max(width - 4, 20), break_long_words=False, break_on_hyphens=False)
    return [("  – " if k == 0 else "    ") + line for k, line in enumerate(lines or [""])]


def _plain_summary(title: str, rows: list[tuple[str, str]], warnings: list, paths: list[str],
                   words: tuple[str, str, str, str] = ("quantity", "value", "warning", "wrote")) -> str | None:
    """The text Rich prints for :func:`print_summary` (its Table's default heavy-head box,
    the title centred over it, then one line per warning and per file), or None where
    Rich could print anything else: a terminal or a forced one (styles), a console
    width or encoding Rich reads otherwise (COLUMNS, LINES, not UTF, Windows, Jupyter),
    text Rich would parse (markup, emoji codes), characters of another width, leading or
    trailing blanks, or a line that does not fit (Rich wraps it). tests/test_speed_paths.py
    compares the two."""
    import os
    import sys
    out = sys.stdout
    env = os.environ
    if (out is None or sys.platform == "win32" or "get_ipython" in vars(__import__("builtins"))
            or any(k in env for k in ("COLUMNS", "LINES", "FORCE_COLOR", "TTY_COMPATIBLE"))
            or not (getattr(out, "encoding", None) or "utf-8").lower().startswith("utf")
            or getattr(sys.stdin, "__module__", "").startswith("idlelib")):
        return None
    try:
        if out.isatty():
            return None
    except Exception:  # noqa: BLE001 - Rich's own answer then
        return None
    width = 0
    for fd in (0, 1, 2):                       # Rich's console width: the first terminal's
        try:
            width = os.get_terminal_size(fd)[0]
        except (AttributeError, ValueError, OSError):
            continue
        break
    width = width or 80
    head, value, warning, wrote = words
    warnings = _with_items(warnings)
    texts = [title, *(c for r in rows for c in r), *(t for w, items in warnings for t in (w, *items)), *paths,
             *words]
    if any(not _ONE_CELL.fullmatch(t) or _MARKUP_OR_EMOJI.search(t) or t != t.strip() for t in texts) \
            or not title.strip():
        return None
    w1 = max([len(head), *(len(q) for q, _ in rows)])
    w2 = max([len(value), *(len(v) for _, v in rows)])
    table = w1 + w2 + 7                        # two cells, each padded by a space a side, three rules
    lines = []
    for w, items in warnings:
        wrapped = _wrapped(f"{warning}: {w}", width)
        if wrapped is None:
            return None
        lines.extend(wrapped)
        for item in items:
            lines.extend(_item_lines(item, width))
    for p in paths:
        wrapped = _wrapped(f"{wrote} {p}", width)
        if wrapped is None:
            return None
        lines.extend(wrapped)
    if table >= width or len(title) >= table or any(len(s) >= width for s in lines):
        return None
    left = (table - len(title)) // 2
    text = [" " * left + title + " " * (table - len(title) - left),
            "┏" + "━" * (w1 + 2) + "┳" + "━" * (w2 + 2) + "┓",
            f"┃ {head.ljust(w1)} ┃ {value.rjust(w2)} ┃",
            "┡" + "━" * (w1 + 2) + "╇" + "━" * (w2 + 2) + "┩",
            *(f"│ {q.ljust(w1)} │ {v.rjust(w2)} │" for q, v in rows),
            "└" + "─" * (w1 + 2) + "┴" + "─" * (w2 + 2) + "┘",
            *lines]
    return "\n".join(text) + "\n"


_WORD = re.compile(r"\s*\S+\s*")


def _wrapped(s: str, width: int) -> list[str] | None:
    """``s`` broken into lines as Rich wraps a printed line of one-cell characters (rich._wrap's
    divide_line: a word with its trailing blanks goes on while its letters fit; a wrapped line keeps
    its trailing blanks up to the width), or None where Rich would fold a word longer than the
    width (then Rich prints it)."""
    breaks, off = [], 0
    for m in _WORD.finditer(s):
        word = m.group(0)
        n = len(word.rstrip())
        if n > width:
            return None
        if width - off >= n:
            off += len(word)
        elif off and m.start():
            breaks.append(m.start())
            off = len(word)
    out = []
    for a, b in zip([0, *breaks], [*breaks, len(s)]):
        piece = s[a:b]
        if len(piece) > width:                  # Text.rstrip_end(width): blanks beyond the width dropped
            keep = len(piece.rstrip())
            piece = piece[:max(width, keep)]
        out.append(piece)
    return out


STATUS_STYLE = {"ok": "green", "sign": "magenta", "outside": "red", "missing": "yellow",
                "unknown_path": "yellow", "not_computed": "cyan", "no_answers": "yellow", "invalid": "red",
                "failed": "red", "computed": "blue"}


def shown_status(row: dict) -> str:
    """The status a batch row is shown with: summary.csv's ``ok`` of a variant that ran with
    no answers to check (none were expected) reads ``computed``, not a verdict."""
    st = row["status"]
    return "computed" if st == "ok" and not row.get("answers") else st


def status_words(lang: str) -> dict[str, str]:
    """A row's status ('computed', 'outside', ...) as the terminal and summary.html say it in
    ``lang`` (the warnings catalogue's ``status`` terms; English: the status itself)."""
    if lang == "en":
        return {}
    from .messages import catalogue
    return dict(catalogue(lang)["terms"].get("status", {}))


def row_who(row: dict) -> str:
    """Who a batch row is: the student's name, else the answers file, else the task file's name
    (a variant nobody signed): the terminal's table and summary.html name every row alike."""
    return str(row.get("student") or row.get("answers_file") or Path(str(row.get("file") or "")).name)


def row_names(rows: list[dict]) -> list[str]:
    """Each row's :func:`row_who`, with its file's name after it where two rows would read
    alike (one student's two submissions of a variant, two copies of a starter signed with its
    placeholder name): 'Petrov P. (petrov_v1b.yaml)'."""
    import collections
    who = [row_who(r) for r in rows]
    seen = collections.Counter((w, str(r.get("variant", ""))) for w, r in zip(who, rows))
    paths = [Path(str(r.get("answers_file") or r.get("file") or "")) for r in rows]
    names = collections.Counter(p.name for p in paths)
    out = []
    for w, r, p in zip(who, rows, paths):
        # the file's name, or its folder and name where two folders hold a file of that name
        name = p.name if names[p.name] < 2 or not p.parent.name else f"{p.parent.name}/{p.name}"
        out.append(f"{w} ({name})" if seen[(w, str(r.get("variant", "")))] > 1 and p.name and name != w else w)
    return out


def _short_path(p: str, n: int = 30) -> str:
    """A result path shortened for an 80-column terminal: 'kinematics[1].points.B.v' ->
    'kin[1].B.v'."""
    s = (p.replace("kinematics", "kin").replace("kinetostatics", "kst").replace(".points.", ".")
         .replace(".links.", ".").replace(".reactions.", "."))
    return s if len(s) <= n else "…" + s[-(n - 1):]


def _path_lines(path: str, width: int) -> str:
    """``path`` broken into lines of at most ``width`` characters after its dots and before
    its brackets ('kst[5].balancing_moment' -> 'kst[5].' / 'balancing_moment'), as a
    reader splits it; a single name longer than the line is left for the table to fold."""
    import re
    parts = re.findall(r"[^.\[]*\.|\[[^\]]*\]\.?|[^.\[]+|\[", path)
    if "".join(parts) != path:          # (every character kept: a student's '[1.v' as written)
        return path
    lines = [""]
    for part in parts:
        if lines[-1] and len(lines[-1]) + len(part) > width:
            lines.append("")
        lines[-1] += part
    return "\n".join(lines)


def _tol_shown(text: str, absolute: bool) -> str:
    """A tolerance as the terminal table shows it, in the error column's terms: a relative
    bound in percent ('0.05' -> '5 %'), a plain number against a zero reference as the
    absolute bound it is ('abs 0.05'), a band as its ends ('77.92…162.1'); check.csv keeps the
    tolerance as written."""
    words = text.split()
    if words[0] == "band":                     # an interval the answer must lie in: '77.92…162.1'
        lo, hi = (float(v) for v in words[1].split(".."))
        return f"{lo:.4g}…{hi:.4g}"
    if len(words) == 1:
        v = float(words[0])
        return f"abs {v:g}" if absolute else f"{100 * v:g} %"
    return " ".join(f"{100 * float(v):g} %" if k == "rel" else (f"abs {v}" if k == "abs" else "|x|")
                    for k, v in zip(words[::2], words[1::2]))


def print_check(rows: list[dict], source, lang: str = "en") -> None:
    """The graded answers of one set: path, answer, reference, error, status; fits 80 columns;
    in ``lang`` (`tmm check --lang`: the heads and statuses from the catalogue, the notes
    rendered from their codes, the numbers with the decimal comma)."""
    from rich.table import Table
    from rich.text import Text

    from .check import counts
    from .messages import Message, in_lang
    from .numfmt import localize as typeset
    from .numfmt import plural

    C = _words("check", lang)
    status = status_words(lang)
    con = _console()
    who = " ".join(x for x in (rows[0].get("student"), rows[0].get("group")) if x) if rows else ""
    t = Table(title=Text(f"{C['title']}: {Path(str(source)).name}" + (f" - {who}" if who else "")),
              title_justify="left")
    heads = [C[c] for c in ("quantity", "answer", "reference", "error", "tol", "status")]
    t.add_column(Text(heads[0]), overflow="fold", max_width=26)
    for c in heads[1:-1]:
        t.add_column(Text(c), justify="right", no_wrap=True)
    t.add_column(Text(heads[-1]), no_wrap=True)
    notes, table = [], []
    for r in rows:
        st = r["status"]
        zero_ref = r["reference"] == 0 and r["tolerance"].split()[0] not in ("rel", "abs")
        absolute = r["note"] == "absolute error" or "abs" in r["tolerance"] or zero_ref
        err = "-" if r["error"] is None else (_f(r["error"], 3) if absolute else f"{100 * r['error']:.2f} %")
        style = STATUS_STYLE.get(st, "white")
        if r["note"] and (st in ("unknown_path", "sign", "invalid") or (st == "outside" and isinstance(r["note"], Message))):
            note = in_lang(r["note"], lang)
            notes.append(note if r["note"].startswith(r["path"]) else f"{r['path']}: {note}")
        cells = [_f(r["answer"]), _f(r["reference"]), err, _tol_shown(r["tolerance"], zero_ref or r["note"] == "absolute error")]
        cells = [typeset(c, lang) for c in cells]
        if st == "invalid":                   # what the student wrote, as written ('11.644,6' is no 11,644,6)
            from .limits import printable
            cells[0] = printable(str(r["answer"]))
        table.append((_short_path(r["path"], 26), cells, str(status.get(st, st)), style))
    # the quantity column gets what the others leave of the terminal's width (a cell of
    # padding either side and a rule between columns); a path longer than that is broken
    # after its dots, not folded mid-word
    others = [max([len(h)] + [len(c) for _, cells, _, _ in table for c in cells[k:k + 1]])
              for k, h in enumerate(heads[1:-1])]
    others.append(max([len(heads[-1])] + [len(w) for _, _, w, _ in table]))
    room = max(8, con.width - sum(others) - 3 * len(heads) - 1)
    for path, cells, word, style in table:
        t.add_row(Text(_path_lines(path, room)), *(Text(c) for c in cells), Text(word, style=style))
    con.print(t)
    for n in notes:
        con.print(n, markup=False, highlight=False)
    c = counts(rows)
    n = len(rows) - c.get("unknown_path", 0)          # a misspelt path answers no quantity (as summary.csv)
    if lang == "en":
        con.print(f"{c['ok']} of {n} answers within tolerance"
                  + "".join(f", {v} {k}" for k, v in c.items() if v and k != "ok"), markup=False)
    else:
        con.print(C["count"].format(ok=c["ok"], answers=plural(n, C["answers"], lang))
                  + "".join(f"; {status.get(k, k)}: {v}" for k, v in c.items() if v and k != "ok"), markup=False)


def batch_words(lang: str = "en") -> dict:
    """The terminal's words of `tmm batch` in ``lang`` (the catalogue's summary ``batch`` table)."""
    return _words("batch", lang)


def print_batch(rows: list[dict], out: Path, skipped=(), removed=(), notes=(), lang: str = "en") -> None:
    """The batch table (student or file, variant, status, score, message) as wide as the terminal, in
    ``lang`` (`tmm batch --lang`: the words, the statuses and the coded messages as
    summary.html has them); ``notes``: lines printed as warnings after it (an output the
    batch could not make)."""
    from rich.table import Table
    from rich.text import Text

    from .messages import Message, in_lang, localize
    from .numfmt import plural
    B = batch_words(lang)
    status = status_words(lang)
    con = _console()
    t = Table(title=Text(f"{B['title']}: {plural(len(rows), B['rows'], lang)}"), title_justify="left")
    cells = []
    for r, who in zip(rows, row_names(rows)):
        st = shown_status(r)
        var = str(r.get("variant", ""))
        cells.append((who, var if len(var) <= 6 else var[:5] + "…", str(status.get(st, st)), st,
                      f"{100 * float(r['score']):.0f} %" if r.get("answers") else "-",
                      _cut(_message(r, lang, localize), 200)))
    # the widths given, not left to Rich (which folds a file name mid-word first): the split of
    # the room between the name and the message that prints the fewest lines (a name folded,
    # a message wrapped at its words), names whole on a tie
    def widest(k: int, head: str) -> int:
        return max([len(c[k]) for c in cells] + [len(head)])
    fixed = widest(1, B["var"]) + widest(2, B["status"]) + widest(4, B["score"])
    room = max(con.width - 16 - fixed, 24)             # 16: the borders and padding of 5 columns
    who_w, msg_w = _split_width(room, [c[0] for c in cells], [c[5] for c in cells],
                                len(B["who"].split(" / ")[0]), len(B["message"]))
    t.add_column(Text(B["who"]), overflow="fold", width=who_w)
    t.add_column(Text(B["var"]), no_wrap=True)
    t.add_column(Text(B["status"]), no_wrap=True)
    t.add_column(Text(B["score"]), justify="right", no_wrap=True)
    t.add_column(Text(B["message"]), overflow="fold", width=msg_w)
    for who, var, word, st, score, msg in cells:
        t.add_row(Text(who), Text(var), Text(word, style=STATUS_STYLE.get(st, "")), score, Text(msg))
    con.print(t)
    if skipped:
        con.print(B["skipped"].format(n=len(skipped), names=", ".join(Path(s).name for s in list(skipped)[:5])),
                  markup=False)
    if removed:
        con.print(B["removed"].format(n=len(removed)), markup=False)
    words = run_words(lang)
    for n in notes:          # the advice on angles' tolerance a note, as `tmm check` prints it
        word = words["note" if isinstance(n, Message) and n.code == "answers.angle_relative" else "warning"]
        con.print(f"{word}: {in_lang(n, lang)}", markup=False)
    con.print(B["wrote"].format(csv=out / "summary.csv"), markup=False)


def _split_width(room: int, names: list[str], messages: list[str], name_min: int = 8,
                 message_min: int = 8) -> tuple[int, int]:
    """(name width, message width) summing to at most ``room``: the split that prints the
    rows in the fewest lines, each cell wrapped at its words and a word longer than the
    column folded (textwrap, as Rich wraps); on a tie the wider name column. Neither column
    wider than its longest cell."""
    import textwrap
    want_name = max([len(n) for n in names] + [name_min])
    want_msg = max([len(m) for m in messages] + [message_min])
    if want_name + want_msg <= room:
        return want_name, want_msg
    best = None
    for w in range(min(want_name, room - 8), min(want_name, 8) - 1, -1):     # names of 7 or fewer too
        m = min(room - w, want_msg)
        lines = sum(max(len(textwrap.wrap(n, w, break_on_hyphens=False)) or 1,
                        len(textwrap.wrap(t, m, break_on_hyphens=False)) or 1)
                    for n, t in zip(names, messages))
        if best is None or lines < best[0]:
            best = (lines, w, m)
    return (best[1], best[2]) if best else (max(room // 2, 8), max(room - room // 2, 8))


def _cut(text: str, n: int) -> str:
    """``text`` shortened to ``n`` characters, its end marked by an ellipsis where cut (summary.csv
    and summary.html have it whole; the table once cut English mid-word without a mark)."""
    if len(text) <= n:
        return text
    return text[:n - 1] + "…"


I18N = locales.table("summary", "text")
COLOURS = {"ok": "#c8e6c9", "outside": "#ffcdd2", "sign": "#e1bee7", "missing": "#fff9c4",
           "unknown_path": "#ffe0b2", "not_computed": "#e0e0e0", "no_answers": "#cfd8dc", "invalid": "#ef9a9a",
           "failed": "#ef9a9a", "computed": "#e3f2fd"}


def flag_text(flag: str, lang: str = "en", same: dict | None = None) -> str:
    """A summary.csv flag as summary.html says it in ``lang``: 'same_as=Ivanov' -> "same answers as
    Ivanov" (with ``same`` {who: (answers agreeing, of them wrong)}: how many agree and whether
    they are the same mistakes or only the same right results), 'key_of=17' -> "within tolerance of
    variant 17's key", 'repeat=a.yaml|b.yaml' -> "another submission: a.yaml, b.yaml"; a flag of
    another kind as written."""
    from .messages import Message, in_lang
    kind, _, value = flag.partition("=")
    if kind == "same_as":
        text = in_lang(Message("batch.flag_same_as", who=value), lang)
        if same and value in same:
            n, wrong = same[value]
            why = (Message("batch.same_wrong", n=n, wrong=wrong) if wrong
                   else Message("batch.same_right", n=n))
            text += f" ({in_lang(why, lang)})"
        return text
    if kind == "key_of":
        return in_lang(Message("batch.flag_key_of", variant=value), lang)
    if kind == "repeat":
        return in_lang(Message("batch.flag_repeat", files=value.split("|")), lang)
    return flag


def summary_html(rows: list[dict], paths: list[str], source: str, lang: str = "en",
                 written: set[str] | None = None) -> str:
    """summary.html: students x quantities, a colour per status, the score, links to each
    variant's report, check file and feedback. Every user string is escaped. ``written``:
    the files the batch wrote (relative to the page's folder): only those are linked (an
    invalid variant has no report, a json-only batch none at all); None links every one."""
    import html
    from urllib.parse import quote

    from .messages import catalogue, localize

    T = dict(I18N.get(lang, I18N["en"]))
    if lang != "en":                     # the status words: the catalogue's, as in the messages
        T.update(status_words(lang))
    from .limits import printable
    words = catalogue(lang)["terms"]["grading"]
    e = lambda x: html.escape(printable(str(x)), quote=True)  # noqa: E731  (no control character raw)
    # a path nobody's results have (a typo) gets no column: the row's message names it
    paths = [p for p in paths if any(r.get(p) not in ("", None, "unknown_path") for r in rows)]
    has_grade = any("grade" in r for r in rows)
    head = "".join(f"<th>{e(T[c])}</th>" for c in ("who", "group", "variant", "status", "score"))
    head += f"<th>{e(words['grade'])}</th>" if has_grade else ""
    head += f"<th>{e(words['flags'])}</th>"
    head += "".join(f'<th class="q" title="{e(p)}"><span>{e(p)}</span></th>' for p in paths)
    head += f"<th>{e(T['files'])}</th><th>{e(T['message'])}</th>"
    body = []
    for r, who in zip(rows, row_names(rows)):
        st = shown_status(r)
        score = f"{100 * float(r['score']):.0f} %" if r.get("answers") else "–"
        cells = [e(who), e(r.get("group", "")), e(r.get("variant", "")),
                 f'<span class="st">{e(T.get(st, st))}</span>', e(score)]
        tds = "".join(f"<td>{c}</td>" for c in cells[:3])
        tds += f'<td style="background:{COLOURS.get(st, "#fff")}">{cells[3]}</td><td>{cells[4]}</td>'
        if has_grade:
            tds += f"<td>{e(r.get('grade', ''))}</td>"
        flags = [f for f in str(r.get("flags") or "").split(";") if f]
        # each in words, its summary.csv form in the title (what a script or a search of the page finds)
        tds += "<td class='fl'>" + "<br>".join(f'<span title="{e(f)}">{e(flag_text(f, lang, r.get("_same")))}</span>'
                                             for f in flags) + "</td>"
        for p in paths:
            ps = r.get(p, "")
            tds += (f'<td class="m" style="background:{COLOURS.get(ps, "#fff")}" title="{e(p)}: {e(T.get(ps, ps))}">'
                    f'{e(_mark(ps))}</td>')
        links = []
        folder = r.get("folder") or ""
        if folder:
            for name, label in (("report.html", "report"), ("check.csv", "check")):
                if written is None or f"{folder}/{name}" in written:
                    links.append(f'<a href="{e(quote(folder))}/{name}">{e(T[label])}</a>')
        for fb in r.get("feedback", []) or []:
            if fb.endswith(".html") and (written is None or fb in written):
                links.append(f'<a href="{e(quote(fb))}">{e(T["feedback"])}</a>')
        tds += f"<td>{' '.join(links)}</td><td class='msg'>{e(_message(r, lang, localize))}</td>"
        body.append(f"<tr>{tds}</tr>")
    legend = " ".join(f'<span class="lg" style="background:{c}">{e(_mark(s))} {e(T.get(s, s))}</span>'
                      for s, c in COLOURS.items())
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'>"
            f"<title>{e(T['title'])}</title>"
            "<style>body{font-family:sans-serif;margin:1em}table{border-collapse:collapse;font-size:13px}"
            "td,th{border:1px solid #999;padding:3px 6px;text-align:left}th.q{vertical-align:bottom;"
            "font-weight:normal;font-size:11px}th.q span{writing-mode:vertical-rl;transform:rotate(180deg);"
            "white-space:nowrap;display:inline-block}td.m{text-align:center}td.fl{font-size:11px;color:#b71c1c}"
            ".lg{padding:2px 6px;margin:0 4px 4px 0;border:1px solid #999;display:inline-block}.msg{font-size:11px;max-width:30em;white-space:pre-line}</style>"
            f"</head><body><h1>{e(T['title'])}: {e(source)}</h1><p>{e(T['rows'])}: {len(rows)}</p>"
            f"<p>{e(T['legend'])}: {legend}</p>"
            f"<table><tr>{head}</tr>{''.join(body)}</table></body></html>\n")


def _message(row: dict, lang: str, localize) -> str:
    """A row's message in ``lang``: its coded parts through the catalogue (an error's
    text, uncoded, stays as written)."""
    parts = row.get("message_parts")
    if parts is None or lang == "en":
        return str(row.get("message", ""))
    return "".join(localize(p.to_dict(), lang) if hasattr(p, "to_dict") else str(p) for p in parts)


def _mark(status: str) -> str:
    return {"ok": "✓", "outside": "✗", "sign": "±", "missing": "–", "unknown_path": "?",
            "not_computed": "·", "no_answers": "∅", "invalid": "!", "failed": "!", "computed": "○"}.get(status, "")
