#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>

#include "raylane/core/strings.h"

namespace raylane::cli {

namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the flag is set in a signal handler");

extern "C" void on_sigint(int) {
  if (g_interrupted.exchange(true)) _exit(130);  // the second Ctrl-C: leave at once
}

extern "C" void on_stop_request(int) {
  g_interrupted.store(true);
}

void print_time(char* out, std::size_t n, double s) {
  if (s >= 3600)
    std::snprintf(out, n, "%dh%02dm", int(s / 3600), int(s / 60) % 60);
  else if (s >= 60)
    std::snprintf(out, n, "%dm%02ds", int(s / 60), int(s) % 60);
  else
    std::snprintf(out, n, "%.1fs", s);
}

}  // namespace

Progress::Progress(int total_passes, double time_limit, bool quiet)
    : total_(std::max(1, total_passes)),
      time_limit_(time_limit),
      quiet_(quiet),
      tty_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(int done) {
  if (quiet_) return;
  double t = elapsed();
  double eta = done > 0 ? t / done * (total_ - done) : 0;
  if (time_limit_ > 0) eta = std::min(eta, std::max(0.0, time_limit_ - t));
  double frac = std::min(1.0, time_limit_ > 0 ? std::max(double(done) / total_, t / time_limit_)
                                              : double(done) / total_);
  char el[32], et[32];
  print_time(el, sizeof el, t);
  print_time(et, sizeof et, eta);
  if (tty_) {
    constexpr int kWidth = 30;
    char bar[kWidth + 1];
    int fill = int(frac * kWidth);
    for (int i = 0; i < kWidth; ++i)
      bar[i] = i < fill ? '#' : '.';
    bar[kWidth] = 0;
    std::fprintf(stderr, "\r[%s] %d/%s spp  %s elapsed  ETA %s ", bar, done, total_text().c_str(),
                 el, et);
    drawn_ = true;
  } else if (t - last_report_ >= 10 || done == total_) {  // plain lines at most every 10 s
    std::fprintf(stderr, "%d/%s spp, %s elapsed, ETA %s\n", done, total_text().c_str(), el, et);
    last_report_ = t;
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (drawn_) std::fputc('\n', stderr);
  drawn_ = false;
}

void install_interrupt_handler(bool under_launcher) {
  struct sigaction sa = {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  // SIGTERM is what `timeout`, batch schedulers and `kill` send, SIGUSR1 a stop request: on
  // one process they stop the render like Ctrl-C, the image converged so far written (and a
  // second one leaves at once, as a scheduler's grace period ends). Under mpirun, SIGTERM is how
  // mpirun stops its processes when its own Ctrl-C arrives, and SIGUSR1 a signal it forwards to
  // them (docs/cluster.md, "What works across processes"): there each only asks for the stop
  // after the pass, never for the immediate exit of a second Ctrl-C.
  if (under_launcher) sa.sa_handler = on_stop_request;
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGUSR1, &sa, nullptr);
}

bool interrupted() {
  return g_interrupted.load();
}

void print_phases(const PathStats& s, double seconds, int threads) {
  const PathPhases& p = s.phases;
  double available = seconds * threads;
  double idle = std::max(0.0, available - p.total());
  std::fprintf(stderr, "where the time went (thread-seconds of %s × %.3f s):\n",
               counted(threads, "thread").c_str(), seconds);
  const std::pair<const char*, double> rows[] = {{"camera rays", p.camera},
                                                 {"tracing camera rays", p.trace_camera},
                                                 {"tracing bounce + shadow rays", p.trace_rest},
                                                 {"shading (BSDF, roulette)", p.shade},
                                                 {"light sampling", p.lights},
                                                 {"film", p.film},
                                                 {"idle and other", idle}};
  for (const auto& [what, t] : rows)
    std::fprintf(stderr, "  %-30s %9.3f s %6.1f %%\n", what, t, 100 * t / available);
  auto rate = [](uint64_t n, double t) { return t > 0 ? n / t * 1e-6 : 0.0; };
  std::fprintf(stderr, "  camera rays: %llu, %.2f Mrays/s of tracing time per thread\n",
               (unsigned long long)s.camera_rays, rate(s.camera_rays, p.trace_camera));
  std::fprintf(stderr,
               "  bounce rays: %llu, shadow rays: %llu; together %.2f Mrays/s of tracing time "
               "per thread\n",
               (unsigned long long)s.bounce_rays, (unsigned long long)s.shadow_rays,
               rate(s.bounce_rays + s.shadow_rays, p.trace_rest));
  if (s.steps > 0)
    std::fprintf(stderr, "  wavefront steps: %llu, %.0f rays each on average\n",
                 (unsigned long long)s.steps, double(s.rays()) / double(s.steps));
}

}  // namespace raylane::cli
