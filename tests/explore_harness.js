// Runs the report's explorer (templates/explore.js) outside a browser, on a minimal
// document, at every crank angle of its grid, and prints, as JSON, every drawing's
// texts that overlap or leave it: [[drawing id, k, text, text]].  Input on stdin:
// {"js": source, "data": ..., "labels": ..., "forces": ... | null, "figs": {id: [w, h]},
// "centres": true to tick the instant centres' box}.
"use strict";
const input = JSON.parse(require("fs").readFileSync(0, "utf8"));
class El {
  constructor(tag) { this.tag = tag; this.children = []; this.attrs = {}; this.dataset = {}; this.textContent = ""; this.listeners = {}; }
  setAttribute(k, v) { this.attrs[k] = String(v); }
  getAttribute(k) { return this.attrs[k]; }
  appendChild(c) { this.children.push(c); c.parent = this; return c; }
  removeChild(c) { this.children = this.children.filter((x) => x !== c); return c; }
  get firstChild() { return this.children[0] || null; }
  get cells() { return this.children; }
  addEventListener(n, f) { this.listeners[n] = f; }
}
const byId = {};
function node(id, text) { const e = new El("div"); e.textContent = text || ""; byId[id] = e; return e; }
node("ex-data", JSON.stringify(input.data));
node("ex-labels", JSON.stringify(input.labels));
if (input.forces) node("ex-forces", JSON.stringify(input.forces));
for (const id of ["ex-angle", "ex-play", "ex-readout", "ex-table", "ex-marks", "ex-centres-note"]) node(id);
if (input.centres) node("ex-centres").checked = true;      // the instant centres drawn too
for (const [id, [w, h]] of Object.entries(input.figs)) { const e = node(id); e.dataset.w = String(w); e.dataset.h = String(h); }
global.document = {
  getElementById: (id) => byId[id] || null,
  createElement: (t) => new El(t),
  createElementNS: (ns, t) => new El(t),
};
global.setInterval = () => 0; global.clearInterval = () => 0;
new Function(input.js)();
function box(t) {
  // the text and its subscript (tspan), 0.6 x the font size a character, as the placer
  const fs = +t.attrs["font-size"], sub = t.children.filter((c) => c.tag === "tspan").map((c) => c.textContent).join("");
  const w = 0.6 * fs * t.textContent.length + 0.6 * 8 * sub.length, h = fs + (sub ? 3 : 0);
  const x = +t.attrs.x, y = +t.attrs.y, x0 = t.attrs["text-anchor"] === "middle" ? x - w / 2 : x;
  return [x0, y - 0.8 * h, x0 + w, y + 0.2 * h];
}
const bad = [];
const slider = byId["ex-angle"];
for (let k = 0; k <= +slider.max; k++) {
  slider.value = String(k);
  slider.listeners.input();                   // show(snapped(k)): the drawings at that angle
  for (const id of Object.keys(input.figs)) {
    const svg = byId[id].firstChild;
    if (!svg) continue;
    const W = +svg.attrs.width, H = +svg.attrs.height;
    const texts = svg.children.filter((c) => c.tag === "text");
    const bs = texts.map(box);
    bs.forEach((b, i) => {
      if (b[0] < -0.5 || b[1] < -0.5 || b[2] > W + 0.5 || b[3] > H + 0.5) bad.push([id, k, texts[i].textContent, "(outside)"]);
      for (let j = i + 1; j < bs.length; j++) {
        const c = bs[j];
        if (Math.min(b[2], c[2]) - Math.max(b[0], c[0]) > 0.5 && Math.min(b[3], c[3]) - Math.max(b[1], c[1]) > 0.5)
          bad.push([id, k, texts[i].textContent, texts[j].textContent]);
      }
    });
  }
}
process.stdout.write(JSON.stringify(bad));
