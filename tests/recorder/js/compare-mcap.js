// node compare-mcap.js FILE.mcap EXPECTED.json: reads a recording with @mcap/core and decodes every
// omgidl message with Foxglove's reader; each topic must hold exactly the messages EXPECTED.json
// lists for it ({topic: [message, ...]}, 64-bit integers as strings), compared field by field as
// multisets (keyed topics arrive per instance). {"$others": {topic: {field: value}}} names messages
// of a topic that others published too (the recorder's own health): those are left out. A format mismatch can decode into plausible garbage
// without an error: only this comparison shows it. Prints one line per topic; exit 1 on any difference.
const { McapIndexedReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { FileHandleReadable } = require("@mcap/nodejs");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const fs = require("fs/promises");

// One form for both sides: BigInt as its decimal string, typed arrays as arrays, keys sorted.
const canon = (v) => {
  if (typeof v === "bigint") return String(v);
  if (ArrayBuffer.isView(v)) return Array.from(v, canon);
  if (Array.isArray(v)) return v.map(canon);
  if (v !== null && typeof v === "object") {
    const o = {};
    for (const k of Object.keys(v).sort()) o[k] = canon(v[k]);
    return o;
  }
  return v;
};
// The first field where a and b differ, as a path.
const firstDiff = (a, b, path = "") => {
  if (typeof a !== typeof b || Array.isArray(a) !== Array.isArray(b)) return `${path}: ${JSON.stringify(a)} vs ${JSON.stringify(b)}`.slice(0, 400);
  if (a !== null && typeof a === "object") {
    const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
    if (Array.isArray(a) && a.length !== b.length) return `${path}: ${a.length} elements vs ${b.length}`;
    for (const k of keys) {
      if (!(k in a) || !(k in b)) return `${path}.${k}: only in ${k in a ? "the recording" : "what was published"}`;
      const d = firstDiff(a[k], b[k], `${path}.${k}`);
      if (d) return d;
    }
    return null;
  }
  return a === b ? null : `${path}: ${JSON.stringify(a)} vs ${JSON.stringify(b)}`.slice(0, 400);
};

(async () => {
  const [file, expectedFile] = process.argv.slice(2);
  const expected = JSON.parse(await fs.readFile(expectedFile, "utf8"));
  const others = expected["$others"] || {};
  delete expected["$others"];
  const isOther = (topic, v) => topic in others && Object.entries(others[topic]).every(([k, x]) => v[k] === x);
  const fh = await fs.open(file, "r");
  const reader = await McapIndexedReader.Initialize({ readable: new FileHandleReadable(fh), decompressHandlers: await loadDecompressHandlers() });
  const readers = new Map();
  for (const [id, ch] of reader.channelsById) {
    const s = reader.schemasById.get(ch.schemaId);
    if (s.encoding === "omgidl") readers.set(id, new MessageReader(s.name, parseIDL(new TextDecoder().decode(s.data))));
  }
  const got = new Map();
  let bad = 0;
  for await (const m of reader.readMessages()) {
    const topic = reader.channelsById.get(m.channelId).topic;
    const r = readers.get(m.channelId);
    try {
      const v = r ? canon(r.readMessage(m.data)) : JSON.parse(new TextDecoder().decode(m.data));
      if (r) (got.get(topic) || got.set(topic, []).get(topic)).push(v);
    } catch (e) {
      if (bad++ < 5) console.log(`${topic}: undecodable: ${e.message}`);
    }
  }
  await fh.close();
  let failed = bad > 0;
  for (const topic of new Set([...Object.keys(expected), ...got.keys()])) {
    const want = (expected[topic] || []).map(canon), all = got.get(topic) || [];
    const have = all.filter((v) => !isOther(topic, v));
    const note = all.length > have.length ? ` (${all.length - have.length} of others left out)` : "";
    const key = (v) => JSON.stringify(v);
    const left = new Map();
    for (const v of have) left.set(key(v), (left.get(key(v)) || []).concat([v]));
    const missing = [];
    for (const v of want) {
      const l = left.get(key(v));
      if (l && l.length) l.pop();
      else missing.push(v);
    }
    const extra = [...left.values()].flat();
    if (missing.length === 0 && extra.length === 0 && want.length > 0) {
      console.log(`${topic}: ${have.length} messages, every field equal${note}`);
      continue;
    }
    failed = true;
    let why = `${topic}: published ${want.length}, recorded ${have.length}, ${missing.length} not found`;
    if (missing.length && extra.length) why += `; first difference ${firstDiff(extra[0], missing[0])}`;
    console.log(why);
  }
  console.log(`undecodable: ${bad}`);
  process.exit(failed ? 1 : 0);
})().catch((e) => { console.error(e); process.exit(1); });
