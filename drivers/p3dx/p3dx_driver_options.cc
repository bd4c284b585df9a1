#include "drivers/p3dx/p3dx_driver_options.h"

namespace slammtt {

const char* CommandAuthenticationName(P3dxDriverOptions::CommandAuthentication mode) {
  return mode == P3dxDriverOptions::CommandAuthentication::kNone ? "none" : "hmac-sha256";
}

}  // namespace slammtt
