#include "mpgc/dds/raw_writer.hpp"

#include <utility>

#include <dds/ddsi/ddsi_serdata.h>

namespace mpgc::dds {

namespace {
constexpr const char* kPrimePartition = "mpgc.raw_writer.type";
}

RawWriter::RawWriter(const Participant& p, Entity topic, const std::string& name, const QosProfile& profile,
                     const void* default_sample)
    : topic_(name), topic_entity_(std::move(topic)) {
  writer_ = Entity(check(dds_create_writer(p.handle(), topic_entity_.handle(), Qos(profile, true).get(), nullptr),
                         "create writer on '" + name + "'"));
  // The sertype: one default sample through a writer and reader of this participant on a
  // partition of their own (local delivery is synchronous), kept as the serdata it arrives in.
  dds_qos_t* q = dds_create_qos();
  const char* parts[] = {kPrimePartition};
  dds_qset_partition(q, 1, parts);
  dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(q, DDS_HISTORY_KEEP_LAST, 1);
  Entity pub(check(dds_create_publisher(p.handle(), q, nullptr), "create publisher for '" + name + "'"));
  Entity sub(check(dds_create_subscriber(p.handle(), q, nullptr), "create subscriber for '" + name + "'"));
  Entity pw(check(dds_create_writer(pub.handle(), topic_entity_.handle(), q, nullptr), "create writer on '" + name + "'"));
  Entity pr(check(dds_create_reader(sub.handle(), topic_entity_.handle(), q, nullptr), "create reader on '" + name + "'"));
  dds_delete_qos(q);
  check(dds_write(pw.handle(), default_sample), "write on '" + name + "'");
  dds_sample_info_t info;
  ddsi_serdata* sd = nullptr;
  const dds_return_t n = check(dds_takecdr(pr.handle(), &sd, 1, &info, DDS_ANY_STATE), "take on '" + name + "'");
  if (n != 1 || sd == nullptr) throw Error("'" + name + "': take of the sample that gives the type", DDS_RETCODE_ERROR);
  type_sample_ = sd;
}

RawWriter::RawWriter(RawWriter&& o) noexcept
    : topic_(std::move(o.topic_)),
      topic_entity_(std::move(o.topic_entity_)),
      writer_(std::move(o.writer_)),
      type_sample_(std::exchange(o.type_sample_, nullptr)) {}

RawWriter& RawWriter::operator=(RawWriter&& o) noexcept {
  if (this != &o) {
    if (type_sample_ != nullptr) ddsi_serdata_unref(type_sample_);
    writer_ = std::move(o.writer_);
    topic_entity_ = std::move(o.topic_entity_);
    topic_ = std::move(o.topic_);
    type_sample_ = std::exchange(o.type_sample_, nullptr);
  }
  return *this;
}

RawWriter::~RawWriter() {
  writer_ = Entity();
  if (type_sample_ != nullptr) ddsi_serdata_unref(type_sample_);
}

namespace {
// Cyclone checks (normalises) the bytes against the type here: nullptr for a malformed sample.
ddsi_serdata* serdata_of(const ddsi_serdata* type_sample, const void* data, std::size_t size) {
  if (size < 4 || size > UINT32_MAX) return nullptr;
  ddsrt_iovec_t iov;
  iov.iov_base = const_cast<void*>(data);
  iov.iov_len = static_cast<ddsrt_iov_len_t>(size);
  return ddsi_serdata_from_ser_iov(type_sample->type, SDK_DATA, 1, &iov, size);
}
}  // namespace

bool RawWriter::write(const void* data, std::size_t size) {
  ddsi_serdata* sd = serdata_of(type_sample_, data, size);
  if (sd == nullptr) return false;
  check(dds_writecdr(writer_.handle(), sd), "write on '" + topic_ + "'");  // takes the reference
  return true;
}

bool RawWriter::to_c_sample(const void* data, std::size_t size, void* sample) const {
  ddsi_serdata* sd = serdata_of(type_sample_, data, size);
  if (sd == nullptr) return false;
  const bool ok = ddsi_serdata_to_sample(sd, sample, nullptr, nullptr);
  ddsi_serdata_unref(sd);
  return ok;
}

void RawWriter::wait_for_acks(double timeout_s) const {
  dds_wait_for_acks(writer_.handle(), static_cast<dds_duration_t>(timeout_s * 1e9));  // a timeout is no error here
}

uint32_t RawWriter::matched() const {
  dds_publication_matched_status_t st{};
  check(dds_get_publication_matched_status(writer_.handle(), &st), "publication matched status");
  return st.current_count;
}

}  // namespace mpgc::dds
