#include "drivers/p3dx/p3dx_packet.h"

#include <stdexcept>
#include <string>

namespace slammtt {

uint16_t P3dxChecksum(const uint8_t* payload, size_t size) {
  uint32_t sum = 0;
  size_t i = 0;
  for (; i + 1 < size; i += 2) {
    sum = (sum + ((static_cast<uint32_t>(payload[i]) << 8) | payload[i + 1])) & 0xFFFFu;
  }
  if (i < size) sum ^= payload[i];
  return static_cast<uint16_t>(sum);
}

std::vector<uint8_t> FrameP3dxPacket(const std::vector<uint8_t>& payload) {
  if (payload.empty() || payload.size() > kP3dxMaxPayload) {
    throw std::invalid_argument("FrameP3dxPacket: payload of " + std::to_string(payload.size()) +
                                " bytes, expected 1 to " + std::to_string(kP3dxMaxPayload));
  }
  std::vector<uint8_t> packet;
  packet.reserve(payload.size() + 5);
  packet.push_back(kP3dxHeader0);
  packet.push_back(kP3dxHeader1);
  packet.push_back(static_cast<uint8_t>(payload.size() + 2));
  packet.insert(packet.end(), payload.begin(), payload.end());
  const uint16_t checksum = P3dxChecksum(payload.data(), payload.size());
  packet.push_back(static_cast<uint8_t>(checksum >> 8));
  packet.push_back(static_cast<uint8_t>(checksum & 0xFF));
  return packet;
}

void P3dxPacketDecoder::Feed(const uint8_t* data, size_t size) {
  buffer_.insert(buffer_.end(), data, data + size);
  Decode();
}

std::optional<std::vector<uint8_t>> P3dxPacketDecoder::Next() {
  if (ready_.empty()) return std::nullopt;
  std::vector<uint8_t> payload = std::move(ready_.front());
  ready_.pop_front();
  return payload;
}

void P3dxPacketDecoder::Decode() {
  while (!buffer_.empty()) {
    if (buffer_[0] != kP3dxHeader0) {
      buffer_.pop_front();
      ++counters_.bytes_skipped;
      continue;
    }
    if (buffer_.size() < 2) return;
    if (buffer_[1] != kP3dxHeader1) {
      buffer_.pop_front();
      ++counters_.bytes_skipped;
      continue;
    }
    if (buffer_.size() < 3) return;
    const int count = buffer_[2];
    if (count < kP3dxMinByteCount || count > kP3dxMaxByteCount) {
      ++counters_.bad_byte_counts;
      buffer_.pop_front();
      ++counters_.bytes_skipped;
      continue;
    }
    const size_t total = 3 + static_cast<size_t>(count);
    if (buffer_.size() < total) return;
    std::vector<uint8_t> payload(buffer_.begin() + 3, buffer_.begin() + 3 + (count - 2));
    const uint16_t received =
        static_cast<uint16_t>((buffer_[total - 2] << 8) | buffer_[total - 1]);
    if (received != P3dxChecksum(payload.data(), payload.size())) {
      // Do not trust the frame: look for a header again from the next byte.
      ++counters_.checksum_errors;
      buffer_.pop_front();
      ++counters_.bytes_skipped;
      continue;
    }
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(total));
    ready_.push_back(std::move(payload));
    ++counters_.packets;
  }
}

void P3dxPacketDecoder::DiscardPartial() {
  bool first = true;
  while (!buffer_.empty()) {
    if (first && buffer_[0] == kP3dxHeader0) ++counters_.truncated;
    first = false;
    buffer_.pop_front();
    ++counters_.bytes_skipped;
    Decode();  // a complete packet may still sit behind the abandoned one
  }
}

void P3dxPacketDecoder::Reset() { buffer_.clear(); ready_.clear(); }

}  // namespace slammtt
