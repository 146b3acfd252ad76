// mpgc_netem: a userspace link emulator (loss, delay, jitter) for kernels without sch_netem.
// Packets reach it through an iptables NFQUEUE rule; each one gets a verdict: NF_DROP now (loss),
// or NF_ACCEPT once it is due (delay). The decisions are LinkModel's (link_model.hpp); this file
// only talks to the kernel. See README.md beside it.
// <arpa/inet.h> (glibc's netinet/in.h) before the netfilter headers, which would pull linux/in.h.
#include <arpa/inet.h>
#include <libnetfilter_queue/libnetfilter_queue.h>
#include <libnfnetlink/libnfnetlink.h>
#include <linux/netfilter.h>  // NF_ACCEPT, NF_DROP
#include <linux/netfilter/nfnetlink_queue.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "link_model.hpp"

namespace {

using mpgc::netem::Held;
using mpgc::netem::LinkModel;

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

struct Context {
  LinkModel* model;
};

int on_packet(nfq_q_handle* qh, nfgenmsg*, nfq_data* nfa, void* data) {
  auto& ctx = *static_cast<Context*>(data);
  const nfqnl_msg_packet_hdr* ph = nfq_get_msg_packet_hdr(nfa);
  if (!ph) {
    ctx.model->on_error();
    return 0;
  }
  const std::uint32_t id = ntohl(ph->packet_id);
  if (ctx.model->on_packet(id, now_ns()) && nfq_set_verdict(qh, id, NF_DROP, 0, nullptr) < 0) ctx.model->on_error();
  return 0;
}

void print_summary(int queue, const LinkModel& model) {
  std::printf("%s\n", mpgc::netem::summary_line(queue, model.stats()).c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const auto parsed = mpgc::netem::parse_options(std::vector<std::string>(argv, argv + argc));
  if (!parsed.options) {
    std::fprintf(stderr, "mpgc_netem: %s\n%s", parsed.error.c_str(), mpgc::netem::usage().c_str());
    return 2;
  }
  const auto& opt = *parsed.options;
  if (opt.help) {
    std::printf("%s", mpgc::netem::usage().c_str());
    return 0;
  }

  // Signals arrive through a descriptor polled with the queue's, never in the middle of a verdict.
  sigset_t mask;
  sigemptyset(&mask);
  sigaddset(&mask, SIGTERM);
  sigaddset(&mask, SIGINT);
  sigaddset(&mask, SIGUSR1);
  sigprocmask(SIG_BLOCK, &mask, nullptr);
  signal(SIGPIPE, SIG_IGN);
  const int sfd = signalfd(-1, &mask, SFD_CLOEXEC | SFD_NONBLOCK);
  if (sfd < 0) {
    std::fprintf(stderr, "mpgc_netem: signalfd: %s\n", std::strerror(errno));
    return 1;
  }
  prctl(PR_SET_TIMERSLACK, 1UL);  // wake up on time (default slack: 50 us)

  LinkModel model(opt.delay_ms, opt.jitter_ms, opt.loss_pct, opt.seed);
  Context ctx{&model};
  nfq_handle* h = nfq_open();
  if (!h) {
    std::fprintf(stderr, "mpgc_netem: nfq_open: %s (needs root or CAP_NET_ADMIN)\n", std::strerror(errno));
    return 1;
  }
  nfq_q_handle* qh = nfq_create_queue(h, static_cast<std::uint16_t>(opt.queue), &on_packet, &ctx);
  if (!qh) {
    std::fprintf(stderr, "mpgc_netem: cannot bind NFQUEUE %d: %s (bound by another process?)\n", opt.queue,
                 std::strerror(errno));
    nfq_close(h);
    return 1;
  }
  if (nfq_set_mode(qh, NFQNL_COPY_META, 0) < 0) {
    std::fprintf(stderr, "mpgc_netem: nfq_set_mode(COPY_META): %s\n", std::strerror(errno));
    nfq_destroy_queue(qh);
    nfq_close(h);
    return 1;
  }
  if (nfq_set_queue_maxlen(qh, 65536) < 0)
    std::fprintf(stderr, "mpgc_netem: warning: nfq_set_queue_maxlen(65536): %s\n", std::strerror(errno));
  const unsigned ring = nfnl_rcvbufsiz(nfq_nfnlh(h), 8u << 20);
  const int fd = nfq_fd(h);
  std::fprintf(stderr, "netem: queue %d bound: delay %g ms jitter %g ms loss %g%% seed %llu duration %g s ring %u bytes\n",
               opt.queue, opt.delay_ms, opt.jitter_ms, opt.loss_pct, static_cast<unsigned long long>(opt.seed),
               opt.duration_s, ring);

  // Reads what the kernel has queued, at most `max` messages (then verdicts are due again).
  alignas(8) static char buf[65536 + 4096];
  auto read_queue = [&](int max) {
    for (int i = 0; i < max; ++i) {
      const ssize_t n = recv(fd, buf, sizeof buf, MSG_DONTWAIT);
      if (n >= 0) {
        if (nfq_handle_packet(h, buf, static_cast<int>(n)) < 0) model.on_error();
        continue;
      }
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return;
      // ENOBUFS: the ring overflowed; the kernel dropped those packets and skipped their ids, which
      // LinkModel counts as overflow. Anything else is an error, counted; the loop goes on.
      if (errno != ENOBUFS) {
        model.on_error();
        return;
      }
    }
  };
  auto accept = [&](const std::vector<Held>& released) {
    for (const Held& p : released) {
      if (nfq_set_verdict(qh, p.id, NF_ACCEPT, 0, nullptr) < 0)
        model.on_error();
      else
        model.on_accepted(p, now_ns());
    }
  };

  const std::int64_t deadline = opt.duration_s > 0 ? now_ns() + static_cast<std::int64_t>(opt.duration_s * 1e9) : 0;
  bool stop = false;
  while (!stop) {
    std::int64_t now = now_ns();
    accept(model.release_due(now));
    now = now_ns();
    if (deadline && now >= deadline) break;
    std::int64_t wake = -1;
    if (const auto due = model.next_due()) wake = *due;
    if (deadline && (wake < 0 || deadline < wake)) wake = deadline;
    timespec ts{}, *tsp = nullptr;
    if (wake >= 0) {
      const std::int64_t wait = wake > now ? wake - now : 0;
      ts.tv_sec = wait / 1000000000;
      ts.tv_nsec = wait % 1000000000;
      tsp = &ts;
    }
    pollfd fds[2] = {{fd, POLLIN, 0}, {sfd, POLLIN, 0}};
    const int r = ppoll(fds, 2, tsp, nullptr);
    if (r < 0) {
      if (errno != EINTR) {
        model.on_error();
        usleep(1000);
      }
      continue;
    }
    if (fds[1].revents & POLLIN) {
      signalfd_siginfo si{};
      while (read(sfd, &si, sizeof si) == static_cast<ssize_t>(sizeof si)) {
        if (si.ssi_signo == SIGUSR1)
          print_summary(opt.queue, model);
        else
          stop = true;
      }
    }
    if (fds[0].revents) read_queue(1024);
  }

  // Shutdown without a black hole: from now on the kernel accepts new packets itself (queue "full"
  // at 0 entries, fail-open), the ones already handed over are read, and every held one is accepted.
  // Without this, packets queued between the last read and the unbind would be dropped by it.
  if (nfq_set_queue_flags(qh, NFQA_CFG_F_FAIL_OPEN, NFQA_CFG_F_FAIL_OPEN) < 0 || nfq_set_queue_maxlen(qh, 0) < 0)
    model.on_error();
  read_queue(1 << 20);
  accept(model.release_all());
  nfq_destroy_queue(qh);
  nfq_close(h);
  print_summary(opt.queue, model);
  return 0;
}
