/* Guest-side check that socket(AF_CAN, SOCK_RAW, CAN_RAW) works on a vcan
 * interface: one socket sends a frame, a second one bound to the same
 * interface with a filter on that id receives it intact.
 *   can-socket-check IFNAME    exits 0 on success, 1 with a message otherwise */
#define _DEFAULT_SOURCE
#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

static int fail(const char *what) {
  fprintf(stderr, "can-socket-check: %s: %s\n", what, strerror(errno));
  return 1;
}

static int open_bound(const char *ifname) {
  int s = socket(AF_CAN, SOCK_RAW, CAN_RAW);
  if (s < 0) return -1;
  struct sockaddr_can addr;
  memset(&addr, 0, sizeof addr);
  addr.can_family = AF_CAN;
  addr.can_ifindex = (int)if_nametoindex(ifname);
  if (addr.can_ifindex == 0 || bind(s, (struct sockaddr *)&addr, sizeof addr) < 0) {
    close(s);
    return -1;
  }
  return s;
}

int main(int argc, char **argv) {
  const char *ifname = argc > 1 ? argv[1] : "vcan0";
  int tx = open_bound(ifname);
  if (tx < 0) return fail("socket/bind tx");
  int rx = open_bound(ifname);
  if (rx < 0) return fail("socket/bind rx");
  struct can_filter flt = {.can_id = 0x1ab, .can_mask = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG};
  if (setsockopt(rx, SOL_CAN_RAW, CAN_RAW_FILTER, &flt, sizeof flt) < 0) return fail("CAN_RAW_FILTER");

  struct can_frame other = {.can_id = 0x1ac, .can_dlc = 1, .data = {0x55}};
  struct can_frame f = {.can_id = 0x1ab, .can_dlc = 8, .data = {1, 2, 3, 4, 5, 6, 7, 8}};
  if (write(tx, &other, sizeof other) != (ssize_t)sizeof other) return fail("write filtered-out frame");
  if (write(tx, &f, sizeof f) != (ssize_t)sizeof f) return fail("write");

  struct pollfd p = {.fd = rx, .events = POLLIN};
  int n = poll(&p, 1, 5000);
  if (n <= 0) {
    if (n == 0) errno = ETIMEDOUT;
    return fail("poll rx");
  }
  struct can_frame r;
  if (read(rx, &r, sizeof r) != (ssize_t)sizeof r) return fail("read");
  if (r.can_id != f.can_id || r.can_dlc != f.can_dlc || memcmp(r.data, f.data, 8) != 0) {
    fprintf(stderr, "can-socket-check: received id %03x dlc %u, want 1ab dlc 8 01..08\n",
            (unsigned)r.can_id, (unsigned)r.can_dlc);
    return 1;
  }
  printf("can-socket-check: AF_CAN raw socket on %s ok (frame 1ab#0102030405060708 received, 1ac filtered)\n",
         ifname);
  close(tx);
  close(rx);
  return 0;
}
