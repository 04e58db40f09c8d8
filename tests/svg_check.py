"""An independent checker of the SVG tmm writes: the document is parsed as XML and
every presentation attribute (and every declaration of a `style` attribute or a
<style> element) is read with the SVG 1.1 / CSS 2 grammar of its value: colours
(#rgb, #rrggbb, rgb(...), the SVG 1.1 colour keywords), paints, lengths, numbers,
opacity, dash arrays, keywords, transforms, path data.  Anything a browser would
drop (``stroke="k"``, ``fill="0.35"``, ``stroke-width="1e-05"`` in CSS, ...) is
reported.  Used by test_svg_valid.py; the grammar is written out here, not taken
from the writers under test."""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"

# SVG 1.1 recognized colour keyword names (SVG 1.1, section 4.4), all 147
COLOR_KEYWORDS = frozenset("""
aliceblue antiquewhite aqua aquamarine azure beige bisque black blanchedalmond blue
blueviolet brown burlywood cadetblue chartreuse chocolate coral cornflowerblue cornsilk
crimson cyan darkblue darkcyan darkgoldenrod darkgray darkgreen darkgrey darkkhaki
darkmagenta darkolivegreen darkorange darkorchid darkred darksalmon darkseagreen
darkslateblue darkslategray darkslategrey darkturquoise darkviolet deeppink deepskyblue
dimgray dimgrey dodgerblue firebrick floralwhite forestgreen fuchsia gainsboro ghostwhite
gold goldenrod gray grey green greenyellow honeydew hotpink indianred indigo ivory khaki
lavender lavenderblush lawngreen lemonchiffon lightblue lightcoral lightcyan
lightgoldenrodyellow lightgray lightgreen lightgrey lightpink lightsalmon lightseagreen
lightskyblue lightslategray lightslategrey lightsteelblue lightyellow lime limegreen linen
magenta maroon mediumaquamarine mediumblue mediumorchid mediumpurple mediumseagreen
mediumslateblue mediumspringgreen mediumturquoise mediumvioletred midnightblue mintcream
mistyrose moccasin navajowhite navy oldlace olive olivedrab orange orangered orchid
palegoldenrod palegreen paleturquoise palevioletred papayawhip peachpuff peru pink plum
powderblue purple red rosybrown royalblue saddlebrown salmon seagreen seashell sienna
silver skyblue slateblue slategray slategrey snow springgreen steelblue tan teal thistle
tomato turquoise violet wheat white whitesmoke yellow yellowgreen
""".split())

# numbers: SVG 1.1 attribute syntax allows an exponent, CSS 2 property values do not
_NUM_ATTR = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
_NUM_CSS = r"[+-]?(?:\d+|\d*\.\d+)"
_UNITS = r"(?:em|ex|px|in|cm|mm|pt|pc|%)?"
_INT = r"\d{1,3}"
_PCT = r"(?:\d{1,3}(?:\.\d+)?)%"
_COLOR = re.compile(
    r"#[0-9a-fA-F]{3}|#[0-9a-fA-F]{6}"
    rf"|rgb\(\s*{_INT}\s*,\s*{_INT}\s*,\s*{_INT}\s*\)"
    rf"|rgb\(\s*{_PCT}\s*,\s*{_PCT}\s*,\s*{_PCT}\s*\)")
_URL = re.compile(r"url\(\s*#[A-Za-z_][\w.:-]*\s*\)")


def is_color(v: str) -> bool:
    v = v.strip()
    if _COLOR.fullmatch(v):
        if v.startswith("rgb(") and "%" not in v:
            return all(0 <= int(x) <= 255 for x in re.findall(r"\d+", v))
        return True
    return v.lower() in COLOR_KEYWORDS or v == "currentColor"


def is_paint(v: str) -> bool:
    v = v.strip()
    if v in ("none", "currentColor", "inherit") or is_color(v):
        return True
    m = _URL.match(v)
    if m:
        rest = v[m.end():].strip()
        return rest == "" or rest == "none" or is_color(rest)
    return False


def _number_re(css: bool) -> str:
    return _NUM_CSS if css else _NUM_ATTR


def is_number(v: str, css=False) -> bool:
    return re.fullmatch(_number_re(css), v.strip()) is not None


def is_length(v: str, css=False, nonneg=False) -> bool:
    v = v.strip()
    if not re.fullmatch(_number_re(css) + _UNITS, v):
        return False
    return not (nonneg and v.startswith("-"))


def is_opacity(v: str, css=False) -> bool:
    return is_number(v, css) and 0.0 <= float(v) <= 1.0


def is_dasharray(v: str, css=False) -> bool:
    v = v.strip()
    if v in ("none", "inherit"):
        return True
    parts = [p for p in re.split(r"[\s,]+", v) if p]
    return bool(parts) and all(is_length(p, css, nonneg=True) for p in parts)


def is_viewbox(v: str) -> bool:
    parts = [p for p in re.split(r"[\s,]+", v.strip()) if p]
    return len(parts) == 4 and all(is_number(p) for p in parts) and float(parts[2]) > 0 \
        and float(parts[3]) > 0


_TF_ARGS = {"matrix": (6,), "translate": (1, 2), "scale": (1, 2), "rotate": (1, 3),
            "skewX": (1,), "skewY": (1,)}


def is_transform(v: str) -> bool:
    pos, v = 0, v.strip()
    found = False
    for m in re.finditer(r"\s*,?\s*(\w+)\s*\(([^)]*)\)", v):
        if m.start() != pos:
            return False
        pos = m.end()
        name, args = m.group(1), [a for a in re.split(r"[\s,]+", m.group(2).strip()) if a]
        if name not in _TF_ARGS or len(args) not in _TF_ARGS[name] or not all(is_number(a) for a in args):
            return False
        found = True
    return found and v[pos:].strip() == ""


_PATH_ARGS = {"m": 2, "l": 2, "h": 1, "v": 1, "c": 6, "s": 4, "q": 4, "t": 2, "a": 7, "z": 0}


def is_path_data(v: str) -> bool:
    toks = re.findall(rf"[MmLlHhVvCcSsQqTtAaZz]|{_NUM_ATTR}|[\s,]+|.", v)
    cmd, nums, first = None, 0, True
    for t in toks:
        if re.fullmatch(r"[\s,]+", t):
            continue
        if re.fullmatch(r"[MmLlHhVvCcSsQqTtAaZz]", t):
            if cmd is not None and _PATH_ARGS[cmd.lower()] and (nums == 0 or nums % _PATH_ARGS[cmd.lower()]):
                return False
            if first and t not in "Mm":
                return False
            cmd, nums, first = t, 0, False
        elif re.fullmatch(_NUM_ATTR, t):
            if cmd is None or cmd in "Zz":
                return False
            nums += 1
        else:
            return False
    return cmd is not None and (_PATH_ARGS[cmd.lower()] == 0 or (nums and nums % _PATH_ARGS[cmd.lower()] == 0))


def is_points(v: str) -> bool:
    parts = [p for p in re.split(r"[\s,]+", v.strip()) if p]
    return len(parts) % 2 == 0 and all(is_number(p) for p in parts)


def _kw(*words):
    allowed = set(words) | {"inherit"}
    return lambda v, css=False: v.strip() in allowed


def _font_family(v: str, css=False) -> bool:
    return all(re.fullmatch(r"'[^']+'|\"[^\"]+\"|[A-Za-z][\w -]*", f.strip()) for f in v.split(","))


def _font_size(v, css=False):
    return is_length(v, css, nonneg=True) or v.strip() in ("small", "medium", "large", "x-small",
                                                              "x-large", "smaller", "larger")


def _clip(v, css=False):
    return v.strip() in ("none", "inherit") or _URL.fullmatch(v.strip()) is not None


# presentation properties: usable as attributes and in style declarations
PROPERTIES = {
    "fill": lambda v, css=False: is_paint(v),
    "stroke": lambda v, css=False: is_paint(v),
    "color": lambda v, css=False: is_color(v),
    "stop-color": lambda v, css=False: is_color(v),
    "flood-color": lambda v, css=False: is_color(v),
    "stroke-width": lambda v, css=False: is_length(v, css, nonneg=True),
    "stroke-miterlimit": lambda v, css=False: is_number(v, css) and float(v) >= 1,
    "stroke-dasharray": is_dasharray,
    "stroke-dashoffset": lambda v, css=False: is_length(v, css),
    "stroke-linejoin": _kw("miter", "round", "bevel"),
    "stroke-linecap": _kw("butt", "round", "square"),
    "fill-rule": _kw("nonzero", "evenodd"),
    "clip-rule": _kw("nonzero", "evenodd"),
    "opacity": is_opacity, "fill-opacity": is_opacity, "stroke-opacity": is_opacity,
    "stop-opacity": is_opacity,
    "font-size": _font_size,
    "font-family": _font_family,
    "font-style": _kw("normal", "italic", "oblique"),
    "font-weight": _kw("normal", "bold", "bolder", "lighter", "100", "200", "300", "400", "500",
                       "600", "700", "800", "900"),
    "text-anchor": _kw("start", "middle", "end"),
    "dominant-baseline": _kw("auto", "middle", "central", "hanging", "alphabetic", "text-before-edge",
                             "text-after-edge", "mathematical", "ideographic"),
    "clip-path": _clip,
    "visibility": _kw("visible", "hidden", "collapse"),
    "display": _kw("inline", "block", "none"),
}

COORDS = {"x", "y", "dx", "dy", "cx", "cy", "x1", "y1", "x2", "y2"}
NONNEG_LENGTHS = {"width", "height", "r", "rx", "ry"}
OTHER_ATTRS = {
    "d": is_path_data, "points": is_points, "viewBox": is_viewbox, "transform": is_transform,
    "patternTransform": is_transform, "gradientTransform": is_transform,
    "id": lambda v: re.fullmatch(r"[A-Za-z_][\w.:-]*", v) is not None,
    "class": lambda v: re.fullmatch(r"[\w -]+", v) is not None,
    "version": lambda v: v == "1.1",
    "patternUnits": lambda v: v in ("userSpaceOnUse", "objectBoundingBox"),
    "clipPathUnits": lambda v: v in ("userSpaceOnUse", "objectBoundingBox"),
    "preserveAspectRatio": lambda v: re.fullmatch(r"none|x(Min|Mid|Max)Y(Min|Mid|Max)( meet| slice)?", v)
    is not None,
    "type": lambda v: v == "text/css",
    "style": None,   # checked declaration by declaration
}
ELEMENTS = {"svg", "g", "defs", "path", "text", "tspan", "use", "circle", "ellipse", "rect", "line",
            "polyline", "polygon", "clipPath", "pattern", "style", "metadata", "title", "desc",
            "linearGradient", "radialGradient", "stop", "symbol", "image", "marker", "mask"}


def _declarations(text: str, where: str, problems: list[str]) -> None:
    for decl in text.split(";"):
        if not decl.strip():
            continue
        if ":" not in decl:
            problems.append(f"{where}: not a declaration: {decl.strip()!r}")
            continue
        prop, val = (s.strip() for s in decl.split(":", 1))
        check = PROPERTIES.get(prop)
        if check is None:
            problems.append(f"{where}: unknown property {prop!r}")
        elif not check(val, css=True):
            problems.append(f"{where}: invalid {prop}: {val!r}")


def problems(svg_text: str, name: str = "svg") -> list[str]:
    """Every value in the SVG document that SVG 1.1 / CSS 2 does not allow."""
    out: list[str] = []
    root = ET.fromstring(svg_text.encode("utf-8") if isinstance(svg_text, str) else svg_text)
    if root.tag != f"{{{SVG_NS}}}svg":
        return [f"{name}: root element is {root.tag}, not an SVG <svg>"]
    for el in root.iter():
        tag = el.tag
        if tag.startswith(f"{{{SVG_NS}}}"):
            local = tag.split("}", 1)[1]
            if local not in ELEMENTS:
                out.append(f"{name}: unknown element <{local}>")
        else:
            continue        # metadata (RDF, Dublin Core) is outside the SVG namespace
        where = f"{name} <{local}{' id=' + el.get('id') if el.get('id') else ''}>"
        if local == "style" and el.text:
            for rule in re.finditer(r"([^{}]+)\{([^{}]*)\}", el.text):
                _declarations(rule.group(2), f"{where} rule {rule.group(1).strip()}", out)
        for key, val in el.attrib.items():
            if key.startswith("{"):
                if key == f"{{{XLINK_NS}}}href" and re.fullmatch(r"#[A-Za-z_][\w.:-]*", val):
                    continue
                if key.startswith(f"{{{XLINK_NS}}}") or key.startswith("{http://www.w3.org/XML/1998"):
                    out.append(f"{where}: invalid {key}={val!r}")
                continue
            if key == "style":
                _declarations(val, where, out)
            elif key in PROPERTIES:
                if not PROPERTIES[key](val):
                    out.append(f"{where}: invalid {key}={val!r}")
            elif key in COORDS:
                if not is_length(val):
                    out.append(f"{where}: invalid {key}={val!r}")
            elif key in NONNEG_LENGTHS:
                if not is_length(val, nonneg=True):
                    out.append(f"{where}: invalid {key}={val!r}")
            elif key in OTHER_ATTRS:
                check = OTHER_ATTRS[key]
                if check is not None and not check(val):
                    out.append(f"{where}: invalid {key}={val!r}")
            else:
                out.append(f"{where}: unknown attribute {key}={val!r}")
    return out
