// Plain UDP for device wires (NMEA 0183 over UDP, as IEC 61162-450 and serial-to-LAN converters
// carry it): a non-blocking receiver that splits datagrams into lines, and a sender. No DDS.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mpgc::net {

class UdpReceiver {
 public:
  // Binds host:port (an IPv4 address, e.g. 127.0.0.1). Throws std::runtime_error naming both.
  UdpReceiver(const std::string& host, int port);
  ~UdpReceiver();
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;
  // Every line (CR/LF stripped, empty ones dropped) of every datagram waiting; never blocks.
  // At most max_datagrams are read per call so a flood cannot starve the caller.
  std::vector<std::string> receive_lines(int max_datagrams = 1000);
  int port() const { return port_; }

 private:
  int fd_ = -1;
  int port_ = 0;
};

class UdpSender {
 public:
  UdpSender(const std::string& host, int port);  // throws std::runtime_error naming both
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;
  // One datagram; returns false (and counts) when the kernel refused it.
  bool send(const std::string& payload);
  uint64_t failures() const { return failures_; }

 private:
  int fd_ = -1;
  uint64_t failures_ = 0;
  std::vector<unsigned char> addr_;
};

}  // namespace mpgc::net
