// Writes serialised samples as they were recorded (dds_takecdr's bytes: the 4-byte encapsulation
// header and the XCDR body) on a topic, for replay. Cyclone 0.10 has no public call for a writer's
// sertype, so the constructor takes it from one default sample written and read back inside the
// participant, on a partition no other reader is in.
//
//   auto w = dds::RawWriter::make<msg::NavState>(participant, "nav/own_state", dds::QosProfile::state());
//   if (!w.write(bytes.data(), bytes.size())) ...  // not a valid sample of the type
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "mpgc/dds/dds.hpp"

struct ddsi_serdata;

namespace mpgc::dds {

class RawWriter {
 public:
  template <class T>
  static RawWriter make(const Participant& p, const std::string& topic, const QosProfile& profile) {
    const T v{};  // the C sample points into it
    Arena arena;
    typename T::CType c{};
    to_c(v, c, arena);
    return RawWriter(p, Entity(check(dds_create_topic(p.handle(), &T::descriptor(), topic.c_str(), nullptr, nullptr),
                                     "create topic '" + topic + "'")),
                     topic, profile, &c);
  }
  RawWriter(RawWriter&&) noexcept;
  RawWriter& operator=(RawWriter&&) noexcept;
  ~RawWriter();

  // False (nothing written) when the bytes are not a sample of the topic's type.
  bool write(const void* data, std::size_t size);
  // The sample the bytes hold, if they are one of T, the topic's type (make<T>'s).
  template <class T>
  std::optional<T> decode(const void* data, std::size_t size) const {
    typename T::CType c{};
    if (!to_c_sample(data, size, &c)) return std::nullopt;
    T v;
    from_c(c, v);
    dds_sample_free(&c, &T::descriptor(), DDS_FREE_CONTENTS);
    return v;
  }
  uint32_t matched() const;
  // Until every reliable reader has acknowledged what was written, at most timeout_s.
  void wait_for_acks(double timeout_s) const;
  const std::string& topic() const { return topic_; }

 private:
  bool to_c_sample(const void* data, std::size_t size, void* sample) const;
  RawWriter(const Participant& p, Entity topic, const std::string& name, const QosProfile& profile,
            const void* default_sample);
  std::string topic_;
  Entity topic_entity_, writer_;
  ddsi_serdata* type_sample_ = nullptr;  // holds the sertype the bytes are turned into samples of
};

}  // namespace mpgc::dds
