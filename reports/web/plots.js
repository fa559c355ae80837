// The explorer's Plots tab (docs/explorer.md#plots): one metric of the runs the table's filters
// select, drawn with Observable Plot (on d3), which `coverbench serve` serves from the build
// (/vendor/, installed by scripts/setup.sh): per planner configuration distributions (box plot,
// empirical CDF), Dolan-Moré performance profiles, the metric against a swept parameter (median
// and interquartile range per planner family) and against another metric (every run). Always one
// dataset and one tool at a time: the report never pools tools, and pools datasets only in its
// size plots, which are not drawn here. Each plot downloads as SVG and PNG.
// explorer.js calls window.coverbenchPlots.show(experiment, query, choice, onChange) when the tab
// shows: `choice` holds the controls' values from the page's address (kind, metric, versus,
// param, dataset, tool; a missing or unknown one takes its default), and a control the user
// changes is handed to `onChange` with the others, to become the address, which shows it.
(function () {
  const KINDS = [["box", "distribution: box plot"], ["ecdf", "distribution: empirical CDF"], ["profile", "performance profile"],
                 ["sweep", "against a swept parameter"], ["scatter", "against another metric"]];
  const LIBRARY = ["/vendor/d3.min.js", "/vendor/plot.umd.min.js"];
  const INSTALL = "The plots' charting library is not installed: run `bash scripts/setup.sh` (it installs Observable Plot into reports/web/vendor), then reload.";
  const state = {
    exp: "", filters: "",
    /** @type {Record<string, string>} */ choice: {},  // the controls' values asked for
    /** @type {((choice: Record<string, string>) => void) | null} */ onChange: null,
    /** @type {Map<string, any>} */ specs: new Map(),
    /** @type {any} */ experiment: null,  // the runs API's answer with no run: metrics and parameters
    /** @type {any} */ data: null,        // the values answer the plot is drawn from
    fetched: "",                          // its request
    requested: 0,
    /** @type {Promise<boolean> | null} */ library: null,
    /** @type {any} */ drawn: null,       // what the plot shows, for the tests: {kind, metric, dataset, tool, series...}
    /** @type {any} */ figure: null,
  };
  /** @param {string} id @returns {any} */
  const $ = id => document.getElementById(id);

  async function api(url) {
    const res = await fetch(url);
    const body = await res.json();
    if (!res.ok) throw new Error(body.error || res.statusText);
    return body;
  }
  function note(text, error = false) {
    $("plots-note").textContent = text;
    $("plots-note").className = error ? "error" : "";
  }

  /** The charting library, loaded once: false (and the tab says how to install it) when it is missing. */
  function loadLibrary() {
    if (!state.library) {
      state.library = (async () => {
        for (const src of LIBRARY) {
          const loaded = await new Promise(resolve => {
            const s = document.createElement("script");
            s.src = src;
            s.onload = () => resolve(true);
            s.onerror = () => resolve(false);
            document.head.append(s);
          });
          if (!loaded) return false;
        }
        return Boolean(window.Plot && window.d3);
      })();
    }
    return state.library;
  }

  // --- controls -------------------------------------------------------------------------------

  function build() {
    const root = $("plots");
    root.innerHTML = `<div class="filters">
      <label>plot <select id="plots-kind"></select></label>
      <label>metric <select id="plots-metric"></select></label>
      <label id="plots-versus-label">against <select id="plots-versus"></select></label>
      <label id="plots-param-label">parameter <select id="plots-param"></select></label>
      <label>dataset <select id="plots-dataset"></select></label>
      <label>tool <select id="plots-tool"></select></label></div>
      <div class="filters"><button type="button" id="plots-svg">download SVG</button>
      <button type="button" id="plots-png">download PNG</button><span id="plots-note" role="status"></span></div>
      <div id="plots-chart"></div>`;
    for (const [value, text] of KINDS) $("plots-kind").add(new Option(text, value));
    for (const id of ["plots-kind", "plots-metric", "plots-versus", "plots-param", "plots-dataset", "plots-tool"]) $(id).addEventListener("change", changed);
    $("plots-svg").addEventListener("click", () => save(new Blob([svgText()], {type: "image/svg+xml"}), "svg"));
    $("plots-png").addEventListener("click", () => pngBlob().then(b => save(b, "png")).catch(failed));
  }
  function failed(e) { note(String(e.message || e), true); }

  /** The controls' values: the versus metric for a scatter plot, the parameter for a sweep. */
  function currentChoice() {
    const kind = $("plots-kind").value;
    /** @type {Record<string, string>} */
    const c = {kind, metric: $("plots-metric").value};
    if (kind === "scatter") c.versus = $("plots-versus").value;
    if (kind === "sweep" && $("plots-param").value) c.param = $("plots-param").value;
    for (const k of ["dataset", "tool"]) if ($("plots-" + k).value) c[k] = $("plots-" + k).value;
    return c;
  }
  /** A control the user changed: handed to the page with the others, or drawn at once. */
  function changed() {
    if (state.onChange) { state.onChange(currentChoice()); return; }
    state.choice = currentChoice();
    refresh().catch(failed);
  }
  /** Sets `select` to `value`, or when it has no such option to `fallback`, or else to its first. */
  function choose(select, value, fallback) {
    const has = v => v && [...select.options].some(o => o.value === v);
    select.value = has(value) ? value : has(fallback) ? fallback : select.options[0]?.value ?? "";
  }

  function fill(select, values, keep) {
    const old = keep ? select.value : "";
    select.replaceChildren(...values.map(([v, text]) => new Option(text, v)));
    if (values.some(([v]) => v === old)) select.value = old;
  }

  /**
   * Shows the plot of the experiment's runs that `query` (the table's filters) selects, as `choice` says.
   * @param {string} exp
   * @param {URLSearchParams} query
   * @param {Record<string, string>} [choice]
   * @param {(choice: Record<string, string>) => void} [onChange]
   */
  async function show(exp, query, choice = {}, onChange = undefined) {
    if (!$("plots-kind")) build();
    state.choice = choice;
    state.onChange = onChange || null;
    const filters = new URLSearchParams(query);
    for (const k of ["sort", "order", "offset", "limit"]) filters.delete(k);
    if (!(await loadLibrary())) {
      note(INSTALL, true);
      return;
    }
    if (!state.specs.size) for (const s of (await api("/api/metrics")).metrics) state.specs.set(s.name, s);
    if (exp !== state.exp) {
      const [db, id] = exp.split("/");
      state.experiment = await api(`/api/experiments/${db}/${id}/runs?limit=0`);
      state.exp = exp;
      const metrics = state.experiment.metrics.filter(m => m !== "valid").map(m => [m, m]);
      fill($("plots-metric"), metrics, true);
      fill($("plots-versus"), metrics, true);
      const swept = Object.entries(state.experiment.params).filter(([, v]) => v.length > 1).map(([p]) => [p, p]);
      fill($("plots-param"), swept, true);
    }
    choose($("plots-kind"), choice.kind, "box");
    choose($("plots-metric"), choice.metric, "length_total");
    choose($("plots-versus"), choice.versus, "coverage_reachable");
    choose($("plots-param"), choice.param, "");
    state.filters = filters.toString();
    await refresh();
  }

  /** Asks for the values the plot needs (when they are not those held), then draws. */
  async function refresh() {
    if (!state.exp || !$("plots-metric").value) return;  // the experiment's metrics are not known yet
    const kind = $("plots-kind").value;
    $("plots-versus-label").hidden = kind !== "scatter";
    $("plots-param-label").hidden = kind !== "sweep";
    const [db, id] = state.exp.split("/");
    const q = new URLSearchParams(state.filters);
    q.set("metric", $("plots-metric").value);
    if (kind === "scatter") q.set("versus", $("plots-versus").value);
    const url = `/api/experiments/${db}/${id}/values?${q}`;
    if (url !== state.fetched) {
      const seq = ++state.requested;
      $("plots").dataset.loading = "1";
      let data;
      try {
        data = await api(url);
      } finally {
        if (seq === state.requested) delete $("plots").dataset.loading;
      }
      if (seq !== state.requested) return;  // a newer request was made
      state.data = data;
      state.fetched = url;
      const datasets = [...new Set(data.runs.dataset)].sort((a, b) => a - b).map(i => [data.datasets[i], data.datasets[i]]);
      const tools = [...new Set(data.runs.tool)].sort((a, b) => a - b).map(i => [data.tools[i], "tool " + data.tools[i]]);
      fill($("plots-dataset"), datasets, true);
      fill($("plots-tool"), tools, true);
    }
    choose($("plots-dataset"), state.choice.dataset, "");
    choose($("plots-tool"), state.choice.tool, "");
    draw();
  }

  // --- the runs of one dataset and tool ---------------------------------------------------------

  /** The held runs of the chosen dataset and tool, as objects. */
  function chosenRuns() {
    const d = state.data, r = d.runs;
    const dataset = d.datasets.indexOf($("plots-dataset").value), tool = d.tools.indexOf($("plots-tool").value);
    const out = [];
    for (let i = 0; i < r.value.length; ++i) {
      if (r.dataset[i] !== dataset || r.tool[i] !== tool) continue;
      out.push({wall: r.wall[i], config: d.configurations[r.configuration[i]], family: d.families[r.configuration[i]],
                params: d.params[r.configuration[i]], usable: r.usable[i], value: r.value[i], versus: r.versus ? r.versus[i] : null});
    }
    return out;
  }
  /** Values summarised: usable runs with a value (as the report's box plots). */
  const summarised = runs => runs.filter(r => r.usable && r.value !== null);
  const configsOf = runs => [...new Set(runs.map(r => r.config))];

  /** An axis's label and tick format for a metric: shares in percent, bytes in MiB. */
  function axis(name) {
    const s = state.specs.get(name) || {unit: "1", format: "number", better: 0};
    const arrow = s.better > 0 ? " \u2191" : s.better < 0 ? " \u2193" : "";
    if (s.format === "percent") return {label: `${name} (%)${arrow}`, tickFormat: v => String(+(100 * v).toFixed(6))};
    if (s.format === "bytes") return {label: `${name} (MiB)${arrow}`, tickFormat: v => String(+(v / 1048576).toFixed(3))};
    const unit = s.unit === "um" ? "\u00b5m" : s.unit.replace("m2", "m\u00b2");  // as the tables write it
    return {label: s.unit === "1" ? name + arrow : `${name} (${unit})${arrow}`};
  }

  /** The chart's width: its column's, so its text is shown at its own size (at least 480 px). */
  const chartWidth = () => Math.max(480, Math.floor($("plots-chart").clientWidth) || 760);

  // --- the plots --------------------------------------------------------------------------------

  function boxPlot(runs, metric) {
    const values = summarised(runs), configs = configsOf(runs);
    const drawn = configs.map(c => ({config: c, values: values.filter(r => r.config === c).map(r => r.value)}));
    const plot = window.Plot.plot({
      marginBottom: 90, marginLeft: 70, width: chartWidth(), height: 440, y: {...axis(metric), grid: true},
      x: {domain: configs, label: null, tickRotate: -25},
      marks: [window.Plot.boxY(values, {x: "config", y: "value", fill: "config"})],
      color: {domain: configs},
    });
    return {plot, drawn: {kind: "box", metric, series: drawn}};
  }

  function ecdfPlot(runs, metric) {
    const values = summarised(runs), configs = configsOf(runs);
    const points = [], drawn = [];
    for (const c of configs) {
      const v = values.filter(r => r.config === c).map(r => r.value).sort((a, b) => a - b);
      if (!v.length) continue;
      points.push({config: c, value: v[0], share: 0});
      v.forEach((x, i) => points.push({config: c, value: x, share: (i + 1) / v.length}));
      drawn.push({config: c, values: v});
    }
    const plot = window.Plot.plot({
      marginLeft: 60, width: chartWidth(), height: 440, x: {...axis(metric), grid: true},
      y: {label: "share of the configuration's usable runs", domain: [0, 1], grid: true},
      color: {domain: configs, legend: true},
      marks: [window.Plot.line(points, {x: "value", y: "share", z: "config", stroke: "config", curve: "step-after"})],
    });
    return {plot, drawn: {kind: "ecdf", metric, series: drawn}};
  }

  /**
   * Dolan-Moré profiles as the report draws them (stats.performance_profile): over the walls every
   * compared configuration ran on, a configuration's cost on a wall is its value when its run is
   * usable and has one, else infinite (a failure never reaches any τ); a wall where every one
   * failed counts against all of them. Overlap is shifted by its absolute tie band first.
   */
  function profile(runs, metric) {
    const configs = configsOf(runs), spec = state.specs.get(metric);
    const shift = metric === "overlap" ? spec.tie_absolute : 0;
    const byWall = new Map();
    for (const r of runs) {
      if (!byWall.has(r.wall)) byWall.set(r.wall, new Map());
      byWall.get(r.wall).set(r.config, r.usable && r.value !== null ? r.value + shift : Infinity);
    }
    const walls = [...byWall.values()].filter(m => configs.every(c => m.has(c)));
    const ratios = configs.map(() => /** @type {number[]} */ ([]));
    for (const m of walls) {
      const best = Math.min(...configs.map(c => m.get(c)));
      configs.forEach((c, j) => ratios[j].push(Number.isFinite(best) && Number.isFinite(m.get(c)) ? m.get(c) / best : Infinity));
    }
    const finite = ratios.flat().filter(Number.isFinite);
    const top = Math.max(2, finite.length ? Math.max(...finite) * 1.05 : 2);
    const taus = [...new Set([1, ...finite, top])].sort((a, b) => a - b);
    const series = configs.map((c, j) => ({config: c, rho: taus.map(t => ratios[j].filter(x => x <= t).length / walls.length)}));
    return {configs, walls: walls.length, taus, series, shift};
  }

  function profilePlot(runs, metric) {
    const spec = state.specs.get(metric);
    if (!spec || spec.better >= 0) return {message: `Performance profiles compare costs: choose a metric where lower is better (${metric} is not one).`};
    const p = profile(runs, metric);
    if (!p.walls) return {message: "No wall here has a run of every configuration: there is nothing to profile."};
    const points = p.series.flatMap(s => s.rho.map((rho, k) => ({config: s.config, tau: p.taus[k], rho})));
    const plot = window.Plot.plot({
      marginLeft: 60, width: chartWidth(), height: 440, x: {type: "log", base: 2, label: "\u03c4 (within \u03c4 \u00d7 best)", grid: true},
      y: {label: `share of the ${p.walls} walls every configuration ran on`, domain: [0, 1.02], grid: true},
      color: {domain: p.configs, legend: true},
      marks: [window.Plot.line(points, {x: "tau", y: "rho", z: "config", stroke: "config", curve: "step-after"})],
    });
    const caption = `${metric}: a failure never reaches any \u03c4` + (p.shift ? ` (+${p.shift} to all)` : "");
    return {plot, caption, drawn: {kind: "profile", metric, walls: p.walls, taus: p.taus, series: p.series}};
  }

  /**
   * The sweeps of `param`: per planner family, its configurations that differ in `param` alone
   * (the others' values the same), when there are two or more; each a line of medians with the
   * interquartile range, over usable runs.
   */
  function sweeps(runs, param) {
    const values = summarised(runs), groups = new Map();
    for (const c of configsOf(runs)) {
      const r = runs.find(x => x.config === c);
      if (!(param in r.params)) continue;
      const rest = Object.entries(r.params).filter(([k]) => k !== param).sort().map(([k, v]) => k + "=" + v).join(",");
      const key = r.family + "\u0000" + rest;
      if (!groups.has(key)) groups.set(key, {family: r.family, configs: []});
      groups.get(key).configs.push({config: c, text: r.params[param]});
    }
    const lines = [...groups.values()].filter(g => new Set(g.configs.map(c => c.text)).size > 1);
    const numeric = lines.every(g => g.configs.every(c => Number.isFinite(Number(c.text))));
    const out = [];
    lines.forEach((g, k) => {
      const name = g.family + (lines.filter(o => o.family === g.family).length > 1 ? ` #${k + 1}` : "");
      for (const c of g.configs) {
        const v = values.filter(r => r.config === c.config).map(r => r.value).sort((a, b) => a - b);
        if (!v.length) continue;
        out.push({line: name, config: c.config, x: numeric ? Number(c.text) : c.text, runs: v.length,
                  median: window.d3.quantileSorted(v, 0.5), q1: window.d3.quantileSorted(v, 0.25), q3: window.d3.quantileSorted(v, 0.75)});
      }
    });
    if (numeric) out.sort((a, b) => a.x - b.x);
    return {points: out, numeric};
  }

  function sweepPlot(runs, metric) {
    const param = $("plots-param").value;
    if (!param) return {message: "No planner parameter takes two or more values in this experiment: there is no sweep to plot."};
    const s = sweeps(runs, param);
    if (!s.points.length) return {message: `No planner here has configurations that differ in ${param} alone.`};
    const lines = [...new Set(s.points.map(p => p.line))];
    const plot = window.Plot.plot({
      marginLeft: 70, width: chartWidth(), height: 440, x: {label: param, ...(s.numeric ? {} : {type: "point"}), grid: true},
      y: {...axis(metric), grid: true}, color: {domain: lines, legend: true},
      marks: [
        window.Plot.ruleX(s.points, {x: "x", y1: "q1", y2: "q3", stroke: "line", strokeWidth: 2, strokeOpacity: 0.5}),
        window.Plot.line(s.points, {x: "x", y: "median", z: "line", stroke: "line"}),
        window.Plot.dot(s.points, {x: "x", y: "median", fill: "line", r: 4, title: p => `${p.config}: median of ${p.runs} runs`}),
      ],
    });
    return {plot, caption: "median and interquartile range of the usable runs", drawn: {kind: "sweep", metric, param, points: s.points}};
  }

  function scatterPlot(runs, metric) {
    const versus = $("plots-versus").value;
    const points = runs.filter(r => r.usable && r.value !== null && r.versus !== null), configs = configsOf(runs);
    const plot = window.Plot.plot({
      marginLeft: 70, width: chartWidth(), height: 440, x: {...axis(versus), grid: true}, y: {...axis(metric), grid: true},
      color: {domain: configs, legend: true},
      marks: [window.Plot.dot(points, {x: "versus", y: "value", fill: "config", r: 3, fillOpacity: 0.8, title: "config"})],
    });
    return {plot, drawn: {kind: "scatter", metric, versus, points: points.map(p => ({config: p.config, x: p.versus, y: p.value}))}};
  }

  const DRAW = {box: boxPlot, ecdf: ecdfPlot, profile: profilePlot, sweep: sweepPlot, scatter: scatterPlot};

  function draw() {
    const chart = $("plots-chart");
    chart.replaceChildren();
    state.drawn = null;
    state.figure = null;
    if (!state.data) return;
    const kind = $("plots-kind").value, metric = state.data.metric, runs = chosenRuns();
    if (!runs.length) {
      note("The filters select no run of this dataset and tool.");
      return;
    }
    const r = DRAW[kind](runs, metric);
    if (r.message) {
      note(r.message);
      return;
    }
    const usable = summarised(runs).length;
    note(`${$("plots-dataset").value}, tool ${$("plots-tool").value}: ${runs.length} runs, ${usable} usable with a value` +
         (r.caption ? `; ${r.caption}` : ""));
    chart.append(r.plot);
    state.figure = r.plot;
    state.drawn = {...r.drawn, dataset: $("plots-dataset").value, tool: $("plots-tool").value};
  }

  // --- downloads ----------------------------------------------------------------------------------

  /** The plot as one SVG file: the chart, and its colour legend drawn below it. */
  function svgText() {
    const fig = state.figure;
    if (!fig) return "";
    const main = fig.tagName.toLowerCase() === "svg" ? fig : fig.querySelector(":scope > svg");
    const svg = main.cloneNode(true);
    const w = Number(main.getAttribute("width")), h = Number(main.getAttribute("height"));
    const ns = "http://www.w3.org/2000/svg";
    let height = h;
    if (fig !== main && fig.scale("color")) {
      const c = fig.scale("color");
      c.domain.forEach((name, k) => {
        const y = h + 8 + 18 * k;
        const rect = document.createElementNS(ns, "rect");
        for (const [a, v] of Object.entries({x: 20, y, width: 12, height: 12, fill: fig.scale("color").apply(name)})) rect.setAttribute(a, String(v));
        const text = document.createElementNS(ns, "text");
        for (const [a, v] of Object.entries({x: 38, y: y + 10, "font-size": 12, "font-family": "sans-serif", "text-anchor": "start"})) text.setAttribute(a, String(v));
        text.textContent = name;
        svg.append(rect, text);
        height = y + 18;
      });
    }
    svg.setAttribute("xmlns", ns);
    svg.setAttribute("height", String(height));
    svg.setAttribute("viewBox", `0 0 ${w} ${height}`);
    svg.style.background = "white";
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + new XMLSerializer().serializeToString(svg);
  }

  /** The SVG drawn at twice its size on a white canvas, as PNG. @returns {Promise<Blob>} */
  async function pngBlob() {
    const text = svgText();
    if (!text) throw new Error("no plot is shown");
    const url = URL.createObjectURL(new Blob([text], {type: "image/svg+xml"}));
    try {
      const img = new Image();
      await new Promise((resolve, reject) => { img.onload = resolve; img.onerror = () => reject(new Error("the SVG did not load as an image")); img.src = url; });
      const canvas = document.createElement("canvas");
      canvas.width = 2 * img.width;
      canvas.height = 2 * img.height;
      const ctx = canvas.getContext("2d");
      ctx.fillStyle = "white";
      ctx.fillRect(0, 0, canvas.width, canvas.height);
      ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
      return await new Promise((resolve, reject) => canvas.toBlob(b => b ? resolve(b) : reject(new Error("no PNG")), "image/png"));
    } finally {
      URL.revokeObjectURL(url);
    }
  }

  function save(blob, ext) {
    if (!state.drawn) return;
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob);
    a.download = `${state.drawn.kind}-${state.drawn.metric}-${$("plots-dataset").value}.${ext}`.replace(/[^\w.-]+/g, "_");
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  }

  window.coverbenchPlots = {show, drawn: () => state.drawn, figure: () => state.figure, svgText, pngBlob};
})();
