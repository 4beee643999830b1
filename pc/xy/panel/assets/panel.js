// The panel page (docs/panel.md): reads the state the server pushes (server-sent events),
// shows it, and turns the operator's actions into checked requests. A value that is not a
// number, is out of its range or too long is refused here with the reason and never sent;
// the ranges come from the codec's table the server hands out (/api/info).
"use strict";

const state = { timer: null, info: null, board: 0, boards: [], sleeping: false, hist: [], lastEvent: 0, held: {}, rotZero: 0, rot: null, rotHist: [] };
const $ = (id) => document.getElementById(id);

async function post(path, body) {
  const r = await fetch(path, { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
  let j = {};
  try { j = await r.json(); } catch (e) { j = { ok: false, error: "no answer from the panel" }; }
  if (!j.ok) refuse(j.error || j.reply || "refused");
  return j;
}

function refuse(why) { $("refusal").textContent = why; }
function clearRefusal() { $("refusal").textContent = ""; }

function command(key) { return state.info.commands.find((c) => c.key === key); }

// mm (up to 3 decimals) -> integer micrometres within the command's range; the reason otherwise.
function micrometres(text, key, label) {
  const t = text.trim();
  if (t.length === 0) return { error: label + ": empty" };
  if (t.length > 12) return { error: label + ": longer than 12 characters" };
  if (!/^[-+]?\d+([.,]\d{1,3})?$/.test(t)) return { error: label + ": '" + t + "' is not a number in mm (up to 3 decimals)" };
  const um = Math.round(parseFloat(t.replace(",", ".")) * 1000);
  const c = command(key);
  if (um < c.min || um > c.max) {
    return { error: label + ": " + t + " mm outside " + (c.min / 1000) + " .. " + (c.max / 1000) + " mm (" + c.meaning + ")" };
  }
  return { um };
}

function speedLevel() { return $("speed-slow").checked ? 1 : 2; }

async function send(part, key, data) {
  clearRefusal();
  return post("/api/command", { board: state.board, part, key, data });
}

// ---- the Menu switches the dynamic panel ----
function showPanel(name) {
  for (const d of document.querySelectorAll(".dyn")) d.classList.toggle("shown", d.id === "panel-" + name);
  for (const b of document.querySelectorAll(".menu")) b.classList.toggle("active", b.dataset.panel === name);
}

// ---- manual: held buttons and arrow keys ----
async function hold(axis, dir) {
  const level = dir * speedLevel();
  if (state.held[axis] === level) return;
  state.held[axis] = level;
  clearRefusal();
  await post("/api/hold", { board: state.board, axis, level });
}
async function release(axis) {
  if (!state.held[axis]) return;
  state.held[axis] = 0;
  await post("/api/hold", { board: state.board, axis, level: 0 });
}
const keys = { ArrowLeft: [0, -1], ArrowRight: [0, 1], ArrowUp: [1, 1], ArrowDown: [1, -1] };

function setup() {
  for (const b of document.querySelectorAll(".menu")) b.addEventListener("click", () => showPanel(b.dataset.panel));
  showPanel("manual");
  for (const b of document.querySelectorAll(".jog")) {
    const axis = Number(b.dataset.axis), dir = Number(b.dataset.dir);
    b.addEventListener("mousedown", () => { if (!b.disabled) hold(axis, dir); });
    b.addEventListener("mouseup", () => release(axis));
    b.addEventListener("mouseleave", () => release(axis));
  }
  document.addEventListener("keydown", (e) => {
    if (e.shiftKey && (e.key === "V" || e.key === "v")) { $("dev").hidden = !$("dev").hidden; return; }
    const k = keys[e.key];
    if (!k || e.target.tagName === "INPUT" || e.repeat) return;
    e.preventDefault();
    if (state.sleeping || !connected()) return refuse(state.sleeping ? "the unit sleeps: wake it first" : "not connected");
    hold(k[0], k[1]);
  });
  document.addEventListener("keyup", (e) => { const k = keys[e.key]; if (k) release(k[0]); });
  $("home-x").addEventListener("click", () => send("x", "home", 0));
  $("home-y").addEventListener("click", () => send("y", "home", 0));
  $("stop").addEventListener("click", () => { send("x", "stop", 0); send("y", "stop", 0); });
  $("abs-go").addEventListener("click", () => {
    const slow = speedLevel() === 1;
    const x = micrometres($("abs-x").value, "goto", "X"), y = micrometres($("abs-y").value, "goto", "Y");
    if (x.error || y.error) return refuse(x.error || y.error);
    send("x", slow ? "goto_slow" : "goto", x.um);
    send("y", slow ? "goto_slow" : "goto", y.um);
  });
  $("rel-go").addEventListener("click", () => {
    const slow = speedLevel() === 1;
    const x = micrometres($("rel-x").value, "move", "X increment"), y = micrometres($("rel-y").value, "move", "Y increment");
    if (x.error || y.error) return refuse(x.error || y.error);
    if (x.um !== 0) send("x", slow ? "move_slow" : "move", x.um);
    if (y.um !== 0) send("y", slow ? "move_slow" : "move", y.um);
  });
  $("dyn-save").addEventListener("click", async () => {
    const f = micrometres($("dyn-fast").value, "fast", "Fast speed");
    const s = micrometres($("dyn-slow").value, "slow", "Slow speed");
    const a = micrometres($("dyn-accel").value, "accel", "Acceleration");
    if (f.error || s.error || a.error) return refuse(f.error || s.error || a.error);
    if (s.um > f.um) return refuse("Slow speed above the fast speed");
    // Saved to FRAM at once (thesis §8.2: the dynamics are kept automatically).
    await send("unit", "fast", f.um);
    await send("unit", "slow", s.um);
    await send("unit", "accel", a.um);
    await send("unit", "save", 0);
  });
  $("sleep").addEventListener("click", () => send("unit", state.sleeping ? "wake" : "sleep", 0));
  $("connect").addEventListener("click", () => post("/api/connect", { board: state.board, on: true }));
  $("disconnect").addEventListener("click", () => post("/api/connect", { board: state.board, on: false }));
  $("board-select").addEventListener("change", (e) => { state.board = Number(e.target.value); state.hist = []; });
  // developer extension
  const env = async (line) => { const j = await post("/api/env", { board: state.board, line }); $("dev-reply").textContent = line + ": " + (j.reply || j.error); };
  // Thesis §8.3: a timer that shows, every 100 ms, the message the UI's commands make (here the
  // frame the client last put on the wire, in the readable form of `axisproof frame`).
  $("dev-timer").addEventListener("click", () => {
    if (state.timer) { clearInterval(state.timer); state.timer = null; $("dev-timer").textContent = "Start the message timer"; return; }
    state.timer = setInterval(() => {
      const b = state.boards.find((x) => x.id === state.board);
      $("dev-frame").textContent = b && b.last_frame ? b.last_frame : "-";
    }, 100);
    $("dev-timer").textContent = "Stop the message timer";
  });
  $("rotation-zero").addEventListener("click", () => {
    if (state.rot !== null) { state.rotZero = state.rot; state.rotHist = []; }
  });
  $("dev-charger-on").addEventListener("click", () => env("charger 1"));
  $("dev-charger-off").addEventListener("click", () => env("charger 0"));
  $("dev-usb-on").addEventListener("click", () => env("usb 1"));
  $("dev-usb-off").addEventListener("click", () => env("usb 0"));
  $("dev-reboot").addEventListener("click", () => env("reboot"));
  $("dev-battery-set").addEventListener("click", () => {
    const t = $("dev-battery").value.trim();
    if (!/^\d{1,5}$/.test(t)) return refuse("Battery: '" + t + "' is not a whole number of mV");
    env("battery " + t);
  });
  $("dev-temp-set").addEventListener("click", () => {
    const t = $("dev-temp").value.trim();
    if (!/^-?\d{1,3}([.,]\d{1,3})?$/.test(t)) return refuse("Temperature: '" + t + "' is not a number of °C");
    env("temperature " + Math.round(parseFloat(t.replace(",", ".")) * 1000));
  });
  $("dev-echo").addEventListener("click", async () => {
    const p = micrometres($("dev-pos").value, "goto", "Simulated position");
    if (p.error) return refuse(p.error);
    await post("/api/simecho", { board: state.board, status: $("dev-status").value, data: p.um });
  });
}

function connected() {
  const b = state.boards.find((x) => x.id === state.board);
  return !!(b && b.connected);
}

function mm(um) { return (um / 1000).toFixed(3); }

function render(s) {
  state.boards = s.boards || [];
  const sel = $("board-select");
  const ids = state.boards.filter((b) => b.on_bus).map((b) => b.id);
  if (sel.options.length !== ids.length || [...sel.options].some((o, i) => Number(o.value) !== ids[i])) {
    sel.innerHTML = "";
    for (const id of ids) { const o = document.createElement("option"); o.value = id; o.textContent = "board " + id; sel.appendChild(o); }
    sel.value = String(state.board);
  }
  $("sim-time").textContent = ((s.t_us || 0) / 1e6).toFixed(2);
  const b = state.boards.find((x) => x.id === state.board);
  const ind = $("ble-indicator");
  if (!b || !b.on_bus) { ind.textContent = "board not on the bus"; ind.className = "ind warn"; }
  else if (!b.connected) { ind.textContent = "not connected"; ind.className = "ind off"; }
  else if (!b.in_range) { ind.textContent = "out of range"; ind.className = "ind warn"; }
  else { ind.textContent = "connected"; ind.className = "ind on"; }
  $("link-stats").textContent = b && b.connected && b.link
    ? "link: " + b.link.sent + " frames sent, " + b.link.retransmissions + " sent again" + (b.link.link_down ? ", link down" : "")
    : "";
  if (b && b.connected && b.axes) {
    for (const [i, n] of [[0, "x"], [1, "y"]]) {
      const a = b.axes[i];
      $(n + "-pos").textContent = mm(a.data);
      $(n + "-status").textContent = a.wording;
      $(n + "-status").dataset.status = a.status;
    }
    const sb = b.subs || {};
    $("battery").textContent = sb.battery_mv !== undefined ? sb.battery_mv + " mV" : "-";
    $("charge").textContent = sb.charge_ma !== undefined ? sb.charge_ma + " mA" : "-";
    $("temperature").textContent = sb.temperature_mc !== undefined ? (sb.temperature_mc / 1000).toFixed(1) + " °C" : "-";
    $("rotation").textContent = sb.rotation_mdeg !== undefined ? (sb.rotation_mdeg / 1000).toFixed(1) + "°" : "-";
    if (sb.rotation_mdeg !== undefined) {
      state.rot = sb.rotation_mdeg;
      state.rotHist.push(sb.rotation_mdeg - state.rotZero);
      if (state.rotHist.length > 600) state.rotHist.shift();
      $("rotation-rel").textContent = ((sb.rotation_mdeg - state.rotZero) / 1000).toFixed(1) + "°";
    }
    const p = b.params || {};
    if (p.fast !== undefined) $("p-fast").textContent = mm(p.fast);
    if (p.slow !== undefined) $("p-slow").textContent = mm(p.slow);
    if (p.accel !== undefined) $("p-accel").textContent = mm(p.accel);
    state.sleeping = b.axes[0].status === "sleeping" || b.axes[1].status === "sleeping";
    state.hist.push({ t: s.t_us / 1e6, x: b.axes[0].data, y: b.axes[1].data });
    if (state.hist.length > 600) state.hist.shift();
  }
  // Sleep locks the control buttons (thesis §8.2, the Static panel); Sleep itself turns to Wake.
  const lock = state.sleeping || !connected();
  for (const c of document.querySelectorAll(".control")) c.disabled = lock;
  $("sleep").textContent = state.sleeping ? "Wake" : "Sleep";
  $("sleep").disabled = !connected();
  $("lock").textContent = state.sleeping ? "controls locked: the unit sleeps" : "";
  $("lock").className = state.sleeping ? "ind warn" : "";
  for (const e of s.events || []) {
    state.lastEvent = Math.max(state.lastEvent, e.id);
    if (e.type === "outcome" && e.board === state.board) {
      const li = document.createElement("li");
      li.className = "outcome-" + e.outcome;
      li.dataset.command = e.command;
      li.dataset.outcome = e.outcome;
      li.textContent = e.part + " " + e.command + " " + e.data + ": " + e.outcome + " (" + e.status + ", " + e.transmissions + " transmission" + (e.transmissions === 1 ? "" : "s") + ")";
      $("outcomes").prepend(li);
    } else if (e.type === "connection" || e.type === "error" || e.type === "env") {
      const li = document.createElement("li");
      li.textContent = (e.board >= 0 ? "board " + e.board + ": " : "") + (e.what || (e.line + " -> " + e.reply));
      $("events").prepend(li);
    }
  }
  plot();
}

// Seed 000 §9.4.2: the rotation subscriber plotted in a graph that can be saved, a coordinate
// system turned by the angle, and a zero the user sets (on the PC side).
function plotRotation() {
  const c = $("plot-rotation"), g = c.getContext("2d");
  g.fillStyle = "#fff";
  g.fillRect(0, 0, c.width, c.height);
  const h = state.rotHist;
  if (h.length > 1) {
    let lo = Math.min(...h), hi = Math.max(...h);
    if (hi - lo < 1000) { hi += 500; lo -= 500; }
    g.fillStyle = "#333";
    g.fillText((hi / 1000).toFixed(1) + "°", 2, 10);
    g.fillText((lo / 1000).toFixed(1) + "°", 2, c.height - 2);
    g.strokeStyle = "#393";
    g.beginPath();
    h.forEach((v, i) => {
      const x = (i / (h.length - 1)) * c.width, y = c.height - ((v - lo) / (hi - lo)) * (c.height - 14) - 7;
      if (i === 0) g.moveTo(x, y); else g.lineTo(x, y);
    });
    g.stroke();
  }
  $("rotation-save").href = c.toDataURL("image/png");  // "Save graph" downloads what is drawn
  const a = $("rotation-axes"), ga = a.getContext("2d");
  ga.clearRect(0, 0, a.width, a.height);
  const ang = state.rot === null ? 0 : -((state.rot - state.rotZero) / 1000) * Math.PI / 180;
  ga.save();
  ga.translate(a.width / 2, a.height / 2);
  ga.rotate(ang);
  ga.strokeStyle = "#c33"; ga.beginPath(); ga.moveTo(0, 0); ga.lineTo(55, 0); ga.stroke(); ga.fillText("x", 57, 4);
  ga.strokeStyle = "#33c"; ga.beginPath(); ga.moveTo(0, 0); ga.lineTo(0, -55); ga.stroke(); ga.fillText("y", -3, -58);
  ga.restore();
}

function plot() {
  plotRotation();
  const h = state.hist;
  for (const [id, f] of [["plot-pos", (p) => [p.x, p.y]], ["plot-speed", null]]) {
    const c = $(id), g = c.getContext("2d");
    g.clearRect(0, 0, c.width, c.height);
    if (h.length < 2) continue;
    const series = h.map((p, i) => {
      if (f) return f(p);
      if (i === 0) return [0, 0];
      const dt = p.t - h[i - 1].t || 1e-3;
      return [(p.x - h[i - 1].x) / dt, (p.y - h[i - 1].y) / dt];
    });
    let lo = Infinity, hi = -Infinity;
    for (const s of series) for (const v of s) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    if (hi - lo < 1) { hi += 1; lo -= 1; }
    g.fillStyle = "#333";
    g.fillText((id === "plot-pos" ? mm(hi) + " mm" : mm(hi) + " mm/s"), 2, 10);
    g.fillText((id === "plot-pos" ? mm(lo) + " mm" : mm(lo) + " mm/s"), 2, c.height - 2);
    for (const [k, colour] of [[0, "#c33"], [1, "#33c"]]) {
      g.strokeStyle = colour;
      g.beginPath();
      series.forEach((s, i) => {
        const x = (i / (series.length - 1)) * c.width;
        const y = c.height - ((s[k] - lo) / (hi - lo)) * (c.height - 14) - 7;
        if (i === 0) g.moveTo(x, y); else g.lineTo(x, y);
      });
      g.stroke();
    }
  }
}

async function start() {
  state.info = await (await fetch("/api/info")).json();
  $("title").textContent = state.info.title;
  for (const s of state.info.statuses) {
    const o = document.createElement("option"); o.value = s.key; o.textContent = s.meaning; $("dev-status").appendChild(o);
  }
  setup();
  const es = new EventSource("/api/events");
  es.onmessage = (m) => render(JSON.parse(m.data));
  es.onerror = () => { $("ble-indicator").textContent = "panel server gone"; $("ble-indicator").className = "ind warn"; };
}
start();
