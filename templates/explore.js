(function () {
  "use strict";
  var D = JSON.parse(document.getElementById("ex-data").textContent);
  var L = JSON.parse(document.getElementById("ex-labels").textContent);
  var NS = "http://www.w3.org/2000/svg";
  var n = D.turn.length, step = D.step, SNAP = 3.0;
  var slider = document.getElementById("ex-angle");
  var play = document.getElementById("ex-play");
  var out = document.getElementById("ex-readout");
  var table = document.getElementById("ex-table");
  var names = Object.keys(D.points);
  var movers = names.filter(function (p) { return D.ground.indexOf(p) < 0; });
  slider.max = String(n - 1);
  var marks = D.positions.map(function (m) { return {index: m.index, k: Math.round(m.turn / step) % n}; });
  var dl = document.getElementById("ex-marks");
  marks.forEach(function (m) { var o = document.createElement("option"); o.value = m.k; o.label = String(m.index); dl.appendChild(o); });

  function fin(v) { return v !== null && v !== undefined && isFinite(v); }
  // round-off of an exact zero (|v| < 1e-10) is shown as 0, as in the report's tables
  // a number to 4 significant digits as the report's tables write it: with the decimal comma,
  // a power of ten (1,2·10⁴) and the minus sign (−0,5) in ru and uk (L.decimal), the point,
  // 1.2e+4 and the hyphen-minus in English
  var SUP = {"0": "⁰", "1": "¹", "2": "²", "3": "³", "4": "⁴", "5": "⁵", "6": "⁶", "7": "⁷", "8": "⁸", "9": "⁹", "-": "⁻"};
  function dec(s) {
    if (L.decimal !== ",") return s;
    var m = s.match(/^(-?[\d.]+)e\+?(-?)(\d+)$/);
    if (m) s = m[1] + "·10" + (m[2] + m[3]).split("").map(function (c) { return SUP[c]; }).join("");
    return s.replace(".", ",").replace(/^-/, "\u2212");
  }
  function num(v) {
    if (!fin(v)) return "—";
    if (Math.abs(v) < 1e-10) return "0";
    return dec(Number(v).toPrecision(4).replace(/^(-?\d+\.\d*?)0+e/, "$1e"));
  }
  function extent(xs, ys) {
    var x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (var i = 0; i < xs.length; i++) { if (!fin(xs[i]) || !fin(ys[i])) continue;
      x0 = Math.min(x0, xs[i]); x1 = Math.max(x1, xs[i]); y0 = Math.min(y0, ys[i]); y1 = Math.max(y1, ys[i]); }
    return [x0, x1, y0, y1];
  }
  // fixed scales over the whole turn, so the drawing moves and does not rescale
  var mx = [], my = [];
  names.forEach(function (p) { mx = mx.concat(D.points[p].x); my = my.concat(D.points[p].y); });
  var ME = extent(mx, my);
  function vmax(kx, ky) { var m = 0; movers.forEach(function (p) { var a = D.points[p][kx], b = D.points[p][ky];
    for (var i = 0; i < n; i++) if (fin(a[i]) && fin(b[i])) m = Math.max(m, Math.hypot(a[i], b[i])); }); return m || 1; }
  var VM = vmax("vx", "vy"), AM = vmax("ax", "ay");
  // the instant centres P_ij (the results' instant_centres at the grid): drawn when the box is
  // ticked, those within centre_room of the mechanism's size beyond its extent over the turn
  // (the drawing's fixed scale then takes them in); the others, and those at infinity, listed
  var C = D.centres || {}, CK = Object.keys(C), CB = document.getElementById("ex-centres");
  var CN = document.getElementById("ex-centres-note"), CCOL = L.centre_color || "#b03060";
  var room = (L.centre_room || 0.5) * Math.max(ME[1] - ME[0], ME[3] - ME[2]);
  function near(x, y) { return x >= ME[0] - room && x <= ME[1] + room && y >= ME[2] - room && y <= ME[3] + room; }
  CK.forEach(function (key) { var c = C[key];      // two links joined by a pin: the pin
    if (c.pin) { c.x = D.points[c.pin].x; c.y = D.points[c.pin].y; } });
  var CE = ME.slice();
  CK.forEach(function (key) { var c = C[key];
    for (var i = 0; i < n; i++) if (fin(c.x[i]) && fin(c.y[i]) && near(c.x[i], c.y[i])) {
      CE[0] = Math.min(CE[0], c.x[i]); CE[1] = Math.max(CE[1], c.x[i]);
      CE[2] = Math.min(CE[2], c.y[i]); CE[3] = Math.max(CE[3], c.y[i]); } });
  function centresOn() { return !!(CB && CB.checked && CK.length); }

  function el(svg, tag, attrs, text) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    svg.appendChild(e); return e;
  }
  // the drawings are made here (none in the HTML source: the report's figure tools see only its own figures)
  function canvas(id) {
    var box = document.getElementById(id), svg = box.firstChild;
    if (!svg) {
      svg = document.createElementNS(NS, "svg");
      svg.setAttribute("width", box.dataset.w); svg.setAttribute("height", box.dataset.h);
      box.appendChild(svg);
    }
    while (svg.firstChild) svg.removeChild(svg.firstChild);
    svg.boxes = [];
    return svg;
  }
  // a label's box (the report's measure: 0.6 x the font size a character, the size high) and
  // where it goes: at (x, y) if it overlaps no label already placed, else the nearest free
  // place round it, inside the drawing
  function boxAt(x, y, w, h, anchor) {
    var x0 = anchor === "middle" ? x - w / 2 : x;
    return [x0, y - 0.8 * h, x0 + w, y + 0.2 * h];
  }
  function overlaps(a, b) { return Math.min(a[2], b[2]) - Math.max(a[0], b[0]) > 0 && Math.min(a[3], b[3]) - Math.max(a[1], b[1]) > 0; }
  function spot(svg, x, y, w, h, anchor) {
    var W = +svg.getAttribute("width"), H = +svg.getAttribute("height");
    var at;
    function inside(px, py) {       // moved into the drawing where it would leave it
      var b = boxAt(px, py, w, h, anchor);
      px += Math.max(0, -b[0]) - Math.max(0, b[2] - W);
      py += Math.max(0, -b[1]) - Math.max(0, b[3] - H);
      return [px, py];
    }
    function free(px, py) {
      at = inside(px, py);
      var b = boxAt(at[0], at[1], w, h, anchor);
      for (var i = 0; i < svg.boxes.length; i++) if (overlaps(b, svg.boxes[i])) return null;
      return b;
    }
    var best = free(x, y);
    for (var r = 4; !best && r <= 60; r += 4) {
      for (var i = 0; i < 16 && !best; i++) {
        var t = Math.PI * i / 8;
        best = free(x + r * Math.cos(t), y - r * Math.sin(t));
      }
    }
    if (!best) { at = inside(x, y); best = boxAt(at[0], at[1], w, h, anchor); }
    svg.boxes.push(best);
    return at;
  }
  // a text placed clear of the others: attrs x, y the wanted place; sub a subscript
  function tag(svg, attrs, text, sub) {
    var fs = +attrs["font-size"], w = 0.6 * fs * text.length + (sub ? 0.6 * 8 * sub.length : 0);
    var at = spot(svg, attrs.x, attrs.y, w, fs + (sub ? 3 : 0), attrs["text-anchor"] || "start");
    attrs.x = at[0]; attrs.y = at[1];
    return el(svg, "text", attrs, text);
  }
  function mapper(svg, x0, x1, y0, y1) {
    var W = +svg.getAttribute("width"), H = +svg.getAttribute("height"), pad = 22;
    var s = Math.min((W - 2 * pad) / Math.max(x1 - x0, 1e-12), (H - 2 * pad) / Math.max(y1 - y0, 1e-12));
    var cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    return function (x, y) { return [W / 2 + (x - cx) * s, H / 2 - (y - cy) * s]; };
  }
  function drawMech(k) {
    var svg = canvas("ex-mech"), on = centresOn(), E = on ? CE : ME;
    var f = mapper(svg, E[0], E[1], E[2], E[3]);
    function P(p) { return f(D.points[p].x[k], D.points[p].y[k]); }
    D.shapes.forEach(function (sh) {
      if (sh.kind === "slider") {
        var c = P(sh.origin);
        el(svg, "rect", {x: c[0] - 9, y: c[1] - 6, width: 18, height: 12, fill: "#fff", stroke: "#000", "stroke-width": 1.5});
      } else if (sh.points.length >= 2) {
        var pts = sh.points.map(function (p) { return P(p).join(","); });
        if (sh.points.length > 2) pts.push(pts[0]);
        el(svg, "polyline", {points: pts.join(" "), fill: sh.points.length > 2 ? "#eef" : "none", stroke: "#000", "stroke-width": 2});
      }
    });
    D.ground.forEach(function (g) { var c = P(g);
      el(svg, "path", {d: "M" + c[0] + "," + c[1] + " l-7,11 h14 z", fill: "none", stroke: "#000"}); });
    names.forEach(function (p) { if (p.charAt(0) === "S") return; var c = P(p);
      el(svg, "circle", {cx: c[0], cy: c[1], r: 3, fill: "#fff", stroke: "#000", "data-point": p});
      tag(svg, {x: c[0] + 5, y: c[1] - 5, "font-size": 11}, p); });
    if (CN) while (CN.firstChild) CN.removeChild(CN.firstChild);
    if (!on) return;
    var inf = [], far = [];
    CK.forEach(function (key) {
      var c = C[key], x = c.x[k], y = c.y[k], sub = key.replace("-", "");
      if (!fin(x) || !fin(y)) { inf.push(sub); return; }
      if (!near(x, y)) { far.push([sub, x, y]); return; }
      var q = f(x, y);
      el(svg, "circle", {cx: q[0], cy: q[1], r: 4, fill: "none", stroke: CCOL, "stroke-width": 1.2, "data-centre": key});
      label(svg, q[0] + 9, q[1] - 6, "P", sub, CCOL);
    });
    function name(sub) { var i = document.createElement("i"); i.textContent = "P"; CN.appendChild(i);
      var s = document.createElement("sub"); s.textContent = sub; CN.appendChild(s); }
    function text(t) { var s = document.createElement("span"); s.textContent = t; CN.appendChild(s); }
    if (!CN) return;
    if (inf.length) { text(L["worked.centres_inf"] + " ");
      inf.forEach(function (sub, i) { if (i) text(", "); name(sub); }); text(". "); }
    if (far.length) { text(L["worked.centres_far"] + " ");
      far.forEach(function (t, i) { if (i) text("; "); name(t[0]); text(" (" + num(t[1]) + "; " + num(t[2]) + ")"); }); text("."); }
  }
  function drawPlan(id, kx, ky, M, k, letter) {
    var svg = canvas(id);
    // the scale of this position's plan (as on the sheet), at least 1/20 of the largest over the turn
    var m = 0;
    movers.forEach(function (p) { var a = D.points[p][kx][k], b = D.points[p][ky][k];
      if (fin(a) && fin(b)) m = Math.max(m, Math.hypot(a, b)); });
    m = Math.max(m, M / 20);
    var f = mapper(svg, -m, m, -m, m);
    var o = f(0, 0);
    el(svg, "circle", {cx: o[0], cy: o[1], r: 2.5, fill: "#000"});
    tag(svg, {x: o[0] - 12, y: o[1] + 12, "font-size": 11}, letter);
    var ends = [];                 // coincident ends share one label ("a3, b3"), as in the report
    movers.forEach(function (p) {
      var a = D.points[p][kx][k], b = D.points[p][ky][k];
      if (!fin(a) || !fin(b)) return;
      var e = f(a, b), grey = p.charAt(0) === "S";
      el(svg, "line", {x1: o[0], y1: o[1], x2: e[0], y2: e[1], stroke: grey ? "#888" : "#000", "stroke-width": grey ? 1 : 1.6});
      el(svg, "circle", {cx: e[0], cy: e[1], r: 1.8, fill: grey ? "#888" : "#000"});
      var same = ends.filter(function (q) { return Math.hypot(q.e[0] - e[0], q.e[1] - e[1]) < 2; })[0];
      if (same) { same.names.push(p.toLowerCase()); same.grey = same.grey && grey; }
      else ends.push({e: e, names: [p.toLowerCase()], grey: grey});
    });
    ends.forEach(function (q) {
      tag(svg, {x: q.e[0] + 3, y: q.e[1] - 3, "font-size": 10, fill: q.grey ? "#666" : "#000"}, q.names.join(", "));
    });
  }
  // a heading from the catalogue in the course's notation: M_b written as M with b lowered, as
  // the report writes it (a letter, "_", then letters and digits or {a braced group})
  function heading(cell, text) {
    var re = /(\p{L})_(\{[^{}]+\}|[\p{L}\p{N}]+)/gu, at = 0, m;
    function put(tag, t) { if (t) { var e = document.createElement(tag); e.textContent = t; cell.appendChild(e); } }
    while ((m = re.exec(text)) !== null) {
      put("span", text.slice(at, m.index + m[1].length));
      put("sub", m[2].replace(/^\{|\}$/g, ""));
      at = re.lastIndex;
    }
    put("span", text.slice(at));
  }
  function row(cells, th) {
    var tr = document.createElement("tr");
    cells.forEach(function (c) {
      var td = document.createElement(th ? "th" : "td");
      if (th) heading(td, c); else td.textContent = c;
      tr.appendChild(td);
    });
    table.appendChild(tr); return tr;
  }
  function fill(k) {
    while (table.firstChild) table.removeChild(table.firstChild);
    row([L["explore.point"], L["explore.v"], L["explore.a"]], true);
    movers.forEach(function (p) {
      var q = D.points[p];
      var v = fin(q.vx[k]) && fin(q.vy[k]) ? Math.hypot(q.vx[k], q.vy[k]) : null;
      var a = fin(q.ax[k]) && fin(q.ay[k]) ? Math.hypot(q.ax[k], q.ay[k]) : null;
      row([p, num(v), num(a)]).dataset.point = p;
    });
    row([L["explore.link"], L["explore.w"], L["explore.e"]], true);
    Object.keys(D.links).forEach(function (l) {
      row([l, num(D.links[l].omega[k]), num(D.links[l].epsilon[k])]).dataset.link = l;
    });
  }
  // ---- forces (kinetostatics): the force polygon of each group, Zhukovsky's lever, reactions, M_b
  var FE = document.getElementById("ex-forces");
  var F = FE ? JSON.parse(FE.textContent) : null, COL = F ? F.colors : {};
  function label(svg, x, y, sym, sub, col) {
    var t = tag(svg, {x: x, y: y, "font-size": 11, "font-style": "italic", fill: col || "#000",
      "text-anchor": "middle"}, sym, sub);
    if (sub) { var s = document.createElementNS(NS, "tspan"); s.setAttribute("dy", "3");
      s.setAttribute("font-size", "8"); s.textContent = sub; t.appendChild(s); }
    return t;
  }
  function arrow(svg, a, b, col, w) {
    el(svg, "line", {x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: col, "stroke-width": w || 1.4});
    var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.hypot(dx, dy);
    if (L < 1e-9) return;
    var ux = dx / L, uy = dy / L, h = Math.min(7, L * 0.45);
    el(svg, "path", {d: "M" + b[0] + "," + b[1] + " L" + (b[0] - h * ux - h * 0.35 * uy) + "," + (b[1] - h * uy + h * 0.35 * ux) +
      " L" + (b[0] - h * ux + h * 0.35 * uy) + "," + (b[1] - h * uy - h * 0.35 * ux) + " z", fill: col});
  }
  function drawPolygon(gi, k) {
    var g = F.groups[gi], svg = canvas("ex-poly-" + gi);
    var vs = g.vecs.filter(function (v) { return fin(v.x[k]) && fin(v.y[k]); });
    var Fm = 0; vs.forEach(function (v) { Fm = Math.max(Fm, Math.hypot(v.x[k], v.y[k])); });
    vs = vs.filter(function (v) { return Math.hypot(v.x[k], v.y[k]) > 1e-9 * Fm; });
    if (!vs.length) return;
    var tips = [[0, 0]];
    vs.forEach(function (v) { var t = tips[tips.length - 1]; tips.push([t[0] + v.x[k], t[1] + v.y[k]]); });
    var e = extent(tips.map(function (t) { return t[0]; }), tips.map(function (t) { return t[1]; }));
    var f = mapper(svg, e[0], e[1], e[2], e[3]);
    vs.forEach(function (v, i) {
      var a = f(tips[i][0], tips[i][1]), b = f(tips[i + 1][0], tips[i + 1][1]), col = COL[v.kind] || "#000";
      arrow(svg, a, b, col, 1.4);
      var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.hypot(dx, dy) || 1;
      label(svg, (a[0] + b[0]) / 2 - 9 * dy / L, (a[1] + b[1]) / 2 + 9 * dx / L + 4, v.sym, v.sub, col);
    });
    var o = f(0, 0); el(svg, "circle", {cx: o[0], cy: o[1], r: 2.5, fill: "#000"});
  }
  function drawLever(k) {
    var svg = canvas("ex-lever");
    var ends = [[0, 0]];
    movers.forEach(function (p) { var q = D.points[p]; if (fin(q.vx[k]) && fin(q.vy[k])) ends.push([-q.vy[k], q.vx[k]]); });
    F.lever.forEach(function (l) { if (fin(l.vx[k]) && fin(l.vy[k])) ends.push([-l.vy[k], l.vx[k]]); });
    var e = extent(ends.map(function (t) { return t[0]; }), ends.map(function (t) { return t[1]; }));
    var m = Math.max(e[1] - e[0], e[3] - e[2]) * 0.15 + 1e-9;
    var f = mapper(svg, e[0] - m, e[1] + m, e[2] - m, e[3] + m), o = f(0, 0);
    movers.forEach(function (p) { var q = D.points[p]; if (!fin(q.vx[k]) || !fin(q.vy[k])) return;
      var b = f(-q.vy[k], q.vx[k]);
      el(svg, "line", {x1: o[0], y1: o[1], x2: b[0], y2: b[1], stroke: "#aaa", "stroke-width": 1});
      tag(svg, {x: b[0] + 3, y: b[1] - 3, "font-size": 9, fill: "#666"}, p.toLowerCase()); });
    var Fm = 0; F.lever.forEach(function (l) { if (fin(l.x[k]) && fin(l.y[k])) Fm = Math.max(Fm, Math.hypot(l.x[k], l.y[k])); });
    function force(at, Fx, Fy, col, sym, sub, len) {
      var n = Math.hypot(Fx, Fy); if (!(n > 1e-9 * Fm)) return;
      var a = f(at[0], at[1]), ux = Fx / n, uy = -Fy / n, b = [a[0] + ux * len, a[1] + uy * len];
      arrow(svg, a, b, col, 1.3); label(svg, b[0] + 8 * ux, b[1] + 8 * uy + 4, sym, sub, col);
    }
    F.lever.forEach(function (l) {
      if (!fin(l.x[k]) || !fin(l.vx[k])) return;
      force([-l.vy[k], l.vx[k]], l.x[k], l.y[k], COL[l.kind] || "#000", l.sym, l.sub, 14 + 16 * Math.sqrt(Math.hypot(l.x[k], l.y[k]) / (Fm || 1)));
    });
    if (F.kind === "moment" && F.pin && fin(F.Mb[k])) {
      var q = D.points[F.pin], vx = q.vx[k], vy = q.vy[k], v2 = vx * vx + vy * vy;
      if (v2 > 0 && F.Mb[k] !== 0) { var c = F.Mb[k] * F.omega1 / v2; Fm = Math.max(Fm, 1e-300);
        force([-vy, vx], c * vx, c * vy, COL.balance || "#117a65", "P", "b", 26); }
    }
    el(svg, "circle", {cx: o[0], cy: o[1], r: 2.5, fill: "#000"});
    tag(svg, {x: o[0] - 12, y: o[1] + 12, "font-size": 11}, "p");
  }
  function fillForces(k) {
    var h = row([L["explore.pair"], L["explore.R"], ""], true);
    F.reactions.forEach(function (r) {
      var tr = row(["", num(r.R[k]), ""]); tr.dataset.pair = r.key;
      tr.cells[0].textContent = r.sym; var s = document.createElement("sub"); s.textContent = r.sub; tr.cells[0].appendChild(s);
    });
    row([F.kind === "moment" ? L["explore.mb"] : L["explore.pb"], L["explore.by_groups"], L["explore.by_lever"]], true);
    var tr = row([F.kind === "moment" ? "M" : "P", num(F.Mb[k]), num(F.Mzh[k])]); tr.dataset.mb = "1";
    var s = document.createElement("sub"); s.textContent = "b"; tr.cells[0].appendChild(s);
  }
  function show(k) {
    k = ((k % n) + n) % n;
    slider.value = String(k);
    var m = marks.filter(function (x) { return x.k === k; })[0];
    out.textContent = num(D.turn[k]) + "°  (φ = " + dec(Number(D.phi[k]).toFixed(2)) + "°)" +
      (m ? "  — " + L["explore.pos"] + " " + m.index : "");
    out.dataset.k = String(k);
    drawMech(k); drawPlan("ex-vplan", "vx", "vy", VM, k, "p"); drawPlan("ex-aplan", "ax", "ay", AM, k, "π"); fill(k);
    if (F) { F.groups.forEach(function (g, i) { drawPolygon(i, k); }); drawLever(k); fillForces(k); }
  }
  function snapped(k) {
    var best = null, bd = SNAP / step + 1e-9;
    marks.forEach(function (m) { var d = Math.abs(m.k - k); d = Math.min(d, n - d); if (d <= bd) { bd = d; best = m.k; } });
    return best === null ? k : best;
  }
  slider.addEventListener("input", function () { show(snapped(+slider.value)); });
  if (CB) CB.addEventListener("change", function () { show(+slider.value); });
  var timer = null;
  play.addEventListener("click", function () {
    if (timer) { clearInterval(timer); timer = null; play.textContent = L["explore.play"]; return; }
    play.textContent = L["explore.pause"];
    timer = setInterval(function () { show(+slider.value + 1); }, 40);
  });
  show(0);
})();
