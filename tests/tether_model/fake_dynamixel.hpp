#pragma once
// A fake Dynamixel MX servo (Protocol 2.0 firmware) on the master side of a
// pseudo-terminal pair: a thread that answers Ping, Read and Write like the MX
// control table (torque lock on EEPROM fields, velocity mode integrating the
// position), with switches to stay silent or corrupt a reply, for the driver tests.

#include <poll.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "ferret/tether_model/dynamixel_protocol.hpp"
#include "support/pty_pair.hpp"

namespace ferret::test {

namespace dxl = ferret::tether::dxl;

class FakeDynamixel {
 public:
  explicit FakeDynamixel(std::uint16_t model_number = 311, std::uint8_t id = 1)
      : id_(id), master_(pty_.master()) {
    table_.fill(0);
    table_[0] = static_cast<std::uint8_t>(model_number & 0xFF);
    table_[1] = static_cast<std::uint8_t>(model_number >> 8);
    table_[6] = 41;  // firmware version
    table_[7] = id;
    table_[11] = 3;  // position mode, the factory default
    thread_ = std::thread([this] { serve(); });
  }
  ~FakeDynamixel() {
    stop_ = true;
    thread_.join();
  }
  FakeDynamixel(const FakeDynamixel&) = delete;
  FakeDynamixel& operator=(const FakeDynamixel&) = delete;

  [[nodiscard]] const std::string& port() const { return pty_.slave_name(); }
  /// Ignore the next n requests (the driver sees timeouts).
  void drop_next(int n) { drop_ = n; }
  /// Flip a CRC bit in the next n replies.
  void corrupt_next(int n) { corrupt_ = n; }
  /// Present Current register value (signed, 3.36 mA units on the MX-64).
  void set_present_current(std::int16_t units) {
    write_table(126, dxl::to_le(static_cast<std::uint16_t>(units), 2));
  }
  [[nodiscard]] std::int32_t goal_velocity() {
    return static_cast<std::int32_t>(read_table(104, 4));
  }
  [[nodiscard]] std::uint32_t read_table(std::uint16_t address, std::size_t size) {
    std::lock_guard lock(mutex_);
    return dxl::from_le(std::span(table_).subspan(address, size));
  }
  [[nodiscard]] int requests() const { return requests_; }

 private:
  void write_table(std::uint16_t address, const std::vector<std::uint8_t>& data) {
    std::lock_guard lock(mutex_);
    std::copy(data.begin(), data.end(), table_.begin() + address);
  }

  // Velocity mode: the position follows Goal Velocity (0.229 rpm units, 4096 ticks a rev).
  void integrate(double dt_s) {
    std::lock_guard lock(mutex_);
    const bool moving = table_[64] == 1 && table_[11] == 1;
    const auto goal = static_cast<std::int32_t>(dxl::from_le(std::span(table_).subspan(104, 4)));
    const std::int32_t velocity = moving ? goal : 0;
    position_ticks_ += velocity * 0.229 / 60.0 * 4096.0 * dt_s;
    const auto ticks = static_cast<std::int32_t>(std::lround(position_ticks_));
    const auto v = dxl::to_le(static_cast<std::uint32_t>(velocity), 4);
    const auto p = dxl::to_le(static_cast<std::uint32_t>(ticks), 4);
    std::copy(v.begin(), v.end(), table_.begin() + 128);
    std::copy(p.begin(), p.end(), table_.begin() + 132);
  }

  void serve() {
    std::vector<std::uint8_t> rx;
    auto last = std::chrono::steady_clock::now();
    while (!stop_) {
      pollfd p{master_, POLLIN, 0};
      const int r = ::poll(&p, 1, 5);
      const auto now = std::chrono::steady_clock::now();
      integrate(std::chrono::duration<double>(now - last).count());
      last = now;
      if (r <= 0 || !(p.revents & POLLIN)) continue;
      std::array<std::uint8_t, 256> chunk{};
      const ssize_t n = ::read(master_, chunk.data(), chunk.size());
      if (n <= 0) continue;
      rx.insert(rx.end(), chunk.begin(), chunk.begin() + n);
      while (true) {
        const auto d = dxl::decode(rx);
        rx.erase(rx.begin(), rx.begin() + static_cast<long>(d.consumed));
        if (d.status == dxl::DecodeResult::Status::kIncomplete) break;
        if (d.status != dxl::DecodeResult::Status::kPacket) continue;
        handle(d.packet);
      }
    }
  }

  void handle(const dxl::Packet& req) {
    if (req.id != id_ && req.id != dxl::kBroadcastId) return;
    ++requests_;
    if (drop_ > 0) {
      --drop_;
      return;
    }
    std::vector<std::uint8_t> reply;
    std::lock_guard lock(mutex_);
    switch (req.instruction) {
      case dxl::instruction::kPing:
        reply =
            dxl::encode_status(id_, 0, std::vector<std::uint8_t>{table_[0], table_[1], table_[6]});
        break;
      case dxl::instruction::kRead: {
        if (req.params.size() != 4) {
          reply = dxl::encode_status(id_, 0x05);  // data length error
          break;
        }
        const auto address = dxl::from_le(std::span(req.params).subspan(0, 2));
        const auto length = dxl::from_le(std::span(req.params).subspan(2, 2));
        if (address + length > table_.size()) {
          reply = dxl::encode_status(id_, 0x07);  // access error
          break;
        }
        reply = dxl::encode_status(id_, 0, std::span(table_).subspan(address, length));
        break;
      }
      case dxl::instruction::kWrite: {
        const auto address = dxl::from_le(std::span(req.params).subspan(0, 2));
        const std::size_t length = req.params.size() - 2;
        // EEPROM area (below 64) is locked while torque is on; out of range is an access error.
        if (address + length > table_.size() || (address < 64 && table_[64] == 1) || address < 7) {
          reply = dxl::encode_status(id_, 0x07);
          break;
        }
        std::copy(req.params.begin() + 2, req.params.end(), table_.begin() + address);
        reply = dxl::encode_status(id_, 0);
        break;
      }
      default:
        reply = dxl::encode_status(id_, 0x02);  // instruction error
    }
    if (corrupt_ > 0) {
      --corrupt_;
      reply.back() ^= 0x01;
    }
    if (::write(master_, reply.data(), reply.size()) < 0) return;
  }

  std::uint8_t id_;
  PtyPair pty_;
  int master_ = -1;
  std::array<std::uint8_t, 256> table_{};
  double position_ticks_ = 0.0;
  std::mutex mutex_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<int> drop_{0}, corrupt_{0}, requests_{0};
};

}  // namespace ferret::test
