// The explorer's page (`coverbench serve`): experiments, their runs in a table paged by the
// server, filtered by facet, wall, planner parameter and metric range, sorted by any column; a
// run's picture that plays back (player.js); and runs on one wall side by side, played on one
// clock (compare.js). The view (experiment, filters, sort, page, columns, the open run or the
// compared runs, their playback time, speed and pictures' zoom, the tab, the plot's controls) is
// the page's address: every change is a history entry (the playback time, and a wheel's run of
// zoom steps, change the current one), back and forward return to it, and a copied address shows
// the same view. An answer is shown only if it answers the latest request. Everything shown from data is set as text, never as markup.
"use strict";
(function () {
  const FACETS = [["planner", "planner"], ["dataset", "dataset"], ["status", "status-filter"], ["tool", "tool"]];
  const TEXT_COLUMNS = ["wall_name", "planner", "dataset", "status"];
  const PAGE_SIZES = [50, 100, 200, 500, 1000];
  /** The address's names that are not the runs API's (and those that start with "plot."). */
  const PAGE_NAMES = ["exp", "cols", "run", "cmp", "t", "zoom", "speed", "tab", "plot"];
  /** The plot's controls (plots.js) other than its kind, each in the address as "plot." + name. */
  const PLOT_NAMES = ["metric", "versus", "param", "dataset", "tool"];
  /** The players' speeds (player.js, compare.js) and the one they start at. */
  const SPEEDS = [0.25, 0.5, 1, 2, 5, 10, 20], DEFAULT_SPEED = 5;
  /**
   * A view: `zoom` holds each shown picture's zoom in order (none: all fit), `speed` the players'
   * speed (null: the default), `plot` the plot's controls by name ("kind" and PLOT_NAMES; none: the defaults).
   * @typedef {{exp: string, query: URLSearchParams, cols: string[] | null, run: string, cmp: string[], t: number | null,
   *            zoom: number[], speed: number | null, tab: string, plot: Record<string, string>}} View
   */
  const state = {
    /** @type {View | null} */ view: null,
    /** @type {any[]} */ experiments: [],
    /** @type {Map<string, any>} */ specs: new Map(),
    /** @type {any} */ answer: null,  // the runs answer the table shows
    shown: "",                       // its experiment and query
    requested: 0,                    // the latest runs request's number
    /** @type {AbortController | null} */ pending: null,
    opened: 0,                       // the latest opened run's number
    chosen: "",                      // the key of the run in the viewer
    comparing: "",                   // the keys of the compared runs in the viewer, comma-separated
    picked: new Map(),               // key -> run, for the comparison
    restoring: false,                // a player being held at the address's time
    zoomGesture: false,              // the current entry was made by a wheel's zoom
  };
  /**
   * An element of the page by id (any: each is used as the element it is).
   * @param {string} id
   * @returns {any}
   */
  const $ = id => document.getElementById(id);

  async function api(url, signal) {
    const res = await fetch(url, {signal});
    const body = await res.json();
    if (!res.ok) throw new Error(body.error || res.statusText);
    return body;
  }
  function showError(e) {
    if (e && e.name === "AbortError") return;  // a request replaced by a newer one
    $("status").className = "error";
    $("status").textContent = String(e.message || e);
  }
  function clearError() {
    if ($("status").className === "error") { $("status").className = ""; $("status").textContent = ""; }
  }
  function cell(row, text, cls, title) {
    const td = row.insertCell();
    td.textContent = text;
    if (cls) td.className = cls;
    if (title) td.title = title;
  }

  // --- numbers as the report shows them (the metric registry's format, GET /api/metrics) ------

  /** Three significant digits without exponent for everyday magnitudes (the report's `number`). */
  function significant(v) {
    if (v === 0) return "0";
    const mag = Math.floor(Math.log10(Math.abs(v)));
    if (mag >= 2) return v.toFixed(0);
    if (mag < -4) return v.toExponential(2).replace(/e([+-])(\d)$/, "e$10$2");  // 5.50e-05, as Python writes it
    return v.toFixed(2 - mag);
  }
  /** A unit as a reader writes it: m² for m2, µm for um. */
  function unitText(unit) {
    return unit === "um" ? "\u00b5m" : unit.replace("m2", "m\u00b2");
  }
  function unitLabel(name) {
    const s = state.specs.get(name);
    if (!s) return "";
    if (s.format === "percent") return "%";
    if (s.format === "bytes") return "MiB";
    return s.unit === "1" ? "" : unitText(s.unit);
  }
  /** A metric's value with its unit: shares in percent, bytes in MiB, counts whole. */
  function formatted(name, v) {
    if (v === undefined || v === null) return "-";
    const s = state.specs.get(name);
    if (!s) return significant(v);
    if (s.format === "percent") return (100 * v).toFixed(2) + " %";
    if (s.format === "bytes") return significant(v / 1048576) + " MiB";
    if (s.format === "count") return Number.isInteger(v) ? String(v) : significant(v);
    const unit = unitLabel(name);
    return significant(v) + (unit ? " " + unit : "");
  }
  /** A value typed in the metric's shown unit, as the API takes it. */
  function fromShown(name, text) {
    const s = state.specs.get(name), v = Number(text);
    return !s ? v : s.format === "percent" ? v / 100 : s.format === "bytes" ? v * 1048576 : v;
  }

  // --- the view and the address ---------------------------------------------------------------

  /** @returns {View} */
  function readAddress() {
    const all = new URLSearchParams(location.search);
    const query = new URLSearchParams();
    for (const [k, v] of all) if (!PAGE_NAMES.includes(k) && !k.startsWith("plot.")) query.append(k, v);
    const t = all.get("t"), speed = Number(all.get("speed"));
    /** @type {Record<string, string>} */
    const plot = {};
    if (all.get("plot")) plot.kind = all.get("plot");
    for (const name of PLOT_NAMES) if (all.get("plot." + name)) plot[name] = all.get("plot." + name);
    // A zoom the pictures cannot take is a picture at fit.
    const zoom = (all.get("zoom") || "").split(",").filter(Boolean).map(z => Number(z) >= 1 && Number(z) <= 32 ? Number(z) : 1);
    return {exp: all.get("exp") || "", query, cols: all.has("cols") ? all.get("cols").split(",").filter(Boolean) : null,
            run: all.get("run") || "", cmp: (all.get("cmp") || "").split(",").filter(k => /^[0-9a-f]{64}$/.test(k)),
            t: t !== null && t !== "" && Number.isFinite(Number(t)) ? Number(t) : null,
            zoom: zoom.some(z => z !== 1) ? zoom : [], speed: SPEEDS.includes(speed) ? speed : null,
            tab: all.get("tab") || "", plot};
  }
  /** @param {View} v */
  function addressOf(v) {
    const out = new URLSearchParams({exp: v.exp});
    for (const [k, value] of v.query) out.append(k, value);
    if (v.cols) out.set("cols", v.cols.join(","));
    if (v.run) out.set("run", v.run);
    if (v.cmp.length) out.set("cmp", v.cmp.join(","));
    if ((v.run || v.cmp.length) && v.t !== null) out.set("t", v.t.toFixed(3));
    if ((v.run || v.cmp.length) && v.zoom.length) out.set("zoom", v.zoom.map(z => String(Number(z.toFixed(3)))).join(","));
    if (v.speed !== null) out.set("speed", String(v.speed));
    if (v.tab) out.set("tab", v.tab);
    if (v.plot.kind) out.set("plot", v.plot.kind);
    for (const name of PLOT_NAMES) if (v.plot[name]) out.set("plot." + name, v.plot[name]);
    return "?" + out.toString();
  }
  /**
   * The view changed as `change` says, made a history entry (or the current one, `replace`) and
   * shown. Other pictures shown (another run, other runs compared) start at fit.
   * @param {{exp?: string, query?: URLSearchParams, cols?: string[] | null, run?: string, cmp?: string[], t?: number | null,
   *          zoom?: number[], speed?: number | null, tab?: string, plot?: Record<string, string>}} change
   */
  function go(change, replace = false) {
    const old = state.view;
    if (!("zoom" in change) && ((change.run !== undefined && change.run !== old.run) || (change.cmp && change.cmp.join() !== old.cmp.join()))) change = {...change, zoom: []};
    state.zoomGesture = false;
    const view = {...old, ...change};
    history[replace ? "replaceState" : "pushState"](null, "", addressOf(view));
    show(view).catch(showError);
  }
  /** The current query with `set` ({name: value, "" or null to drop}) applied and, for a filter, page 1. */
  function changedQuery(set, keepPage = false) {
    const q = new URLSearchParams(state.view.query);
    for (const [k, v] of Object.entries(set)) { if (v === null || v === "") q.delete(k); else q.set(k, String(v)); }
    if (!keepPage) q.delete("offset");
    return q;
  }
  const limitOf = q => Number(q.get("limit") || 100);

  /** Shows `view`: its controls at once, its table when the answer to it comes, its run. @param {View} view */
  async function show(view) {
    state.view = view;
    showTab(view.tab === "workbench" ? "workbench" : "experiments");
    showPlots(view);
    $("experiment").value = view.exp;
    setControls(view, state.answer);
    const key = view.exp + "?" + view.query;
    const table = key === state.shown ? null : loadRuns(view, key);
    const cmp = view.cmp.join(",");
    if (cmp) {
      if (cmp !== state.comparing) openCompare(view).catch(showError);
      else { seekCompare(view.t); applyViewer(view); }
    } else {
      if (state.comparing) closeCompare();
      if (view.run !== state.chosen) openRun(view).catch(showError);
      else if (view.run) { seekTo(view.t); applyViewer(view); }
      if (!view.run) closeRun();
    }
    await table;
  }

  /** The table's request for `view`: its answer is shown only if no newer request was made. */
  async function loadRuns(view, key) {
    const seq = ++state.requested;
    if (state.pending) state.pending.abort();
    const controller = state.pending = new AbortController();
    $("runs").dataset.loading = "1";
    const [db, id] = view.exp.split("/");
    let r;
    try {
      r = await api(`/api/experiments/${db}/${id}/runs?${view.query}`, controller.signal);
    } catch (e) {
      if (seq === state.requested) { delete $("runs").dataset.loading; showError(e); }
      return;
    }
    if (seq !== state.requested) return;  // an older answer, come after a newer request
    delete $("runs").dataset.loading;
    clearError();
    state.answer = r;
    state.shown = key;
    setControls(view, r);
    renderTable(view, r);
    $("runs").dataset.shown = key;
  }

  // --- controls -------------------------------------------------------------------------------

  function options(select, values, value, first) {
    select.length = 0;
    if (first !== undefined) select.add(new Option(first, ""));
    for (const [v, text] of values) select.add(new Option(text, v));
    if (value && ![...select.options].some(o => o.value === value)) select.add(new Option(value + " (none)", value));
    select.value = value;
  }
  /** The controls as `view` says (the facets and names from `r`, the latest answer). @param {View} view */
  function setControls(view, r) {
    const q = view.query;
    for (const [name, id] of FACETS) options($(id), r ? r.facets[name].map(v => [v, v]) : [], q.get(name) || "", "all");
    $("wall").value = q.get("wall") || "";
    const metrics = r ? r.metrics : [];
    const params = r ? Object.keys(r.params) : [];
    const columns = [...TEXT_COLUMNS, "tool", ...metrics, ...params.map(p => "param." + p)];
    options($("sort"), columns.map(c => [c, c + (unitLabel(c) ? ` (${unitLabel(c)})` : "")]), q.get("sort") || "", "run key");
    $("order").value = q.get("order") === "desc" ? "desc" : "asc";
    options($("page-size"), PAGE_SIZES.map(n => [String(n), n + " a page"]), String(limitOf(q)));
    const pname = $("param-name").value;
    options($("param-name"), params.map(p => [p, p]), params.includes(pname) ? pname : "", "parameter");
    fillParamValues();
    const rname = $("range-metric").value;
    options($("range-metric"), metrics.map(m => [m, m + (unitLabel(m) ? ` (${unitLabel(m)})` : "")]), metrics.includes(rname) ? rname : "", "metric");
    showChips(q);
    showColumnChoice(view, metrics);
    const [db, id] = view.exp.split("/");
    const csv = new URLSearchParams(q);
    csv.delete("offset");
    csv.delete("limit");
    $("csv").href = `/api/experiments/${db}/${id}/runs.csv?${csv}`;
  }
  function fillParamValues() {
    const name = $("param-name").value, r = state.answer;
    options($("param-value"), name && r ? r.params[name].map(v => [v, v]) : [], "", "value");
  }
  /** The filters that are not a select's: wall, parameters and metric ranges, each with its × button. */
  function showChips(q) {
    const chips = $("chips");
    chips.textContent = "";
    for (const [k, v] of q) {
      let text = "";
      if (k === "wall") text = `wall = ${v}`;
      else if (k.startsWith("param.")) text = `${k.slice(6)} = ${v}`;
      else if (k.startsWith("min.")) text = `${k.slice(4)} \u2265 ${formatted(k.slice(4), Number(v))}`;
      else if (k.startsWith("max.")) text = `${k.slice(4)} \u2264 ${formatted(k.slice(4), Number(v))}`;
      else continue;
      const chip = document.createElement("span");
      chip.className = "chip";
      chip.dataset.filter = k;
      chip.textContent = text + " ";
      const x = document.createElement("button");
      x.type = "button";
      x.textContent = "\u00d7";
      x.title = "remove this filter";
      x.addEventListener("click", () => go({query: changedQuery({[k]: null})}));
      chip.appendChild(x);
      chips.appendChild(chip);
    }
  }
  /** The metric columns shown: the view's, or the registry's headline metrics. @param {View} view */
  function shownColumns(view, metrics) {
    const chosen = view.cols || metrics.filter(m => state.specs.get(m)?.headline);
    const sort = view.query.get("sort") || "";
    const out = chosen.filter(m => metrics.includes(m));
    if (metrics.includes(sort) && !out.includes(sort)) out.unshift(sort);  // the sorted column is always shown, first
    return out;
  }
  function showColumnChoice(view, metrics) {
    const box = $("column-choice");
    box.textContent = "";
    const shown = shownColumns(view, metrics);
    for (const m of metrics) {
      const label = document.createElement("label");
      const tick = document.createElement("input");
      tick.type = "checkbox";
      tick.value = m;
      tick.checked = shown.includes(m);
      tick.addEventListener("change", () => {
        const cols = [...box.querySelectorAll("input")].filter(i => i.checked).map(i => i.value);
        go({cols});
      });
      label.append(tick, " " + m);
      label.title = state.specs.get(m)?.description || "";
      box.appendChild(label);
    }
  }

  // --- the table ------------------------------------------------------------------------------

  /** @param {View} view */
  function renderTable(view, r) {
    const q = view.query, sort = q.get("sort") || "", order = q.get("order") || "asc";
    const columns = shownColumns(view, r.metrics);
    const offset = r.offset, n = r.runs.length;
    $("count").textContent = r.total === 0 ? "no runs match" : n === 0 ? `no rows past ${r.total} runs`
      : `rows ${offset + 1}\u2013${offset + n} of ${r.total}`;
    $("first").disabled = $("previous").disabled = offset === 0;
    $("next").disabled = $("last").disabled = offset + r.limit >= r.total;
    const head = $("runs").tHead;
    head.textContent = "";
    const hr = head.insertRow();
    const pickHead = document.createElement("th");
    pickHead.textContent = "compare";
    pickHead.className = "text";
    hr.appendChild(pickHead);
    for (const c of [...TEXT_COLUMNS, ...columns]) {
      const th = document.createElement("th");
      const unit = unitLabel(c);
      // A button in the heading, so that the keyboard sorts too (Enter or Space).
      const sorter = document.createElement("button");
      sorter.type = "button";
      sorter.className = "sort";
      sorter.textContent = c + (unit ? ` (${unit})` : "") + (sort === c ? (order === "asc" ? " \u25b2" : " \u25bc") : "");
      sorter.title = (state.specs.get(c)?.description || c) + ": sort by it";
      th.appendChild(sorter);
      th.dataset.column = c;
      th.scope = "col";
      if (sort === c) th.setAttribute("aria-sort", order === "asc" ? "ascending" : "descending");
      if (TEXT_COLUMNS.includes(c)) th.className = "text";
      th.addEventListener("click", () => go({query: changedQuery({sort: c, order: sort === c && order === "asc" ? "desc" : "asc"})}));
      hr.appendChild(th);
    }
    const body = $("runs").tBodies[0];
    body.textContent = "";
    for (const run of r.runs) {
      const row = body.insertRow();
      row.dataset.key = run.key;
      row.tabIndex = 0;  // reached by Tab, opened with Enter
      if (run.key === state.chosen) row.className = "chosen";
      const pick = document.createElement("input");
      pick.type = "checkbox";
      pick.className = "pick";
      pick.setAttribute("aria-label", `compare ${run.planner} on ${run.wall_name}`);
      pick.checked = state.picked.has(run.key);
      pick.addEventListener("click", e => e.stopPropagation());
      pick.addEventListener("change", () => {
        if (pick.checked) state.picked.set(run.key, run); else state.picked.delete(run.key);
        updateCompare();
      });
      row.insertCell().appendChild(pick);
      cell(row, run.wall_name, "text");
      cell(row, run.planner, "text", Object.entries(run.params).map(([k, v]) => `${k}=${v}`).join(", "));
      cell(row, run.dataset, "text");
      cell(row, run.status, "text");
      for (const c of columns) cell(row, formatted(c, run.metrics[c]), "", run.metrics[c] === undefined ? "" : String(run.metrics[c]));
      row.addEventListener("click", () => go({run: run.key, cmp: [], t: null}));
      row.addEventListener("keydown", e => {
        if (e.key === "Enter" && e.target === row) { e.preventDefault(); go({run: run.key, cmp: [], t: null}); }
      });
    }
  }

  /** A page: `to` is "first", "previous", "next" or "last". */
  function page(to) {
    const r = state.answer, q = state.view.query, limit = limitOf(q);
    const offset = Number(q.get("offset") || 0);
    const last = Math.max(0, Math.floor((r.total - 1) / limit) * limit);
    const at = {first: 0, previous: Math.max(0, offset - limit), next: offset + limit, last}[to];
    go({query: changedQuery({offset: at || null}, true)});
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
    const [db, id] = state.view.exp.split("/");
    const base = `/api/experiments/${db}/${id}/runs/${run.key}`;
    const figure = document.createElement("figure");
    const img = document.createElement("img");
    img.src = base + "/picture.svg";
    img.alt = run.wall_name + " / " + run.planner;
    figure.appendChild(img);
    const caption = document.createElement("figcaption");
    caption.textContent = `${run.wall_name} / ${run.planner}: ${run.status}`;
    figure.appendChild(caption);
    if (run.status !== "error" && run.metrics.waypoints > 1) figure.dataset.playback = base + "/playback.js";
    figure.dataset.speed = String(state.view.speed ?? DEFAULT_SPEED);  // the speed its player starts at
    return figure;
  }

  /** The runs of `keys`: from the table's answer where it has them, else asked for by key. */
  async function runsByKey(exp, keys) {
    const [db, id] = exp.split("/");
    const have = state.answer && state.shown.startsWith(exp + "?") ? state.answer.runs : [];
    return Promise.all(keys.map(async key => {
      const run = have.find(r => r.key === key) || (await api(`/api/experiments/${db}/${id}/runs?key=${key}&limit=1`)).runs[0];
      if (!run) throw new Error(`experiment ${exp} has no run ${key}`);
      return run;
    }));
  }

  // The view's compared runs side by side on one clock (compare.js), across the page's width.
  /** @param {View} view */
  async function openCompare(view) {
    const seq = ++state.opened, cmp = view.cmp.join(",");
    const hadFocus = $("viewer").contains(document.activeElement) || document.activeElement === document.body;
    state.chosen = "";
    state.comparing = cmp;
    for (const r of $("runs").tBodies[0].rows) r.className = "";
    const runs = await runsByKey(view.exp, view.cmp);
    if (seq !== state.opened) return;
    $("experiments").classList.add("comparing");
    const all = await window.coverbenchCompareView.open($("viewer"), runs, {
      figureFor, formatted, specs: state.specs, t: view.t, speed: view.speed, alive: () => seq === state.opened});
    if (all) await zoomPictures(view, seq);
    if (all && hadFocus) /** @type {HTMLElement} */ ($("viewer").querySelector(".compare-play")).focus();
  }
  function closeCompare() {
    state.comparing = "";
    ++state.opened;
    $("experiments").classList.remove("comparing");
    const p = document.createElement("p");
    p.textContent = "Choose a run to see its path and play it back.";
    $("viewer").replaceChildren(p);
    stopCompare();
  }
  function stopCompare() {
    $("viewer").coverbenchCompare?.pause();
    delete $("viewer").coverbenchCompare;
  }
  function seekCompare(t) {
    const all = $("viewer").coverbenchCompare;
    if (t === null || !all || Math.abs(all.time() - t) < 0.0005) return;
    all.pause();
    all.seek(t);
  }
  /** Every planner configuration's run on `run`'s wall with its tool: the table filtered to them, and compared. */
  async function compareWall(run) {
    const [db, id] = state.view.exp.split("/");
    const q = new URLSearchParams({wall: run.wall_name, tool: run.tool, dataset: run.dataset, limit: "1000"});
    const r = await api(`/api/experiments/${db}/${id}/runs?${q}`);
    const keys = r.runs.filter(o => o.wall === run.wall).map(o => o.key);
    go({query: changedQuery({wall: run.wall_name, tool: run.tool, dataset: run.dataset, planner: null}), run: "", cmp: keys, t: null});
  }

  // --- the run in the viewer ------------------------------------------------------------------

  /** Opens the view's run: from the table's answer at once, else asked for by its key. @param {View} view */
  async function openRun(view) {
    const seq = ++state.opened;
    if (!view.run) return;
    let run = state.answer && state.shown.startsWith(view.exp + "?") ? state.answer.runs.find(r => r.key === view.run) : undefined;
    if (!run) {
      const [db, id] = view.exp.split("/");
      const r = await api(`/api/experiments/${db}/${id}/runs?key=${encodeURIComponent(view.run)}&limit=1`);
      if (seq !== state.opened) return;
      run = r.runs[0];
      if (!run) throw new Error(`experiment ${view.exp} has no run ${view.run}`);
    }
    showRun(run);
    const zoomed = zoomPictures(view, seq);
    if (view.t !== null) await startAt(view.t, seq);
    await zoomed;
  }
  /** The viewer's pictures: the open run's, or the compared runs' in order. @returns {HTMLElement[]} */
  const pictures = () => [...$("viewer").querySelectorAll("figure:not(.coat)")];
  /** Each picture at the view's zoom, once it has loaded (its size is known then). @param {View} view */
  async function zoomPictures(view, seq) {
    await Promise.all(pictures().map(async (f, i) => {
      const z = view.zoom[i] || 1, img = f.querySelector("img");
      if (!f.coverbenchZoom || f.coverbenchZoom.zoom() === z) return;
      if (img) await img.decode().catch(() => null);
      // Unless another run was opened, or the view's zoom changed, meanwhile.
      if (seq === state.opened && (state.view.zoom[i] || 1) === z && f.coverbenchZoom.zoom() !== z) f.coverbenchZoom.set(z);
    }));
  }
  /** The shown viewer's zoom and speed as `view` says (back, forward). @param {View} view */
  function applyViewer(view) {
    zoomPictures(view, state.opened).catch(showError);
    const speed = view.speed ?? DEFAULT_SPEED, all = $("viewer").coverbenchCompare;
    if (all && all.speed() !== speed) all.setSpeed(speed);
    for (const f of pictures()) {
      f.dataset.speed = String(speed);
      if (!all && f.coverbenchPlayer && f.coverbenchPlayer.speed() !== speed) f.coverbenchPlayer.setSpeed(speed);
    }
  }
  function closeRun() {
    if (!state.chosen) return;
    state.chosen = "";
    ++state.opened;
    for (const r of $("runs").tBodies[0].rows) r.className = "";
    const p = document.createElement("p");
    p.textContent = "Choose a run to see its path and play it back.";
    $("viewer").replaceChildren(p);
  }
  /** Starts the open run's player and holds it at `t` s. */
  async function startAt(t, seq) {
    const figure = $("viewer").querySelector("figure[data-playback]");
    if (!figure) return;
    state.restoring = true;
    try {
      await startPlayer(figure, seq);
    } finally {
      state.restoring = false;
    }
    if (seq !== state.opened || !figure.coverbenchPlayer) return;
    figure.coverbenchPlayer.pause();
    figure.coverbenchPlayer.seek(t);
    figure.dataset.restored = t.toFixed(3);
  }
  async function startPlayer(figure, seq) {
    if (!figure.coverbenchPlayer) {
      const start = figure.querySelector(".player-start");
      if (start && !start.disabled) start.click();
      for (let k = 0; k < 800 && !figure.coverbenchPlayer && seq === state.opened; ++k) await new Promise(r => setTimeout(r, 25));
    }
    // Held at once: the player starts playing as it is made.
    if (seq === state.opened && figure.coverbenchPlayer) figure.coverbenchPlayer.pause();
  }
  function seekTo(t) {
    const player = $("viewer").querySelector("figure[data-playback]")?.coverbenchPlayer;
    if (t === null || !player || Math.abs(player.time() - t) < 0.0005) return;
    player.pause();
    player.seek(t);
  }
  // The open run's playback time, kept in the address (the current entry) as it changes.
  function followPlayback() {
    const v = state.view;
    const all = $("viewer").coverbenchCompare;
    if (v && v.cmp.length && all && state.comparing === v.cmp.join(",")) {
      const t = Math.round(all.time() * 1000) / 1000;
      if (v.t === null ? t > 0 : Math.abs(t - v.t) >= 0.0005) {
        state.view = {...v, t};
        history.replaceState(null, "", addressOf(state.view));
      }
      return;
    }
    const player = $("viewer").querySelector("figure[data-playback]")?.coverbenchPlayer;
    if (!player || !v || !v.run || state.chosen !== v.run || state.restoring) return;
    const t = Math.round(player.time() * 1000) / 1000;
    if (v.t === null ? t > 0 : Math.abs(t - v.t) >= 0.0005) {
      state.view = {...v, t};
      history.replaceState(null, "", addressOf(state.view));
    }
  }

  function showRun(run) {
    state.chosen = run.key;
    $("experiments").classList.remove("comparing");
    stopCompare();
    for (const r of $("runs").tBodies[0].rows) r.className = r.dataset.key === run.key ? "chosen" : "";
    const viewer = $("viewer");
    viewer.textContent = "";
    const figure = figureFor(run);
    viewer.appendChild(figure);
    if (figure.dataset.playback) window.coverbenchAttachPlayer(figure);
    const dl = document.createElement("dl");
    dl.className = "metrics";
    const add = (k, text, title) => {
      const dt = document.createElement("dt"), dd = document.createElement("dd");
      dt.textContent = k;
      dd.textContent = text;
      if (title) dd.title = title;
      dl.append(dt, dd);
    };
    add("wall", `${run.wall_name} (${run.dataset})`);
    add("planner", run.planner + (Object.keys(run.params).length ? ": " + Object.entries(run.params).map(([k, v]) => `${k}=${v}`).join(", ") : ""));
    add("tool", run.tool);
    // In the registry's order, then any the registry does not know.
    const names = [...state.specs.keys()].filter(k => k in run.metrics);
    for (const k of [...names, ...Object.keys(run.metrics).filter(k => !state.specs.has(k))]) add(k, formatted(k, run.metrics[k]), String(run.metrics[k]));
    viewer.appendChild(dl);
    if (run.status !== "ok") showOutcome(run, viewer);
    const tools = document.createElement("div");
    tools.className = "run-tools";
    const button = (id, text, f) => {
      const b = document.createElement("button");
      b.type = "button";
      b.id = id;
      b.textContent = text;
      b.addEventListener("click", f);
      tools.appendChild(b);
    };
    button("open-in-workbench", "open this wall and planner in the workbench", async () => {
      try {
        const [db, id] = state.view.exp.split("/");
        const p = await api(`/api/experiments/${db}/${id}/runs/${run.key}/problem`);
        go({tab: "workbench"});
        window.coverbenchWorkbench.setProblem(p);
      } catch (e) { showError(e); }
    });
    button("same-wall", "other planners on this wall", () => compareWall(run).catch(showError));
    // A tool with a flux profile lays a coat: its thickness map, drawn by the server when asked.
    if ("thickness_mean" in run.metrics) button("show-coat", "the coat's thickness", () => showCoat(run).catch(showError));
    viewer.insertBefore(tools, figure);
  }

  /** The open run's coat (docs/deposition.md) under its picture; the server's error if it has none. */
  async function showCoat(run) {
    const [db, id] = state.view.exp.split("/");
    const b = /** @type {HTMLButtonElement} */ ($("show-coat"));
    b.disabled = true;
    try {
      const res = await fetch(`/api/experiments/${db}/${id}/runs/${run.key}/coat.svg`);
      if (!res.ok) throw new Error((await res.json()).error || res.statusText);
      const blob = await res.blob();
      if (state.chosen !== run.key || $("viewer").querySelector("figure.coat")) return;
      const figure = document.createElement("figure");
      figure.className = "coat";
      const img = document.createElement("img");
      img.alt = `${run.wall_name} / ${run.planner}: the coat`;
      img.src = URL.createObjectURL(blob);
      img.addEventListener("load", () => URL.revokeObjectURL(img.src), {once: true});
      const caption = document.createElement("figcaption");
      caption.textContent = "the coat's thickness, \u00b5m: green within 10 % of the mean, blues thinner, oranges to dark red thicker";
      figure.append(img, caption);
      $("viewer").querySelector("figure")?.after(figure);
    } catch (e) {
      b.disabled = false;
      throw e;
    }
  }

  // Why a run failed or left parts out, and the end of an external planner's stderr: planner
  // output, so only ever text (textContent), never markup.
  async function showOutcome(run, viewer) {
    let o;
    try {
      const [db, id] = state.view.exp.split("/");
      o = await api(`/api/experiments/${db}/${id}/runs/${run.key}/outcome`);
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

  /** The Plots tab (plots.js): in place of the run viewer, over the table's filters. @param {View} view */
  function showPlots(view) {
    const on = view.tab === "plots";
    $("plots").hidden = !on;
    $("viewer").hidden = on;
    $("tab-plots").setAttribute("aria-selected", String(on));
    if (on) $("tab-experiments").setAttribute("aria-selected", "false");
    if (on && view.exp) window.coverbenchPlots.show(view.exp, view.query, view.plot, plot => go({plot})).catch(showError);
  }

  // --- wiring ---------------------------------------------------------------------------------

  function listen() {
    $("experiment").addEventListener("change", () => go({exp: $("experiment").value, query: new URLSearchParams(), run: "", cmp: [], t: null}));
    for (const [name, id] of FACETS) $(id).addEventListener("change", () => go({query: changedQuery({[name]: $(id).value})}));
    $("wall").addEventListener("change", () => go({query: changedQuery({wall: $("wall").value.trim()})}));
    $("sort").addEventListener("change", () => go({query: changedQuery({sort: $("sort").value, order: $("sort").value ? $("order").value : null})}));
    $("order").addEventListener("change", () => go({query: changedQuery({order: $("order").value})}));
    $("page-size").addEventListener("change", () => go({query: changedQuery({limit: $("page-size").value})}));
    $("param-name").addEventListener("change", fillParamValues);
    $("param-add").addEventListener("click", () => {
      if ($("param-name").value && $("param-value").value) go({query: changedQuery({["param." + $("param-name").value]: $("param-value").value})});
    });
    $("range-add").addEventListener("click", () => {
      const m = $("range-metric").value, set = {};
      if (!m) return;
      for (const side of ["min", "max"]) {
        const text = $("range-" + side).value.trim();
        if (text !== "" && Number.isFinite(Number(text))) set[`${side}.${m}`] = fromShown(m, text);
      }
      if (Object.keys(set).length) go({query: changedQuery(set)});
    });
    for (const to of ["first", "previous", "next", "last"]) $(to).addEventListener("click", () => page(to));
    for (const t of ["experiments", "workbench", "plots"]) $("tab-" + t).addEventListener("click", () => go({tab: t === "experiments" ? "" : t}));
    $("compare").addEventListener("click", () => go({run: "", cmp: [...state.picked.keys()], t: null}));
    window.addEventListener("popstate", () => show(readAddress()).catch(showError));
    // The user's speed and zoom (player.js, compare.js): a history entry each, but a wheel's run
    // of zoom steps is one.
    $("viewer").addEventListener("coverbench:speed", e => go({speed: e.detail.speed}));
    $("viewer").addEventListener("coverbench:zoom", e => {
      const zoom = pictures().map(f => Number(f.dataset.zoom || 1));
      go({zoom: zoom.some(z => z !== 1) ? zoom : []}, e.detail.gesture && state.zoomGesture);
      state.zoomGesture = Boolean(e.detail.gesture);
    });
    setInterval(followPlayback, 250);
  }

  async function start() {
    const [r, m] = await Promise.all([api("/api/experiments"), api("/api/metrics")]);
    for (const s of m.metrics) state.specs.set(s.name, s);
    state.experiments = r.experiments;
    const select = $("experiment");
    for (const e of r.experiments)
      select.add(new Option(`${e.name} (${e.runs} runs; ${e.file}, id ${e.id})`, `${e.db}/${e.id}`));
    listen();
    updateCompare();
    const view = readAddress();
    if (!r.experiments.length) {
      $("count").textContent = "no experiment databases are served: the workbench is open";
      showTab("workbench");
      document.body.dataset.ready = "1";
      return;
    }
    if (!r.experiments.some(e => `${e.db}/${e.id}` === view.exp)) {
      const last = r.experiments.at(-1);
      view.exp = `${last.db}/${last.id}`;
      history.replaceState(null, "", addressOf(view));
    }
    // The scripts after this one (plots.js, workbench.js) may still be loading when the list comes:
    // an address that opens their tab waits for them.
    if (document.readyState === "loading") await new Promise(r => document.addEventListener("DOMContentLoaded", r, {once: true}));
    await show(view);
    document.body.dataset.ready = "1";
  }
  start().catch(showError);
})();
