// The explorer's workbench (`coverbench serve`, docs/explorer.md#workbench): make or edit a wall
// in a form, a drawing and its wall file text, checked by the server as it is typed (the command
// line's messages); choose a planner and its parameters from a form built from the registry's
// specs; plan in the server's worker process, watch the path play back, read its metrics; save
// the wall to the walls database or export it as a wall file. Everything shown from data is set
// as text, never as markup.
"use strict";
(function () {
  /**
   * An element of the page by id (any: each is used as the element it is).
   * @param {string} id
   * @returns {any}
   */
  const $ = id => document.getElementById(id);
  const SVG = "http://www.w3.org/2000/svg";
  // checking: a check of the current request is due or under way; checkError: the last check's
  // message (null: it passed); planning: a plan is under way; planned: what the plan shown was
  // asked for (its wall text and the rest of its request), to mark it stale when either changes.
  const state = {wall: null, planners: [], checkTimer: 0, checkSeq: 0, drag: null,
    checking: false, checkError: null, planning: false, planned: null};

  async function call(method, url, body) {
    // The server changes nothing for a POST that is not application/json (a page elsewhere can
    // send text/plain without asking; this type it cannot).
    const res = await fetch(url, body === undefined ? {method}
      : {method, headers: {"Content-Type": "application/json"}, body: JSON.stringify(body)});
    const text = await res.text();
    let data;
    try { data = JSON.parse(text); } catch (e) { data = {error: `${url}: HTTP ${res.status}`}; }
    if (!res.ok) throw new Error(data.error || `${url}: HTTP ${res.status}`);
    return data;
  }

  // --- the wall: text <-> model -------------------------------------------------------------------
  function num(v) { return Math.round(v * 1e6) / 1e6; }
  function wallText(w) {
    const head = {name: w.name};
    if (w.boundary) head.boundary = w.boundary; else { head.width = w.width; head.height = w.height; }
    for (const k of ["start", "end", "description"]) if (w[k] !== undefined) head[k] = w[k];
    const fields = o => Object.entries(o).map(([k, v]) => JSON.stringify(k) + ": " + JSON.stringify(v)).join(", ");
    const lines = fields(head);
    const obstacles = (w.obstacles || []).map(o => "    {" + fields(o) + "}");
    return `{ ${lines},\n  "obstacles": [${obstacles.length ? "\n" + obstacles.join(",\n") + " " : ""}] }\n`;
  }
  // A wall as wallToJson writes it has its boundary and rectangles as polygons; the form edits
  // an axis-aligned rectangle as one (the same wall: the canonical text is unchanged).
  function asRect(points) {
    if (!Array.isArray(points) || points.length !== 4) return null;
    const xs = [...new Set(points.map(p => p[0]))], ys = [...new Set(points.map(p => p[1]))];
    if (xs.length !== 2 || ys.length !== 2) return null;
    const corners = new Set(points.map(p => p[0] + "," + p[1]));
    if (corners.size !== 4) return null;
    const [x0, x1] = xs.sort((a, b) => a - b), [y0, y1] = ys.sort((a, b) => a - b);
    return {x: x0, y: y0, width: num(x1 - x0), height: num(y1 - y0)};
  }
  function simplified(w) {
    const b = w.boundary && asRect(w.boundary);
    const out = {name: w.name};
    if (b && b.x === 0 && b.y === 0) { out.width = b.width; out.height = b.height; } else if (w.boundary) out.boundary = w.boundary;
    else { out.width = w.width; out.height = w.height; }
    for (const k of ["start", "end", "description"]) if (w[k] !== undefined) out[k] = w[k];
    out.obstacles = (w.obstacles || []).map(o => {
      const r = o.type === "polygon" && asRect(o.points);
      return r ? Object.assign({type: "rect"}, r, o.label ? {label: o.label} : {}) : o;
    });
    return out;
  }
  function setWall(w) {
    state.wall = w;
    $("wb-text").value = wallText(w);
    renderForm();
    renderDrawing();
    scheduleCheck();
  }
  function textChanged() {
    try {
      const w = JSON.parse($("wb-text").value);
      if (w && typeof w === "object" && !Array.isArray(w)) {
        state.wall = w;
        renderForm();
        renderDrawing();
      }
    } catch (e) { /* the server's check names the problem */ }
    scheduleCheck();
  }

  // --- checking as it is typed ---------------------------------------------------------------------
  function request(withPlanner) {
    const body = {wall: $("wb-text").value};
    const tw = Number($("wb-tool").value), cl = Number($("wb-clearance").value), tl = Number($("wb-time").value);
    if ($("wb-tool").value !== "") body.tool_width = tw;
    if ($("wb-clearance").value !== "") body.clearance = cl;
    if ($("wb-time").value !== "") body.time_limit_s = tl;
    if (withPlanner && $("wb-planner").value) {
      body.planner = $("wb-planner").value;
      body.params = {};
      for (const input of $("wb-params").querySelectorAll("[data-param]")) {
        if (input.type === "checkbox") body.params[input.dataset.param] = input.checked ? "true" : "false";
        else if (input.value !== "") body.params[input.dataset.param] = input.value;
      }
    }
    return body;
  }
  // Every change comes here: the plan button is off until the changed request has been checked,
  // and the plan shown is marked stale at once.
  function scheduleCheck() {
    clearTimeout(state.checkTimer);
    state.checking = true;
    updatePlanButton();
    markStale();
    state.checkTimer = setTimeout(check, 150);
  }
  // The plan button is on only for a request that has been checked and passed, while no plan runs;
  // beside it, why it is off.
  function updatePlanButton() {
    const reason = state.planning ? "" : state.checkError ? state.checkError : state.checking ? "checking\u2026"
      : !$("wb-planner").value ? "choose a planner" : "";
    $("wb-plan").disabled = state.planning || state.checking || state.checkError !== null || !$("wb-planner").value;
    $("wb-plan-reason").textContent = reason;
    $("wb-plan-reason").className = state.checkError && !state.planning ? "error" : "";
  }
  function markStale() {
    const p = state.planned;
    const {wall, ...rest} = request(true);
    const why = !p ? "" : p.wall !== wall ? "the wall" : p.rest !== JSON.stringify(rest) ? "the parameters" : "";
    $("wb-result").classList.toggle("stale", why !== "");
    $("wb-stale").hidden = why === "";
    $("wb-stale").textContent = why ? `stale: ${why} changed since this plan` : "";
  }
  async function check() {
    const seq = ++state.checkSeq;
    const line = $("wb-check");
    for (const el of document.querySelectorAll("#workbench .invalid")) el.classList.remove("invalid");
    try {
      const r = await call("POST", "/api/check", request(true));
      if (seq !== state.checkSeq) return;
      if (!r.ok) throw new Error(r.error);
      line.className = "ok";
      line.textContent = `\u2713 ${r.name}: a valid wall with ${r.obstacles} obstacle${r.obstacles === 1 ? "" : "s"}; planner and parameters accepted`;
      state.checkError = null;
    } catch (e) {
      if (seq !== state.checkSeq) return;
      line.className = "error";
      line.textContent = e.message;
      state.checkError = e.message;
      // Mark the parameter the message names ("params: overlap: ...").
      const m = /^params: ([^:]+):/.exec(e.message);
      const input = m && $("wb-params").querySelector(`[data-param="${CSS.escape(m[1])}"]`);
      if (input) input.classList.add("invalid");
      else if (/^wall: /.test(e.message)) $("wb-text").classList.add("invalid");
    }
    state.checking = false;
    updatePlanButton();
  }

  // --- the form ------------------------------------------------------------------------------------
  const FIELDS = {rect: ["x", "y", "width", "height"], circle: ["x", "y", "radius"], polygon: []};
  // A number field of the form: one that is empty or not a number is marked, and its value is NaN
  // in the wall (null in its text: the check names it; the drawing leaves it out).
  function numberInput(value, onchange, cls) {
    const input = document.createElement("input");
    input.type = "number";
    input.step = "any";
    const mark = v => input.setAttribute("aria-invalid", String(!Number.isFinite(v)));
    input.value = Number.isFinite(value) ? String(value) : "";
    mark(value);
    if (cls) input.className = cls;
    input.addEventListener("input", () => {
      const v = input.value === "" ? NaN : Number(input.value);
      mark(v);
      onchange(v);
    });
    return input;
  }
  function changed() {
    $("wb-text").value = wallText(state.wall);
    renderDrawing();
    scheduleCheck();
  }
  function renderForm() {
    const w = state.wall;
    const form = $("wb-form");
    form.textContent = "";
    if (!w) return;
    const top = document.createElement("div");
    top.className = "row";
    const name = document.createElement("input");
    name.value = w.name || "";
    name.id = "wb-name";
    name.addEventListener("input", () => { w.name = name.value; name.removeAttribute("aria-invalid"); changed(); });
    const lab = document.createElement("label");
    lab.append("name ", name);
    top.append(lab);
    if (!w.boundary) {
      for (const k of ["width", "height"]) {
        const l = document.createElement("label");
        l.append(k + " (m) ", numberInput(w[k], v => { w[k] = v; changed(); }, "wb-" + k));
        top.append(l);
      }
    } else {
      top.append(`boundary: a polygon of ${w.boundary.length} points (edit it in the text)`);
    }
    form.append(top);
    const table = document.createElement("table");
    table.className = "wb-obstacles";
    const head = table.createTHead().insertRow();
    for (const h of ["obstacle", "label", "x", "y", "width / radius", "height", ""]) {
      const th = document.createElement("th");
      th.textContent = h;
      head.appendChild(th);
    }
    const body = table.createTBody();
    (w.obstacles || []).forEach((o, i) => {
      const row = body.insertRow();
      row.insertCell().textContent = `${i + 1}: ${o.type}`;
      const label = document.createElement("input");
      label.value = o.label || "";
      label.size = 8;
      label.setAttribute("aria-label", `obstacle ${i + 1}: label`);
      label.addEventListener("input", () => { if (label.value) o.label = label.value; else delete o.label; changed(); });
      row.insertCell().appendChild(label);
      for (const k of FIELDS[o.type] || []) {
        const field = numberInput(o[k], v => { o[k] = v; changed(); });
        field.setAttribute("aria-label", `obstacle ${i + 1}: ${k} (m)`);
        row.insertCell().appendChild(field);
      }
      for (let k = (FIELDS[o.type] || []).length; k < 4; ++k) row.insertCell().textContent = o.type === "polygon" && k === 0 ? `${(o.points || []).length} points` : "";
      const del = document.createElement("button");
      del.type = "button";
      del.textContent = "\u2715";
      del.title = "remove this obstacle";
      del.addEventListener("click", () => { w.obstacles.splice(i, 1); renderForm(); changed(); });
      row.insertCell().appendChild(del);
    });
    const wrap = document.createElement("div");
    wrap.className = "wb-table-wrap";  // a table wider than its column scrolls within it
    wrap.append(table);
    form.append(wrap);
  }

  // --- the drawing: drag on free space to add a window, drag an obstacle to move it ----------------
  function bounds(w) {
    const pts = w.boundary || [[0, 0], [w.width, w.height]];
    const xs = pts.map(p => p[0]).filter(Number.isFinite), ys = pts.map(p => p[1]).filter(Number.isFinite);
    if (!xs.length || !ys.length) return null;
    const b = {x0: Math.min(...xs), x1: Math.max(...xs), y0: Math.min(...ys), y1: Math.max(...ys)};
    return b.x1 > b.x0 && b.y1 > b.y0 ? b : null;
  }
  const finite = (...vs) => vs.every(Number.isFinite);
  const finitePoints = ps => Array.isArray(ps) && ps.every(p => Array.isArray(p) && finite(p[0], p[1]));
  function renderDrawing() {
    const svg = $("wb-drawing");
    const w = state.wall;
    const b = w && bounds(w);
    if (!b || (w.boundary && !finitePoints(w.boundary))) return;  // the last wall drawn stays
    svg.textContent = "";
    const pad = 0.04 * Math.max(b.x1 - b.x0, b.y1 - b.y0);
    svg.setAttribute("viewBox", `${b.x0 - pad} ${-(b.y1 + pad)} ${b.x1 - b.x0 + 2 * pad} ${b.y1 - b.y0 + 2 * pad}`);
    const add = (tag, attrs, parent) => {
      const el = document.createElementNS(SVG, tag);
      for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, String(v));
      (parent || svg).appendChild(el);
      return el;
    };
    const pts = w.boundary || [[0, 0], [w.width, 0], [w.width, w.height], [0, w.height]];
    add("polygon", {points: pts.map(p => `${p[0]},${-p[1]}`).join(" "), class: "wb-wall"});
    (w.obstacles || []).forEach((o, i) => {
      let el;
      // An obstacle with a field that is not a number is left out until it has one.
      if (o.type === "rect" && finite(o.x, o.y, o.width, o.height))
        el = add("rect", {x: o.x, y: -(o.y + o.height), width: Math.max(o.width, 0), height: Math.max(o.height, 0)});
      else if (o.type === "circle" && finite(o.x, o.y, o.radius)) el = add("circle", {cx: o.x, cy: -o.y, r: Math.max(o.radius, 0)});
      else if (o.type === "polygon" && finitePoints(o.points)) el = add("polygon", {points: o.points.map(p => `${p[0]},${-p[1]}`).join(" ")});
      if (!el) return;
      el.setAttribute("class", "wb-obstacle");
      el.dataset.index = String(i);
    });
    for (const [k, colour] of [["start", "#1a7f37"], ["end", "#b00020"]])
      if (finitePoints([w[k]])) add("circle", {cx: w[k][0], cy: -w[k][1], r: pad / 3, fill: colour});
  }
  function wallPoint(svg, e) {
    const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(svg.getScreenCTM().inverse());
    return [num(p.x), num(-p.y)];
  }
  function startDrag(e) {
    const svg = $("wb-drawing");
    if (!state.wall || !svg.getScreenCTM()) return;
    const at = wallPoint(svg, e);
    const index = e.target.dataset ? e.target.dataset.index : undefined;
    if (index !== undefined) {
      const o = state.wall.obstacles[Number(index)];
      state.drag = {kind: "move", o, from: at, orig: JSON.parse(JSON.stringify(o))};
    } else {
      state.wall.obstacles = state.wall.obstacles || [];
      const o = {type: "rect", x: at[0], y: at[1], width: 0, height: 0, label: "window"};
      state.wall.obstacles.push(o);
      state.drag = {kind: "add", o, from: at};
    }
    svg.setPointerCapture(e.pointerId);
    e.preventDefault();
  }
  function moveDrag(e) {
    const d = state.drag;
    if (!d) return;
    const at = wallPoint($("wb-drawing"), e);
    const dx = at[0] - d.from[0], dy = at[1] - d.from[1];
    if (d.kind === "add") {
      Object.assign(d.o, {x: num(Math.min(at[0], d.from[0])), y: num(Math.min(at[1], d.from[1])), width: num(Math.abs(dx)), height: num(Math.abs(dy))});
    } else if (d.o.type === "polygon") {
      d.o.points = d.orig.points.map(p => [num(p[0] + dx), num(p[1] + dy)]);
    } else {
      d.o.x = num(d.orig.x + dx);
      d.o.y = num(d.orig.y + dy);
    }
    renderDrawing();
    $("wb-text").value = wallText(state.wall);
    markStale();
  }
  function endDrag() {
    const d = state.drag;
    if (!d) return;
    state.drag = null;
    if (d.kind === "add" && (d.o.width === 0 || d.o.height === 0)) state.wall.obstacles.pop();  // a click, not a drag
    renderForm();
    changed();
  }

  // --- the planner form ----------------------------------------------------------------------------
  function renderParams() {
    const box = $("wb-params");
    box.textContent = "";
    const p = state.planners.find(q => q.name === $("wb-planner").value);
    if (!p) return;
    $("wb-summary").textContent = p.summary;
    for (const s of p.params) {
      const label = document.createElement("label");
      label.title = s.description;
      let input;
      if (s.type === "bool") {
        input = document.createElement("input");
        input.type = "checkbox";
        input.checked = s.default === true;
      } else if (s.type === "choice") {
        input = document.createElement("select");
        for (const c of s.choices) input.add(new Option(c, c, false, c === s.default));
      } else {
        input = document.createElement("input");
        input.type = "number";
        input.min = String(s.min);
        input.max = String(s.max);
        input.step = s.type === "integer" ? "1" : "any";
        input.value = String(s.default);
      }
      input.dataset.param = s.name;
      input.addEventListener(input.tagName === "SELECT" || input.type === "checkbox" ? "change" : "input", scheduleCheck);
      const range = s.type === "number" || s.type === "integer" ? ` [${s.min}, ${s.max}]` : "";
      label.append(`${s.name}${s.unit ? " (" + s.unit + ")" : ""}${range} `, input);
      box.appendChild(label);
    }
  }
  function setProblem(p) {
    if (p.planner) $("wb-planner").value = p.planner;
    renderParams();
    for (const [k, v] of Object.entries(p.params || {})) {
      const input = $("wb-params").querySelector(`[data-param="${CSS.escape(k)}"]`);
      if (!input) continue;
      if (input.type === "checkbox") input.checked = v === "true"; else input.value = v;
    }
    if (p.tool_width !== undefined) $("wb-tool").value = String(p.tool_width);
    if (p.clearance !== undefined) $("wb-clearance").value = String(p.clearance);
    setWall(simplified(JSON.parse(p.wall)));
  }

  // --- plan, watch, score; save, export -----------------------------------------------------------
  async function plan() {
    const out = $("wb-result");
    out.textContent = "planning\u2026";
    const body = request(true);
    const {wall, ...rest} = body;
    state.planning = true;
    state.planned = null;
    markStale();
    updatePlanButton();
    try {
      const r = await call("POST", "/api/plan", body);
      state.planned = {wall, rest: JSON.stringify(rest)};
      out.textContent = "";
      const line = document.createElement("p");
      line.id = "wb-outcome";
      line.textContent = `${r.planner}: ${r.status}${r.reason ? " (" + r.reason + ")" : ""}, ${r.valid ? "valid" : "NOT valid"}, ` +
        `${r.waypoints} waypoints, planned in ${r.plan_time_ms.toFixed(1)} ms`;
      out.appendChild(line);
      const figure = document.createElement("figure");
      const img = document.createElement("img");
      img.src = r.picture;
      img.alt = "the planned path";
      figure.appendChild(img);
      out.appendChild(figure);
      if (r.playback) {
        figure.dataset.playback = r.playback;
        window.coverbenchAttachPlayer(figure);
      }
      const dl = document.createElement("dl");
      dl.className = "metrics";
      for (const [k, v] of Object.entries(r.metrics)) {
        const dt = document.createElement("dt"), dd = document.createElement("dd");
        dt.textContent = k;
        dd.textContent = Number.isInteger(v) ? String(v) : v.toPrecision(4);
        dl.append(dt, dd);
      }
      out.appendChild(dl);
      document.body.dataset.planned = String(r.id);
    } catch (e) {
      out.textContent = "";
      const p = document.createElement("p");
      p.className = "error";
      p.id = "wb-outcome";
      p.textContent = e.message;
      out.appendChild(p);
      p.scrollIntoView({block: "nearest"});
    } finally {
      state.planning = false;
      markStale();
      updatePlanButton();
    }
  }
  // A wall is saved under its name, and opened again by it: a blank one is refused here as the
  // server refuses it.
  async function save() {
    let wall = null;
    try { wall = JSON.parse($("wb-text").value); } catch (e) { /* the server names the problem */ }
    const name = wall && typeof wall === "object" ? wall.name : null;
    if (name === undefined || (typeof name === "string" && !/\S/.test(name))) {
      $("wb-saved").className = "error";
      $("wb-saved").textContent = "name: a saved wall needs a name that is not blank (it is how it is opened again)";
      if ($("wb-name")) $("wb-name").setAttribute("aria-invalid", "true");
      return;
    }
    try {
      const r = await call("POST", "/api/walls", request(false));
      $("wb-saved").className = "ok";
      $("wb-saved").textContent = `saved as '${r.name}' in ${r.file}`;
      await listWalls();
    } catch (e) {
      $("wb-saved").className = "error";
      $("wb-saved").textContent = e.message;
    }
  }
  async function exportWall() {
    try {
      const r = await call("POST", "/api/check", request(false));
      if (!r.ok) throw new Error(r.error);
      const a = document.createElement("a");
      a.href = URL.createObjectURL(new Blob([r.wall], {type: "application/json"}));
      a.download = (r.name || "wall") + ".json";
      a.click();
      URL.revokeObjectURL(a.href);
    } catch (e) {
      $("wb-saved").className = "error";
      $("wb-saved").textContent = e.message;
    }
  }
  async function listWalls() {
    const r = await call("GET", "/api/walls");
    const select = $("wb-open");
    select.length = 1;
    for (const w of r.walls) {
      const url = w.url || "/api/walls/db/" + encodeURIComponent(w.name);
      select.add(new Option(w.source === "folder" ? `${w.name} (${w.folder})` : `${w.name} (saved, ${w.saved_at})`, url));
    }
    $("wb-save").disabled = !r.walls_db;
    $("wb-save").title = r.walls_db ? "save to " + r.walls_db : "start coverbench serve with --walls-db FILE to save walls";
  }
  async function open(url) {
    const res = await fetch(url);
    const text = await res.text();
    if (!res.ok) throw new Error(JSON.parse(text).error);
    let w = null;
    try { w = JSON.parse(text); } catch (e) { /* shown as it is: the check names the problem */ }
    if (w && typeof w === "object" && !Array.isArray(w)) return setWall(simplified(w));
    $("wb-text").value = text;
    textChanged();
  }

  async function start() {
    state.planners = (await call("GET", "/api/planners")).planners;
    for (const p of state.planners) $("wb-planner").add(new Option(p.name, p.name));
    $("wb-planner").addEventListener("change", () => { renderParams(); scheduleCheck(); });
    renderParams();
    for (const id of ["wb-tool", "wb-clearance", "wb-time"]) $(id).addEventListener("input", scheduleCheck);
    $("wb-text").addEventListener("input", textChanged);
    $("wb-new").addEventListener("click", () => setWall({name: "new-wall", width: 4, height: 2.5, obstacles: [
      {type: "rect", x: 1.5, y: 0.9, width: 1.0, height: 1.0, label: "window"}]}));
    $("wb-add").addEventListener("click", () => {
      const b = bounds(state.wall) || {x0: 0, y0: 0, x1: 1, y1: 1};
      state.wall.obstacles = state.wall.obstacles || [];
      state.wall.obstacles.push({type: "rect", x: num(b.x0 + (b.x1 - b.x0) * 0.4), y: num(b.y0 + (b.y1 - b.y0) * 0.4),
        width: num((b.x1 - b.x0) * 0.2), height: num((b.y1 - b.y0) * 0.2), label: "window"});
      renderForm();
      changed();
    });
    $("wb-open").addEventListener("change", () => { if ($("wb-open").value) open($("wb-open").value).catch(e => { $("wb-check").className = "error"; $("wb-check").textContent = e.message; }); });
    $("wb-plan").addEventListener("click", plan);
    $("wb-save").addEventListener("click", save);
    $("wb-export").addEventListener("click", exportWall);
    const svg = $("wb-drawing");
    svg.addEventListener("pointerdown", startDrag);
    svg.addEventListener("pointermove", moveDrag);
    svg.addEventListener("pointerup", endDrag);
    await listWalls();
    $("wb-new").click();
    window.coverbenchWorkbench = {setProblem, plan, check: () => check()};
    document.body.dataset.workbench = "1";
  }
  start().catch(e => { $("wb-check").className = "error"; $("wb-check").textContent = e.message; });
})();
