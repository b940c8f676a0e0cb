/* S2Sim remote protocol, version 1: the wire format and a header-only C client.
 *
 * The `remote` controller (plugins/remote) serves a robot's or a scene's inputs and signals
 * over UDP; docs/remote.md is the specification. This header is C99 and C++ compatible, needs
 * only POSIX sockets, and allocates nothing: firmware-style code can use it as it is.
 *
 * Every datagram is a 16-byte header followed by `length` bytes of payload, all little-endian:
 *
 *   offset size field
 *   0      4    magic 'S','2','S','R'
 *   4      2    version (1)
 *   6      2    type (S2SIM_REMOTE_*)
 *   8      4    sequence number (requests: the client's, increasing; replies: the request's)
 *   12     4    length of the payload in bytes
 *   16     ...  payload: IEEE-754 doubles (8 bytes each), or UTF-8 text for DESCRIBE
 */
#ifndef S2SIM_REMOTE_H
#define S2SIM_REMOTE_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define S2SIM_REMOTE_VERSION 1
#define S2SIM_REMOTE_HEADER_SIZE 16
#define S2SIM_REMOTE_DEFAULT_PORT 9808
/* The largest UDP payload on IPv4: no valid datagram is larger. */
#define S2SIM_REMOTE_MAX_DATAGRAM 65507

enum s2sim_remote_type {
  S2SIM_REMOTE_HELLO = 1,    /* client -> sim, no payload: answered by DESCRIBE */
  S2SIM_REMOTE_DESCRIBE = 2, /* sim -> client, text: mode, period, input and signal names */
  S2SIM_REMOTE_INPUTS = 3,   /* client -> sim, one double per served input, in order */
  S2SIM_REMOTE_OBSERVE = 4,  /* client -> sim, no payload: answered by SIGNALS now */
  S2SIM_REMOTE_SIGNALS = 5,  /* sim -> client, doubles: time [s], then one per served signal */
  S2SIM_REMOTE_BUSY = 6,     /* sim -> another sender, text: the link serves another client */
  S2SIM_REMOTE_BYE = 7,      /* client -> sim, no payload: ends the client's session */
  S2SIM_REMOTE_END = 8       /* sim -> client, a double (time [s]) and text: the run ended */
};

typedef struct s2sim_remote_header {
  uint16_t version;
  uint16_t type;
  uint32_t sequence;
  uint32_t length;
} s2sim_remote_header;

static inline void s2sim_remote_put_u16(unsigned char* p, uint16_t v) {
  p[0] = (unsigned char)(v & 0xffu);
  p[1] = (unsigned char)(v >> 8);
}
static inline void s2sim_remote_put_u32(unsigned char* p, uint32_t v) {
  int i;
  for (i = 0; i < 4; ++i)
    p[i] = (unsigned char)((v >> (8 * i)) & 0xffu);
}
static inline uint16_t s2sim_remote_get_u16(const unsigned char* p) {
  return (uint16_t)(p[0] | (p[1] << 8));
}
static inline uint32_t s2sim_remote_get_u32(const unsigned char* p) {
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}
/* Doubles travel as their IEEE-754 bit pattern, least significant byte first. */
static inline void s2sim_remote_put_f64(unsigned char* p, double v) {
  uint64_t bits;
  int i;
  memcpy(&bits, &v, sizeof bits);
  for (i = 0; i < 8; ++i)
    p[i] = (unsigned char)((bits >> (8 * i)) & 0xffu);
}
static inline double s2sim_remote_get_f64(const unsigned char* p) {
  uint64_t bits = 0;
  double v;
  int i;
  for (i = 0; i < 8; ++i)
    bits |= (uint64_t)p[i] << (8 * i);
  memcpy(&v, &bits, sizeof v);
  return v;
}

/* Writes a header; returns S2SIM_REMOTE_HEADER_SIZE. */
static inline size_t s2sim_remote_write_header(unsigned char* out, uint16_t type, uint32_t sequence,
                                               uint32_t length) {
  out[0] = 'S';
  out[1] = '2';
  out[2] = 'S';
  out[3] = 'R';
  s2sim_remote_put_u16(out + 4, S2SIM_REMOTE_VERSION);
  s2sim_remote_put_u16(out + 6, type);
  s2sim_remote_put_u32(out + 8, sequence);
  s2sim_remote_put_u32(out + 12, length);
  return S2SIM_REMOTE_HEADER_SIZE;
}

/* Reads and checks a header against the datagram's size. Returns 0 when the datagram is well
 * formed (magic, version, length == size - 16), else a negative reason:
 * -1 shorter than a header, -2 bad magic, -3 other version, -4 length disagrees with size. */
static inline int s2sim_remote_read_header(const unsigned char* in, size_t size,
                                           s2sim_remote_header* h) {
  if (size < S2SIM_REMOTE_HEADER_SIZE) return -1;
  if (in[0] != 'S' || in[1] != '2' || in[2] != 'S' || in[3] != 'R') return -2;
  h->version = s2sim_remote_get_u16(in + 4);
  h->type = s2sim_remote_get_u16(in + 6);
  h->sequence = s2sim_remote_get_u32(in + 8);
  h->length = s2sim_remote_get_u32(in + 12);
  if (h->version != S2SIM_REMOTE_VERSION) return -3;
  if ((size_t)h->length != size - S2SIM_REMOTE_HEADER_SIZE) return -4;
  return 0;
}

/* ---- the client (POSIX sockets); define S2SIM_REMOTE_NO_CLIENT to leave it out ---------- */
#ifndef S2SIM_REMOTE_NO_CLIENT
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

typedef struct s2sim_remote_client {
  int fd;
  struct sockaddr_in server;
  uint32_t sequence; /* of the last request sent */
  unsigned char buffer[S2SIM_REMOTE_MAX_DATAGRAM + 1];
} s2sim_remote_client;

/* Opens a client of the simulation at `ipv4_address`:`port`. Returns 0, or -1 (errno set). */
static inline int s2sim_remote_open(s2sim_remote_client* c, const char* ipv4_address,
                                    uint16_t port) {
  memset(&c->server, 0, sizeof c->server);
  c->server.sin_family = AF_INET;
  c->server.sin_port = htons(port);
  if (inet_pton(AF_INET, ipv4_address, &c->server.sin_addr) != 1) return -1;
  c->fd = socket(AF_INET, SOCK_DGRAM, 0);
  c->sequence = 0;
  return c->fd < 0 ? -1 : 0;
}

static inline void s2sim_remote_close(s2sim_remote_client* c) {
  if (c->fd >= 0) { /* the session ends now, not when the link stops waiting for us */
    unsigned char bye[S2SIM_REMOTE_HEADER_SIZE];
    c->sequence += 1;
    s2sim_remote_write_header(bye, S2SIM_REMOTE_BYE, c->sequence, 0);
    (void)sendto(c->fd, bye, sizeof bye, 0, (const struct sockaddr*)&c->server, sizeof c->server);
    close(c->fd);
  }
  c->fd = -1;
}

/* Sends a request of `type` with `count` doubles; returns its sequence number, or 0 on error. */
static inline uint32_t s2sim_remote_send(s2sim_remote_client* c, uint16_t type,
                                         const double* values, size_t count) {
  size_t i, size = S2SIM_REMOTE_HEADER_SIZE + 8 * count;
  if (size > S2SIM_REMOTE_MAX_DATAGRAM) return 0;
  c->sequence += 1;
  s2sim_remote_write_header(c->buffer, type, c->sequence, (uint32_t)(8 * count));
  for (i = 0; i < count; ++i)
    s2sim_remote_put_f64(c->buffer + 16 + 8 * i, values[i]);
  if (sendto(c->fd, c->buffer, size, 0, (const struct sockaddr*)&c->server, sizeof c->server) !=
      (ssize_t)size)
    return 0;
  return c->sequence;
}

/* Waits up to `timeout_ms` for a SIGNALS reply with `sequence` (0: any); copies its time and
 * at most `capacity` signal values. Returns the number of signal values in the reply, -1 on
 * timeout or error, -2 when the link answered BUSY (it serves another client), or -3 when the
 * run ended (END, whatever its sequence: no reply will come; `*time_s` is the time of the
 * link's last control period). Replies to older requests are skipped. */
static inline int s2sim_remote_receive(s2sim_remote_client* c, uint32_t sequence, double* time_s,
                                       double* values, size_t capacity, int timeout_ms) {
  for (;;) {
    struct pollfd p;
    s2sim_remote_header h;
    ssize_t got;
    size_t i, count;
    p.fd = c->fd;
    p.events = POLLIN;
    if (poll(&p, 1, timeout_ms) <= 0) return -1;
    got = recv(c->fd, c->buffer, sizeof c->buffer, 0);
    if (got < 0) return -1;
    if (s2sim_remote_read_header(c->buffer, (size_t)got, &h) != 0) continue;
    if (h.type == S2SIM_REMOTE_BUSY && (sequence == 0 || h.sequence == sequence)) return -2;
    if (h.type == S2SIM_REMOTE_END && h.length >= 8) {
      *time_s = s2sim_remote_get_f64(c->buffer + 16);
      return -3;
    }
    if (h.type != S2SIM_REMOTE_SIGNALS || h.length < 8 || h.length % 8 != 0) continue;
    if (sequence != 0 && h.sequence != sequence) continue;
    *time_s = s2sim_remote_get_f64(c->buffer + 16);
    count = h.length / 8 - 1;
    for (i = 0; i < count && i < capacity; ++i)
      values[i] = s2sim_remote_get_f64(c->buffer + 24 + 8 * i);
    return (int)count;
  }
}

/* Lock-step: sends the inputs and waits for the signals one control period later. Returns the
 * number of signal values, -1 (timeout, error), -2 (BUSY) or -3 (the run ended: END). */
static inline int s2sim_remote_step(s2sim_remote_client* c, const double* inputs,
                                    size_t input_count, double* time_s, double* values,
                                    size_t capacity, int timeout_ms) {
  uint32_t seq = s2sim_remote_send(c, S2SIM_REMOTE_INPUTS, inputs, input_count);
  if (seq == 0) return -1;
  return s2sim_remote_receive(c, seq, time_s, values, capacity, timeout_ms);
}
#endif /* S2SIM_REMOTE_NO_CLIENT */

#endif /* S2SIM_REMOTE_H */
