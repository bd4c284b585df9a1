#include "drivers/launcher/bus_network.h"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <linux/netlink.h>
#include <linux/rtnetlink.h>
#include <net/if.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "runtime/lcm_url.h"

namespace slammtt {

GroupRoute RouteOfGroup(const std::string& group) {
  in_addr destination{};
  if (inet_pton(AF_INET, group.c_str(), &destination) != 1) {
    throw std::runtime_error("'" + group + "' is not an IPv4 address");
  }
  // Ask the kernel's routing table as "ip route get GROUP" does (rtnetlink(7): RTM_GETROUTE
  // with RTA_DST; the reply's RTA_OIF is the output interface).
  const int fd = socket(AF_NETLINK, SOCK_RAW | SOCK_CLOEXEC, NETLINK_ROUTE);
  if (fd < 0) throw std::runtime_error(std::string("netlink socket: ") + std::strerror(errno));
  struct {
    nlmsghdr header;
    rtmsg route;
    char attributes[64];
  } request{};
  request.header.nlmsg_len = NLMSG_LENGTH(sizeof(rtmsg));
  request.header.nlmsg_type = RTM_GETROUTE;
  request.header.nlmsg_flags = NLM_F_REQUEST;
  request.header.nlmsg_seq = 1;
  request.route.rtm_family = AF_INET;
  request.route.rtm_dst_len = 32;
  auto* attribute = reinterpret_cast<rtattr*>(reinterpret_cast<char*>(&request) +
                                              NLMSG_ALIGN(request.header.nlmsg_len));
  attribute->rta_type = RTA_DST;
  attribute->rta_len = RTA_LENGTH(sizeof destination);
  std::memcpy(RTA_DATA(attribute), &destination, sizeof destination);
  request.header.nlmsg_len = NLMSG_ALIGN(request.header.nlmsg_len) + attribute->rta_len;
  sockaddr_nl kernel{};
  kernel.nl_family = AF_NETLINK;
  char reply[8192];
  ssize_t received = -1;
  if (sendto(fd, &request, request.header.nlmsg_len, 0, reinterpret_cast<sockaddr*>(&kernel),
             sizeof kernel) >= 0) {
    received = recv(fd, reply, sizeof reply, 0);
  }
  const int saved_errno = errno;
  close(fd);
  if (received < 0) {
    throw std::runtime_error(std::string("route lookup failed: ") + std::strerror(saved_errno));
  }
  int interface_index = 0;
  for (auto* message = reinterpret_cast<nlmsghdr*>(reply);
       NLMSG_OK(message, static_cast<unsigned int>(received));
       message = NLMSG_NEXT(message, received)) {
    if (message->nlmsg_type == NLMSG_ERROR) {
      const auto* error = static_cast<const nlmsgerr*>(NLMSG_DATA(message));
      throw std::runtime_error("no route for the LCM group " + group + " (" +
                               std::strerror(-error->error) + ")");
    }
    if (message->nlmsg_type != RTM_NEWROUTE) continue;
    auto* route = static_cast<rtmsg*>(NLMSG_DATA(message));
    int length = static_cast<int>(RTM_PAYLOAD(message));
    for (auto* a = RTM_RTA(route); RTA_OK(a, length); a = RTA_NEXT(a, length)) {
      if (a->rta_type == RTA_OIF) std::memcpy(&interface_index, RTA_DATA(a), sizeof(int));
    }
  }
  if (interface_index <= 0) throw std::runtime_error("no route for the LCM group " + group);
  GroupRoute result;
  char name[IF_NAMESIZE] = "";
  const bool named = if_indextoname(static_cast<unsigned int>(interface_index), name) != nullptr;
  result.interface_name = named ? name : "interface " + std::to_string(interface_index);
  ifaddrs* interfaces = nullptr;
  if (getifaddrs(&interfaces) == 0) {
    for (const ifaddrs* i = interfaces; i != nullptr; i = i->ifa_next) {
      if (result.interface_name != i->ifa_name) continue;
      result.loopback = (i->ifa_flags & IFF_LOOPBACK) != 0;
      if (i->ifa_addr != nullptr && i->ifa_addr->sa_family == AF_INET) {
        char text[INET_ADDRSTRLEN] = "";
        inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr, text,
                  sizeof text);
        result.address = text;
      }
    }
    freeifaddrs(interfaces);
  }
  return result;
}

std::string BusNetworkProblem(const std::string& lcm_url, BusNetwork network) {
  LcmUrl url;
  try {
    url = ParseLcmUrl(lcm_url);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  if (network == BusNetwork::kLan) return "";
  if (!IsLocalOnly(url)) {
    return "robot.network is loopback but the bus '" + lcm_url +
           "' sends its packets beyond this computer (ttl " + std::to_string(url.ttl) +
           "): use ttl=0, or set robot.network: lan and give the robot a command key "
           "(docs/robot.md)";
  }
  if (url.provider != "udpm") return "";
  GroupRoute route;
  try {
    route = RouteOfGroup(url.group);
  } catch (const std::runtime_error& e) {
    return std::string(e.what()) + ": install config/systemd/slammtt-lcm-route.service, or ip "
           "route add " + url.group + "/32 dev lo (docs/robot.md)";
  }
  if (!route.loopback) {
    return "robot.network is loopback but the LCM group " + url.group + " is routed on " +
           route.interface_name + (route.address.empty() ? "" : " (" + route.address + ")") +
           ", so multicast from that network reaches the bus: install "
           "config/systemd/slammtt-lcm-route.service, or ip route add " + url.group +
           "/32 dev lo, or set robot.network: lan (docs/robot.md)";
  }
  return "";
}

}  // namespace slammtt
