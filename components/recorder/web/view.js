// mpgc live view: a foxglove.websocket.v1 client of the server that serves this page. It subscribes
// to the JSON channels Foxglove's Map panel gets too (map/own_ship, map/targets/<name>, map/safety,
// map/plan, map/chart) and to view/state (plan status, encounters, target speeds), and draws them
// on a local flat projection around own ship (north up). Tests read the canvas's data-* attributes
// and the "Ships drawn" list.
"use strict";

const R_EARTH = 6371000; // [m] enough for a screen within a few tens of km
const VECTOR_S = 360; // [s] length of a target's velocity vector, as on a radar: 6 minutes

const SITUATIONS = {
  ENCOUNTER_NONE: "no encounter",
  ENCOUNTER_HEAD_ON: "head-on (rule 14)",
  ENCOUNTER_CROSSING_GIVE_WAY: "crossing, give way (rule 15)",
  ENCOUNTER_CROSSING_STAND_ON: "crossing, stand on (rule 17)",
  ENCOUNTER_OVERTAKING: "overtaking (rule 13)",
  ENCOUNTER_OVERTAKEN: "overtaken (rule 13)",
};
const ROLES = { ROLE_NONE: "–", ROLE_GIVE_WAY: "give way", ROLE_STAND_ON: "stand on", ROLE_BOTH_GIVE_WAY: "both give way" };

const state = { own: null, targets: new Map(), safety: null, plan: null, chart: null, view: null, messages: 0 };
const canvas = document.getElementById("view");
const $ = (id) => document.getElementById(id);

// ---- the protocol (../shared/notes/mcap-foxglove.md): JSON text frames, binary message data ----
function connect() {
  const url = `ws://${location.host}/`;
  const ws = new WebSocket(url, ["foxglove.websocket.v1"]);
  ws.binaryType = "arraybuffer";
  const topics = new Map(); // subscription id -> topic
  let nextSub = 1;
  ws.onopen = () => {
    // A new server (the next scenario's recorder): nothing of the last run stays on the screen.
    Object.assign(state, { own: null, safety: null, plan: null, chart: null, view: null });
    state.targets.clear();
    $("conn").textContent = `connected to ${url}`;
    scheduleDraw();
  };
  ws.onmessage = (ev) => {
    if (typeof ev.data === "string") {
      const m = JSON.parse(ev.data);
      if (m.op === "advertise") {
        const subs = [];
        for (const c of m.channels) {
          if (c.encoding !== "json" || !(c.topic.startsWith("map/") || c.topic.startsWith("view/"))) continue;
          topics.set(nextSub, c.topic);
          subs.push({ id: nextSub++, channelId: c.id });
        }
        if (subs.length > 0) ws.send(JSON.stringify({ op: "subscribe", subscriptions: subs }));
      } else if (m.op === "status") {
        $("conn").textContent = `server: ${m.message}`;
      }
      return;
    }
    const dv = new DataView(ev.data);
    if (dv.byteLength < 13 || dv.getUint8(0) !== 1) return;
    const topic = topics.get(dv.getUint32(1, true));
    if (topic === undefined) return;
    try {
      receive(topic, JSON.parse(new TextDecoder().decode(new Uint8Array(ev.data, 13))));
    } catch (e) {
      console.warn(topic, e);
    }
  };
  ws.onclose = () => {
    $("conn").textContent = `disconnected from ${url}; retrying`;
    setTimeout(connect, 1000);
  };
}

function receive(topic, m) {
  state.messages++;
  if (topic === "map/own_ship") state.own = m;
  else if (topic.startsWith("map/targets/")) state.targets.set(topic.slice("map/targets/".length), m);
  else if (topic === "map/safety") state.safety = JSON.parse(m.geojson);
  else if (topic === "map/plan") state.plan = JSON.parse(m.geojson);
  else if (topic === "map/chart") state.chart = JSON.parse(m.geojson);
  else if (topic === "view/state") state.view = m;
  scheduleDraw();
}

// ---- drawing ----
let pending = false;
function scheduleDraw() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => {
    pending = false;
    draw();
  });
}

// The targets to draw: those of the newest view/state (tracks now confirmed or coasting); the
// map/targets channels keep a dropped track's last fix.
function liveTargets() {
  const out = [];
  const speeds = new Map();
  if (state.view) for (const t of state.view.targets) speeds.set(t.name, t);
  for (const [name, fix] of state.targets) {
    if (state.view && !speeds.has(name)) continue;
    if (!Number.isFinite(fix.latitude) || !Number.isFinite(fix.longitude)) continue;
    out.push({ name, fix, v: speeds.get(name) });
  }
  return out;
}

function draw() {
  const w = (canvas.width = canvas.clientWidth * devicePixelRatio);
  const h = (canvas.height = canvas.clientHeight * devicePixelRatio);
  const g = canvas.getContext("2d");
  g.clearRect(0, 0, w, h);
  const targets = liveTargets();
  const ref = state.own ?? targets[0]?.fix;
  const shipsList = [];
  if (!ref) return publishDom(0, false, targets, shipsList, {});
  const lat0 = ref.latitude, lon0 = ref.longitude, k = Math.cos((lat0 * Math.PI) / 180);
  const toM = (lon, lat) => [(((lon - lon0) * Math.PI) / 180) * R_EARTH * k, (((lat - lat0) * Math.PI) / 180) * R_EARTH];

  // Scale: own ship, the targets with their vectors and the plan in view; 1 km across at least.
  let span = 1000;
  const grow = ([x, y]) => (span = Math.max(span, Math.abs(x) * 1.15, Math.abs(y) * 1.15));
  for (const t of targets) grow(toM(t.fix.longitude, t.fix.latitude));
  for (const f of state.plan?.features ?? []) for (const c of f.geometry.coordinates) grow(toM(c[0], c[1]));
  const px = Math.min(w, h) / 2 / span; // pixels per metre
  const screen = ([x, y]) => [w / 2 + x * px, h / 2 - y * px];
  const S = devicePixelRatio;

  const path = (coords, close) => {
    g.beginPath();
    coords.forEach((c, i) => {
      const [sx, sy] = screen(toM(c[0], c[1]));
      if (i === 0) g.moveTo(sx, sy);
      else g.lineTo(sx, sy);
    });
    if (close) g.closePath();
  };
  const drawn = { circles: 0, planPoints: 0, chartPolygons: 0 };
  for (const f of state.chart?.features ?? []) {
    if (f.geometry.type === "Polygon") {
      drawn.chartPolygons++;
      path(f.geometry.coordinates[0], true);
      g.fillStyle = "#c8a165";
      g.fill();
    } else if (f.geometry.type === "LineString") {
      path(f.geometry.coordinates, false);
      g.strokeStyle = "#808080";
      g.setLineDash([6 * S, 6 * S]);
      g.stroke();
      g.setLineDash([]);
    }
  }
  for (const f of state.safety?.features ?? []) {
    path(f.geometry.coordinates[0], true);
    drawn.circles++;
    g.strokeStyle = "#ff4040";
    g.lineWidth = 1.5 * S;
    g.stroke();
  }
  for (const f of state.plan?.features ?? []) {
    path(f.geometry.coordinates, false);
    drawn.planPoints += f.geometry.coordinates.length;
    g.strokeStyle = "#4a8cff";
    g.lineWidth = 2.5 * S;
    g.stroke();
  }
  const ship = (x, y, heading, color, size) => {
    g.save();
    g.translate(x, y);
    g.rotate(heading);
    g.beginPath();
    g.moveTo(0, -size);
    g.lineTo(size * 0.5, size * 0.6);
    g.lineTo(0, size * 0.3);
    g.lineTo(-size * 0.5, size * 0.6);
    g.closePath();
    g.fillStyle = color;
    g.fill();
    g.restore();
  };
  g.font = `${11 * S}px system-ui, sans-serif`;
  for (const t of targets) {
    const [x, y] = screen(toM(t.fix.longitude, t.fix.latitude));
    const cog = t.v?.cog ?? t.fix.heading ?? 0, sog = t.v?.sog ?? 0;
    if (Number.isFinite(cog) && Number.isFinite(sog) && sog > 0) {
      g.beginPath();
      g.moveTo(x, y);
      g.lineTo(x + Math.sin(cog) * sog * VECTOR_S * px, y - Math.cos(cog) * sog * VECTOR_S * px);
      g.strokeStyle = "#ffb340";
      g.lineWidth = 1.5 * S;
      g.stroke();
    }
    ship(x, y, Number.isFinite(cog) ? cog : 0, "#ffb340", 9 * S);
    g.fillStyle = "#ffd9a0";
    g.fillText(t.name, x + 10 * S, y - 8 * S);
    shipsList.push(`${t.name}: ${t.fix.latitude.toFixed(5)}°, ${t.fix.longitude.toFixed(5)}°, ${(sog * 1.943844).toFixed(1)} kn`);
  }
  const hasOwn = state.own !== null && Number.isFinite(state.own.latitude);
  if (hasOwn) {
    const [x, y] = screen([0, 0]);
    ship(x, y, state.own.heading ?? 0, "#ffffff", 13 * S);
    shipsList.unshift(`own ship: ${state.own.latitude.toFixed(5)}°, ${state.own.longitude.toFixed(5)}°, heading ${deg(state.own.heading)}`);
  }
  $("scale").textContent = `${((2 * span) / 1000).toFixed(1)} km across`;
  publishDom(targets.length + (hasOwn ? 1 : 0), hasOwn, targets, shipsList, drawn);
}

const deg = (rad) => (Number.isFinite(rad) ? `${(((rad * 180) / Math.PI + 360) % 360).toFixed(0)}°` : "–");
const metres = (m) => (Number.isFinite(m) ? (Math.abs(m) >= 2000 ? `${(m / 1852).toFixed(2)} nm` : `${m.toFixed(0)} m`) : "–");

function publishDom(ships, hasOwn, targets, shipsList, drawn) {
  canvas.dataset.ships = String(ships);
  canvas.dataset.circles = String(drawn.circles ?? 0);
  canvas.dataset.planPoints = String(drawn.planPoints ?? 0);
  canvas.dataset.chartPolygons = String(drawn.chartPolygons ?? 0);
  canvas.dataset.own = hasOwn ? "1" : "0";
  canvas.dataset.targets = String(targets.length);
  canvas.dataset.updates = String(state.messages);
  const list = $("ships");
  list.replaceChildren(...shipsList.map((s) => Object.assign(document.createElement("li"), { textContent: s })));
  if (hasOwn) {
    const sog = state.view?.own_sog;
    $("own").textContent = `${state.own.latitude.toFixed(5)}°, ${state.own.longitude.toFixed(5)}°, heading ${deg(state.own.heading)}` +
      (Number.isFinite(sog) ? `, ${(sog * 1.943844).toFixed(1)} kn` : "");
  }
  const v = state.view;
  if (!v) return;
  $("time").textContent = `t = ${(v.timestamp.sec + v.timestamp.nsec * 1e-9).toFixed(1)} s`;
  if (v.plan.status) {
    const ps = $("plan-status");
    ps.textContent = v.plan.status.replace("PLAN_", "").replace("_", " ");
    ps.className = v.plan.status;
    canvas.dataset.planStatus = v.plan.status;
    $("plan-id").textContent = `plan ${v.plan.id}`;
    $("plan-reason").textContent = v.plan.reason;
  }
  const rows = v.encounters.map((e) => {
    const tr = document.createElement("tr");
    const name = e.mmsi ? `mmsi_${e.mmsi}` : `track_${e.track_id}`;
    for (const text of [name, SITUATIONS[e.situation] ?? e.situation, ROLES[e.role] ?? e.role, metres(e.range), metres(e.cpa),
      Number.isFinite(e.tcpa) ? `${e.tcpa.toFixed(0)} s` : "–"]) {
      tr.appendChild(Object.assign(document.createElement("td"), { textContent: text }));
    }
    tr.dataset.situation = e.situation;
    return tr;
  });
  document.querySelector("#encounters tbody").replaceChildren(...rows);
}

window.addEventListener("resize", scheduleDraw);
connect();
