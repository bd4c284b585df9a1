#include "drivers/rplidar/rplidar_driver_options.h"

#include <stdexcept>

namespace slammtt {
namespace rplidar {

const char* ScanModeName(ScanMode mode) {
  return mode == ScanMode::kExpress ? "express" : "standard";
}

ScanMode ParseScanMode(const std::string& text) {
  if (text == "standard") return ScanMode::kStandard;
  if (text == "express") return ScanMode::kExpress;
  throw std::invalid_argument("scan mode must be standard or express, got \"" + text + "\"");
}

}  // namespace rplidar
}  // namespace slammtt
