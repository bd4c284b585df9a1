// Packet framing of the Pioneer P3-DX microcontroller link (ARCOS / P2OS), both directions.
//
//   0xFA 0xFB | N | payload (N - 2 bytes, first byte = command number or packet type) | checksum
//
// N counts the payload and the two checksum bytes. The checksum adds the payload as 16-bit
// big-endian words, truncating every sum to 16 bits; with an odd payload length the last byte is
// XORed into the low byte; it is sent high byte first. Integers inside payloads are
// little-endian. Sources: Pioneer 3 Operations Manual (MobileRobots 2006), ARCOS chapter,
// "Packet Protocols" and Table 4; ARIA ArRobotPacket::calcCheckSum() (the p2os driver's receive
// check is wrong and is no reference). See ../shared/design/protocols/p3dx.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

namespace slammtt {

inline constexpr uint8_t kP3dxHeader0 = 0xFA;
inline constexpr uint8_t kP3dxHeader1 = 0xFB;
// Byte count limits: the smallest packet carries one payload byte (its id); the ARCOS manual
// gives 207 as the largest byte count (payload 205 + checksum 2).
inline constexpr int kP3dxMinByteCount = 3;
inline constexpr int kP3dxMaxByteCount = 207;
inline constexpr size_t kP3dxMaxPayload = kP3dxMaxByteCount - 2;

// The ARCOS checksum of a payload (ARIA's algorithm, see the file comment).
uint16_t P3dxChecksum(const uint8_t* payload, size_t size);

// Frames a payload: header, byte count, payload, checksum. The payload must hold 1 to
// kP3dxMaxPayload bytes (a programming error otherwise: std::invalid_argument).
std::vector<uint8_t> FrameP3dxPacket(const std::vector<uint8_t>& payload);

// Counters of what the decoder saw and threw away.
struct P3dxDecoderCounters {
  int64_t packets = 0;          // well-framed packets with a good checksum
  int64_t checksum_errors = 0;  // framed packets whose checksum did not match
  int64_t bad_byte_counts = 0;  // a header followed by a byte count outside [3, 207]
  int64_t truncated = 0;        // partial packets abandoned by DiscardPartial()
  int64_t bytes_skipped = 0;    // bytes dropped while looking for a header (resync)
};

// Streaming decoder: feed bytes as they arrive, take whole packets out. It never trusts a
// header: when a candidate packet has a bad byte count or a bad checksum, only its first byte is
// dropped and the search goes on from the next byte, so a real packet hidden inside a false
// frame (garbage that happens to contain 0xFA 0xFB) is still found. Memory is bounded: at most
// one maximal packet is buffered.
class P3dxPacketDecoder {
 public:
  // Appends bytes and decodes every complete packet they finish.
  void Feed(const uint8_t* data, size_t size);
  // The next decoded payload (id byte first, checksum removed), oldest first.
  std::optional<std::vector<uint8_t>> Next();
  // True when the buffer holds the beginning of a packet that is not complete yet.
  bool HasPartial() const { return !buffer_.empty(); }
  // Drops an incomplete packet (the link went quiet in the middle of it: a truncated packet);
  // counted as truncated when it began with a header. Call when no byte came for a while.
  void DiscardPartial();
  // Forgets everything buffered (a new connection); counters are kept.
  void Reset();
  const P3dxDecoderCounters& counters() const { return counters_; }

 private:
  void Decode();
  std::deque<uint8_t> buffer_;
  std::deque<std::vector<uint8_t>> ready_;
  P3dxDecoderCounters counters_;
};

}  // namespace slammtt
