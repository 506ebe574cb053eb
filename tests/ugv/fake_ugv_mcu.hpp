#pragma once
// A fake miniUGV microcontroller on the master side of a pseudo-terminal pair, for the
// hardware backend's tests: a thread that answers HELLO with INFO, takes DRIVE and EPM,
// and streams STATE at its rate. Its wheels follow the DRIVE set-points (integrated in
// real time into encoder counts) unless a test scripts the counts itself; it stops the
// wheels on its own watchdog like the real firmware. Switches make it go silent, send
// garbage only, corrupt CRCs, or speak another protocol version.

#include <poll.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/ugv/ugv_mcu_protocol.hpp"
#include "support/pty_pair.hpp"

namespace ferret::test {

namespace mcu = ferret::ugv::mcu;

class FakeUgvMcu {
 public:
  struct Options {
    std::uint8_t ir_count = 3;  ///< the miniUGV's URDF has three ir sensors
    double wheel_radius_m = 0.02;
    double ticks_per_rev = 360.0;
    std::uint16_t watchdog_ms = 300;
    int state_rate_hz = 50;
    /// Wheels follow DRIVE (true) or only scripted counts (add_ticks).
    bool integrate_drive = true;
  };

  FakeUgvMcu() : FakeUgvMcu(Options{}) {}
  explicit FakeUgvMcu(Options options) : options_(options), master_(pty_.master()) {
    state_.ir_mm.assign(options.ir_count, mcu::kIrNoReturn);
    state_.battery_mv = 7800;
    state_.battery_percent = 87;
    thread_ = std::thread([this] { serve(); });
  }
  ~FakeUgvMcu() {
    stop_ = true;
    thread_.join();
  }
  FakeUgvMcu(const FakeUgvMcu&) = delete;
  FakeUgvMcu& operator=(const FakeUgvMcu&) = delete;

  [[nodiscard]] const std::string& port() const { return pty_.slave_name(); }

  // ---- what the sensors read
  void set_ir_mm(const std::vector<std::uint16_t>& mm) {
    std::lock_guard lock(mutex_);
    state_.ir_mm = mm;
    ++state_.ir_seq;
  }
  void set_imu_cdeg(std::int16_t roll, std::int16_t pitch, std::int16_t yaw) {
    std::lock_guard lock(mutex_);
    state_.roll_cdeg = roll;
    state_.pitch_cdeg = pitch;
    state_.yaw_cdeg = yaw;
  }
  void set_battery(std::uint16_t mv, std::uint8_t percent) {
    std::lock_guard lock(mutex_);
    state_.battery_mv = mv;
    state_.battery_percent = percent;
  }
  void set_contact(bool contact) {
    std::lock_guard lock(mutex_);
    set_flag(mcu::flag::kContact, contact);
  }
  void set_faults(std::uint16_t faults) {
    std::lock_guard lock(mutex_);
    state_.faults = faults;
  }
  /// The EPM ignores pulses (a broken driver): the state stays, the fault bit is set.
  void break_epm(bool broken) { epm_broken_ = broken; }
  /// Scripted wheel motion: adds counts to both encoders at once (between two STATEs).
  void add_ticks(std::int32_t left, std::int32_t right) {
    std::lock_guard lock(mutex_);
    left_ticks_ += left;
    right_ticks_ += right;
  }
  /// Restarts: the clock and the counts start from 0 again.
  void restart() {
    std::lock_guard lock(mutex_);
    start_ = std::chrono::steady_clock::now();
    left_ticks_ = right_ticks_ = 0.0;
  }

  // ---- misbehaviour
  void go_silent(bool silent) { silent_ = silent; }
  /// Only noise on the line (another device, a wrong baud rate); STATE and INFO stop.
  void send_garbage_only(bool garbage) { garbage_ = garbage; }
  /// Flip a payload bit in the CRC of the next n frames it sends.
  void corrupt_next(int n) { corrupt_ = n; }
  /// Noise bytes between frames (resynchronisation), each frame preceded by `n` of them.
  void noise_between_frames(int n) { noise_ = n; }
  /// The version byte of every frame it sends.
  void set_protocol_version(std::uint8_t version) { version_ = version; }
  /// No INFO replies to HELLO (STATE continues).
  void ignore_hello(bool ignore) { ignore_hello_ = ignore; }

  // ---- what it received
  [[nodiscard]] mcu::DriveCommand last_drive() {
    std::lock_guard lock(mutex_);
    return drive_;
  }
  [[nodiscard]] int drive_frames() const { return drive_frames_; }
  [[nodiscard]] int hello_frames() const { return hello_frames_; }
  [[nodiscard]] int epm_pulses() const { return epm_pulses_; }
  [[nodiscard]] bool epm_on() {
    std::lock_guard lock(mutex_);
    return state_.flags & mcu::flag::kEpmOn;
  }
  [[nodiscard]] int states_sent() const { return states_sent_; }
  [[nodiscard]] bool watchdog_stopped() {
    std::lock_guard lock(mutex_);
    return state_.flags & mcu::flag::kWatchdogStop;
  }
  [[nodiscard]] std::int32_t left_ticks() {
    std::lock_guard lock(mutex_);
    return static_cast<std::int32_t>(std::lround(left_ticks_));
  }
  [[nodiscard]] std::int32_t right_ticks() {
    std::lock_guard lock(mutex_);
    return static_cast<std::int32_t>(std::lround(right_ticks_));
  }

 private:
  void set_flag(std::uint8_t bit, bool on) {
    state_.flags = static_cast<std::uint8_t>(on ? (state_.flags | bit) : (state_.flags & ~bit));
  }

  void send(std::vector<std::uint8_t> bytes) {
    if (silent_) return;
    if (noise_ > 0) {
      std::vector<std::uint8_t> pre;
      for (int i = 0; i < noise_; ++i)
        pre.push_back(static_cast<std::uint8_t>(rng_.uniform_int(0, 255)));
      pre.push_back(mcu::kSync0);  // a false start of a frame
      bytes.insert(bytes.begin(), pre.begin(), pre.end());
    }
    if (corrupt_ > 0) {
      --corrupt_;
      bytes[bytes.size() - 3] ^= 0x10;  // the last payload byte: the CRC no longer matches
    }
    if (::write(master_, bytes.data(), bytes.size()) < 0) return;
  }

  std::vector<std::uint8_t> framed(std::uint8_t type, std::vector<std::uint8_t> payload) {
    return mcu::encode_frame(mcu::Frame{version_, type, tx_seq_++, std::move(payload)});
  }

  void handle(const mcu::Frame& f) {
    last_rx_ = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    switch (f.type) {
      case mcu::type::kDrive:
        if (const auto d = mcu::decode_drive(f.payload)) {
          drive_ = *d;
          ++drive_frames_;
          set_flag(mcu::flag::kWatchdogStop, false);
        }
        break;
      case mcu::type::kEpm:
        if (const auto e = mcu::decode_epm(f.payload)) {
          const bool on = state_.flags & mcu::flag::kEpmOn;
          if (e->on != on) {  // a pulse only on a change
            ++epm_pulses_;
            if (epm_broken_)
              state_.faults |= mcu::fault::kEpm;
            else
              set_flag(mcu::flag::kEpmOn, e->on);
          }
        }
        break;
      case mcu::type::kHello:
        ++hello_frames_;
        if (!ignore_hello_) {
          mcu::McuInfo info{1, 4, options_.ir_count, options_.watchdog_ms,
                            static_cast<std::uint8_t>(options_.state_rate_hz)};
          pending_.push_back(framed(mcu::type::kInfo, mcu::encode_payload(info)));
        }
        break;
      default:
        break;
    }
  }

  void integrate(double dt_s) {
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    const bool fed =
        std::chrono::duration<double>(now - last_rx_).count() * 1000.0 < options_.watchdog_ms;
    if (!fed && (drive_.left_mmps != 0 || drive_.right_mmps != 0)) {
      drive_ = {};  // the firmware's watchdog: the host went quiet, stop
      set_flag(mcu::flag::kWatchdogStop, true);
    }
    if (!options_.integrate_drive) return;
    const double ticks_per_m =
        options_.ticks_per_rev / (2.0 * std::numbers::pi * options_.wheel_radius_m);
    left_ticks_ += drive_.left_mmps / 1000.0 * dt_s * ticks_per_m;
    right_ticks_ += drive_.right_mmps / 1000.0 * dt_s * ticks_per_m;
  }

  void serve() {
    mcu::FrameReader reader;
    auto last = std::chrono::steady_clock::now();
    auto next_state = last;
    const auto period = std::chrono::microseconds(1000000 / options_.state_rate_hz);
    while (!stop_) {
      pollfd p{master_, POLLIN, 0};
      const int r = ::poll(&p, 1, 2);
      const auto now = std::chrono::steady_clock::now();
      integrate(std::chrono::duration<double>(now - last).count());
      last = now;
      if (r > 0 && (p.revents & POLLIN)) {
        std::array<std::uint8_t, 256> chunk{};
        const ssize_t n = ::read(master_, chunk.data(), chunk.size());
        if (n > 0) reader.push(std::span(chunk).first(static_cast<std::size_t>(n)));
        while (const auto ev = reader.next())
          if (ev->status == mcu::DecodeResult::Status::kFrame) handle(ev->frame);
      }
      std::vector<std::vector<std::uint8_t>> out;
      {
        std::lock_guard lock(mutex_);
        out.swap(pending_);
      }
      if (garbage_) {
        std::vector<std::uint8_t> junk(24);
        for (auto& b : junk) b = static_cast<std::uint8_t>(rng_.uniform_int(0, 255));
        if (now >= next_state) {
          next_state = now + period;
          if (!silent_ && ::write(master_, junk.data(), junk.size()) < 0) continue;
        }
        continue;
      }
      for (auto& bytes : out) send(std::move(bytes));
      if (now >= next_state) {
        next_state = now + period;
        mcu::McuState s;
        {
          std::lock_guard lock(mutex_);
          s = state_;
          s.mcu_time_ms = static_cast<std::uint32_t>(
              std::chrono::duration_cast<std::chrono::milliseconds>(now - start_).count());
          s.left_ticks = static_cast<std::int32_t>(std::lround(left_ticks_));
          s.right_ticks = static_cast<std::int32_t>(std::lround(right_ticks_));
        }
        send(framed(mcu::type::kState, mcu::encode_payload(s)));
        ++states_sent_;
      }
    }
  }

  Options options_;
  PtyPair pty_;
  int master_ = -1;
  std::mutex mutex_;
  mcu::McuState state_;
  mcu::DriveCommand drive_;
  double left_ticks_ = 0.0, right_ticks_ = 0.0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_rx_ = std::chrono::steady_clock::now();
  std::vector<std::vector<std::uint8_t>> pending_;
  std::uint8_t tx_seq_ = 0;
  Rng rng_{7};
  std::thread thread_;
  std::atomic<bool> stop_{false}, silent_{false}, garbage_{false}, ignore_hello_{false},
      epm_broken_{false};
  std::atomic<int> corrupt_{0}, noise_{0}, drive_frames_{0}, hello_frames_{0}, epm_pulses_{0},
      states_sent_{0};
  std::atomic<std::uint8_t> version_{mcu::kProtocolVersion};
};

}  // namespace ferret::test
