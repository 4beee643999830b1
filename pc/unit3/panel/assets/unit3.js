// Seed 001's PC program (seed-001.md §7; docs/panel.md "The unit3 panel"): per axis a step
// size, a thread and a displacement in mm; Send has the panel turn each into the nearest
// achievable move and send it, "0 0 0" sends `C;`. A displacement that is not a number, too
// long or out of range is refused here with the reason and never sent.
"use strict";

const $ = (id) => document.getElementById(id);
let info = null;
let thread = [0, 0, 0];
// The unit's step modes and threads as its last settings reply said; a reply that changes them
// (after `G;`, a Send or the unit's menu) sets the selection boxes (seed-001.md §7 [I]).
// A reply that repeats what this page last sent leaves the boxes alone: the operator may already
// have chosen the next settings.
const reported = [{ mode: -1, thread: -1 }, { mode: -1, thread: -1 }, { mode: -1, thread: -1 }];
const lastSent = [{ mode: -1, thread: -1 }, { mode: -1, thread: -1 }, { mode: -1, thread: -1 }];

function refuse(why) { $("refusal").textContent = why; }

function micrometres(text, axis) {
  const t = text.trim();
  const name = ["X", "Y", "Z"][axis];
  if (t.length === 0) return { error: name + ": empty" };
  if (t.length > 12) return { error: name + ": longer than 12 characters" };
  if (!/^[-+]?\d+([.,]\d{1,3})?$/.test(t)) return { error: name + ": '" + t + "' is not a number in mm (up to 3 decimals)" };
  const um = Math.round(parseFloat(t.replace(",", ".")) * 1000);
  if (Math.abs(um) > info.max_um) return { error: name + ": " + t + " mm outside ±" + info.max_um / 1000 + " mm" };
  return { um };
}

async function post(path, body) {
  const r = await fetch(path, { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
  let j = {};
  try { j = await r.json(); } catch (e) { j = { ok: false, error: "no answer from the panel" }; }
  if (!j.ok) refuse(j.error || "refused");
  return j;
}

function showSent(j) {
  if (!j.ok) return;
  $("refusal").textContent = "";
  (j.conversions || []).forEach((c, a) => {
    $("achieved-" + a).textContent = (c.achieved_um / 1000).toFixed(3) + " mm";
    $("count-" + a).textContent = (c.sign < 0 ? "-" : "+") + c.count;
  });
  const li = document.createElement("li");
  li.textContent = j.lines.join(" ") || "(nothing to move)";
  $("sent").prepend(li);
}

async function send() {
  const um = [], mode = [], th = [];
  for (let a = 0; a < 3; a++) {
    const v = micrometres($("mm-" + a).value, a);
    if (v.error) return refuse(v.error);
    um.push(v.um);
    mode.push(Number($("mode-" + a).value));
    th.push(Number($("thread-" + a).value));
  }
  thread = th;
  for (let a = 0; a < 3; a++) { lastSent[a].mode = mode[a]; lastSent[a].thread = th[a]; }
  showSent(await post("/api/send", { um, mode, thread: th }));
}

function render(s) {
  $("bus").textContent = s.on_bus ? "unit on the bus" : "looking for the unit";
  $("bus").className = s.on_bus ? "ind on" : "ind off";
  (s.axes || []).forEach((x, a) => {
    $("pos-" + a).textContent = (x.position_um / 1000).toFixed(3);
    $("counter-" + a).textContent = x.count;
    for (const k of ["mode", "thread"]) {
      if (x[k] < 0 || x[k] === reported[a][k]) continue;
      reported[a][k] = x[k];
      if (x[k] !== lastSent[a][k]) $(k + "-" + a).value = String(x[k]);
    }
  });
  $("replies").textContent = (s.replies || []).join("\n");
  for (const e of s.events || []) {
    if (e.type === "refusal") {
      const li = document.createElement("li");
      li.dataset.code = e.code;
      li.textContent = e.line + " " + e.meaning;
      $("refusals").prepend(li);
    }
  }
}

async function start() {
  info = await (await fetch("/api/info")).json();
  $("title").textContent = info.title;
  for (let a = 0; a < 3; a++) {
    for (const m of info.modes) { const o = document.createElement("option"); o.value = m.digit; o.textContent = m.name; $("mode-" + a).appendChild(o); }
    for (const t of info.threads) { const o = document.createElement("option"); o.value = t.digit; o.textContent = t.name + " (" + t.pitch_um / 1000 + " mm)"; $("thread-" + a).appendChild(o); }
  }
  $("send").addEventListener("click", send);
  $("zero").addEventListener("click", async () => showSent(await post("/api/clear", {})));
  $("get").addEventListener("click", async () => {
    // The answer sets the boxes, whatever this page sent before.
    for (const r of reported.concat(lastSent)) { r.mode = -1; r.thread = -1; }
    showSent(await post("/api/get", {}));
  });
  const es = new EventSource("/api/events");
  es.onmessage = (m) => render(JSON.parse(m.data));
}
start();
