#include "ferret/link/codec.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <concepts>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include "ferret/core/crc32.hpp"
#include "ferret/core/error.hpp"

namespace ferret::link {
namespace {

using Reason = Rejection::Reason;

// What a field may hold. The ranges refuse what no miniUGV or UAV can send (a pose
// 100 km from the entry, 100 m/s), not what a controller would call unusual: a
// receiver must never drop a true message.
struct Range {
  double lo, hi;
  std::string_view text;
};
constexpr double kPi = std::numbers::pi;
constexpr Range kTime{0.0, 1e9, "a number in [0, 1e9] s"};
constexpr Range kPosition{-1e5, 1e5, "a number in [-1e5, 1e5] m"};
// Either convention, (-pi, pi] or [0, 2 pi): the sender need not wrap.
constexpr Range kHeading{-2 * kPi, 2 * kPi, "a number in [-2 pi, 2 pi] rad"};
constexpr Range kTilt{-kPi, kPi, "a number in [-pi, pi] rad"};
constexpr Range kSpeed{-100.0, 100.0, "a number in [-100, 100] m/s"};
constexpr Range kAcceleration{-1000.0, 1000.0, "a number in [-1000, 1000] m/s^2"};
constexpr Range kFraction{0.0, 1.0, "a number in [0, 1]"};
constexpr Range kLength{0.0, 1e4, "a number in [0, 1e4] m"};
constexpr Range kPlanDt{0.0, 10.0, "a number in [0, 10] s"};

// The three flag bits of telemetry; the other five are reserved and must be zero.
constexpr std::uint8_t kFlagEpmOn = 1u << 0;
constexpr std::uint8_t kFlagObjectHeld = 1u << 1;
constexpr std::uint8_t kFlagWantsRetraction = 1u << 2;
constexpr std::uint8_t kFlagsDefined = kFlagEpmOn | kFlagObjectHeld | kFlagWantsRetraction;

template <class M, class T>
concept Is = std::same_as<std::remove_const_t<M>, T>;

template <class U>
void put_le(std::vector<std::uint8_t>& out, U value) {
  for (std::size_t i = 0; i < sizeof(U); ++i)
    out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}
template <class U>
U get_le(std::span<const std::uint8_t> bytes) {
  U value = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i)
    value |= static_cast<U>(static_cast<U>(bytes[i]) << (8 * i));
  return value;
}

// ---------------------------------------------------------------------------------
// One description of each payload, walked by three visitors: Writer (encode), Checker
// (validate) and Reader (decode: read, then check as Checker does). The layout and
// the ranges cannot disagree between the sender and the receiver.

template <class Io, class M>
requires Is<M, UgvTelemetry>
void fields(Io& io, M& m) {
  io.f64("t_s", m.t_s, kTime);
  io.f64("x_m", m.x_m, kPosition);
  io.f64("y_m", m.y_m, kPosition);
  io.f64("yaw_rad", m.yaw_rad, kHeading);
  io.f32("vx_mps", m.vx_mps, kSpeed);
  io.f32("vy_mps", m.vy_mps, kSpeed);
  io.f32("ax_mps2", m.ax_mps2, kAcceleration);
  io.f32("ay_mps2", m.ay_mps2, kAcceleration);
  io.enumeration("mode", m.mode, UgvMode::kIdle, UgvMode::kDone);
  io.enumeration("outcome", m.outcome, UgvOutcome::kNone, UgvOutcome::kRecalled);
  io.flags("flags", m.epm_on, m.object_held, m.wants_retraction);
  io.f32("battery_fraction", m.battery_fraction, kFraction);
  io.f64("tether_anchor_x_m", m.tether_anchor_x_m, kPosition);
  io.f64("tether_anchor_y_m", m.tether_anchor_y_m, kPosition);
  io.f64("tether_to_anchor_m", m.tether_to_anchor_m, kLength);
  io.f32("tether_uncertainty_m", m.tether_uncertainty_m, kLength);
  io.f32("roll_rad", m.roll_rad, kTilt);
  io.f32("pitch_rad", m.pitch_rad, kTilt);
  io.u32("last_request_id", m.last_request_id, 0);
  const std::size_t n = io.count("plan_count", m.plan, UgvTelemetry::kMaxPlanSamples);
  for (std::size_t i = 0; i < n; ++i) {
    io.element("plan", i);
    auto& s = m.plan[i];
    io.f32("dt_s", s.dt_s, kPlanDt);
    io.f32("x_m", s.x_m, kPosition);
    io.f32("y_m", s.y_m, kPosition);
    io.f32("vx_mps", s.vx_mps, kSpeed);
    io.f32("vy_mps", s.vy_mps, kSpeed);
  }
  io.end_element();
  io.increasing_dt(m.plan);
}

template <class Io, class M>
requires Is<M, UavRequest>
void fields(Io& io, M& m) {
  io.u32("request_id", m.request_id, 1);
  io.enumeration("kind", m.kind, UavRequest::Kind::kStartSearch, UavRequest::Kind::kAbort);
  io.f64("entry_x_m", m.entry_x_m, kPosition);
  io.f64("entry_y_m", m.entry_y_m, kPosition);
  io.f64("entry_z_m", m.entry_z_m, kPosition);
  io.f64("entry_yaw_rad", m.entry_yaw_rad, kHeading);
  io.text("reason", m.reason, UavRequest::kMaxReasonBytes);
}

template <class Io, class M>
requires Is<M, Ack>
void fields(Io& io, M& m) { io.u32("request_id", m.request_id, 1); }

template <class Io, class M>
requires Is<M, Heartbeat>
void fields(Io& io, M& m) {
  io.f64("t_s", m.t_s, kTime);
  io.f64("ugv_telemetry_t_s", m.ugv_telemetry_t_s, kTime);
}

// Appends the payload's bytes. It checks nothing: encode() validates first.
class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>& out) : out_(out) {}
  void f64(std::string_view, double v, const Range&) {
    put_le(out_, std::bit_cast<std::uint64_t>(v));
  }
  void f32(std::string_view, float v, const Range&) {
    put_le(out_, std::bit_cast<std::uint32_t>(v));
  }
  void u32(std::string_view, std::uint32_t v, std::uint32_t) { put_le(out_, v); }
  template <class E>
  void enumeration(std::string_view, E v, E, E) {
    out_.push_back(static_cast<std::uint8_t>(v));
  }
  void flags(std::string_view, bool epm_on, bool object_held, bool wants_retraction) {
    out_.push_back(static_cast<std::uint8_t>((epm_on ? kFlagEpmOn : 0) |
                                             (object_held ? kFlagObjectHeld : 0) |
                                             (wants_retraction ? kFlagWantsRetraction : 0)));
  }
  void text(std::string_view, const std::string& s, std::size_t max_bytes) {
    const std::string_view sent = wire_reason(s, max_bytes);
    out_.push_back(static_cast<std::uint8_t>(sent.size()));
    out_.insert(out_.end(), sent.begin(), sent.end());
  }
  std::size_t count(std::string_view, const std::vector<PlanSample>& plan, std::size_t) {
    out_.push_back(static_cast<std::uint8_t>(plan.size()));
    return plan.size();
  }
  void element(std::string_view, std::size_t) {}
  void end_element() {}
  void increasing_dt(const std::vector<PlanSample>&) {}

 private:
  std::vector<std::uint8_t>& out_;
};

// Checks a message's values; keeps the first rejection, with the field's path.
class Checker {
 public:
  explicit Checker(std::string_view message) : message_(message) {}

  void f64(std::string_view name, double v, const Range& r) { number(name, v, r); }
  void f32(std::string_view name, float v, const Range& r) { number(name, v, r); }
  void u32(std::string_view name, std::uint32_t v, std::uint32_t min) {
    if (v < min)
      fail(Reason::kOutOfRange, name, fmt::format("an integer >= {}", min), fmt::format("{}", v));
  }
  template <class E>
  void enumeration(std::string_view name, E v, E first, E last) {
    const auto raw = static_cast<std::uint8_t>(v);
    if (raw < static_cast<std::uint8_t>(first) || raw > static_cast<std::uint8_t>(last))
      fail(Reason::kBadEnum, name,
           fmt::format("{} ({}) to {} ({})", static_cast<int>(first), to_string(first),
                       static_cast<int>(last), to_string(last)),
           fmt::format("{}", raw));
  }
  void flags(std::string_view, bool, bool, bool) {}                // a bool cannot be out of range
  void text(std::string_view, const std::string&, std::size_t) {}  // encode() cuts it
  std::size_t count(std::string_view name, const std::vector<PlanSample>& plan, std::size_t max) {
    if (plan.size() > max)
      fail(Reason::kOutOfRange, name, fmt::format("at most {} plan samples", max),
           fmt::format("{}", plan.size()));
    return failed() ? 0 : plan.size();
  }
  void element(std::string_view list, std::size_t i) { element_ = fmt::format("{}[{}]", list, i); }
  void end_element() { element_.clear(); }
  void increasing_dt(const std::vector<PlanSample>& plan) {
    for (std::size_t i = 1; i < plan.size() && !failed(); ++i)
      if (!(plan[i].dt_s > plan[i - 1].dt_s)) {
        element("plan", i);
        fail(Reason::kOutOfRange, "dt_s",
             fmt::format("more than plan[{}].dt_s = {} (samples in time order)", i - 1,
                         plan[i - 1].dt_s),
             fmt::format("{}", plan[i].dt_s));
        end_element();
      }
  }

  [[nodiscard]] bool failed() const { return rejection_.has_value(); }
  [[nodiscard]] std::optional<Rejection>& rejection() { return rejection_; }

 protected:
  /// "telemetry.plan[3].dt_s": the message, the element if inside one, the field.
  [[nodiscard]] std::string path(std::string_view name) const {
    return fmt::format("{}.{}{}{}", message_, element_, element_.empty() ? "" : ".", name);
  }
  void fail(Reason reason, std::string_view name, std::string expected, std::string got) {
    if (!failed()) rejection_ = Rejection{reason, path(name), std::move(expected), std::move(got)};
  }
  void fail_whole(Reason reason, std::string field, std::string expected, std::string got) {
    if (!failed())
      rejection_ = Rejection{reason, std::move(field), std::move(expected), std::move(got)};
  }

 private:
  void number(std::string_view name, double v, const Range& r) {
    if (!std::isfinite(v))
      fail(Reason::kNotFinite, name, "a finite number", fmt::format("{}", v));
    else if (v < r.lo || v > r.hi)
      fail(Reason::kOutOfRange, name, std::string(r.text), fmt::format("{}", v));
  }

  std::string_view message_;
  std::string element_;  ///< "plan[3]" inside a plan sample, else empty
  std::optional<Rejection> rejection_;
};

// Reads the payload's bytes into a message and checks each value as it goes. Never
// reads past the payload: a field that does not fit is a length mismatch.
class Reader : public Checker {
 public:
  Reader(std::string_view message, std::span<const std::uint8_t> payload)
      : Checker(message), payload_(payload) {}

  void f64(std::string_view name, double& v, const Range& r) {
    v = std::bit_cast<double>(take<std::uint64_t>(name));
    if (!failed()) Checker::f64(name, v, r);
  }
  void f32(std::string_view name, float& v, const Range& r) {
    v = std::bit_cast<float>(take<std::uint32_t>(name));
    if (!failed()) Checker::f32(name, v, r);
  }
  void u32(std::string_view name, std::uint32_t& v, std::uint32_t min) {
    v = take<std::uint32_t>(name);
    if (!failed()) Checker::u32(name, v, min);
  }
  template <class E>
  void enumeration(std::string_view name, E& v, E first, E last) {
    // Any byte is a value of an enum with a fixed underlying type: the cast is defined,
    // and the check below refuses the ones not named.
    v = static_cast<E>(take<std::uint8_t>(name));
    if (!failed()) Checker::enumeration(name, v, first, last);
  }
  void flags(std::string_view name, bool& epm_on, bool& object_held, bool& wants_retraction) {
    const auto f = take<std::uint8_t>(name);
    if (failed()) return;
    if (f & ~kFlagsDefined)
      fail(Reason::kBadEnum, name, "bits 0-2 only (epm_on, object_held, wants_retraction)",
           fmt::format("0x{:02x}", f));
    epm_on = f & kFlagEpmOn;
    object_held = f & kFlagObjectHeld;
    wants_retraction = f & kFlagWantsRetraction;
  }
  void text(std::string_view name, std::string& s, std::size_t max_bytes) {
    const std::size_t n = take<std::uint8_t>(name);
    if (failed()) return;
    if (n > max_bytes) {
      fail(Reason::kBadText, name, fmt::format("at most {} bytes", max_bytes),
           fmt::format("{} bytes", n));
      return;
    }
    const auto bytes = take_bytes(name, n);
    if (failed()) return;
    s.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (first_invalid_utf8(s) != std::string_view::npos)
      fail(Reason::kBadText, name, "UTF-8 text", s);
  }
  std::size_t count(std::string_view name, std::vector<PlanSample>& plan, std::size_t max) {
    const std::size_t n = take<std::uint8_t>(name);
    if (failed()) return 0;
    if (n > max) {
      fail(Reason::kOutOfRange, name, fmt::format("at most {} plan samples", max),
           fmt::format("{}", n));
      return 0;
    }
    plan.resize(n);
    return n;
  }

  /// Bytes of the payload not read: a frame longer than its fields is refused.
  [[nodiscard]] std::size_t unread() const { return payload_.size() - at_; }
  [[nodiscard]] std::size_t read() const { return at_; }

 private:
  std::span<const std::uint8_t> take_bytes(std::string_view name, std::size_t n) {
    if (failed()) return {};
    if (n > payload_.size() - at_) {
      // Names the header's field, which promised too few bytes, and the field that did
      // not fit.
      fail_whole(Reason::kLengthMismatch, "header.payload_length",
                 fmt::format("room for {}", path(name)), fmt::format("{} bytes", payload_.size()));
      return {};
    }
    const auto bytes = payload_.subspan(at_, n);
    at_ += n;
    return bytes;
  }
  template <class U>
  U take(std::string_view name) {
    const auto bytes = take_bytes(name, sizeof(U));
    return bytes.empty() ? U{0} : get_le<U>(bytes);
  }

  std::span<const std::uint8_t> payload_;
  std::size_t at_ = 0;
};

// The message's name in field paths: "telemetry.vx_mps".
template <class M>
std::string_view name_of() {
  if constexpr (std::is_same_v<M, UgvTelemetry>)
    return to_string(MessageType::kTelemetry);
  else if constexpr (std::is_same_v<M, UavRequest>)
    return to_string(MessageType::kRequest);
  else if constexpr (std::is_same_v<M, Ack>)
    return to_string(MessageType::kAck);
  else
    return to_string(MessageType::kHeartbeat);
}

template <class M>
std::optional<Rejection> check(const M& m) {
  Checker checker(name_of<M>());
  fields(checker, m);
  return std::move(checker.rejection());
}

template <class M>
DecodeResult read_frame(std::uint32_t sequence, std::span<const std::uint8_t> payload) {
  M m;
  const std::string_view name = name_of<M>();
  Reader reader(name, payload);
  fields(reader, m);
  if (reader.failed()) return std::move(*reader.rejection());
  if (reader.unread() > 0)
    return Rejection{Reason::kLengthMismatch, "header.payload_length",
                     fmt::format("{} bytes for this {}", reader.read(), name),
                     fmt::format("{}", payload.size())};
  return Frame{sequence, Message(std::move(m))};
}

void append_payload(std::vector<std::uint8_t>& out, const Message& message) {
  std::visit(
      [&](const auto& m) {
        Writer writer(out);
        fields(writer, m);
      },
      message);
}

}  // namespace

std::string_view to_string(Rejection::Reason reason) {
  switch (reason) {
    case Reason::kTruncated:
      return "truncated";
    case Reason::kBadMagic:
      return "bad magic";
    case Reason::kUnknownVersion:
      return "unknown version";
    case Reason::kUnknownType:
      return "unknown type";
    case Reason::kBadSender:
      return "bad sender";
    case Reason::kLengthMismatch:
      return "length mismatch";
    case Reason::kCrcMismatch:
      return "CRC mismatch";
    case Reason::kNotFinite:
      return "not finite";
    case Reason::kOutOfRange:
      return "out of range";
    case Reason::kBadEnum:
      return "bad enum";
    case Reason::kBadText:
      return "bad text";
  }
  return "unknown";
}

std::string Rejection::message() const {
  // One printable line whatever the bytes held (a reason string may be anything).
  std::string out = printable(field) + ": expected " + printable(expected);
  if (!got.empty()) out += " (got " + printable(got, 120) + ")";
  return out;
}

std::string_view wire_reason(std::string_view reason, std::size_t max_bytes) {
  std::size_t n = std::min(first_invalid_utf8(reason), reason.size());
  if (n > max_bytes) {
    n = max_bytes;
    // Back to the start of the character the cut falls in (continuation bytes are 10xxxxxx).
    while (n > 0 && (static_cast<std::uint8_t>(reason[n]) & 0xC0) == 0x80) --n;
  }
  return reason.substr(0, n);
}

std::optional<Rejection> validate(const Message& message) {
  return std::visit([](const auto& m) { return check(m); }, message);
}

std::size_t encoded_size(const Message& message) {
  std::vector<std::uint8_t> payload;
  append_payload(payload, message);
  return kHeaderBytes + payload.size() + kCrcBytes;
}

std::vector<std::uint8_t> encode(std::uint32_t sequence, const Message& message) {
  if (auto rejection = validate(message))
    throw std::invalid_argument("link: cannot send this " +
                                std::string(to_string(type_of(message))) + ": " +
                                rejection->message());
  const MessageType type = type_of(message);
  std::vector<std::uint8_t> out;
  out.reserve(kHeaderBytes + 320 + kCrcBytes);
  out.insert(out.end(), kMagic.begin(), kMagic.end());
  out.push_back(kProtocolVersion);
  out.push_back(static_cast<std::uint8_t>(type));
  out.push_back(static_cast<std::uint8_t>(sender_of(type)));
  put_le(out, sequence);
  put_le(out, std::uint16_t{0});  // the payload length, filled in below
  append_payload(out, message);
  // The largest payload (full telemetry) is about 300 bytes: never near 65535.
  const auto payload_bytes = static_cast<std::uint16_t>(out.size() - kHeaderBytes);
  out[kHeaderBytes - 2] = static_cast<std::uint8_t>(payload_bytes & 0xff);
  out[kHeaderBytes - 1] = static_cast<std::uint8_t>(payload_bytes >> 8);
  put_le(out, crc32(out));
  return out;
}

DecodeResult decode(std::span<const std::uint8_t> d) {
  const auto got_bytes = [&] { return fmt::format("{} bytes", d.size()); };
  // The header's first bytes are checked as far as they are there, so even a short
  // datagram is named for what is wrong with it (another protocol, another version).
  if ((d.size() >= 1 && d[0] != kMagic[0]) || (d.size() >= 2 && d[1] != kMagic[1]))
    return Rejection{
        Reason::kBadMagic, "header.magic", "\"FL\" (46 4c)",
        d.size() >= 2 ? fmt::format("{:02x} {:02x}", d[0], d[1]) : fmt::format("{:02x}", d[0])};
  if (d.size() >= 3 && d[2] != kProtocolVersion)
    return Rejection{Reason::kUnknownVersion, "header.version",
                     fmt::format("protocol version {}", kProtocolVersion),
                     fmt::format("version {}", d[2])};
  if (d.size() >= 4 && (d[3] < static_cast<std::uint8_t>(MessageType::kTelemetry) ||
                        d[3] > static_cast<std::uint8_t>(MessageType::kHeartbeat)))
    return Rejection{Reason::kUnknownType, "header.type", "1 (telemetry) to 4 (heartbeat)",
                     fmt::format("{}", d[3])};
  if (d.size() >= 5) {
    const auto type = static_cast<MessageType>(d[3]);
    const Sender expected = sender_of(type);
    if (d[4] != static_cast<std::uint8_t>(expected))
      return Rejection{Reason::kBadSender, "header.sender",
                       fmt::format("{} ({}), the sender of {}", static_cast<int>(expected),
                                   to_string(expected), to_string(type)),
                       fmt::format("{}", d[4])};
  }
  if (d.size() < kHeaderBytes + kCrcBytes)
    return Rejection{Reason::kTruncated, "frame",
                     fmt::format("at least {} bytes (header and CRC)", kHeaderBytes + kCrcBytes),
                     got_bytes()};
  const auto sequence = get_le<std::uint32_t>(d.subspan(5, 4));
  const std::size_t payload_bytes = get_le<std::uint16_t>(d.subspan(9, 2));
  const std::size_t frame_bytes = kHeaderBytes + payload_bytes + kCrcBytes;
  if (d.size() < frame_bytes)
    return Rejection{
        Reason::kTruncated, "frame",
        fmt::format("{} bytes (header, payload_length {}, CRC)", frame_bytes, payload_bytes),
        got_bytes()};
  if (d.size() > frame_bytes)
    return Rejection{
        Reason::kLengthMismatch, "frame",
        fmt::format("{} bytes (header, payload_length {}, CRC)", frame_bytes, payload_bytes),
        got_bytes()};
  const std::uint32_t sent_crc =
      get_le<std::uint32_t>(d.subspan(kHeaderBytes + payload_bytes, kCrcBytes));
  const std::uint32_t crc = crc32(d.first(kHeaderBytes + payload_bytes));
  if (crc != sent_crc)
    return Rejection{Reason::kCrcMismatch, "crc",
                     fmt::format("0x{:08x} (CRC-32 of the bytes before it)", crc),
                     fmt::format("0x{:08x}", sent_crc)};
  const auto payload = d.subspan(kHeaderBytes, payload_bytes);
  switch (static_cast<MessageType>(d[3])) {
    case MessageType::kTelemetry:
      return read_frame<UgvTelemetry>(sequence, payload);
    case MessageType::kRequest:
      return read_frame<UavRequest>(sequence, payload);
    case MessageType::kAck:
      return read_frame<Ack>(sequence, payload);
    case MessageType::kHeartbeat:
      return read_frame<Heartbeat>(sequence, payload);
  }
  return Rejection{Reason::kUnknownType, "header.type", "1 (telemetry) to 4 (heartbeat)",
                   fmt::format("{}", d[3])};
}

}  // namespace ferret::link
