// node check-mcap.js FILE.mcap: opens a recording with @mcap/core (indexed, zstd through @mcap/support),
// decodes every message with Foxglove's omgidl reader or JSON.parse, and prints per topic the count
// and the first decoded value; exit 1 if any message does not decode. (npm ci here first.)
const { McapIndexedReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { FileHandleReadable } = require("@mcap/nodejs");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const fs = require("fs/promises");
(async () => {
  const fh = await fs.open(process.argv[2], "r");
  const reader = await McapIndexedReader.Initialize({ readable: new FileHandleReadable(fh), decompressHandlers: await loadDecompressHandlers() });
  const readers = new Map(), counts = new Map(), first = new Map();
  for (const [id, ch] of reader.channelsById) {
    const s = reader.schemasById.get(ch.schemaId);
    readers.set(id, s.encoding === "omgidl" ? new MessageReader(s.name, parseIDL(new TextDecoder().decode(s.data))) : null);
  }
  let bad = 0;
  for await (const m of reader.readMessages()) {
    const ch = reader.channelsById.get(m.channelId);
    const r = readers.get(m.channelId);
    let v;
    try { v = r ? r.readMessage(m.data) : JSON.parse(new TextDecoder().decode(m.data)); } catch (e) { bad++; if (bad < 5) console.log("FAIL", ch.topic, e.message); continue; }
    counts.set(ch.topic, (counts.get(ch.topic) || 0) + 1);
    if (!first.has(ch.topic) || ch.topic === "sa/tracks" && v.tracks && v.tracks.length && !first.get(ch.topic).tracks.length) first.set(ch.topic, v);
  }
  for (const [t, n] of counts) console.log(t, n, JSON.stringify(first.get(t), (k, x) => typeof x === "bigint" ? String(x) : x).slice(0, 300));
  console.log("undecodable:", bad);
  await fh.close();
  if (bad > 0 || counts.size === 0) process.exit(1);
})().catch((e) => { console.error(e); process.exit(1); });
