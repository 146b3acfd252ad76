// A thin C++17 RAII layer over the Cyclone DDS C API (notes/cyclonedds.md): participant, topic,
// typed writer and reader over the generated C++ value types, and QoS profiles by name.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <dds/dds.h>

#include "mpgc/dds/convert.hpp"

namespace mpgc::dds {

class Error : public std::runtime_error {
 public:
  Error(const std::string& what, dds_return_t rc);
  dds_return_t code() const { return rc_; }

 private:
  dds_return_t rc_;
};

// Throws Error naming `what` when rc is negative; returns rc otherwise.
dds_return_t check(dds_return_t rc, const std::string& what);

// Owns one DDS entity handle; deleting it deletes its children.
class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t h) : h_(h) {}
  Entity(Entity&& o) noexcept : h_(std::exchange(o.h_, 0)) {}
  Entity& operator=(Entity&& o) noexcept {
    if (this != &o) {
      reset();
      h_ = std::exchange(o.h_, 0);
    }
    return *this;
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  ~Entity() { reset(); }
  void reset();
  dds_entity_t handle() const { return h_; }
  explicit operator bool() const { return h_ > 0; }

 private:
  dds_entity_t h_ = 0;
};

// QoS by kind of data (design.md "DDS"; notes/cyclonedds.md "QoS").
struct QosProfile {
  enum class Kind {
    State,    // best-effort, keep-last 1, deadline: own state, tracks, moving obstacles at rate
    Latched,  // reliable, transient-local, keep-last depth: plans, goals, fixed obstacles
    Command,  // reliable, volatile, keep-last depth: actuator commands, acks, health
  };
  Kind kind = Kind::State;
  int depth = 1;                                              // [-] history depth per instance
  double deadline_s = std::numeric_limits<double>::infinity();  // [s] State only
  double lease_s = 1.0;                                       // [s] automatic liveliness lease
  bool reliable = false;  // State only: reliable delivery (simulated time, where a lost sample
                          // would make a lockstep run depend on timing)

  static QosProfile state(double deadline_s = std::numeric_limits<double>::infinity()) {
    return {Kind::State, 1, deadline_s, 1.0, false};
  }
  static QosProfile latched(int depth = 1) {
    return {Kind::Latched, depth, std::numeric_limits<double>::infinity(), 1.0, false};
  }
  static QosProfile command(int depth = 10) {
    return {Kind::Command, depth, std::numeric_limits<double>::infinity(), 1.0, false};
  }
  // The profile used on simulated time: State becomes reliable with a few samples of history, so
  // every sample published in a lockstep step reaches its readers whatever the machine's load.
  QosProfile deterministic() const {
    QosProfile q = *this;
    if (q.kind == Kind::State) {
      q.reliable = true;
      q.depth = std::max(q.depth, 8);
    }
    return q;
  }
  // "state", "latched", "command"; throws std::invalid_argument naming an unknown profile.
  static QosProfile by_name(const std::string& name);
  const char* name() const;
};

// Owns a dds_qos_t built from a profile; `for_writer` adds the writer-only policies.
class Qos {
 public:
  Qos(const QosProfile& p, bool for_writer);
  ~Qos() { dds_delete_qos(q_); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  const dds_qos_t* get() const { return q_; }

 private:
  dds_qos_t* q_;
};

// The embedded loopback Cyclone configuration (deploy/cyclonedds/loopback.xml).
const char* loopback_config();
// Sets CYCLONEDDS_URI to the loopback configuration when it is unset (called by Participant).
void use_loopback_unless_configured();

// A domain participant. Unless CYCLONEDDS_URI is set, the domain is created with the embedded
// loopback configuration, so no process or test ever talks beyond 127.0.0.1 by default.
class Participant {
 public:
  explicit Participant(uint32_t domain_id);
  dds_entity_t handle() const { return e_.handle(); }
  uint32_t domain_id() const { return domain_; }

 private:
  uint32_t domain_;
  Entity e_;
};

template <class T>
class Topic {
 public:
  Topic(const Participant& p, const std::string& name)
      : name_(name),
        e_(check(dds_create_topic(p.handle(), &T::descriptor(), name.c_str(), nullptr, nullptr),
                 "create topic '" + name + "'")) {}
  dds_entity_t handle() const { return e_.handle(); }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  Entity e_;
};

template <class T>
class Writer {
 public:
  Writer(const Participant& p, const Topic<T>& t, const QosProfile& profile)
      : topic_(t.name()), e_(check(dds_create_writer(p.handle(), t.handle(), Qos(profile, true).get(), nullptr),
                                   "create writer on '" + t.name() + "'")) {}
  void write(const T& v) {
    if (muted_ && muted_(v)) return;  // fault injection (Component, faults.accept)
    Arena arena;
    typename T::CType c{};
    to_c(v, c, arena);
    check(dds_write(e_.handle(), &c), "write on '" + topic_ + "'");
  }
  // Number of matched readers (for hand-shakes in tests and latched producers).
  uint32_t matched() const {
    dds_publication_matched_status_t st{};
    check(dds_get_publication_matched_status(e_.handle(), &st), "publication matched status");
    return st.current_count;
  }
  dds_entity_t handle() const { return e_.handle(); }
  const std::string& topic() const { return topic_; }
  // Samples for which `muted` returns true are dropped instead of written.
  void mute_while(std::function<bool(const T&)> muted) { muted_ = std::move(muted); }

 private:
  std::string topic_;
  Entity e_;
  std::function<bool(const T&)> muted_;
};

template <class T>
struct Sample {
  T value;
  dds_sample_info_t info;
};

template <class T>
class Reader {
 public:
  Reader(const Participant& p, const Topic<T>& t, const QosProfile& profile)
      : topic_(t.name()), e_(check(dds_create_reader(p.handle(), t.handle(), Qos(profile, false).get(), nullptr),
                                   "create reader on '" + t.name() + "'")) {}

  // Takes up to max_n samples; key-only samples (writer disposed or gone) are dropped here,
  // so every returned value carries data. Loans are always returned.
  std::vector<Sample<T>> take(std::size_t max_n = 64) {
    std::vector<Sample<T>> out;
    constexpr std::size_t kBatch = 64;
    void* buf[kBatch];
    dds_sample_info_t infos[kBatch];
    while (out.size() < max_n) {
      const std::size_t want = std::min(kBatch, max_n - out.size());
      buf[0] = nullptr;
      const dds_return_t n = check(dds_take(e_.handle(), buf, infos, want, static_cast<uint32_t>(want)),
                                   "take on '" + topic_ + "'");
      if (n <= 0) break;
      LoanGuard guard{e_.handle(), buf, n};
      for (dds_return_t i = 0; i < n; ++i) {
        if (!infos[i].valid_data) continue;
        Sample<T> s{T{}, infos[i]};
        from_c(*static_cast<const typename T::CType*>(buf[i]), s.value);
        out.push_back(std::move(s));
      }
      if (static_cast<std::size_t>(n) < want) break;
    }
    return out;
  }
  uint32_t matched() const {
    dds_subscription_matched_status_t st{};
    check(dds_get_subscription_matched_status(e_.handle(), &st), "subscription matched status");
    return st.current_count;
  }
  // Writers currently alive by liveliness QoS.
  dds_liveliness_changed_status_t liveliness() const {
    dds_liveliness_changed_status_t st{};
    check(dds_get_liveliness_changed_status(e_.handle(), &st), "liveliness status");
    return st;
  }
  dds_entity_t handle() const { return e_.handle(); }
  const std::string& topic() const { return topic_; }

 private:
  struct LoanGuard {
    dds_entity_t reader;
    void** buf;
    dds_return_t n;
    ~LoanGuard() { dds_return_loan(reader, buf, n); }
  };
  std::string topic_;
  Entity e_;
};

}  // namespace mpgc::dds
