// Whether the stack's LCM bus keeps to the computer, checked by slammtt-launch before anything
// starts (robot.network, launch_plan.h; docs/robot.md, "Who can drive the robot").
//
// What LCM 1.3.1's udpm provider binds to (lcm_udpm.c, _setup_recv_parts): its receive socket is
// bound to 0.0.0.0 and the bus port, with SO_REUSEADDR, and joins the group with
// imr_interface = INADDR_ANY, so the kernel joins it on the interface of the group's route; the
// URL has no option for an interface or an address. So a process cannot bind the bus to the
// loopback interface. What can be had:
//  - multicast: with the group routed to the loopback interface, the group is joined on lo only,
//    and multicast from a LAN interface to the group is dropped by the kernel (that interface
//    has not joined it); the stack's own packets go out on lo (and ttl=0 keeps them there
//    whatever the route);
//  - unicast to any address of the computer on the bus port still reaches the socket bound to
//    0.0.0.0: only a firewall stops it (slammtt.service: IPAddressDeny=), and only signed
//    commands keep it from driving the robot.
// In the loopback setup the launcher therefore requires a bus URL that keeps its packets on the
// computer (udpm with ttl=0, or memq) and, for udpm, that the group's route is a loopback
// interface (what config/systemd/slammtt-lcm-route.service sets up).
#pragma once

#include <string>

#include "drivers/launcher/launch_plan.h"

namespace slammtt {

// The interface the kernel routes `group` (an IPv4 address) on, as "ip route get GROUP" says
// (rtnetlink RTM_GETROUTE): its name, an IPv4 address of it ("" without one) and whether it is a
// loopback interface. Throws std::runtime_error, one line, when there is no route.
struct GroupRoute {
  std::string interface_name;
  std::string address;
  bool loopback = false;
};
GroupRoute RouteOfGroup(const std::string& group);

// "" when `lcm_url` fits `network`, else one line saying what is wrong and how to fix it.
// kLoopback: a memq URL, or udpm with ttl=0 whose group is routed on a loopback interface.
// kLan: any URL ParseLcmUrl accepts.
std::string BusNetworkProblem(const std::string& lcm_url, BusNetwork network);

}  // namespace slammtt
