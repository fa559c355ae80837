// CoverBench's path player: plays a gallery picture's path back in place, from disk, with no
// server. A figure with data-playback="gallery/NAME.js" gets a play button; its data (written
// by `coverbench report`, see playbackScript in reports/src/svg.cpp) is loaded on the first
// click, and a canvas over the picture shows the paint accumulate under the run's own time
// model, the tool-off moves apart from it, and the tool where it is. Between two waypoints the
// tool moves at the mean speed the time model gives that segment.
//
// Each player is reachable as figure.coverbenchPlayer (play, pause, seek, setSpeed, time,
// playing, duration, frames, drawMs) for the browser tests and bench/playback_fps.py, and each picture's
// pan and zoom as figure.coverbenchZoom (set, zoom, view). A page that keeps these in its address
// (the explorer) sets the speed a player starts at with figure.dataset.speed, and hears the
// user's own changes as the events "coverbench:speed" ({speed}) and "coverbench:zoom" ({zoom,
// gesture: true for the wheel}), sent from the figure; changes made through the API send none.
"use strict";
(function () {
  const SPEEDS = [0.25, 0.5, 1, 2, 5, 10, 20];
  const DEFAULT_SPEED = 5;
  const ARC_STEPS = 24;  // chords per arc on the canvas (the picture beneath has them within 1 mm)
  const loaded = new Map();  // data file -> decoded data
  const waiting = new Map();  // data file -> callbacks

  // The data file calls this.
  window.coverbenchPlayback = function (raw) {
    loaded.set(raw.id, decode(raw));
    for (const done of waiting.get(raw.id) || []) done();
    waiting.delete(raw.id);
  };

  function load(src, done, failed) {
    if (loaded.has(src)) return done();
    if (waiting.has(src)) return void waiting.get(src).push(done);
    waiting.set(src, [done]);
    const script = document.createElement("script");
    script.src = src;
    script.onerror = () => { waiting.delete(src); failed(); };
    document.head.appendChild(script);
  }

  // Base-64 varints (zigzag, 5 bits a character, lowest first; 32 added: more follow) to the
  // running sums of the steps they hold, divided by `unit`.
  const DIGITS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  function sums(text, unit) {
    const out = [];
    let sum = 0, z = 0, shift = 0;
    for (let k = 0; k < text.length; ++k) {
      const c = DIGITS.indexOf(text[k]);
      z += (c & 31) * 2 ** shift;
      shift += 5;
      if (c & 32) continue;
      sum += z % 2 ? -(z + 1) / 2 : z / 2;
      out.push(sum / unit);
      z = 0;
      shift = 0;
    }
    return Float64Array.from(out);
  }

  // Positions in pixels, the time model's arrival times in seconds.
  function decode(raw) {
    const x = sums(raw.x, 10), y = sums(raw.y, 10), t = sums(raw.t, 100);
    const n = t.length;
    const wait = new Float64Array(Math.max(n - 1, 0)), bulge = new Float64Array(Math.max(n - 1, 0));
    for (const [i, cs] of raw.waits) wait[i] = cs / 100;
    for (const [i, b] of raw.arcs) bulge[i] = b / 1e6;
    return {x, y, t, wait, bulge, on: raw.on, end: raw.end_cs / 100, size: raw.size,
            toolPx: raw.tool_px, lifts: raw.lifts, model: raw.model, bad: raw.bad || []};
  }

  // The point a fraction f along segment i (an arc by its bulge: tan of a quarter of its angle).
  function pointOn(d, i, f) {
    const ax = d.x[i], ay = d.y[i], bx = d.x[i + 1], by = d.y[i + 1], b = d.bulge[i];
    if (b === 0) return [ax + (bx - ax) * f, ay + (by - ay) * f];
    const cx = (bx - ax), cy = (by - ay), c = Math.hypot(cx, cy);
    const phi = 4 * Math.atan(b);
    // The centre lies off the chord's midpoint along its normal; in the picture's y-down frame a
    // positive bulge turns clockwise on screen, whose centre is on the chord's right-hand side.
    const off = c * (1 - b * b) / (4 * b);
    const nx = cy / c, ny = -cx / c;  // left-hand normal in a y-up frame, drawn y-down
    const ox = (ax + bx) / 2 - nx * off, oy = (ay + by) / 2 - ny * off;
    const r = Math.hypot(ax - ox, ay - oy);
    const a0 = Math.atan2(ay - oy, ax - ox);
    const a = a0 + phi * f;
    return [ox + r * Math.cos(a), oy + r * Math.sin(a)];
  }

  function traceSegment(ctx, d, i, f) {
    if (d.bulge[i] === 0) {
      ctx.lineTo(d.x[i] + (d.x[i + 1] - d.x[i]) * f, d.y[i] + (d.y[i + 1] - d.y[i]) * f);
      return;
    }
    const steps = Math.max(1, Math.ceil(ARC_STEPS * f));
    for (let k = 1; k <= steps; ++k) ctx.lineTo(...pointOn(d, i, f * k / steps));
  }

  // The segment the tool is on at time s (the last one whose start is at or before s).
  function segmentAt(d, s) {
    let lo = 0, hi = d.t.length - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (d.t[mid] <= s) lo = mid; else hi = mid;
    }
    return lo;
  }

  function fmt(s) {
    return s < 60 ? s.toFixed(1) + " s" : Math.floor(s / 60) + " min " + String(Math.floor(s % 60)).padStart(2, "0") + " s";
  }

  function makePlayer(figure, d) {
    const link = figure.querySelector("a") || figure.querySelector("img");
    const holder = document.createElement("div");
    holder.className = "player-stage";
    link.replaceWith(holder);
    holder.appendChild(link);
    const canvas = document.createElement("canvas");
    canvas.className = "player-canvas";
    canvas.width = Math.round(d.size[0]);
    canvas.height = Math.round(d.size[1]);
    holder.appendChild(canvas);
    const paint = document.createElement("canvas");  // what has been driven so far, at full opacity
    paint.width = canvas.width;
    paint.height = canvas.height;
    const ctx = canvas.getContext("2d"), pctx = paint.getContext("2d");

    const bar = document.createElement("div");
    bar.className = "player-bar";
    const button = document.createElement("button");
    button.type = "button";
    const speed = document.createElement("select");
    speed.title = "speed, times the time model's";
    speed.setAttribute("aria-label", "speed");
    const initial = SPEEDS.includes(Number(figure.dataset.speed)) ? Number(figure.dataset.speed) : DEFAULT_SPEED;
    for (const s of SPEEDS) speed.add(new Option(s + "x", String(s), s === initial, s === initial));
    const scrub = document.createElement("input");
    scrub.type = "range";
    scrub.min = "0";
    scrub.max = String(d.end);
    scrub.step = "any";
    scrub.value = "0";
    scrub.title = "time";
    scrub.setAttribute("aria-label", "time");
    const clock = document.createElement("span");
    clock.className = "player-clock";
    bar.append(button, speed, scrub, clock);
    (holder.closest(".zoom-view") || holder).after(bar);  // the controls stay out of the zoomed view
    const model = document.createElement("small");
    model.className = "player-model";
    model.textContent = "time model: " + d.model;
    bar.after(model);

    // The canvases' resolution follows the zoom (up to 8x, and 16,000 pixels a side), so a
    // zoomed picture's paint is as sharp as the picture beneath.
    function rescale(zoom) {
      const k = Math.max(1, Math.min(zoom, 8, 16000 / Math.max(d.size[0], d.size[1])));
      for (const c of [canvas, paint]) {
        c.width = Math.round(d.size[0] * k);
        c.height = Math.round(d.size[1] * k);
      }
      ctx.setTransform(k, 0, 0, k, 0, 0);
      pctx.setTransform(k, 0, 0, k, 0, 0);
      drawn = 0;
    }
    let time = 0, rate = initial, playing = false, anchorTime = 0, anchorClock = 0;
    let drawn = 0;  // segments painted onto `paint`
    let frames = 0;

    function styleFor(i, c) {
      if (d.on[i] === "1") {
        c.strokeStyle = "#2f6fd0";
        c.lineWidth = Math.max(d.toolPx, 1);
        c.lineCap = "round";
        c.lineJoin = "round";
        c.setLineDash([]);
      } else {
        c.strokeStyle = d.lifts ? "#8e44ad" : "#e07b00";
        c.lineWidth = 2;
        c.lineCap = "butt";
        c.setLineDash(d.lifts ? [2, 3] : [5, 3]);
      }
    }
    // Paints segments [from, to) in runs of one tool state.
    function paintSegments(from, to) {
      for (let i = from; i < to;) {
        let j = i;
        styleFor(i, pctx);
        pctx.beginPath();
        pctx.moveTo(d.x[i], d.y[i]);
        while (j < to && d.on[j] === d.on[i]) traceSegment(pctx, d, j++, 1);
        pctx.stroke();
        i = j;
      }
    }
    let drawMs = 0;  // time spent drawing, for the frame-rate benchmark (bench/playback_fps.py)
    function draw() {
      const started = performance.now();
      drawFrame();
      drawMs += performance.now() - started;
    }
    function drawFrame() {
      ++frames;
      const i = segmentAt(d, time);
      const last = d.t.length - 1;
      const done = i >= last;
      if (i < drawn) {
        pctx.clearRect(0, 0, d.size[0], d.size[1]);
        drawn = 0;
      }
      const full = done ? last : i;
      if (full > drawn) {
        paintSegments(drawn, full);
        drawn = full;
      }
      // Where on segment i the tool is: waiting at its start, then along it.
      let tx = d.x[Math.min(i, last)], ty = d.y[Math.min(i, last)];
      ctx.clearRect(0, 0, d.size[0], d.size[1]);
      ctx.fillStyle = "rgba(255,255,255,0.72)";  // the whole path beneath, faded
      ctx.fillRect(0, 0, d.size[0], d.size[1]);
      ctx.globalAlpha = 0.5;
      ctx.save();
      ctx.setTransform(1, 0, 0, 1, 0, 0);  // both canvases are at the same resolution
      ctx.drawImage(paint, 0, 0);
      ctx.restore();
      if (!done) {
        const depart = d.t[i] + d.wait[i], span = d.t[i + 1] - depart;
        const f = time <= depart || span <= 0 ? 0 : Math.min(1, (time - depart) / span);
        if (f > 0) {
          styleFor(i, ctx);
          ctx.beginPath();
          ctx.moveTo(d.x[i], d.y[i]);
          traceSegment(ctx, d, i, f);
          ctx.stroke();
          [tx, ty] = pointOn(d, i, f);
        }
      }
      ctx.globalAlpha = 1;
      ctx.setLineDash([]);
      if (d.bad.length) {  // segments that fail the validity check, marked at every moment
        ctx.strokeStyle = "#ff0000";
        ctx.lineWidth = 4;
        ctx.lineCap = "round";
        ctx.beginPath();
        for (const b of d.bad) {
          ctx.moveTo(d.x[b], d.y[b]);
          traceSegment(ctx, d, b, 1);
        }
        ctx.stroke();
      }
      ctx.beginPath();
      ctx.arc(tx, ty, Math.max(d.toolPx / 2, 3), 0, 2 * Math.PI);
      ctx.fillStyle = "rgba(208,47,47,0.35)";
      ctx.fill();
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = "#d02f2f";
      ctx.stroke();
      scrub.value = String(time);
      clock.textContent = fmt(time) + " / " + fmt(d.end);
      button.textContent = playing ? "\u275a\u275a pause" : "\u25b6 play";
      figure.dataset.playhead = time.toFixed(3);
    }
    let raf = 0;  // the one pending animation frame, so that a pause and a play never leave two
    let lastFrame = 0;  // the clock (performance.now()) of the last frame drawn while playing
    function tick(now) {
      if (!playing) return;
      lastFrame = now;
      // A frame's time stamp may be earlier than the moment play was pressed: never before it.
      time = Math.min(d.end, anchorTime + Math.max(0, now - anchorClock) / 1000 * rate);
      if (time >= d.end) playing = false;
      draw();
      if (playing) raf = requestAnimationFrame(tick);
    }
    const api = {
      play() {
        if (time >= d.end) time = 0;
        playing = true;
        anchorTime = time;
        anchorClock = performance.now();
        draw();
        cancelAnimationFrame(raf);
        raf = requestAnimationFrame(tick);
      },
      pause() {
        playing = false;
        cancelAnimationFrame(raf);
        draw();
      },
      seek(s) {
        time = Math.max(0, Math.min(d.end, s));
        anchorTime = time;
        anchorClock = performance.now();
        draw();
      },
      setSpeed(s) {
        anchorTime = time;
        anchorClock = performance.now();
        rate = s;
        speed.value = String(s);
      },
      time: () => time,
      playing: () => playing,
      speed: () => rate,
      duration: () => d.end,
      frames: () => frames,
      lastFrame: () => lastFrame,
      drawMs: () => drawMs,
      waypoints: () => d.t.length,
      marked: () => d.bad.length,
      rescale(zoom) { rescale(zoom); draw(); },
    };
    button.addEventListener("click", () => (playing ? api.pause() : api.play()));
    speed.addEventListener("change", () => {
      api.setSpeed(Number(speed.value));
      figure.dispatchEvent(new CustomEvent("coverbench:speed", {bubbles: true, detail: {speed: rate}}));
    });
    scrub.addEventListener("input", () => api.seek(Number(scrub.value)));
    figure.coverbenchPlayer = api;
    rescale(Number(figure.dataset.zoom || 1));
    draw();
    return api;
  }

  // Pan and zoom: the picture (and the player's canvas over it) in a view that zooms from 1x to
  // 32x with the buttons or Ctrl + wheel (about the pointer), and pans by dragging or scrolling.
  // The picture is laid out larger, not scaled, so the SVG is drawn again at each zoom.
  function zoomable(figure) {
    if (figure.querySelector(".zoom-view")) return;
    const pic = figure.querySelector("a") || figure.querySelector("img");
    if (!pic) return;
    const view = document.createElement("div"), inner = document.createElement("div");
    view.className = "zoom-view";
    inner.className = "zoom-inner";
    pic.replaceWith(view);
    view.appendChild(inner);
    inner.appendChild(pic);
    for (const img of figure.querySelectorAll("img")) img.draggable = false;
    const tools = document.createElement("div");
    tools.className = "zoom-tools";
    let zoom = 1;
    function setZoom(z, cx, cy) {
      z = Math.max(1, Math.min(32, z));
      if (zoom === 1 && z > 1) view.style.height = view.clientHeight + "px";  // the view keeps its size
      const w = view.clientWidth, h = view.clientHeight;
      if (cx === undefined) { cx = w / 2; cy = h / 2; }
      const fx = (view.scrollLeft + cx) / inner.offsetWidth, fy = (view.scrollTop + cy) / inner.offsetHeight;
      zoom = z;
      inner.style.width = 100 * z + "%";
      if (z === 1) view.style.height = "";
      view.scrollLeft = fx * inner.offsetWidth - cx;
      view.scrollTop = fy * inner.offsetHeight - cy;
      figure.dataset.zoom = String(z);
      if (figure.coverbenchPlayer) figure.coverbenchPlayer.rescale(z);
      label.textContent = z === 1 ? "" : z.toFixed(z < 10 ? 1 : 0) + "x";
    }
    /** The user's zoom: set, and told to the page when it changed. */
    function userZoom(z, cx, cy, gesture) {
      const before = zoom;
      setZoom(z, cx, cy);
      if (zoom !== before) figure.dispatchEvent(new CustomEvent("coverbench:zoom", {bubbles: true, detail: {zoom, gesture}}));
    }
    const button = (text, title, f) => {
      const b = document.createElement("button");
      b.type = "button";
      b.textContent = text;
      b.title = title;
      b.addEventListener("click", f);
      tools.appendChild(b);
      return b;
    };
    button("+", "zoom in (or Ctrl + wheel)", () => userZoom(zoom * 2)).className = "zoom-in";
    button("\u2212", "zoom out", () => userZoom(zoom / 2)).className = "zoom-out";
    button("fit", "the whole picture", () => userZoom(1)).className = "zoom-fit";
    const label = document.createElement("span");
    tools.appendChild(label);
    view.before(tools);
    view.addEventListener("wheel", e => {
      if (!e.ctrlKey) return;
      e.preventDefault();
      const r = view.getBoundingClientRect();
      userZoom(zoom * Math.pow(2, -e.deltaY / 300), e.clientX - r.left, e.clientY - r.top, true);
    }, {passive: false});
    let drag = null, moved = false;
    view.addEventListener("pointerdown", e => {
      if (zoom === 1 || e.button !== 0) return;
      drag = {x: e.clientX, y: e.clientY, left: view.scrollLeft, top: view.scrollTop};
      moved = false;
      view.setPointerCapture(e.pointerId);
      e.preventDefault();
    });
    view.addEventListener("pointermove", e => {
      if (!drag) return;
      if (Math.abs(e.clientX - drag.x) + Math.abs(e.clientY - drag.y) > 3) moved = true;
      view.scrollLeft = drag.left - (e.clientX - drag.x);
      view.scrollTop = drag.top - (e.clientY - drag.y);
    });
    view.addEventListener("pointerup", () => { drag = null; });
    view.addEventListener("click", e => { if (moved) { e.preventDefault(); moved = false; } }, true);  // a drag is not a click
    figure.coverbenchZoom = {set: setZoom, zoom: () => zoom, view};
  }

  function attach(figure) {
    zoomable(figure);
    const start = document.createElement("button");
    start.type = "button";
    start.className = "player-start";
    start.textContent = "\u25b6 play the path";
    figure.appendChild(start);
    start.addEventListener("click", () => {
      start.disabled = true;
      const src = figure.dataset.playback;
      load(src, () => {
        const focused = document.activeElement === start;
        start.remove();
        makePlayer(figure, loaded.get(src)).play();
        // The focus stays where it was: on the play button that took the start button's place.
        if (focused) figure.querySelector(".player-bar button")?.focus();
      }, () => {
        start.textContent = "playback data missing: " + src;
      });
    });
  }

  // The player's own look, added once to whichever page loads it.
  const STYLE = `
.player-stage{position:relative}
.player-stage a,.player-stage img{display:block}
.player-canvas{position:absolute;left:0;top:0;width:100%;height:100%;pointer-events:none}
.player-bar{display:flex;gap:6px;align-items:center;font-size:12px;margin:3px 0}
.player-bar input[type=range]{flex:1;min-width:60px}
.player-clock{font-variant-numeric:tabular-nums;white-space:nowrap}
.player-model{display:block;color:#555;font-size:11px}
.player-start{font-size:12px;margin:3px 0}
.zoom-view{overflow:auto;position:relative;cursor:default}
.zoom-view[style*=height]{cursor:grab}
.zoom-inner{width:100%}
.zoom-inner img{width:100%;height:auto}
.zoom-tools{display:flex;gap:4px;align-items:center;font-size:12px;margin:2px 0}
.zoom-tools button{font-size:12px;min-width:2em;padding:0 6px}`;

  function init() {
    const style = document.createElement("style");
    style.textContent = STYLE;
    document.head.appendChild(style);
    for (const figure of document.querySelectorAll("figure[data-playback]")) attach(figure);
  }
  // For pages that add figures later (the explorer, `coverbench serve`).
  window.coverbenchAttachPlayer = attach;
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", init);
  else init();
})();
