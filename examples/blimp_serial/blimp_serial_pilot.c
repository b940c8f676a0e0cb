/* The blimp's microcontroller, stood in for by a program: it opens the serial controller's
 * pseudo-terminal as firmware opens its UART, reads the blimp's state lines and answers each
 * with the spin of its three propellers, flying a list of waypoints
 * (docs/tutorials/blimp-serial.md, the line protocol in docs/remote.md, "Serial link").
 *
 *   blimp_serial_pilot [--waypoints FILE] [--radius M] [--delay S] [--timeout S] DEVICE
 *
 * It asks for the link's description first ("?"), finds the signals and inputs it needs by
 * name, then answers every "S <time> <signals...>" line with one "I <left> <right> <lift>"
 * line, and stops when the simulation closes its end (the device hangs up: the run is over).
 * C99 and POSIX only. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#define MAX_WAYPOINTS 32
#define MAX_LINE 4096
#define MAX_FIELDS 64

/* The blimp of scenes/blimp_serial: each propeller's thrust is kt * spin * |spin| (N). */
static const double kThrustCoefficient = 1e-5; /* N s^2/rad^2 */
static const double kBeam_m = 0.6;             /* between the side propellers */
static const double kMaxThrust_N = 1.0;
static const double kCruise_m_s = 0.5;
static const double kPi = 3.14159265358979323846;

/* The state the pilot needs, by the ends of the served signals' names. */
enum { X, Y, Z, YAW, VX, VY, VZ, WZ, STATE_COUNT };
static const char* const kStateNames[STATE_COUNT] = {"/x",  "/y",  "/z",  "/yaw",
                                                     "/vx", "/vy", "/vz", "/wz"};
/* Its commands, by the ends of the served inputs' names. */
enum { LEFT, RIGHT, LIFT, COMMAND_COUNT };
static const char* const kCommandNames[COMMAND_COUNT] = {"/left/spin", "/right/spin", "/lift/spin"};

typedef struct {
  double x, y, z;
} Point;

/* scenes/blimp's square, the default when no file is given. */
static const Point kBuiltInWaypoints[] = {{3, 0, 2}, {3, 3, 2.5}, {0, 3, 2}, {0, 0, 1.5}};

typedef struct {
  Point waypoints[MAX_WAYPOINTS];
  int count, next;          /* waypoints, the one flown to (count when done) */
  double radius_m;          /* a waypoint within this is reached */
  double altitude_integral; /* m s */
  double last_time_s;       /* of the last state line, < 0 before the first */
} Pilot;

typedef struct {
  int state_index[STATE_COUNT];     /* field of each state value in an S line (-1: absent) */
  int command_index[COMMAND_COUNT]; /* position of each command in an I line */
  int signals, inputs;              /* counts from the description */
  int described;                    /* "# end" seen */
} Link;

static int ends_with(const char* s, const char* end) {
  const size_t n = strlen(s), m = strlen(end);
  return n >= m && strcmp(s + n - m, end) == 0;
}

static double clamp(double v, double lo, double hi) {
  return v < lo ? lo : v > hi ? hi : v;
}

static double wrap_angle(double a) {
  while (a > kPi)
    a -= 2 * kPi;
  while (a < -kPi)
    a += 2 * kPi;
  return a;
}

/* The spin (rad/s) that gives `thrust` (N), within the propeller's limit. */
static double spin_for(double thrust_N) {
  const double t = clamp(thrust_N, -kMaxThrust_N, kMaxThrust_N);
  const double spin = sqrt(fabs(t) / kThrustCoefficient);
  return t < 0 ? -spin : spin;
}

/* Waypoints from a file: "x y z" a line (m), '#' starts a comment. Returns their count, or -1
 * with a message naming the file and line. */
static int read_waypoints(const char* path, Point* out) {
  FILE* f = fopen(path, "r");
  char line[512];
  int count = 0, number = 0;
  if (f == NULL) {
    fprintf(stderr, "blimp_serial_pilot: cannot open %s: %s\n", path, strerror(errno));
    return -1;
  }
  while (fgets(line, sizeof line, f) != NULL) {
    char* hash = strchr(line, '#');
    Point p;
    char rest[2];
    ++number;
    if (hash != NULL) *hash = '\0';
    if (sscanf(line, " %1s", rest) != 1) continue; /* blank */
    if (sscanf(line, "%lf %lf %lf %1s", &p.x, &p.y, &p.z, rest) != 3 || !isfinite(p.x) ||
        !isfinite(p.y) || !isfinite(p.z) || count == MAX_WAYPOINTS) {
      fprintf(stderr, "blimp_serial_pilot: %s:%d: expected 'x y z' (m), at most %d lines\n", path,
              number, MAX_WAYPOINTS);
      fclose(f);
      return -1;
    }
    out[count++] = p;
  }
  fclose(f);
  if (count == 0) fprintf(stderr, "blimp_serial_pilot: %s holds no waypoint\n", path);
  return count == 0 ? -1 : count;
}

/* The device as a raw 8-bit line: no echo, no line editing, no translation of CR or LF. */
static int open_device(const char* path) {
  struct termios t;
  const int fd = open(path, O_RDWR | O_NOCTTY);
  if (fd < 0) {
    fprintf(stderr, "blimp_serial_pilot: cannot open %s: %s\n", path, strerror(errno));
    return -1;
  }
  if (tcgetattr(fd, &t) != 0) {
    fprintf(stderr, "blimp_serial_pilot: %s is not a terminal: %s\n", path, strerror(errno));
    close(fd);
    return -1;
  }
  t.c_iflag &= ~(tcflag_t)(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON);
  t.c_oflag &= ~(tcflag_t)OPOST;
  t.c_lflag &= ~(tcflag_t)(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
  t.c_cflag &= ~(tcflag_t)(CSIZE | PARENB);
  t.c_cflag |= CS8;
  t.c_cc[VMIN] = 1;
  t.c_cc[VTIME] = 0;
  cfsetispeed(&t, B115200); /* as a real UART; a pseudo-terminal ignores it */
  cfsetospeed(&t, B115200);
  /* TCSANOW, not TCSAFLUSH: a state line already waiting is the one to answer. */
  if (tcsetattr(fd, TCSANOW, &t) != 0) {
    fprintf(stderr, "blimp_serial_pilot: cannot set %s raw: %s\n", path, strerror(errno));
    close(fd);
    return -1;
  }
  return fd;
}

static int write_line(int fd, const char* text) {
  size_t left = strlen(text);
  while (left > 0) {
    const ssize_t n = write(fd, text, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return -1;
    text += n;
    left -= (size_t)n;
  }
  return 0;
}

/* One description line: "# signal NAME UNIT" or "# input NAME UNIT" (others ignored). */
static void describe(Link* link, const char* line) {
  char kind[16], name[1024];
  int i;
  if (strcmp(line, "# end") == 0) {
    link->described = 1;
    return;
  }
  if (sscanf(line, "# %15s %1023s", kind, name) != 2) return;
  if (strcmp(kind, "signal") == 0) {
    for (i = 0; i < STATE_COUNT; ++i)
      if (ends_with(name, kStateNames[i]) && link->state_index[i] < 0)
        link->state_index[i] = link->signals;
    ++link->signals;
  } else if (strcmp(kind, "input") == 0) {
    for (i = 0; i < COMMAND_COUNT; ++i)
      if (ends_with(name, kCommandNames[i]) && link->command_index[i] < 0)
        link->command_index[i] = link->inputs;
    ++link->inputs;
  }
}

/* The waypoint-following law, on the state of one S line: the vertical propeller holds the
 * waypoint's altitude (PID on z); in the horizontal plane the velocity wanted points at the
 * waypoint (up to the cruise speed, slower within a few metres), the blimp turns toward what its
 * velocity lacks (differential thrust, PD on that bearing) and pushes by the part of it ahead. */
static void fly(Pilot* pilot, double time_s, const double* s, double* command) {
  const double dt = pilot->last_time_s < 0 ? 0.0 : time_s - pilot->last_time_s;
  const int last = pilot->count - 1;
  Point goal = pilot->waypoints[pilot->next < last ? pilot->next : last];
  double tx = goal.x - s[X], ty = goal.y - s[Y], tz = goal.z - s[Z];
  double horizontal, wanted, ex, ey, bearing, ahead, surge, turn;
  pilot->last_time_s = time_s;
  if (pilot->next < pilot->count && sqrt(tx * tx + ty * ty + tz * tz) < pilot->radius_m) {
    printf("waypoint %d (%g %g %g) reached at %.2f s\n", pilot->next + 1, goal.x, goal.y, goal.z,
           time_s);
    fflush(stdout);
    ++pilot->next;
    goal = pilot->waypoints[pilot->next < last ? pilot->next : last];
    tx = goal.x - s[X];
    ty = goal.y - s[Y];
    tz = goal.z - s[Z];
  }
  pilot->altitude_integral = clamp(pilot->altitude_integral + tz * dt, -2.0, 2.0);
  command[LIFT] = spin_for(1.5 * tz - 2.0 * s[VZ] + 0.5 * pilot->altitude_integral);

  horizontal = sqrt(tx * tx + ty * ty);
  wanted = pilot->next >= pilot->count ? 0.0 : fmin(kCruise_m_s, 0.3 * horizontal);
  ex = (horizontal > 1e-9 ? wanted * tx / horizontal : 0.0) - s[VX];
  ey = (horizontal > 1e-9 ? wanted * ty / horizontal : 0.0) - s[VY];
  bearing = sqrt(ex * ex + ey * ey) > 0.02 ? wrap_angle(atan2(ey, ex) - s[YAW]) : 0.0;
  ahead = fmax(0.0, cos(bearing));
  surge = 2.0 * ahead * (ex * cos(s[YAW]) + ey * sin(s[YAW]));
  turn = 0.15 * bearing - 0.3 * s[WZ];
  command[RIGHT] = spin_for(0.5 * surge + turn / kBeam_m);
  command[LEFT] = spin_for(0.5 * surge - turn / kBeam_m);
}

/* Answers one "S <time> <signals...>" line with one "I ..." line. Returns 0, or -1 on a line
 * that does not match the description. */
static int answer(int fd, const Link* link, Pilot* pilot, const char* line, double delay_s) {
  double field[MAX_FIELDS], state[STATE_COUNT], command[COMMAND_COUNT];
  double ordered[COMMAND_COUNT];
  char out[256];
  const char* at = line + 1;
  int n = 0, i, length = 0;
  for (;;) {
    char* end;
    const double v = strtod(at, &end);
    if (end == at) break;
    if (n == MAX_FIELDS) return -1;
    field[n++] = v;
    at = end;
  }
  if (n != 1 + link->signals) {
    fprintf(stderr, "blimp_serial_pilot: a state line of %d numbers, expected %d: %s\n", n,
            1 + link->signals, line);
    return -1;
  }
  for (i = 0; i < STATE_COUNT; ++i)
    state[i] = field[1 + link->state_index[i]];
  fly(pilot, field[0], state, command);
  for (i = 0; i < COMMAND_COUNT; ++i)
    ordered[link->command_index[i]] = command[i];
  length = snprintf(out, sizeof out, "I");
  for (i = 0; i < COMMAND_COUNT; ++i)
    length += snprintf(out + length, sizeof out - (size_t)length, " %.17g", ordered[i]);
  snprintf(out + length, sizeof out - (size_t)length, "\n");
  if (delay_s > 0) {
    struct timespec pause;
    pause.tv_sec = (time_t)delay_s;
    pause.tv_nsec = (long)((delay_s - (double)pause.tv_sec) * 1e9);
    while (nanosleep(&pause, &pause) != 0 && errno == EINTR) {
    }
  }
  return write_line(fd, out);
}

/* Whether the description names every state value and command, and nothing else to send. */
static int described_enough(const Link* link) {
  int i;
  for (i = 0; i < STATE_COUNT; ++i)
    if (link->state_index[i] < 0) {
      fprintf(stderr, "blimp_serial_pilot: the link serves no signal ending in %s\n",
              kStateNames[i]);
      return 0;
    }
  for (i = 0; i < COMMAND_COUNT; ++i)
    if (link->command_index[i] < 0) {
      fprintf(stderr, "blimp_serial_pilot: the link serves no input ending in %s\n",
              kCommandNames[i]);
      return 0;
    }
  if (link->inputs != COMMAND_COUNT || link->signals + 1 > MAX_FIELDS) {
    fprintf(stderr, "blimp_serial_pilot: the link serves %d inputs (expected %d) and %d signals\n",
            link->inputs, COMMAND_COUNT, link->signals);
    return 0;
  }
  return 1;
}

static int usage(void) {
  fprintf(stderr,
          "usage: blimp_serial_pilot [--waypoints FILE] [--radius M] [--delay S] [--timeout S] "
          "DEVICE\n"
          "  DEVICE      the serial controller's pseudo-terminal (its link='...' path)\n"
          "  --waypoints 'x y z' lines (m); default: scenes/blimp's square\n"
          "  --radius    a waypoint counts as reached within this (m; default 0.2)\n"
          "  --delay     wait this long before each answer, as a slower controller (s; default 0)\n"
          "  --timeout   give up after this long without a line (s; default 30)\n");
  return 2;
}

int main(int argc, char** argv) {
  Pilot pilot;
  Link link;
  const char* device = NULL;
  double timeout_s = 30, delay_s = 0;
  char line[MAX_LINE + 1], held[MAX_LINE + 1], chunk[1024];
  size_t length = 0;
  int fd, i, have_held = 0, overlong = 0;

  memset(&pilot, 0, sizeof pilot);
  memset(&link, 0, sizeof link);
  for (i = 0; i < STATE_COUNT; ++i)
    link.state_index[i] = -1;
  for (i = 0; i < COMMAND_COUNT; ++i)
    link.command_index[i] = -1;
  pilot.radius_m = 0.2;
  pilot.last_time_s = -1;
  pilot.count = (int)(sizeof kBuiltInWaypoints / sizeof kBuiltInWaypoints[0]);
  memcpy(pilot.waypoints, kBuiltInWaypoints, sizeof kBuiltInWaypoints);

  for (i = 1; i < argc; ++i) {
    char* end = NULL;
    if (strcmp(argv[i], "--waypoints") == 0 && i + 1 < argc) {
      pilot.count = read_waypoints(argv[++i], pilot.waypoints);
      if (pilot.count < 0) return 2;
    } else if (strcmp(argv[i], "--radius") == 0 && i + 1 < argc) {
      pilot.radius_m = strtod(argv[++i], &end);
      if (*end != '\0' || !(pilot.radius_m > 0) || !isfinite(pilot.radius_m)) return usage();
    } else if (strcmp(argv[i], "--delay") == 0 && i + 1 < argc) {
      delay_s = strtod(argv[++i], &end);
      if (*end != '\0' || !(delay_s >= 0) || delay_s > 10) return usage();
    } else if (strcmp(argv[i], "--timeout") == 0 && i + 1 < argc) {
      timeout_s = strtod(argv[++i], &end);
      if (*end != '\0' || !(timeout_s > 0) || timeout_s > 1e6) return usage();
    } else if (argv[i][0] != '-' && device == NULL) {
      device = argv[i];
    } else {
      return usage();
    }
  }
  if (device == NULL) return usage();
  fd = open_device(device);
  if (fd < 0) return 1;
  if (write_line(fd, "?\n") != 0) {
    fprintf(stderr, "blimp_serial_pilot: cannot write to %s: %s\n", device, strerror(errno));
    return 1;
  }

  for (;;) {
    struct pollfd p;
    ssize_t got;
    p.fd = fd;
    p.events = POLLIN;
    p.revents = 0;
    if (poll(&p, 1, (int)(timeout_s * 1000)) == 0) {
      fprintf(stderr, "blimp_serial_pilot: no line from %s for %g s\n", device, timeout_s);
      return 1;
    }
    got = read(fd, chunk, sizeof chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break; /* 0 or EIO: the simulation closed its end */
    for (i = 0; i < got; ++i) {
      const char c = chunk[i];
      if (c != '\n' && c != '\r') {
        if (length < MAX_LINE)
          line[length++] = c;
        else
          overlong = 1;
        continue;
      }
      line[length] = '\0';
      if (length == 0 || overlong) {
        length = 0;
        overlong = 0;
        continue;
      }
      length = 0;
      if (line[0] == '#') {
        if (link.described) continue; /* one description is enough */
        describe(&link, line);
        if (link.described) {
          if (!described_enough(&link)) return 1;
          /* A state line that came before the description is the first one to answer. */
          if (have_held && answer(fd, &link, &pilot, held, delay_s) != 0) return 1;
          have_held = 0;
        }
      } else if (line[0] == 'S' && line[1] == ' ') {
        if (!link.described) {
          strcpy(held, line);
          have_held = 1;
        } else if (answer(fd, &link, &pilot, line, delay_s) != 0) {
          return 1;
        }
      }
    }
  }
  printf("the run is over (the device hung up) at %.2f s: %d of %d waypoints reached\n",
         pilot.last_time_s, pilot.next, pilot.count);
  close(fd);
  return 0;
}
