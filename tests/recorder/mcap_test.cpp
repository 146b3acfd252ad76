// The MCAP writer and reader: what is written reads back (chunked, zstd and none, indexed
// summary), a file cut short reads to its cut, and a file that is not MCAP is named as such.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mpgc/msg/all.hpp"
#include "mpgc/recorder/mcap.hpp"
#include "mpgc/recorder/recording.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

namespace mcap = mpgc::mcap;
namespace fs = std::filesystem;

namespace {

std::string tmp(const std::string& name) { return (fs::temp_directory_path() / ("mpgc_mcap_" + name)).string(); }

std::vector<mcap::Message> all_messages(const std::string& path, std::vector<std::string>* topics = nullptr) {
  std::vector<mcap::Message> out;
  mcap::read_messages(path, [&](const mcap::Channel& c, const mcap::Schema&) { if (topics) topics->push_back(c.topic); },
                      [&](const mcap::Message& m) { out.push_back(m); });
  return out;
}

void write_file(const std::string& path, const std::string& compression, int n) {
  mcap::WriterOptions o;
  o.compression = compression;
  o.chunk_size = 4096;  // many chunks
  mcap::Writer w(path, o);
  const auto s = w.add_schema("mpgc::msg::Clock", "omgidl", "module mpgc { module msg { struct Clock { int64 time_ns; }; }; };");
  const auto a = w.add_channel(s, "clock", "cdr");
  const auto b = w.add_channel(s, "other", "cdr", {{"k", "v"}});
  for (int i = 0; i < n; ++i) {
    const std::string payload = "sample " + std::to_string(i);
    w.write(i % 3 == 0 ? b : a, static_cast<uint64_t>(i) * 1000, 7, payload.data(), payload.size());
  }
  w.close();
}

}  // namespace

TEST(Mcap, Crc32IsZlibs) { EXPECT_EQ(mcap::crc32("123456789", 9), 0xCBF43926u); }

TEST(Mcap, WhatIsWrittenReadsBackIndexed) {
  for (const std::string comp : {"zstd", ""}) {
    SCOPED_TRACE(comp);
    const auto path = tmp("rt.mcap");
    write_file(path, comp, 3000);
    std::vector<std::string> topics;
    const auto msgs = all_messages(path, &topics);
    ASSERT_EQ(msgs.size(), 3000u);
    for (int i = 0; i < 3000; ++i) {
      EXPECT_EQ(msgs[i].data, "sample " + std::to_string(i));
      EXPECT_EQ(msgs[i].log_time, static_cast<uint64_t>(i) * 1000);
    }
    EXPECT_EQ(topics.size(), 2u);
    const auto info = mcap::read_info(path);
    EXPECT_TRUE(info.indexed);
    EXPECT_FALSE(info.truncated);
    EXPECT_EQ(info.message_count, 3000u);
    EXPECT_EQ(info.end, 2999u * 1000);
    EXPECT_EQ(info.channel_counts.at(2), 1000u);
    EXPECT_EQ(info.channels.at(2).metadata.at("k"), "v");
    ASSERT_EQ(info.compression.count(comp), 1u);
    EXPECT_GT(info.compression.at(comp).chunks, 5u);
    fs::remove(path);
  }
}

TEST(Mcap, ATruncatedFileReadsToItsCut) {
  const auto path = tmp("cut.mcap");
  write_file(path, "zstd", 3000);
  fs::resize_file(path, fs::file_size(path) / 2);
  const auto msgs = all_messages(path);
  EXPECT_GT(msgs.size(), 100u);
  EXPECT_LT(msgs.size(), 3000u);
  const auto info = mcap::read_info(path);
  EXPECT_TRUE(info.truncated);
  EXPECT_FALSE(info.indexed);
  EXPECT_EQ(info.message_count, msgs.size());
  fs::remove(path);
}

TEST(Mcap, NotAnMcapFileIsNamed) {
  const auto path = tmp("bad.mcap");
  std::ofstream(path) << "hello, this is not an MCAP file at all";
  try {
    mcap::read_info(path);
    FAIL() << "no error";
  } catch (const mcap::Error& e) {
    EXPECT_NE(std::string(e.what()).find("not an MCAP file"), std::string::npos) << e.what();
  }
  EXPECT_THROW(mcap::read_info(tmp("does_not_exist.mcap")), mcap::Error);
  fs::remove(path);
}

TEST(Mcap, ACorruptChunkIsAnError) {
  const auto path = tmp("crc.mcap");
  write_file(path, "", 200);
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(200);
    f.put('#');
  }
  EXPECT_THROW(all_messages(path), mcap::Error);
  fs::remove(path);
}

// A chunk that decompresses to a whole number of the reader's 64 KiB buffers: the reader's last
// call filled the buffer, called zstd once more with nothing left, and read zstd's hint for a next
// frame as a frame cut short (CI failed a replay on such a chunk of a real recording).
TEST(Mcap, AChunkOfWholeDecodeBuffersReadsBack) {
  const auto path = tmp("whole_buffers.mcap");
  // One chunk holding the schema, the channel and one message of `n` bytes; its uncompressed size.
  auto write_one = [&](size_t n) {
    mcap::WriterOptions o;
    o.compression = "zstd";
    o.chunk_size = 1u << 20;
    mcap::Writer w(path, o);
    const auto s = w.add_schema("mpgc::msg::Clock", "omgidl", "module mpgc { module msg { struct Clock { int64 time_ns; }; }; };");
    const auto c = w.add_channel(s, "clock", "cdr");
    std::string payload(n, '\0');
    for (size_t i = 0; i < n; ++i) payload[i] = static_cast<char>((i * 2654435761u) >> 13);
    w.write(c, 1000, 7, payload.data(), payload.size());
    w.close();
    const auto info = mcap::read_info(path);
    return info.compression.at("zstd").uncompressed;
  };
  const uint64_t overhead = write_one(0);
  for (const uint64_t chunk : {uint64_t{1} << 16, uint64_t{1} << 17, (uint64_t{1} << 17) + 1}) {
    ASSERT_EQ(write_one(chunk - overhead), chunk);
    std::vector<mcap::Message> got;
    ASSERT_NO_THROW(got = all_messages(path)) << chunk << "-byte chunk";
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].data.size(), chunk - overhead);
  }
  fs::remove(path);
}

// fuzz_mcap's finding: a zstd chunk of 216 bytes whose header claims 4 GB. The reader used to
// allocate (and zero) the claimed size before decompressing; now it streams, so reading the file
// is an error that costs kilobytes (max RSS grows by far less than the claim).
TEST(Mcap, AChunkClaimingGigabytesIsAnErrorWithoutAllocatingThem) {
  const std::string path = mpgc::testing::source_dir() + "/tests/fuzz/corpus/mcap/oom_chunk_claims_4gb_1.mcap";
  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  try {
    all_messages(path);
    ADD_FAILURE() << "no error";
  } catch (const mcap::Error& e) {
    EXPECT_NE(std::string(e.what()).find("header says 4143972824"), std::string::npos) << e.what();
  }
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 256 * 1024) << "KiB of max RSS while reading";  // 4 GB before
}

// Every topic of topics.hpp names a type of idl/ with its schema: the recorder needs no list.
TEST(Recorder, EveryTopicHasARegisteredTypeAndSchema) {
  for (const auto& t : mpgc::topics::kAll) {
    const auto* type = mpgc::msg::find_type(t.type);
    ASSERT_NE(type, nullptr) << t.name << ": " << t.type;
    const std::string full(t.type);  // "mpgc::msg::NavState": the IDL declares "struct NavState"
    const std::string name = full.substr(full.rfind("::") + 2);
    EXPECT_NE(std::string(type->idl).find("struct " + name + " "), std::string::npos) << t.type;
  }
}

TEST(Recorder, RotationWritesCompleteFiles) {
  mpgc::recorder::RecorderParams p;
  p.file = tmp("rot.mcap");
  p.rotate_s = 10;
  p.chunk_kib = 4;
  std::vector<std::string> files;
  {
    mpgc::recorder::Recording r(p);
    const int ch = r.channel("clock", "mpgc::msg::Clock", "omgidl", "x", "cdr");
    for (int i = 0; i < 100; ++i) r.write(ch, static_cast<uint64_t>(i) * 1'000'000'000ull, 0, "abc", 3);
    r.close();
    files = r.files();
  }
  ASSERT_EQ(files.size(), 10u);
  for (const auto& f : files) {
    const auto info = mcap::read_info(f);
    EXPECT_TRUE(info.indexed) << f;
    EXPECT_EQ(info.message_count, 10u) << f;
    fs::remove(f);
  }
}

TEST(Recorder, StampOfACdrSample) {
  const unsigned char le[] = {0, 1, 0, 0, 0x10, 0x27, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(mpgc::recorder::leading_int64(le, sizeof le), 10000);
  const unsigned char xcdr2[] = {0, 9, 0, 0, 0x10, 0x27, 0, 0, 0, 0, 0, 0};
  EXPECT_FALSE(mpgc::recorder::leading_int64(xcdr2, sizeof xcdr2));
  EXPECT_FALSE(mpgc::recorder::leading_int64(le, 8));
  EXPECT_FALSE(mpgc::recorder::location_fix(0, "x", {NAN, 1.0}));
  EXPECT_TRUE(mpgc::recorder::location_fix(0, "x", {10.0, 63.0}, 0.5));
}
