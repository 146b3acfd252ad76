// node decode-cdr.js FILE.mcap TYPE SAMPLE.cdr...: decodes serialised samples of an IDL type with the
// schema the recording holds for it (Foxglove's omgidl reader) and prints them as JSON.
const { McapIndexedReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { FileHandleReadable } = require("@mcap/nodejs");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const fs = require("fs/promises");
(async () => {
  const [file, type, ...samples] = process.argv.slice(2);
  const fh = await fs.open(file, "r");
  const reader = await McapIndexedReader.Initialize({ readable: new FileHandleReadable(fh), decompressHandlers: await loadDecompressHandlers() });
  const schema = [...reader.schemasById.values()].find((s) => s.name === type);
  if (!schema) throw new Error(`${file} has no schema ${type}`);
  const r = new MessageReader(type, parseIDL(new TextDecoder().decode(schema.data)));
  for (const s of samples) {
    const v = r.readMessage(await fs.readFile(s));
    console.log(s, JSON.stringify(v, (k, x) => (typeof x === "bigint" ? String(x) : ArrayBuffer.isView(x) ? Array.from(x) : x)));
  }
  await fh.close();
})().catch((e) => { console.error(e); process.exit(1); });
