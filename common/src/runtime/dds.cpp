#include "mpgc/dds/dds.hpp"

#include <cstdlib>
#include <mutex>

#include "loopback_config.inc"  // kLoopbackConfig, generated from deploy/cyclonedds/loopback.xml

namespace mpgc::dds {

Error::Error(const std::string& what, dds_return_t rc)
    : std::runtime_error(what + ": " + dds_strretcode(rc)), rc_(rc) {}

dds_return_t check(dds_return_t rc, const std::string& what) {
  if (rc < 0) throw Error(what, rc);
  return rc;
}

void Entity::reset() {
  if (h_ > 0) dds_delete(h_);
  h_ = 0;
}

QosProfile QosProfile::by_name(const std::string& name) {
  if (name == "state") return state();
  if (name == "latched") return latched();
  if (name == "command") return command();
  throw std::invalid_argument("unknown QoS profile '" + name + "' (state, latched, command)");
}

const char* QosProfile::name() const {
  switch (kind) {
    case Kind::State: return "state";
    case Kind::Latched: return "latched";
    case Kind::Command: return "command";
  }
  return "?";
}

static dds_duration_t to_duration(double s) {
  return std::isfinite(s) ? static_cast<dds_duration_t>(s * 1e9) : DDS_INFINITY;
}

Qos::Qos(const QosProfile& p, bool for_writer) : q_(dds_create_qos()) {
  dds_qset_liveliness(q_, DDS_LIVELINESS_AUTOMATIC, to_duration(p.lease_s));
  switch (p.kind) {
    case QosProfile::Kind::State:
      if (p.reliable)
        dds_qset_reliability(q_, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      else
        dds_qset_reliability(q_, DDS_RELIABILITY_BEST_EFFORT, 0);
      dds_qset_history(q_, DDS_HISTORY_KEEP_LAST, p.reliable ? p.depth : 1);
      dds_qset_deadline(q_, to_duration(p.deadline_s));
      break;
    case QosProfile::Kind::Latched:
      dds_qset_reliability(q_, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      dds_qset_durability(q_, DDS_DURABILITY_TRANSIENT_LOCAL);
      dds_qset_history(q_, DDS_HISTORY_KEEP_LAST, p.depth);
      // Pitfall 2: late joiners get the durability-service depth, not the history depth.
      dds_qset_durability_service(q_, 0, DDS_HISTORY_KEEP_LAST, p.depth, DDS_LENGTH_UNLIMITED,
                                  DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
      break;
    case QosProfile::Kind::Command:
      dds_qset_reliability(q_, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      dds_qset_history(q_, DDS_HISTORY_KEEP_LAST, p.depth);
      break;
  }
  // Pitfall 3: a restarting writer must not dispose its instances in every reader.
  if (for_writer) dds_qset_writer_data_lifecycle(q_, false);
}

const char* loopback_config() { return kLoopbackConfig; }

// Unless the user chose a configuration, every domain this process (and the processes it starts)
// creates uses the loopback configuration: Cyclone reads CYCLONEDDS_URI, which may hold inline XML.
void use_loopback_unless_configured() {
  static std::once_flag once;
  std::call_once(once, [] {
    const char* uri = std::getenv("CYCLONEDDS_URI");
    if (uri == nullptr || *uri == '\0') setenv("CYCLONEDDS_URI", kLoopbackConfig, 1);
  });
}

Participant::Participant(uint32_t domain_id) : domain_(domain_id) {
  if (domain_id > 230) throw std::invalid_argument("DDS domain id " + std::to_string(domain_id) + " > 230");
  use_loopback_unless_configured();
  e_ = Entity(check(dds_create_participant(domain_id, nullptr, nullptr),
                    "create participant on domain " + std::to_string(domain_id)));
}

}  // namespace mpgc::dds
