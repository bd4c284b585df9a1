#include "drivers/p3dx/p3dx_session_output.h"

namespace slammtt {

const char* BaseStateName(BaseState state) {
  switch (state) {
    case BaseState::kConnecting: return "connecting";
    case BaseState::kReconnecting: return "reconnecting";
    case BaseState::kSyncing: return "syncing";
    case BaseState::kStoppingEarlierSession: return "stopping-earlier-session";
    case BaseState::kClosingEarlierSession: return "closing-earlier-session";
    case BaseState::kOpening: return "opening";
    case BaseState::kRunning: return "running";
    case BaseState::kStopped: return "stopped";
  }
  return "unknown";
}

}  // namespace slammtt
