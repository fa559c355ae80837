// The explorer's compare view (explorer.js opens it): runs on one wall side by side, their
// pictures played on one clock (the time models' seconds) with one play button, one speed and one
// time slider for all, a readout of the time and its share of the longest run, and the runs'
// metrics in one table with the better value of each marked (the metric registry's `better`:
// +1 higher, -1 lower, 0 not compared; values within its tie tolerances count as equal). Each picture's own player is held paused and set to the
// clock's time on every frame, so all the playheads show the same moment. The user's change of
// the speed is sent from the viewer as the event "coverbench:speed" ({speed}), as the player
// sends its own (player.js). A run with no other on its wall is shown with a line saying so.
"use strict";
(function () {
  const SPEEDS = [0.25, 0.5, 1, 2, 5, 10, 20];
  const DEFAULT_SPEED = 5;

  function fmt(s) {
    return s < 60 ? s.toFixed(1) + " s" : Math.floor(s / 60) + " min " + String(Math.floor(s % 60)).padStart(2, "0") + " s";
  }

  /** Starts each figure's player and holds it paused at 0; resolves with the players made. */
  async function startPlayers(figures, alive) {
    for (const f of figures) {
      if (!f.dataset.playback) continue;
      window.coverbenchAttachPlayer(f);
      /** @type {HTMLButtonElement} */ (f.querySelector(".player-start")).click();
    }
    for (let k = 0; k < 2400 && alive() && figures.some(f => f.dataset.playback && !f.coverbenchPlayer); ++k)
      await new Promise(r => setTimeout(r, 25));
    const players = [];
    for (const f of figures) if (f.coverbenchPlayer) { f.coverbenchPlayer.pause(); f.coverbenchPlayer.seek(0); players.push(f.coverbenchPlayer); }
    return players;
  }

  /**
   * The shared clock over `players`: its bar (play, speed, slider, readout) and its controls.
   * @param {CoverbenchPlayer[]} players
   * @param {HTMLElement} viewer
   * @param {number | null} initial the speed it starts at (null: the default)
   * @returns {{bar: HTMLElement, all: CoverbenchCompare}}
   */
  function clockFor(players, viewer, initial) {
    const start = initial !== null && SPEEDS.includes(initial) ? initial : DEFAULT_SPEED;
    const longest = Math.max(0, ...players.map(p => p.duration()));
    const bar = document.createElement("div");
    bar.className = "player-bar compare-bar";
    const button = document.createElement("button");
    button.type = "button";
    button.className = "compare-play";
    const speed = document.createElement("select");
    speed.title = "speed, times the time models'";
    speed.setAttribute("aria-label", "speed");
    for (const s of SPEEDS) speed.add(new Option(s + "x", String(s), s === start, s === start));
    const scrub = document.createElement("input");
    scrub.type = "range";
    scrub.min = "0";
    scrub.max = String(longest);
    scrub.step = "any";
    scrub.title = "time (the time models' seconds)";
    scrub.setAttribute("aria-label", "time");
    const clock = document.createElement("span");
    clock.className = "player-clock compare-clock";
    clock.setAttribute("aria-live", "off");
    bar.append(button, speed, scrub, clock);

    let time = 0, rate = start, playing = false, anchorTime = 0, anchorClock = 0, raf = 0;
    function draw() {
      for (const p of players) p.seek(time);
      scrub.value = String(time);
      const share = longest > 0 ? Math.round(100 * time / longest) : 0;
      clock.textContent = `${fmt(time)} / ${fmt(longest)} (${share} % of the longest run)`;
      button.textContent = playing ? "\u275a\u275a pause all" : "\u25b6 play all";
      viewer.dataset.clock = time.toFixed(3);
    }
    function tick(now) {
      if (!playing) return;
      time = Math.min(longest, anchorTime + Math.max(0, now - anchorClock) / 1000 * rate);
      if (time >= longest) playing = false;
      draw();
      if (playing) raf = requestAnimationFrame(tick);
    }
    const anchor = () => { anchorTime = time; anchorClock = performance.now(); };
    /** @type {CoverbenchCompare} */
    const all = {
      players,
      play() {
        if (time >= longest) time = 0;
        playing = true;
        anchor();
        cancelAnimationFrame(raf);
        raf = requestAnimationFrame(tick);
        draw();
      },
      pause() { playing = false; cancelAnimationFrame(raf); draw(); },
      toggle() { if (playing) all.pause(); else all.play(); },
      seek(t) { time = Math.max(0, Math.min(longest, t)); anchor(); draw(); },
      setSpeed(s) { anchor(); rate = s; speed.value = String(s); },
      time: () => time,
      speed: () => rate,
      duration: () => longest,
      playing: () => playing,
      times: () => players.map(p => p.time()),
    };
    button.addEventListener("click", () => all.toggle());
    speed.addEventListener("change", () => {
      all.setSpeed(Number(speed.value));
      viewer.dispatchEvent(new CustomEvent("coverbench:speed", {bubbles: true, detail: {speed: rate}}));
    });
    scrub.addEventListener("input", () => all.seek(Number(scrub.value)));
    draw();
    return {bar, all};
  }

  /**
   * The runs' metrics side by side: a row a metric (the registry's order, then any it does not
   * know), a column a run; the better value of each row marked where the registry gives a direction.
   * @param {any[]} runs
   * @param {Map<string, any>} specs
   * @param {(name: string, v: number) => string} formatted
   */
  function metricsTable(runs, specs, formatted) {
    const table = document.createElement("table");
    table.className = "compare-metrics";
    const caption = table.createCaption();
    caption.textContent = "Metrics side by side; \u2605 marks the better value (the metric registry's direction).";
    const head = table.createTHead().insertRow();
    const corner = document.createElement("th");
    corner.textContent = "metric";
    corner.className = "text";
    corner.scope = "col";
    head.appendChild(corner);
    for (const run of runs) {
      const th = document.createElement("th");
      th.scope = "col";
      th.textContent = run.planner;
      th.title = Object.entries(run.params).map(([k, v]) => `${k}=${v}`).join(", ");
      head.appendChild(th);
    }
    const body = table.createTBody();
    const status = body.insertRow();
    const statusHead = document.createElement("th");
    statusHead.scope = "row";
    statusHead.className = "text";
    statusHead.textContent = "status";
    status.appendChild(statusHead);
    for (const run of runs) status.insertCell().textContent = run.status;
    const present = new Set(runs.flatMap(r => Object.keys(r.metrics)));
    const names = [...[...specs.keys()].filter(k => present.has(k)), ...[...present].filter(k => !specs.has(k))];
    for (const name of names) {
      const row = body.insertRow();
      row.dataset.metric = name;
      const th = document.createElement("th");
      th.scope = "row";
      th.className = "text";
      th.textContent = name;
      th.title = specs.get(name)?.description || name;
      row.appendChild(th);
      const values = runs.map(r => r.metrics[name]);
      const known = values.filter(v => v !== undefined && v !== null);
      const spec = specs.get(name), better = spec?.better || 0;
      const best = better > 0 ? Math.max(...known) : Math.min(...known);
      // Equal as the report's statistics say (stats.py): within the registry's tie tolerances.
      const tied = v => Math.abs(v - best) <= (spec?.tie_absolute || 0) + (spec?.tie_relative || 0) * Math.max(Math.abs(v), Math.abs(best));
      const marked = better !== 0 && known.length >= 2 && !known.every(tied);
      for (const v of values) {
        const td = row.insertCell();
        td.textContent = formatted(name, v);
        if (v !== undefined && v !== null) td.title = String(v);
        if (marked && v !== undefined && v !== null && tied(v)) {
          td.className = "better";
          td.append(" \u2605");
        }
      }
    }
    return table;
  }

  /**
   * Opens the comparison of `runs` in `viewer`, held at `t` s and played at `speed`: resolves with
   * its controls once every picture's player is ready (or with null when `alive()` turns false first).
   * @param {HTMLElement} viewer
   * @param {any[]} runs
   * @param {{figureFor: (run: any) => HTMLElement, formatted: (name: string, v: number) => string, specs: Map<string, any>, t: number | null, speed: number | null, alive: () => boolean}} ctx
   * @returns {Promise<CoverbenchCompare | null>}
   */
  async function open(viewer, runs, ctx) {
    viewer.textContent = "";
    const title = document.createElement("h2");
    title.className = "compare-title";
    title.textContent = `${runs.length} run${runs.length === 1 ? "" : "s"} on ${runs[0].wall_name} (${runs[0].dataset}), tool ${runs[0].tool}`;
    const grid = document.createElement("div");
    grid.className = "compare";
    const figures = runs.map(ctx.figureFor);
    grid.append(...figures);
    const wait = document.createElement("p");
    wait.className = "compare-wait";
    wait.textContent = "loading the paths\u2026";
    viewer.append(title);
    if (runs.length === 1) {
      const none = document.createElement("p");
      none.className = "compare-none";
      none.setAttribute("role", "status");
      none.textContent = `No other planner ran on this wall in this experiment with tool ${runs[0].tool}: there is nothing to compare this run with.`;
      viewer.append(none);
    }
    viewer.append(wait, grid, metricsTable(runs, ctx.specs, ctx.formatted));
    const players = await startPlayers(figures, ctx.alive);
    if (!ctx.alive()) return null;
    const {bar, all} = clockFor(players, viewer, ctx.speed);
    wait.replaceWith(bar);
    if (ctx.t !== null) all.seek(ctx.t);
    viewer.coverbenchCompare = all;
    return all;
  }

  window.coverbenchCompareView = {open};
})();
