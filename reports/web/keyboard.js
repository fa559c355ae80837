// The explorer's keys (the runs table's own, Enter on a row and on a heading's button, are in
// explorer.js): Space plays and pauses the open player, or the compare view's shared clock;
// Left and Right move it 1 s back or on (with Shift, 10 s); the "skip to the player" link takes
// the focus to the play button. None acts while the focus is in a field that takes typing, and
// Space leaves buttons, links and ticks to do their own thing.
"use strict";
(function () {
  const $ = id => document.getElementById(id);
  const TYPING = new Set(["INPUT", "TEXTAREA", "SELECT"]);
  const OWN_SPACE = new Set(["BUTTON", "A", "SUMMARY"]);

  /** The visible tab's viewer: the explorer's or the workbench's plan. @returns {HTMLElement} */
  function viewer() {
    return $("experiments").hidden ? $("wb-result") : $("viewer");
  }
  /** The control in charge: the compare view's clock or the open run's player, and its figure. */
  function target() {
    const v = viewer();
    if (v.coverbenchCompare) return {player: v.coverbenchCompare, figure: null};
    const figure = /** @type {HTMLElement | null} */ (v.querySelector("figure[data-playback]"));
    return {player: figure?.coverbenchPlayer || null, figure};
  }
  /** The play button (the compare's, the player's, or the one that starts it), if any. @returns {HTMLElement | null} */
  function playButton() {
    const v = viewer();
    if (v.coverbenchCompare) return /** @type {HTMLElement | null} */ (v.querySelector(".compare-play"));
    return /** @type {HTMLElement | null} */ (v.querySelector("figure[data-playback] .player-bar button") || v.querySelector("figure[data-playback] .player-start"));
  }

  function toggle() {
    const {player, figure} = target();
    if (player) { if (player.playing()) player.pause(); else player.play(); return true; }
    const start = /** @type {HTMLButtonElement | null | undefined} */ (figure?.querySelector(".player-start"));
    if (start && !start.disabled) { start.click(); return true; }
    return false;
  }
  function scrub(seconds) {
    const {player} = target();
    if (!player) return false;
    player.seek(player.time() + seconds);
    return true;
  }

  /** @param {KeyboardEvent} e */
  function onKey(e) {
    if (e.ctrlKey || e.altKey || e.metaKey || e.defaultPrevented) return;
    const el = /** @type {HTMLElement} */ (e.target);
    const range = el instanceof HTMLInputElement && el.type === "range";
    if ((TYPING.has(el.tagName) && !range) || el.isContentEditable) return;
    let done = false;
    if (e.key === " " && !range && !OWN_SPACE.has(el.tagName)) done = toggle();
    else if (e.key === "ArrowLeft" || e.key === "ArrowRight") {
      if (range && !el.closest(".player-bar")) return;  // a slider of its own
      done = scrub((e.key === "ArrowLeft" ? -1 : 1) * (e.shiftKey ? 10 : 1));
    }
    if (done) e.preventDefault();
  }

  document.addEventListener("keydown", onKey);
  $("skip-player").addEventListener("click", e => {
    e.preventDefault();
    const button = playButton();
    if (button) button.focus();
    else { viewer().tabIndex = -1; viewer().focus(); }
  });
})();
