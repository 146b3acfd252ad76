// node live-client.js ws://127.0.0.1:PORT EXPECTED.jsonl: mpgc_record's live view read with
// @foxglove/ws-protocol's FoxgloveClient. Checks serverInfo and the advertised channels (every
// omgidl schema builds Foxglove's reader, as the app would), subscribes to nav/own_state and
// map/own_ship, decodes a CDR sample with Foxglove's omgidl reader and compares every field with the
// sample the test published at that stamp (EXPECTED.jsonl, one NavState per line), and checks that
// a message that is not JSON is answered with an error status without losing the connection.
// Exit 0 and "OK nav/own_state ..." when all holds.
const fs = require("fs");
const WebSocket = require("ws");
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");

const [url, expectedFile] = process.argv.slice(2);
const problems = [];
const done = { serverInfo: false, advertise: false, nav: false, fix: false, errorStatus: false };
const fail = (why) => {
  console.error("FAIL:", why);
  process.exit(1);
};
const plain = (v) => JSON.parse(JSON.stringify(v, (k, x) => (typeof x === "bigint" ? String(x) : x)));
// The published sample of that stamp (a line being appended right now is skipped).
const parsed = (line) => {
  try {
    return [JSON.parse(line)];
  } catch {
    return [];
  }
};
const expectedAt = (stamp) =>
  fs.readFileSync(expectedFile, "utf8").split("\n").flatMap(parsed).find((e) => e.header.stamp_ns === stamp);

function diff(path, got, want, out) {
  if (typeof want === "object" && want !== null) {
    for (const k of Object.keys(want)) diff(`${path}.${k}`, got?.[k], want[k], out);
    for (const k of Object.keys(got ?? {})) if (!(k in want)) out.push(`${path}.${k}: not published`);
  } else if (got !== want) out.push(`${path}: decoded ${JSON.stringify(got)}, published ${JSON.stringify(want)}`);
  return out;
}

const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });
const channels = new Map(); // channel id -> channel
const subs = new Map(); // subscription id -> { channel, reader }

client.on("error", (e) => fail(`connection: ${e?.message ?? e}`));
client.on("serverInfo", (info) => {
  if (info.name !== "mpgc_record") problems.push(`serverInfo.name ${info.name}`);
  if (!Array.isArray(info.capabilities)) problems.push("serverInfo.capabilities is not an array");
  if (!info.sessionId) problems.push("serverInfo has no sessionId");
  done.serverInfo = true;
});
client.on("advertise", (list) => {
  for (const c of list) channels.set(c.id, c);
  if (done.advertise) return; // later ones: new target channels
  done.advertise = true;
  const byTopic = new Map([...channels.values()].map((c) => [c.topic, c]));
  const nav = byTopic.get("nav/own_state");
  if (!nav) return fail(`nav/own_state not advertised (${[...byTopic.keys()].join(", ")})`);
  const want = { encoding: "cdr", schemaName: "mpgc::msg::NavState", schemaEncoding: "omgidl" };
  for (const [k, v] of Object.entries(want)) if (nav[k] !== v) problems.push(`nav/own_state ${k} = ${nav[k]}, not ${v}`);
  for (const c of channels.values()) {
    try {
      if (c.schemaEncoding === "omgidl") new MessageReader(c.schemaName, parseIDL(c.schema));
      else if (c.schemaEncoding === "jsonschema") JSON.parse(c.schema);
      else problems.push(`${c.topic}: schemaEncoding ${c.schemaEncoding}`);
      if (c.encoding !== (c.schemaEncoding === "omgidl" ? "cdr" : "json")) problems.push(`${c.topic}: encoding ${c.encoding}`);
    } catch (e) {
      problems.push(`${c.topic}: schema does not build a reader: ${e.message}`);
    }
  }
  for (const t of ["map/own_ship", "map/chart", "map/safety", "map/plan", "view/state", "sa/tracks", "plan/path", "health"])
    if (!byTopic.has(t)) problems.push(`${t} not advertised`);
  const fix = byTopic.get("map/own_ship");
  if (fix && (fix.encoding !== "json" || fix.schemaName !== "foxglove.LocationFix")) problems.push("map/own_ship is not a JSON foxglove.LocationFix");
  subs.set(client.subscribe(nav.id), { channel: nav, reader: new MessageReader(nav.schemaName, parseIDL(nav.schema)) });
  if (fix) subs.set(client.subscribe(fix.id), { channel: fix });
  ws.send("this is not JSON"); // bad input: an error status, the connection stays
});
client.on("status", (s) => {
  if (s.level === 2 && /not JSON/.test(s.message)) done.errorStatus = true;
  else problems.push(`unexpected status: ${JSON.stringify(s)}`);
  check();
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const sub = subs.get(subscriptionId);
  if (!sub) return problems.push(`message for unknown subscription ${subscriptionId}`);
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  if (sub.channel.topic === "nav/own_state") {
    if (done.nav) return;
    const v = plain(sub.reader.readMessage(bytes));
    if (v.header.stamp_ns !== String(timestamp)) problems.push(`log time ${timestamp} is not the stamp ${v.header.stamp_ns}`);
    const want = expectedAt(v.header.stamp_ns);
    if (!want) return problems.push(`decoded a NavState stamped ${v.header.stamp_ns}, which was never published`);
    problems.push(...diff("nav/own_state", v, want, []));
    done.nav = true;
    console.log(`OK nav/own_state stamp ${v.header.stamp_ns}: every field as published (x ${v.x}, lat ${v.lat}, sog ${v.sog})`);
  } else if (sub.channel.topic === "map/own_ship") {
    const m = JSON.parse(new TextDecoder().decode(bytes));
    const ns = BigInt(m.timestamp.sec) * 1000000000n + BigInt(m.timestamp.nsec);
    if (ns !== timestamp) problems.push(`map/own_ship: log time ${timestamp}, message time ${ns}`);
    const want = expectedAt(String(ns));
    if (!want) return problems.push(`map/own_ship at ${ns}: no such own state published`);
    if (Math.abs(m.latitude - (want.lat * 180) / Math.PI) > 1e-9 || Math.abs(m.longitude - (want.lon * 180) / Math.PI) > 1e-9)
      problems.push(`map/own_ship ${m.latitude}, ${m.longitude}: not the published position in degrees`);
    if (!done.fix) console.log(`OK map/own_ship ${m.latitude.toFixed(6)}, ${m.longitude.toFixed(6)}`);
    done.fix = true;
  }
  check();
});

function check() {
  if (problems.length > 0) fail(problems.join("\n"));
  if (Object.values(done).every(Boolean)) {
    console.log(`OK live view: ${channels.size} channels advertised, error status on bad input`);
    client.close();
    process.exit(0);
  }
}
setTimeout(() => {
  if (problems.length === 0) problems.push(`timed out; still missing: ${Object.keys(done).filter((k) => !done[k]).join(", ")}`);
  fail(problems.join("\n"));
}, 30000);
