#include "mpgc/recorder/live_server.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <unistd.h>

#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <stdexcept>
#include <thread>

namespace mpgc::recorder {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

namespace {

constexpr size_t kMaxClientMessage = 1 << 20;  // [B] a subscribe list of every channel is a few KiB

}  // namespace

// Everything below runs on the I/O thread only, but the constructor, add_channel, publish and the
// atomics.
struct LiveServer::Impl {
  struct Ws;
  Impl(const LiveOptions& o, const std::string& name)
      : hub(name, name + "-" + std::to_string(::getpid())), acceptor(io),
        buffer_limit(static_cast<size_t>(o.client_buffer_mib * 1024 * 1024)) {
    boost::system::error_code ec;
    const auto addr = asio::ip::make_address(o.host, ec);
    if (ec) throw std::invalid_argument("live.host: '" + o.host + "' is not an IP address");
    const tcp::endpoint ep(addr, static_cast<unsigned short>(o.port));
    acceptor.open(ep.protocol());
    acceptor.set_option(asio::socket_base::reuse_address(true));
    acceptor.bind(ep, ec);
    if (ec) throw std::runtime_error("live view: cannot listen on " + o.host + ":" + std::to_string(o.port) + ": " + ec.message());
    acceptor.listen();
    bound_port = acceptor.local_endpoint().port();
    accept();
    thread = std::thread([this] {
      // A handler that throws (it should not) costs that one exchange, never the recorder.
      for (;;) {
        try {
          io.run();
          return;
        } catch (const std::exception&) {
          ++client_errors;
        }
      }
    });
  }

  void accept();
  void send(live::ClientId c, live::Frame f);
  void send_all(const live::Frame& f) {
    for (const auto& [c, w] : clients) send(c, f);
  }

  asio::io_context io;
  live::Hub hub;
  tcp::acceptor acceptor;
  size_t buffer_limit;
  int bound_port = 0;
  std::map<live::ClientId, std::weak_ptr<Ws>> clients;
  live::ClientId next_client = 1;
  std::atomic<uint32_t> next_channel{1};
  std::atomic<uint64_t> n_clients{0}, client_errors{0}, dropped{0};
  std::thread thread;
};

// One WebSocket client: reads its messages, writes the frames queued for it one at a time.
struct LiveServer::Impl::Ws : std::enable_shared_from_this<Ws> {
  Ws(Impl& s, tcp::socket sock, live::ClientId c) : srv(s), ws(std::move(sock)), id(c) {}
  void start(http::request<http::string_body> req) {
    ws.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(http::field::sec_websocket_protocol, live::kSubprotocol); }));
    ws.read_message_max(kMaxClientMessage);
    ws.async_accept(req, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->srv.clients[self->id] = self;
      self->srv.n_clients = self->srv.clients.size();
      for (auto& f : self->srv.hub.open(self->id)) self->queue(std::move(f));
      self->read();
    });
  }
  void read() {
    ws.async_read(in, [self = shared_from_this()](beast::error_code ec, size_t n) {
      if (ec) return self->closed();
      const uint64_t before = self->srv.hub.errors();
      std::vector<live::Frame> out;
      if (self->ws.got_text()) {
        const auto d = self->in.data();
        out = self->srv.hub.on_text(self->id, std::string_view(static_cast<const char*>(d.data()), d.size()));
      } else {
        out = self->srv.hub.on_binary(self->id, n);
      }
      self->srv.client_errors += self->srv.hub.errors() - before;
      self->in.consume(self->in.size());
      for (auto& f : out) self->queue(std::move(f));
      self->read();
    });
  }
  void queue(live::Frame f) {
    if (queued_bytes + f.bytes.size() > srv.buffer_limit) {
      ++srv.dropped;
      if (f.binary) return;  // a slow client loses samples
      // An advertise or status it cannot take: it would go on with a wrong picture (or it is
      // sending bad messages without reading the answers). Disconnect it.
      beast::error_code ec;
      beast::get_lowest_layer(ws).socket().close(ec);
      return;
    }
    queued_bytes += f.bytes.size();
    out.push_back(std::move(f));
    if (out.size() == 1) write();
  }
  void write() {
    ws.binary(out.front().binary);
    ws.async_write(asio::buffer(out.front().bytes), [self = shared_from_this()](beast::error_code ec, size_t) {
      if (ec) return self->closed();
      self->queued_bytes -= self->out.front().bytes.size();
      self->out.pop_front();
      if (!self->out.empty()) self->write();
    });
  }
  void closed() {
    if (srv.clients.erase(id) == 0) return;
    srv.hub.close(id);
    srv.n_clients = srv.clients.size();
  }

  Impl& srv;
  websocket::stream<beast::tcp_stream> ws;
  live::ClientId id;
  beast::flat_buffer in;
  std::deque<live::Frame> out;
  size_t queued_bytes = 0;
};

namespace {

// One HTTP connection: the page's files, or the upgrade to a WebSocket client.
struct Http : std::enable_shared_from_this<Http> {
  using Upgrade = std::function<void(tcp::socket, http::request<http::string_body>)>;
  Http(tcp::socket s, Upgrade up, std::atomic<uint64_t>& errors) : stream(std::move(s)), upgrade(std::move(up)), errors(errors) {}
  void read() {
    req = {};
    stream.expires_after(std::chrono::seconds(30));
    http::async_read(stream, buf, req, [self = shared_from_this()](beast::error_code ec, size_t) {
      if (ec) {
        if (ec != http::error::end_of_stream && ec != beast::error::timeout) ++self->errors;
        self->stream.socket().shutdown(tcp::socket::shutdown_both, ec);
        return;
      }
      self->answer();
    });
  }
  void answer() {
    if (websocket::is_upgrade(req)) {
      if (live::offers_subprotocol(std::string(req[http::field::sec_websocket_protocol]))) {
        stream.expires_never();
        return upgrade(stream.release_socket(), std::move(req));
      }
      ++errors;
      return respond(http::status::bad_request, "text/plain", std::string("offer the WebSocket subprotocol ") + live::kSubprotocol + "\n");
    }
    if (req.method() != http::verb::get) {
      ++errors;
      return respond(http::status::method_not_allowed, "text/plain", "GET only\n");
    }
    const auto f = live::web_file(std::string(req.target()));
    if (!f) return respond(http::status::not_found, "text/plain", "not found\n");
    respond(http::status::ok, f->content_type, f->body);
  }
  void respond(http::status st, const std::string& type, std::string body) {
    auto res = std::make_shared<http::response<http::string_body>>(st, req.version());
    res->set(http::field::server, "mpgc_record");
    res->set(http::field::content_type, type);
    res->set(http::field::cache_control, "no-store");
    res->keep_alive(req.keep_alive());
    res->body() = std::move(body);
    res->prepare_payload();
    http::async_write(stream, *res, [self = shared_from_this(), res](beast::error_code ec, size_t) {
      if (ec || !res->keep_alive()) {
        self->stream.socket().shutdown(tcp::socket::shutdown_both, ec);
        return;
      }
      self->read();
    });
  }
  beast::tcp_stream stream;
  beast::flat_buffer buf;
  http::request<http::string_body> req;
  Upgrade upgrade;
  std::atomic<uint64_t>& errors;
};

}  // namespace

void LiveServer::Impl::accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket s) {
    if (ec == asio::error::operation_aborted) return;  // closing
    if (!ec) {
      auto up = [this](tcp::socket sock, http::request<http::string_body> req) {
        std::make_shared<Ws>(*this, std::move(sock), next_client++)->start(std::move(req));
      };
      std::make_shared<Http>(std::move(s), up, client_errors)->read();
    }
    accept();
  });
}

void LiveServer::Impl::send(live::ClientId c, live::Frame f) {
  const auto it = clients.find(c);
  if (it == clients.end()) return;
  if (auto w = it->second.lock()) w->queue(std::move(f));
}

LiveServer::LiveServer(const LiveOptions& o, const std::string& name) : impl_(std::make_unique<Impl>(o, name)) {}

LiveServer::~LiveServer() {
  Impl& s = *impl_;
  asio::post(s.io, [&s] {
    beast::error_code ec;
    s.acceptor.close(ec);
    for (auto& [c, w] : s.clients)
      if (auto p = w.lock()) beast::get_lowest_layer(p->ws).socket().close(ec);
  });
  // Connections still in an HTTP exchange end at their timeout: stop rather than wait for them.
  asio::post(s.io, [&s] { s.io.stop(); });
  if (s.thread.joinable()) s.thread.join();
}

uint32_t LiveServer::add_channel(live::Channel c) {
  c.id = impl_->next_channel++;
  const uint32_t id = c.id;
  Impl& s = *impl_;
  asio::post(s.io, [&s, c = std::move(c)]() mutable {
    if (auto f = s.hub.add_channel(std::move(c))) s.send_all(*f);
  });
  return id;
}

void LiveServer::publish(uint32_t channel, uint64_t log_time_ns, const void* data, size_t n) {
  // Always, even with no client: the hub keeps each channel's last sample for the next subscriber.
  auto payload = std::make_shared<std::string>(static_cast<const char*>(data), n);
  Impl& s = *impl_;
  asio::post(s.io, [&s, channel, log_time_ns, payload] {
    for (auto& [c, f] : s.hub.sample(channel, log_time_ns, payload->data(), payload->size())) s.send(c, std::move(f));
  });
}

int LiveServer::port() const { return impl_->bound_port; }

LiveServer::Stats LiveServer::stats() const {
  return {impl_->n_clients.load(), impl_->client_errors.load(), impl_->dropped.load()};
}

}  // namespace mpgc::recorder
