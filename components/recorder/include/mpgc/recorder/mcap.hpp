// MCAP files (https://mcap.dev/spec, ../shared/notes/mcap-foxglove.md): a writer that produces
// chunked, indexed files with a summary, so Foxglove and the @mcap readers open them indexed, and
// a reader for `mpgc inspect`, replay and the tests. No DDS and no clock in here.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpgc::mcap {

// A malformed, truncated or unreadable file, or a writer misused; the message names the file
// and what is wrong.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// CRC-32/IEEE (zlib's crc32), continuing from `crc`; crc32("123456789") = 0xCBF43926.
uint32_t crc32(const void* data, size_t n, uint32_t crc = 0);

struct Schema {
  uint16_t id = 0;
  std::string name;      // e.g. "mpgc::msg::NavState" (fully qualified, as Foxglove looks it up)
  std::string encoding;  // "omgidl", "jsonschema"
  std::string data;      // the schema text
};

struct Channel {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  // "cdr", "json"
  std::map<std::string, std::string> metadata;
};

struct WriterOptions {
  std::string compression = "zstd";  // "zstd" or "" (none)
  size_t chunk_size = 1 << 20;       // [byte] uncompressed records per chunk before it is closed
  int zstd_level = 3;                // [-] zstd's default
  std::string library = "mpgc";      // Header.library
};

// Writes one file. Schemas and channels are registered up front or on the way; each is written
// into the chunk of its channel's first message and again in the summary. close() (or the
// destructor) ends the last chunk and writes the indexes, the summary and the footer: a file of
// a writer killed before that keeps every closed chunk, readable by a stream reader.
class Writer {
 public:
  Writer(const std::string& path, WriterOptions options = {});
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  uint16_t add_channel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                       std::map<std::string, std::string> metadata = {});
  // Times in ns; Error for an unknown channel or after close().
  void write(uint16_t channel_id, uint64_t log_time_ns, uint64_t publish_time_ns, const void* data, size_t n);
  void close();

  const std::string& path() const { return path_; }
  uint64_t bytes_written() const { return offset_ + chunk_.size(); }  // [byte] on disk + open chunk
  uint64_t message_count() const { return message_count_; }

 private:
  struct IndexEntry {
    uint64_t log_time;
    uint64_t offset;
  };
  struct ChunkIndex {
    uint64_t start, end, chunk_offset, chunk_length;
    std::map<uint16_t, uint64_t> index_offsets;
    uint64_t index_length;
    uint64_t compressed_size, uncompressed_size;
  };
  void put(const std::string& bytes);
  void flush_chunk();

  std::string path_;
  WriterOptions opt_;
  std::FILE* f_ = nullptr;
  uint64_t offset_ = 0;  // [byte] written to the file
  uint32_t data_crc_ = 0;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<bool> schema_written_, channel_written_;
  std::map<uint16_t, uint32_t> sequence_;
  std::map<uint16_t, uint64_t> channel_counts_;
  std::string chunk_;  // uncompressed records of the open chunk
  std::map<uint16_t, std::vector<IndexEntry>> chunk_index_;
  uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::vector<ChunkIndex> chunk_indexes_;
  uint64_t message_count_ = 0, start_ = 0, end_ = 0;
};

struct Message {
  uint16_t channel_id;
  uint32_t sequence;
  uint64_t log_time;      // [ns]
  uint64_t publish_time;  // [ns]
  std::string data;
};

// What `mcap info` shows: from the summary when the file has one, else from a full scan.
struct Info {
  std::string library, profile;
  uint64_t size = 0;  // [byte] file size
  bool indexed = false;    // summary with chunk indexes, readable without a scan
  bool truncated = false;  // no footer: a writer that did not close (killed, disk full)
  uint64_t message_count = 0, start = 0, end = 0;  // [ns] log times
  std::map<uint16_t, Schema> schemas;
  std::map<uint16_t, Channel> channels;
  std::map<uint16_t, uint64_t> channel_counts;
  struct Compression {
    uint64_t chunks = 0, compressed = 0, uncompressed = 0;  // [byte]
  };
  std::map<std::string, Compression> compression;  // by name; "" = none
};

Info read_info(const std::string& path);

// Calls `on_message` for every message in file order (chunks decompressed and CRC-checked),
// after `on_channel` for its channel. Stops quietly at the cut of a truncated file; Error for
// anything malformed before it.
void read_messages(const std::string& path, const std::function<void(const Channel&, const Schema&)>& on_channel,
                   const std::function<void(const Message&)>& on_message);

}  // namespace mpgc::mcap
