// MCAP writer and reader (mcap.hpp). Record layout and order as ../shared/notes/mcap-foxglove.md
// found McapWriter to write them; all integers little-endian.
#include "mpgc/recorder/mcap.hpp"

#include <zstd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <limits>
#include <memory>

namespace mpgc::mcap {
namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";
constexpr size_t kMagicSize = 8;
constexpr size_t kFooterSize = 1 + 8 + 8 + 8 + 4;  // opcode, length, summary_start, offset_start, crc
// A chunk claiming more than this uncompressed is refused rather than allocated.
constexpr uint64_t kMaxChunk = uint64_t{1} << 32;  // [byte]

enum Op : uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06,
  kMessageIndex = 0x07, kChunkIndex = 0x08, kStatistics = 0x0B, kSummaryOffset = 0x0E, kDataEnd = 0x0F,
};

// Little-endian record builder.
struct Buf {
  std::string b;
  template <class T>
  Buf& num(T v) {
    for (size_t i = 0; i < sizeof(T); ++i) b.push_back(static_cast<char>((static_cast<uint64_t>(v) >> (8 * i)) & 0xff));
    return *this;
  }
  Buf& u8(uint8_t v) { return num(v); }
  Buf& u16(uint16_t v) { return num(v); }
  Buf& u32(uint32_t v) { return num(v); }
  Buf& u64(uint64_t v) { return num(v); }
  Buf& str(const std::string& s) {
    u32(static_cast<uint32_t>(s.size()));
    b += s;
    return *this;
  }
  Buf& raw(const std::string& s) {
    b += s;
    return *this;
  }
};

std::string record(uint8_t op, const std::string& content) {
  Buf r;
  r.u8(op).u64(content.size()).raw(content);
  return std::move(r.b);
}

std::string schema_record(const Schema& s) {
  Buf c;
  c.u16(s.id).str(s.name).str(s.encoding).str(s.data);
  return record(kSchema, c.b);
}

std::string channel_record(const Channel& ch) {
  Buf m;
  for (const auto& [k, v] : ch.metadata) m.str(k).str(v);
  Buf c;
  c.u16(ch.id).u16(ch.schema_id).str(ch.topic).str(ch.message_encoding).str(m.b);
  return record(kChannel, c.b);
}

// Bounds-checked little-endian reader over one record's content.
struct Cursor {
  const std::string& s;
  size_t i = 0;
  const std::string& what;  // "FILE: record at byte N" for errors
  void need(size_t n) const {
    if (n > s.size() - i) throw Error(what + ": field runs past the end of its record");
  }
  template <class T>
  T num() {
    need(sizeof(T));
    uint64_t v = 0;
    for (size_t k = 0; k < sizeof(T); ++k) v |= static_cast<uint64_t>(static_cast<uint8_t>(s[i + k])) << (8 * k);
    i += sizeof(T);
    return static_cast<T>(v);
  }
  std::string bytes(uint64_t n) {
    if (n > s.size() - i) throw Error(what + ": a length of " + std::to_string(n) + " runs past the end of its record");
    std::string r = s.substr(i, n);
    i += n;
    return r;
  }
  std::string str() { return bytes(num<uint32_t>()); }
  std::string rest() { return bytes(s.size() - i); }
};

Schema parse_schema(Cursor c) {
  Schema s;
  s.id = c.num<uint16_t>();
  s.name = c.str();
  s.encoding = c.str();
  s.data = c.str();
  return s;
}

Channel parse_channel(Cursor c) {
  Channel ch;
  ch.id = c.num<uint16_t>();
  ch.schema_id = c.num<uint16_t>();
  ch.topic = c.str();
  ch.message_encoding = c.str();
  const std::string m = c.str();
  Cursor mc{m, 0, c.what};
  while (mc.i < m.size()) {
    std::string k = mc.str();
    ch.metadata[k] = mc.str();
  }
  return ch;
}

Message parse_message(Cursor c) {
  Message m;
  m.channel_id = c.num<uint16_t>();
  m.sequence = c.num<uint32_t>();
  m.log_time = c.num<uint64_t>();
  m.publish_time = c.num<uint64_t>();
  m.data = c.rest();
  return m;
}

struct File {
  std::string path;
  std::FILE* f = nullptr;
  uint64_t size = 0;
  explicit File(const std::string& p) : path(p), f(std::fopen(p.c_str(), "rb")) {
    if (!f) throw Error(p + ": cannot open: " + std::strerror(errno));
    std::fseek(f, 0, SEEK_END);
    size = static_cast<uint64_t>(std::ftell(f));
  }
  ~File() { std::fclose(f); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  std::string at(uint64_t off, uint64_t n) const {
    if (off > size || n > size - off) throw Error(path + ": read of " + std::to_string(n) + " bytes at " +
                                                  std::to_string(off) + " past the end (" + std::to_string(size) + ")");
    std::string r(n, '\0');
    std::fseek(f, static_cast<long>(off), SEEK_SET);
    if (n > 0 && std::fread(r.data(), 1, n, f) != n) throw Error(path + ": read error at byte " + std::to_string(off));
    return r;
  }
  void check_magic() const {
    if (size < kMagicSize || at(0, kMagicSize) != std::string(kMagic, kMagicSize))
      throw Error(path + ": not an MCAP file (no magic at the start)");
  }
};

std::string decompress(const std::string& compression, const std::string& data, uint64_t size, const std::string& what) {
  if (compression.empty()) {
    if (data.size() != size) throw Error(what + ": uncompressed chunk of " + std::to_string(data.size()) +
                                         " bytes, its header says " + std::to_string(size));
    return data;
  }
  if (compression != "zstd") throw Error(what + ": compression '" + compression + "' is not supported (zstd or none)");
  if (size > kMaxChunk) throw Error(what + ": chunk claims " + std::to_string(size) + " bytes uncompressed");
  // Streamed, never sized by the header: a few bytes claiming gigabytes (found by fuzz_mcap, which
  // hit libFuzzer's malloc limit with a 4 GiB claim) cost only what really decompresses, and no
  // more than the claim.
  std::unique_ptr<ZSTD_DStream, size_t (*)(ZSTD_DStream*)> ds(ZSTD_createDStream(), ZSTD_freeDStream);
  if (!ds) throw Error(what + ": zstd: cannot create a decompression stream");
  std::string out;
  out.reserve(std::min<uint64_t>(size, uint64_t{1} << 24));
  std::array<char, 1 << 16> buf;
  ZSTD_inBuffer in{data.data(), data.size(), 0};
  // Done when a frame is complete (r == 0) and no input is left. Calling zstd again after that
  // would start a next frame and return its header's size as a hint, which is no cut frame: a chunk
  // of a whole number of buffers ended that way. A frame is cut short when zstd makes no progress.
  for (;;) {
    ZSTD_outBuffer ob{buf.data(), buf.size(), 0};
    const size_t in_before = in.pos;
    const size_t r = ZSTD_decompressStream(ds.get(), &ob, &in);
    if (ZSTD_isError(r)) throw Error(what + ": zstd: " + ZSTD_getErrorName(r));
    if (out.size() + ob.pos > size)
      throw Error(what + ": chunk decompresses to more than the " + std::to_string(size) + " bytes its header says");
    out.append(buf.data(), ob.pos);
    if (r == 0 && in.pos == in.size) break;
    if (ob.pos == 0 && in.pos == in_before) throw Error(what + ": zstd: the compressed chunk ends inside a frame");
  }
  if (out.size() != size)
    throw Error(what + ": chunk decompressed to " + std::to_string(out.size()) + " bytes, header says " + std::to_string(size));
  return out;
}

}  // namespace

uint32_t crc32(const void* data, size_t n, uint32_t crc) {
  static const auto table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xff] ^ (crc >> 8);
  return ~crc;
}

// ---- Writer ----

Writer::Writer(const std::string& path, WriterOptions options) : path_(path), opt_(std::move(options)) {
  if (opt_.compression != "zstd" && !opt_.compression.empty())
    throw Error(path + ": compression '" + opt_.compression + "' is not supported (zstd or none)");
  f_ = std::fopen(path.c_str(), "wb");
  if (!f_) throw Error(path + ": cannot open for writing: " + std::strerror(errno));
  put(std::string(kMagic, kMagicSize));
  Buf h;
  h.str("").str(opt_.library);
  put(record(kHeader, h.b));
}

Writer::~Writer() {
  try {
    close();
  } catch (const Error&) {
    // close() reports to a caller that asks; a destructor cannot.
  }
}

uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, const std::string& data) {
  if (schemas_.size() >= std::numeric_limits<uint16_t>::max()) throw Error(path_ + ": too many schemas");
  schemas_.push_back({static_cast<uint16_t>(schemas_.size() + 1), name, encoding, data});
  schema_written_.push_back(false);
  return schemas_.back().id;
}

uint16_t Writer::add_channel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                             std::map<std::string, std::string> metadata) {
  if (schema_id == 0 || schema_id > schemas_.size())
    throw Error(path_ + ": channel '" + topic + "' names unknown schema " + std::to_string(schema_id));
  if (channels_.size() >= std::numeric_limits<uint16_t>::max()) throw Error(path_ + ": too many channels");
  channels_.push_back({static_cast<uint16_t>(channels_.size() + 1), schema_id, topic, message_encoding, std::move(metadata)});
  channel_written_.push_back(false);
  return channels_.back().id;
}

void Writer::put(const std::string& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), f_) != bytes.size())
    throw Error(path_ + ": write failed at byte " + std::to_string(offset_) + ": " + std::strerror(errno));
  data_crc_ = crc32(bytes.data(), bytes.size(), data_crc_);
  offset_ += bytes.size();
}

void Writer::write(uint16_t channel_id, uint64_t log_time_ns, uint64_t publish_time_ns, const void* data, size_t n) {
  if (!f_) throw Error(path_ + ": write after close");
  if (channel_id == 0 || channel_id > channels_.size())
    throw Error(path_ + ": write on unknown channel " + std::to_string(channel_id));
  const Channel& ch = channels_[channel_id - 1];
  if (!schema_written_[ch.schema_id - 1]) {
    chunk_ += schema_record(schemas_[ch.schema_id - 1]);
    schema_written_[ch.schema_id - 1] = true;
  }
  if (!channel_written_[channel_id - 1]) {
    chunk_ += channel_record(ch);
    channel_written_[channel_id - 1] = true;
  }
  if (chunk_index_.empty()) chunk_start_ = chunk_end_ = log_time_ns;
  chunk_index_[channel_id].push_back({log_time_ns, chunk_.size()});
  Buf c;
  c.u16(channel_id).u32(sequence_[channel_id]++).u64(log_time_ns).u64(publish_time_ns);
  c.b.append(static_cast<const char*>(data), n);
  chunk_ += record(kMessage, c.b);
  chunk_start_ = std::min(chunk_start_, log_time_ns);
  chunk_end_ = std::max(chunk_end_, log_time_ns);
  if (message_count_ == 0) start_ = end_ = log_time_ns;
  start_ = std::min(start_, log_time_ns);
  end_ = std::max(end_, log_time_ns);
  ++message_count_;
  ++channel_counts_[channel_id];
  if (chunk_.size() >= opt_.chunk_size) flush_chunk();
}

void Writer::flush_chunk() {
  if (chunk_.empty()) return;
  const uint32_t crc = crc32(chunk_.data(), chunk_.size());
  std::string payload;
  if (opt_.compression == "zstd") {
    payload.resize(ZSTD_compressBound(chunk_.size()));
    const size_t n = ZSTD_compress(payload.data(), payload.size(), chunk_.data(), chunk_.size(), opt_.zstd_level);
    if (ZSTD_isError(n)) throw Error(path_ + ": zstd: " + ZSTD_getErrorName(n));
    payload.resize(n);
  } else {
    payload = chunk_;
  }
  Buf c;
  c.u64(chunk_start_).u64(chunk_end_).u64(chunk_.size()).u32(crc).str(opt_.compression).u64(payload.size()).raw(payload);
  ChunkIndex ix{chunk_start_, chunk_end_, offset_, 0, {}, 0, payload.size(), chunk_.size()};
  put(record(kChunk, c.b));
  ix.chunk_length = offset_ - ix.chunk_offset;
  const uint64_t index_start = offset_;
  for (auto& [ch, entries] : chunk_index_) {
    // Readers expect each channel's index in log-time order; samples can arrive out of order.
    std::stable_sort(entries.begin(), entries.end(), [](const IndexEntry& a, const IndexEntry& b) { return a.log_time < b.log_time; });
    Buf e;
    for (const auto& x : entries) e.u64(x.log_time).u64(x.offset);
    Buf m;
    m.u16(ch).str(e.b);
    ix.index_offsets[ch] = offset_;
    put(record(kMessageIndex, m.b));
  }
  ix.index_length = offset_ - index_start;
  chunk_indexes_.push_back(std::move(ix));
  chunk_.clear();
  chunk_index_.clear();
}

void Writer::close() {
  if (!f_) return;
  std::FILE* f = f_;
  try {
    flush_chunk();
    Buf de;
    de.u32(data_crc_);
    put(record(kDataEnd, de.b));
    // Summary: schemas, channels, statistics, chunk indexes; then one offset per group.
    const uint64_t summary_start = offset_;
    std::string sum;
    std::vector<std::pair<uint8_t, std::pair<uint64_t, uint64_t>>> groups;
    auto group = [&](uint8_t op, const std::string& records) {
      if (records.empty()) return;
      groups.push_back({op, {summary_start + sum.size(), records.size()}});
      sum += records;
    };
    std::string g;
    for (const auto& s : schemas_) g += schema_record(s);
    group(kSchema, g);
    g.clear();
    for (const auto& ch : channels_) g += channel_record(ch);
    group(kChannel, g);
    Buf counts;
    for (const auto& [ch, n] : channel_counts_) counts.u16(ch).u64(n);
    Buf st;
    st.u64(message_count_).u16(static_cast<uint16_t>(schemas_.size())).u32(static_cast<uint32_t>(channels_.size()))
        .u32(0).u32(0).u32(static_cast<uint32_t>(chunk_indexes_.size())).u64(start_).u64(end_).str(counts.b);
    group(kStatistics, record(kStatistics, st.b));
    g.clear();
    for (const auto& ix : chunk_indexes_) {
      Buf offs;
      for (const auto& [ch, off] : ix.index_offsets) offs.u16(ch).u64(off);
      Buf c;
      c.u64(ix.start).u64(ix.end).u64(ix.chunk_offset).u64(ix.chunk_length).str(offs.b).u64(ix.index_length)
          .str(opt_.compression).u64(ix.compressed_size).u64(ix.uncompressed_size);
      g += record(kChunkIndex, c.b);
    }
    group(kChunkIndex, g);
    const uint64_t offsets_start = summary_start + sum.size();
    for (const auto& [op, range] : groups) {
      Buf so;
      so.u8(op).u64(range.first).u64(range.second);
      sum += record(kSummaryOffset, so.b);
    }
    Buf foot;
    foot.u8(kFooter).u64(20).u64(summary_start).u64(offsets_start);
    sum += foot.b;  // the summary CRC covers the footer up to summary_offset_start
    Buf crc;
    crc.u32(crc32(sum.data(), sum.size()));
    put(sum + crc.b + std::string(kMagic, kMagicSize));
  } catch (...) {
    std::fclose(f);
    f_ = nullptr;
    throw;
  }
  f_ = nullptr;
  if (std::fclose(f) != 0) throw Error(path_ + ": close failed: " + std::strerror(errno));
}

// ---- Reader ----

void read_messages(const std::string& path, const std::function<void(const Channel&, const Schema&)>& on_channel,
                   const std::function<void(const Message&)>& on_message) {
  File file(path);
  file.check_magic();
  std::map<uint16_t, Schema> schemas;
  std::map<uint16_t, Channel> channels;
  std::map<uint16_t, bool> announced;
  // One record (outside or inside a chunk); returns false at DataEnd / Footer.
  std::function<bool(uint8_t, const std::string&, const std::string&)> handle = [&](uint8_t op, const std::string& content,
                                                                                  const std::string& what) {
    switch (op) {
      case kSchema: {
        Schema s = parse_schema(Cursor{content, 0, what});
        schemas[s.id] = std::move(s);
        return true;
      }
      case kChannel: {
        Channel ch = parse_channel(Cursor{content, 0, what});
        if (ch.schema_id != 0 && !schemas.count(ch.schema_id))
          throw Error(what + ": channel '" + ch.topic + "' before its schema " + std::to_string(ch.schema_id));
        channels[ch.id] = std::move(ch);
        return true;
      }
      case kMessage: {
        Message m = parse_message(Cursor{content, 0, what});
        auto it = channels.find(m.channel_id);
        if (it == channels.end()) throw Error(what + ": message on channel " + std::to_string(m.channel_id) + " before its Channel record");
        if (!announced[m.channel_id]) {
          announced[m.channel_id] = true;
          static const Schema none{};
          auto s = schemas.find(it->second.schema_id);
          if (on_channel) on_channel(it->second, s == schemas.end() ? none : s->second);
        }
        if (on_message) on_message(m);
        return true;
      }
      case kChunk: {
        Cursor c{content, 0, what};
        c.num<uint64_t>();
        c.num<uint64_t>();
        const uint64_t usize = c.num<uint64_t>();
        const uint32_t crc = c.num<uint32_t>();
        const std::string compression = c.str();
        const std::string records = decompress(compression, c.bytes(c.num<uint64_t>()), usize, what);
        if (crc != 0 && crc32(records.data(), records.size()) != crc) throw Error(what + ": incorrect chunk CRC");
        size_t i = 0;
        while (i < records.size()) {
          const std::string inner_what = what + " (chunk record at " + std::to_string(i) + ")";
          Cursor r{records, i, inner_what};
          const auto iop = r.num<uint8_t>();
          const std::string inner = r.bytes(r.num<uint64_t>());
          i = r.i;
          handle(iop, inner, inner_what);
        }
        return true;
      }
      case kDataEnd:
      case kFooter:
        return false;
      default:
        return true;  // Header, indexes, attachments, metadata: not messages
    }
  };
  uint64_t off = kMagicSize;
  while (off + 9 <= file.size) {
    const std::string head = file.at(off, 9);
    const std::string what = path + ": record at byte " + std::to_string(off);
    Cursor h{head, 0, what};
    const auto op = h.num<uint8_t>();
    const auto len = h.num<uint64_t>();
    if (len > file.size - off - 9) return;  // truncated: the cut of a writer that did not close
    if (!handle(op, file.at(off + 9, len), what)) return;
    off += 9 + len;
  }
}

Info read_info(const std::string& path) {
  Info info;
  {
    File file(path);
    file.check_magic();
    info.size = file.size;
    if (file.size >= kMagicSize + 9) {
      const std::string head = file.at(kMagicSize, 9);
      const std::string what = path + ": header";
      Cursor h{head, 0, what};
      if (h.num<uint8_t>() == kHeader) {
        const uint64_t len = h.num<uint64_t>();
        if (len <= file.size - kMagicSize - 9) {
          const std::string content = file.at(kMagicSize + 9, len);
          Cursor c{content, 0, what};
          info.profile = c.str();
          info.library = c.str();
        }
      }
    }
    const bool closed = file.size >= 2 * kMagicSize + kFooterSize &&
                        file.at(file.size - kMagicSize, kMagicSize) == std::string(kMagic, kMagicSize);
    info.truncated = !closed;
    if (closed) {
      const uint64_t foot_at = file.size - kMagicSize - kFooterSize;
      const std::string foot = file.at(foot_at, kFooterSize);
      const std::string what = path + ": footer";
      Cursor f{foot, 0, what};
      if (f.num<uint8_t>() != kFooter || f.num<uint64_t>() != 20) throw Error(path + ": no footer before the closing magic");
      const uint64_t summary_start = f.num<uint64_t>();
      const uint64_t offsets_start = f.num<uint64_t>();
      const uint32_t crc = f.num<uint32_t>();
      if (summary_start != 0) {
        if (summary_start > foot_at) throw Error(path + ": footer points the summary past itself");
        const uint64_t end = offsets_start != 0 ? offsets_start : foot_at;
        if (end < summary_start || end > foot_at) throw Error(path + ": footer's summary offsets are out of order");
        const std::string sum = file.at(summary_start, foot_at - summary_start);
        if (crc != 0) {
          const std::string covered = sum + foot.substr(0, kFooterSize - 4);
          if (crc32(covered.data(), covered.size()) != crc) throw Error(path + ": incorrect summary CRC");
        }
        bool stats = false;
        size_t i = 0;
        while (i < end - summary_start) {
          const std::string rwhat = path + ": summary record at byte " + std::to_string(summary_start + i);
          Cursor r{sum, i, rwhat};
          const auto op = r.num<uint8_t>();
          const std::string content = r.bytes(r.num<uint64_t>());
          i = r.i;
          Cursor c{content, 0, rwhat};
          if (op == kSchema) {
            Schema s = parse_schema(c);
            info.schemas[s.id] = s;
          } else if (op == kChannel) {
            Channel ch = parse_channel(c);
            info.channels[ch.id] = ch;
          } else if (op == kStatistics) {
            stats = true;
            info.message_count = c.num<uint64_t>();
            for (int k = 0; k < 5; ++k) (k == 0 ? (void)c.num<uint16_t>() : (void)c.num<uint32_t>());
            info.start = c.num<uint64_t>();
            info.end = c.num<uint64_t>();
            const std::string counts = c.str();
            Cursor cc{counts, 0, rwhat};
            while (cc.i < counts.size()) {
              const auto ch = cc.num<uint16_t>();
              info.channel_counts[ch] = cc.num<uint64_t>();
            }
          } else if (op == kChunkIndex) {
            for (int k = 0; k < 4; ++k) c.num<uint64_t>();
            c.str();
            c.num<uint64_t>();
            auto& comp = info.compression[c.str()];
            ++comp.chunks;
            comp.compressed += c.num<uint64_t>();
            comp.uncompressed += c.num<uint64_t>();
            info.indexed = true;
          }
        }
        if (stats) return info;
      }
    }
  }
  // No usable summary: count by reading every message.
  info.indexed = false;
  info.compression.clear();
  bool first = true;
  read_messages(path, [&](const Channel& ch, const Schema& s) {
    info.channels[ch.id] = ch;
    if (s.id != 0) info.schemas[s.id] = s;
  }, [&](const Message& m) {
    ++info.message_count;
    ++info.channel_counts[m.channel_id];
    info.start = first ? m.log_time : std::min(info.start, m.log_time);
    info.end = first ? m.log_time : std::max(info.end, m.log_time);
    first = false;
  });
  return info;
}

}  // namespace mpgc::mcap
