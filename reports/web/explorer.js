// The explorer's page (`coverbench serve`): experiments, their runs in a table with filters and
// sorting by any metric, a run's picture that plays back (player.js), and two to four runs on
// one wall side by side, played in step. Everything shown from
// data is set as text, never as markup.
"use strict";
(function () {
  const COLUMNS = ["coverage_reachable", "overlap", "length_ratio", "duration_s", "turns", "plan_time_ms"];
  const state = {db: 0, id: 0, sort: "", order: "asc", chosen: "", picked: new Map()};  // picked: key -> run
  /**
   * An element of the page by id (any: each is used as the element it is).
   * @param {string} id
   * @returns {any}
   */
  const $ = id => document.getElementById(id);

  async function api(url) {
    const res = await fetch(url);
    const body = await res.json();
    if (!res.ok) throw new Error(body.error || res.statusText);
    return body;
  }
  function showError(e) {
    $("status").className = "error";
    $("status").textContent = String(e.message || e);
  }
  function fill(select, values, keep) {
    const current = select.value;
    select.length = 1;
    for (const v of values) select.add(new Option(v, v));
    if (keep && values.includes(current)) select.value = current;
  }
  function cell(row, text, cls) {
    const td = row.insertCell();
    td.textContent = text;
    if (cls) td.className = cls;
  }
  function number(v) {
    if (v === undefined) return "-";
    return Math.abs(v) >= 1000 || Number.isInteger(v) ? String(Math.round(v * 100) / 100) : v.toPrecision(4);
  }

  async function loadRuns() {
    const q = new URLSearchParams({limit: "500"});
    for (const [k, id] of [["planner", "planner"], ["dataset", "dataset"], ["status", "status-filter"], ["tool", "tool"]])
      if ($(id).value) q.set(k, $(id).value);
    if (state.sort) { q.set("sort", state.sort); q.set("order", state.order); }
    const r = await api(`/api/experiments/${state.db}/${state.id}/runs?${q}`);
    fill($("planner"), r.facets.planner, true);
    fill($("dataset"), r.facets.dataset, true);
    fill($("status-filter"), r.facets.status, true);
    fill($("tool"), r.facets.tool, true);
    $("count").textContent = `${r.total} runs` + (r.total > r.runs.length ? ` (first ${r.runs.length} shown)` : "");
    const head = $("runs").tHead;
    head.textContent = "";
    const hr = head.insertRow();
    const pickHead = document.createElement("th");
    pickHead.textContent = "compare";
    pickHead.className = "text";
    hr.appendChild(pickHead);
    for (const c of ["wall_name", "planner", "dataset", "status", ...COLUMNS]) {
      const th = document.createElement("th");
      th.textContent = c + (state.sort === c ? (state.order === "asc" ? " \u25b2" : " \u25bc") : "");
      th.dataset.column = c;
      if (!COLUMNS.includes(c)) th.className = "text";
      th.addEventListener("click", () => {
        state.order = state.sort === c && state.order === "asc" ? "desc" : "asc";
        state.sort = c;
        loadRuns().catch(showError);
      });
      hr.appendChild(th);
    }
    const body = $("runs").tBodies[0];
    body.textContent = "";
    for (const run of r.runs) {
      const row = body.insertRow();
      row.dataset.key = run.key;
      if (run.key === state.chosen) row.className = "chosen";
      const pick = document.createElement("input");
      pick.type = "checkbox";
      pick.className = "pick";
      pick.checked = state.picked.has(run.key);
      pick.addEventListener("click", e => e.stopPropagation());
      pick.addEventListener("change", () => {
        if (pick.checked) state.picked.set(run.key, run); else state.picked.delete(run.key);
        updateCompare();
      });
      row.insertCell().appendChild(pick);
      cell(row, run.wall_name, "text");
      cell(row, run.planner, "text");
      cell(row, run.dataset, "text");
      cell(row, run.status, "text");
      for (const c of COLUMNS) cell(row, number(run.metrics[c]));
      row.addEventListener("click", () => view(run, row));
    }
  }

  // Two to four runs on one wall can be compared.
  function updateCompare() {
    const runs = [...state.picked.values()];
    const walls = new Set(runs.map(r => r.wall));
    const button = $("compare");
    button.disabled = !(runs.length >= 2 && runs.length <= 4 && walls.size === 1);
    button.title = walls.size > 1 ? "the runs must be on one wall" : "pick two to four runs on one wall";
  }

  function figureFor(run) {
    const base = `/api/experiments/${state.db}/${state.id}/runs/${run.key}`;
    const figure = document.createElement("figure");
    const img = document.createElement("img");
    img.src = base + "/picture.svg";
    img.alt = run.wall_name + " / " + run.planner;
    figure.appendChild(img);
    const caption = document.createElement("figcaption");
    caption.textContent = `${run.wall_name} / ${run.planner}: ${run.status}`;
    figure.appendChild(caption);
    if (run.status !== "error" && run.metrics.waypoints > 1) figure.dataset.playback = base + "/playback.js";
    return figure;
  }

  // The picked runs side by side, played in step: one clock (the time models' seconds) for all.
  async function compare() {
    const runs = [...state.picked.values()];
    const viewer = $("viewer");
    viewer.textContent = "";
    const grid = document.createElement("div");
    grid.className = "compare";
    const figures = runs.map(figureFor);
    grid.append(...figures);
    const bar = document.createElement("div");
    bar.className = "player-bar";
    const button = document.createElement("button");
    button.type = "button";
    button.textContent = "\u25b6 play all";
    const speed = document.createElement("select");
    for (const s of [0.25, 0.5, 1, 2, 5, 10, 20]) speed.add(new Option(s + "x", String(s), s === 5, s === 5));
    const scrub = document.createElement("input");
    scrub.type = "range";
    scrub.min = "0";
    scrub.step = "any";
    scrub.value = "0";
    bar.append(button, speed, scrub);
    viewer.append(bar, grid);
    const players = [];
    for (const f of figures) {
      if (!f.dataset.playback) continue;
      window.coverbenchAttachPlayer(f);
      /** @type {HTMLButtonElement} */ (f.querySelector(".player-start")).click();
    }
    for (let k = 0; k < 400 && figures.some(f => f.dataset.playback && !f.coverbenchPlayer); ++k)
      await new Promise(r => setTimeout(r, 25));
    for (const f of figures) if (f.coverbenchPlayer) { f.coverbenchPlayer.pause(); players.push(f.coverbenchPlayer); }
    scrub.max = String(Math.max(0, ...players.map(p => p.duration())));
    let playing = false;
    const all = {
      players,
      play() { playing = true; const t = Number(scrub.value); for (const p of players) { p.setSpeed(Number(speed.value)); p.seek(t); p.play(); } button.textContent = "\u275a\u275a pause all"; },
      pause() { playing = false; for (const p of players) p.pause(); button.textContent = "\u25b6 play all"; },
      seek(t) { scrub.value = String(t); for (const p of players) p.seek(t); },
      setSpeed(s) { speed.value = String(s); for (const p of players) p.setSpeed(s); },
      times: () => players.map(p => p.time()),
    };
    button.addEventListener("click", () => (playing ? all.pause() : all.play()));
    speed.addEventListener("change", () => all.setSpeed(Number(speed.value)));
    scrub.addEventListener("input", () => all.seek(Number(scrub.value)));
    const follow = () => {
      if (playing) scrub.value = String(Math.max(...players.map(p => p.time())));
      if (viewer.contains(bar)) requestAnimationFrame(follow);
    };
    requestAnimationFrame(follow);
    viewer.coverbenchCompare = all;
    return all;
  }

  function view(run, row) {
    state.chosen = run.key;
    for (const r of $("runs").tBodies[0].rows) r.className = r === row ? "chosen" : "";
    const viewer = $("viewer");
    viewer.textContent = "";
    const figure = figureFor(run);
    viewer.appendChild(figure);
    if (figure.dataset.playback) window.coverbenchAttachPlayer(figure);
    const dl = document.createElement("dl");
    dl.className = "metrics";
    for (const [k, v] of Object.entries(run.metrics)) {
      const dt = document.createElement("dt"), dd = document.createElement("dd");
      dt.textContent = k;
      dd.textContent = number(v);
      dl.append(dt, dd);
    }
    viewer.appendChild(dl);
    if (run.status !== "ok") showOutcome(run, viewer);
    const edit = document.createElement("button");
    edit.type = "button";
    edit.id = "open-in-workbench";
    edit.textContent = "open this wall and planner in the workbench";
    edit.addEventListener("click", async () => {
      try {
        const p = await api(`/api/experiments/${state.db}/${state.id}/runs/${run.key}/problem`);
        showTab("workbench");
        window.coverbenchWorkbench.setProblem(p);
      } catch (e) { showError(e); }
    });
    viewer.insertBefore(edit, figure);
  }

  // Why a run failed or left parts out, and the end of an external planner's stderr: planner
  // output, so only ever text (textContent), never markup.
  async function showOutcome(run, viewer) {
    let o;
    try {
      o = await api(`/api/experiments/${state.db}/${state.id}/runs/${run.key}/outcome`);
    } catch (e) { showError(e); return; }
    if (state.chosen !== run.key || (!o.reason && !o.stderr_tail)) return;
    const section = document.createElement("section");
    section.className = "outcome";
    if (o.reason) {
      const p = document.createElement("p");
      p.className = "reason";
      p.textContent = `${o.status}: ${o.reason}`;
      section.appendChild(p);
    }
    if (o.stderr_tail) {
      const label = document.createElement("p");
      label.className = "stderr-label";
      label.textContent = `the end of the planner's stderr (${o.planner} on ${o.wall_name}, s=${o.tool_width} m, c=${o.clearance} m):`;
      const pre = document.createElement("pre");
      pre.className = "stderr";
      pre.textContent = o.stderr_tail;
      section.append(label, pre);
    }
    const dl = viewer.querySelector("dl.metrics");
    if (dl) viewer.insertBefore(section, dl);
  }

  function showTab(name) {
    for (const t of ["experiments", "workbench"]) {
      $(t).hidden = t !== name;
      $("tab-" + t).setAttribute("aria-selected", String(t === name));
    }
  }

  async function start() {
    const r = await api("/api/experiments");
    const select = $("experiment");
    for (const e of r.experiments)
      select.add(new Option(`${e.name} (${e.runs} runs; ${e.file}, id ${e.id})`, `${e.db}/${e.id}`));
    for (const t of ["experiments", "workbench"]) $("tab-" + t).addEventListener("click", () => showTab(t));
    if (!r.experiments.length) {
      $("count").textContent = "no experiment databases are served: the workbench is open";
      showTab("workbench");
      document.body.dataset.ready = "1";
      return;
    }
    select.value = `${r.experiments.at(-1).db}/${r.experiments.at(-1).id}`;
    const pick = () => { [state.db, state.id] = select.value.split("/").map(Number); return loadRuns(); };
    select.addEventListener("change", () => pick().catch(showError));
    for (const id of ["planner", "dataset", "status-filter", "tool"])
      $(id).addEventListener("change", () => loadRuns().catch(showError));
    $("compare").addEventListener("click", () => compare().catch(showError));
    updateCompare();
    await pick();
    document.body.dataset.ready = "1";
  }
  start().catch(showError);
})();
