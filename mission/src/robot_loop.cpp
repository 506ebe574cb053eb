#include "ferret/mission/robot_loop.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <stdexcept>
#include <thread>

namespace ferret {
namespace {

std::atomic<int> g_signal{0};

extern "C" void on_stop_signal(int signal) { g_signal.store(signal); }

// Catches SIGINT and SIGTERM for its lifetime.
class CaughtSignals {
 public:
  CaughtSignals() {
    g_signal.store(0);
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~CaughtSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  CaughtSignals(const CaughtSignals&) = delete;
  CaughtSignals& operator=(const CaughtSignals&) = delete;

 private:
  struct sigaction old_int_ {
  }, old_term_{};
};

}  // namespace

std::string PeriodicLoopResult::summary(double period_s) const {
  return fmt::format("{} steps of {:.0f} ms, {} overran, the longest {:.1f} ms; stopped: {}", steps,
                     period_s * 1e3, overruns, worst_step_s * 1e3, why_stopped);
}

PeriodicLoopResult run_periodic(double period_s, double duration_s,
                                const std::function<bool()>& step) {
  if (!(period_s > 0.0) || !(duration_s >= 0.0))
    throw std::invalid_argument("run_periodic: period > 0, duration >= 0");
  using Clock = std::chrono::steady_clock;
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_s));
  const auto start = Clock::now();
  const auto end = start + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(duration_s));
  CaughtSignals signals;
  PeriodicLoopResult r;
  auto due = start;
  for (;;) {
    if (const int s = g_signal.load(); s != 0) {
      r.why_stopped = s == SIGINT ? "SIGINT" : "SIGTERM";
      return r;
    }
    if (duration_s > 0.0 && Clock::now() >= end) {
      r.why_stopped = "duration";
      return r;
    }
    const auto began = Clock::now();
    const bool more = step();
    const auto ended = Clock::now();
    ++r.steps;
    r.worst_step_s = std::max(r.worst_step_s, std::chrono::duration<double>(ended - began).count());
    if (!more) {
      r.why_stopped = "done";
      return r;
    }
    due += period;
    if (ended > due) {
      ++r.overruns;
      due = ended;  // run late once; do not burst to catch up
    }
    std::this_thread::sleep_until(due);
  }
}

}  // namespace ferret
