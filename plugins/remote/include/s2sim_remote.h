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
/* --- Authentication (docs/remote.md, "Authentication") ---------------------------------------
 * A link with a key_file signs every datagram, both ways: S2SIM_REMOTE_TAG_SIZE bytes of
 * HMAC-SHA256 (RFC 2104 over FIPS 180-4's SHA-256) of the header and the payload, after the
 * payload; the header's length counts the payload alone. */
#define S2SIM_REMOTE_TAG_SIZE 32
#define S2SIM_REMOTE_MIN_KEY 16

typedef struct s2sim_remote_sha256 {
  uint32_t h[8];
  unsigned char block[64];
  size_t used;    /* bytes in block */
  uint64_t bytes; /* hashed so far */
} s2sim_remote_sha256;

static inline uint32_t s2sim_remote_rotr(uint32_t x, int n) {
  return (x >> n) | (x << (32 - n));
}

static inline void s2sim_remote_sha256_block(uint32_t* h, const unsigned char* p) {
  /* The first 32 bits of the fractional parts of the cube roots of the first 64 primes. */
  static const uint32_t k[64] = {
      0x428a2f98u, 0x71374491u, 0xb5c0fbcfu, 0xe9b5dba5u, 0x3956c25bu, 0x59f111f1u, 0x923f82a4u,
      0xab1c5ed5u, 0xd807aa98u, 0x12835b01u, 0x243185beu, 0x550c7dc3u, 0x72be5d74u, 0x80deb1feu,
      0x9bdc06a7u, 0xc19bf174u, 0xe49b69c1u, 0xefbe4786u, 0x0fc19dc6u, 0x240ca1ccu, 0x2de92c6fu,
      0x4a7484aau, 0x5cb0a9dcu, 0x76f988dau, 0x983e5152u, 0xa831c66du, 0xb00327c8u, 0xbf597fc7u,
      0xc6e00bf3u, 0xd5a79147u, 0x06ca6351u, 0x14292967u, 0x27b70a85u, 0x2e1b2138u, 0x4d2c6dfcu,
      0x53380d13u, 0x650a7354u, 0x766a0abbu, 0x81c2c92eu, 0x92722c85u, 0xa2bfe8a1u, 0xa81a664bu,
      0xc24b8b70u, 0xc76c51a3u, 0xd192e819u, 0xd6990624u, 0xf40e3585u, 0x106aa070u, 0x19a4c116u,
      0x1e376c08u, 0x2748774cu, 0x34b0bcb5u, 0x391c0cb3u, 0x4ed8aa4au, 0x5b9cca4fu, 0x682e6ff3u,
      0x748f82eeu, 0x78a5636fu, 0x84c87814u, 0x8cc70208u, 0x90befffau, 0xa4506cebu, 0xbef9a3f7u,
      0xc67178f2u,
  };
  uint32_t w[64], a, b, c, d, e, f, g, hh, t1, t2;
  int i;
  for (i = 0; i < 16; ++i)
    w[i] = (uint32_t)p[4 * i] << 24 | (uint32_t)p[4 * i + 1] << 16 | (uint32_t)p[4 * i + 2] << 8 |
           (uint32_t)p[4 * i + 3];
  for (i = 16; i < 64; ++i) {
    const uint32_t s0 =
        s2sim_remote_rotr(w[i - 15], 7) ^ s2sim_remote_rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
    const uint32_t s1 =
        s2sim_remote_rotr(w[i - 2], 17) ^ s2sim_remote_rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
    w[i] = w[i - 16] + s0 + w[i - 7] + s1;
  }
  a = h[0], b = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], hh = h[7];
  for (i = 0; i < 64; ++i) {
    t1 = hh + (s2sim_remote_rotr(e, 6) ^ s2sim_remote_rotr(e, 11) ^ s2sim_remote_rotr(e, 25)) +
         ((e & f) ^ (~e & g)) + k[i] + w[i];
    t2 = (s2sim_remote_rotr(a, 2) ^ s2sim_remote_rotr(a, 13) ^ s2sim_remote_rotr(a, 22)) +
         ((a & b) ^ (a & c) ^ (b & c));
    hh = g, g = f, f = e, e = d + t1, d = c, c = b, b = a, a = t1 + t2;
  }
  h[0] += a, h[1] += b, h[2] += c, h[3] += d, h[4] += e, h[5] += f, h[6] += g, h[7] += hh;
}

static inline void s2sim_remote_sha256_init(s2sim_remote_sha256* s) {
  /* The first 32 bits of the fractional parts of the square roots of the first 8 primes. */
  static const uint32_t h0[8] = {0x6a09e667u, 0xbb67ae85u, 0x3c6ef372u, 0xa54ff53au,
                                 0x510e527fu, 0x9b05688cu, 0x1f83d9abu, 0x5be0cd19u};
  memcpy(s->h, h0, sizeof h0);
  s->used = 0;
  s->bytes = 0;
}

static inline void s2sim_remote_sha256_update(s2sim_remote_sha256* s, const unsigned char* data,
                                              size_t size) {
  s->bytes += size;
  while (size > 0) {
    size_t take = 64 - s->used;
    if (take > size) take = size;
    memcpy(s->block + s->used, data, take);
    s->used += take;
    data += take;
    size -= take;
    if (s->used == 64) {
      s2sim_remote_sha256_block(s->h, s->block);
      s->used = 0;
    }
  }
}

static inline void s2sim_remote_sha256_final(s2sim_remote_sha256* s, unsigned char* out) {
  const uint64_t bits = s->bytes * 8;
  const unsigned char one = 0x80, zero = 0;
  unsigned char length[8];
  int i;
  for (i = 0; i < 8; ++i)
    length[i] = (unsigned char)(bits >> (56 - 8 * i));
  s2sim_remote_sha256_update(s, &one, 1);
  while (s->used != 56)
    s2sim_remote_sha256_update(s, &zero, 1);
  s2sim_remote_sha256_update(s, length, 8);
  for (i = 0; i < 8; ++i) {
    out[4 * i] = (unsigned char)(s->h[i] >> 24);
    out[4 * i + 1] = (unsigned char)(s->h[i] >> 16);
    out[4 * i + 2] = (unsigned char)(s->h[i] >> 8);
    out[4 * i + 3] = (unsigned char)s->h[i];
  }
}

/* The tag of data[0, size) under `key` (a key of more than 64 bytes is hashed first). */
static inline void s2sim_remote_hmac(const unsigned char* key, size_t key_size,
                                     const unsigned char* data, size_t size, unsigned char* out) {
  unsigned char pad[64], inner[32];
  s2sim_remote_sha256 s;
  size_t i;
  memset(pad, 0, sizeof pad);
  if (key_size > 64) {
    s2sim_remote_sha256_init(&s);
    s2sim_remote_sha256_update(&s, key, key_size);
    s2sim_remote_sha256_final(&s, pad);
  } else {
    memcpy(pad, key, key_size);
  }
  for (i = 0; i < 64; ++i)
    pad[i] ^= 0x36;
  s2sim_remote_sha256_init(&s);
  s2sim_remote_sha256_update(&s, pad, 64);
  s2sim_remote_sha256_update(&s, data, size);
  s2sim_remote_sha256_final(&s, inner);
  for (i = 0; i < 64; ++i)
    pad[i] ^= 0x36 ^ 0x5c;
  s2sim_remote_sha256_init(&s);
  s2sim_remote_sha256_update(&s, pad, 64);
  s2sim_remote_sha256_update(&s, inner, 32);
  s2sim_remote_sha256_final(&s, out);
}

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
  unsigned char key[64];
  size_t key_size; /* 0: the link has no key */
  unsigned char buffer[S2SIM_REMOTE_MAX_DATAGRAM + 1];
} s2sim_remote_client;

/* For a link with a key_file: signs every request with `key` (the key file's bytes, less one
 * trailing newline; at least S2SIM_REMOTE_MIN_KEY bytes) and takes only replies signed with it.
 * Returns 0, or -1 for a shorter key. Call after s2sim_remote_open. */
static inline int s2sim_remote_set_key(s2sim_remote_client* c, const unsigned char* key,
                                       size_t size) {
  if (size < S2SIM_REMOTE_MIN_KEY) return -1;
  if (size > sizeof c->key) { /* RFC 2104: a long key is its hash */
    s2sim_remote_sha256 s;
    s2sim_remote_sha256_init(&s);
    s2sim_remote_sha256_update(&s, key, size);
    s2sim_remote_sha256_final(&s, c->key);
    c->key_size = 32;
  } else {
    memcpy(c->key, key, size);
    c->key_size = size;
  }
  return 0;
}

/* Sends buffer[0, size), signed first when the client has a key (room for the tag after it).
 * Returns 0, or -1. */
static inline int s2sim_remote_send_raw(s2sim_remote_client* c, unsigned char* buffer,
                                        size_t size) {
  if (c->key_size > 0) {
    s2sim_remote_hmac(c->key, c->key_size, buffer, size, buffer + size);
    size += S2SIM_REMOTE_TAG_SIZE;
  }
  return sendto(c->fd, buffer, size, 0, (const struct sockaddr*)&c->server, sizeof c->server) ==
                 (ssize_t)size
             ? 0
             : -1;
}

/* Opens a client of the simulation at `ipv4_address`:`port`. Returns 0, or -1 (errno set). */
static inline int s2sim_remote_open(s2sim_remote_client* c, const char* ipv4_address,
                                    uint16_t port) {
  memset(&c->server, 0, sizeof c->server);
  c->server.sin_family = AF_INET;
  c->server.sin_port = htons(port);
  if (inet_pton(AF_INET, ipv4_address, &c->server.sin_addr) != 1) return -1;
  c->fd = socket(AF_INET, SOCK_DGRAM, 0);
  c->sequence = 0;
  c->key_size = 0;
  return c->fd < 0 ? -1 : 0;
}

static inline void s2sim_remote_close(s2sim_remote_client* c) {
  if (c->fd >= 0) { /* the session ends now, not when the link stops waiting for us */
    unsigned char bye[S2SIM_REMOTE_HEADER_SIZE + S2SIM_REMOTE_TAG_SIZE];
    c->sequence += 1;
    s2sim_remote_write_header(bye, S2SIM_REMOTE_BYE, c->sequence, 0);
    (void)s2sim_remote_send_raw(c, bye, S2SIM_REMOTE_HEADER_SIZE);
    close(c->fd);
  }
  c->fd = -1;
}

/* Sends a request of `type` with `count` doubles; returns its sequence number, or 0 on error. */
static inline uint32_t s2sim_remote_send(s2sim_remote_client* c, uint16_t type,
                                         const double* values, size_t count) {
  size_t i, size = S2SIM_REMOTE_HEADER_SIZE + 8 * count;
  if (size + S2SIM_REMOTE_TAG_SIZE > S2SIM_REMOTE_MAX_DATAGRAM) return 0;
  c->sequence += 1;
  s2sim_remote_write_header(c->buffer, type, c->sequence, (uint32_t)(8 * count));
  for (i = 0; i < count; ++i)
    s2sim_remote_put_f64(c->buffer + 16 + 8 * i, values[i]);
  if (s2sim_remote_send_raw(c, c->buffer, size) != 0) return 0;
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
    if (c->key_size > 0) { /* a reply not signed with the key is nobody's */
      unsigned char tag[S2SIM_REMOTE_TAG_SIZE], differ = 0;
      if (got < S2SIM_REMOTE_TAG_SIZE) continue;
      got -= S2SIM_REMOTE_TAG_SIZE;
      s2sim_remote_hmac(c->key, c->key_size, c->buffer, (size_t)got, tag);
      for (i = 0; i < S2SIM_REMOTE_TAG_SIZE; ++i)
        differ |= (unsigned char)(tag[i] ^ c->buffer[got + (ssize_t)i]);
      if (differ) continue;
    }
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
