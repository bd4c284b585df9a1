// Checks of the array lengths inside encoded LCM messages, before decoding them.
//
// LCM 1.3.1's generated decoders resize every variable-length array to the length the message
// claims before they check that the bytes are there: a corrupt length makes them throw
// std::length_error (negative) or allocate and zero gigabytes (large). These checks read each
// length from the encoding (LCM type specification: big-endian, an 8-byte fingerprint, fields
// in declaration order, strings as int32 length including the NUL, then the bytes) and accept it
// only when every element it announces fits in the remaining bytes at its smallest encoded size.
// DecodeChecked() runs the check for the types the tools read and then the generated decoder,
// and reports any failure as false: a bad message is rejected, never thrown.
#pragma once

#include <exception>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"

namespace slammtt {

// True when the array lengths of an encoded message fit in `size` bytes.
bool PlausibleGroundTruth(const void* data, int size);
bool PlausibleTracks(const void* data, int size);
bool PlausibleMap(const void* data, int size);
bool PlausibleStageTiming(const void* data, int size);

inline bool PlausibleEncoding(const slammtt_msgs::ground_truth_t*, const void* d, int n) {
  return PlausibleGroundTruth(d, n);
}
inline bool PlausibleEncoding(const slammtt_msgs::tracks_t*, const void* d, int n) {
  return PlausibleTracks(d, n);
}
inline bool PlausibleEncoding(const slammtt_msgs::map_t*, const void* d, int n) {
  return PlausibleMap(d, n);
}
inline bool PlausibleEncoding(const slammtt_msgs::stage_timing_t*, const void* d, int n) {
  return PlausibleStageTiming(d, n);
}
// Types without variable-length arrays need no check.
inline bool PlausibleEncoding(const void*, const void*, int) { return true; }

// Decodes `data` into `message`; false (never an exception) when the bytes are not a whole,
// consistent message of that type.
template <class Msg>
bool DecodeChecked(const void* data, int size, Msg* message) {
  if (data == nullptr || size < 0 || !PlausibleEncoding(message, data, size)) return false;
  try {
    return Decode(data, size, message);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace slammtt
