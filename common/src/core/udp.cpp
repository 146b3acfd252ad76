#include "mpgc/net/udp.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace mpgc::net {

namespace {

sockaddr_in make_addr(const std::string& host, int port) {
  if (port < 1 || port > 65535) throw std::runtime_error("UDP port " + std::to_string(port) + " is outside 1..65535");
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  if (inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1)
    throw std::runtime_error("UDP host '" + host + "' is not an IPv4 address");
  return a;
}

}  // namespace

UdpReceiver::UdpReceiver(const std::string& host, int port) : port_(port) {
  const sockaddr_in a = make_addr(host, port);
  fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("UDP socket: ") + std::strerror(errno));
  const int one = 1;
  setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  const int rcvbuf = 1 << 20;  // bursts of NMEA at a high real-time factor
  setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  if (bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    const std::string why = std::strerror(errno);
    close(fd_);
    throw std::runtime_error("cannot bind UDP " + host + ":" + std::to_string(port) + ": " + why);
  }
}

UdpReceiver::~UdpReceiver() {
  if (fd_ >= 0) close(fd_);
}

std::vector<std::string> UdpReceiver::receive_lines(int max_datagrams) {
  std::vector<std::string> lines;
  char buf[65536];
  for (int k = 0; k < max_datagrams; ++k) {
    const ssize_t n = recv(fd_, buf, sizeof buf, 0);
    if (n <= 0) break;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= static_cast<std::size_t>(n); ++i) {
      if (i == static_cast<std::size_t>(n) || buf[i] == '\n' || buf[i] == '\r') {
        if (i > start) lines.emplace_back(buf + start, i - start);
        start = i + 1;
      }
    }
  }
  return lines;
}

UdpSender::UdpSender(const std::string& host, int port) {
  const sockaddr_in a = make_addr(host, port);
  addr_.assign(reinterpret_cast<const unsigned char*>(&a), reinterpret_cast<const unsigned char*>(&a) + sizeof a);
  fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("UDP socket: ") + std::strerror(errno));
}

UdpSender::~UdpSender() {
  if (fd_ >= 0) close(fd_);
}

bool UdpSender::send(const std::string& payload) {
  const ssize_t n = sendto(fd_, payload.data(), payload.size(), 0, reinterpret_cast<const sockaddr*>(addr_.data()),
                           static_cast<socklen_t>(addr_.size()));
  if (n == static_cast<ssize_t>(payload.size())) return true;
  ++failures_;
  return false;
}

}  // namespace mpgc::net
